#!/usr/bin/env python3
"""The perception node in the headless stack (sorting world): every object of a fixed layout is found near its
simulated pose with its colour class and keeps its id over frames, move_group's planning scene holds what is
seen (and drops what is gone), and sort_objects.py sorts a small layout into the bins (exit 0), reports and skips
an object out of reach (exit 1) and finds nothing to sort once every object is in its bin (exit 0)."""

import math
import subprocess
import sys
import time
import unittest

import rospy
import rostest
from moveit_msgs.msg import PlanningSceneComponents
from moveit_msgs.srv import GetPlanningScene, GetPlanningSceneRequest
from shape_msgs.msg import SolidPrimitive
from sixdof_commander.colors import color_class
from sixdof_commander.sim_world import wait_for_world
from std_msgs.msg import ColorRGBA

from sixdof_msgs.msg import DetectedObjectArray, ObjectStates, SimObject
from sixdof_msgs.srv import DeleteObject, GetObjectState, SpawnObject

# Hang guards only: the tests assert outcomes, never durations.
STARTUP_TIMEOUT = 240.0
POSITION_BOUND = 0.008  # m between a detection and the simulated object's centre


def dynamic_objects() -> dict:
    """Simulator ground truth (the test's own check, never the perception node's input): name -> (xyz, colour)."""
    states = rospy.wait_for_message("sixdof_sim/object_states", ObjectStates, timeout=30.0)
    get = rospy.ServiceProxy("sixdof_sim/get_object_state", GetObjectState)
    out = {}
    for name, pose in zip(states.name, states.pose, strict=True):
        obj = get(name).object
        if not obj.is_static:
            p = pose.position
            out[name] = ((p.x, p.y, p.z), color_class(obj.color.r, obj.color.g, obj.color.b))
    return out


def frames(count: int, after: rospy.Time) -> list[DetectedObjectArray]:
    out = []
    deadline = time.monotonic() + STARTUP_TIMEOUT
    while len(out) < count and time.monotonic() < deadline:
        msg = rospy.wait_for_message("detected_objects", DetectedObjectArray, timeout=STARTUP_TIMEOUT)
        if msg.header.stamp > after and (not out or msg.header.stamp > out[-1].header.stamp):
            out.append(msg)
    return out


def scene_ids() -> set:
    request = GetPlanningSceneRequest()
    request.components.components = PlanningSceneComponents.WORLD_OBJECT_NAMES
    scene = rospy.ServiceProxy("get_planning_scene", GetPlanningScene)(request).scene
    return {o.id for o in scene.world.collision_objects}


class PerceptionInTheStack(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_perception_sort")
        rospy.wait_for_service("get_planning_scene", timeout=STARTUP_TIMEOUT)
        rospy.wait_for_service("sixdof_sim/get_object_state", timeout=STARTUP_TIMEOUT)

    def check_layout(self, truth: dict) -> list:
        """Three frames after now: each object found once near its pose with its colour; ids stable."""
        seen = frames(3, rospy.Time.now() + rospy.Duration(0.5))
        self.assertEqual(len(seen), 3, "fewer than 3 detected_objects frames")
        ids_per_frame = []
        for msg in seen:
            detections = {o.id: o for o in msg.objects}
            self.assertEqual(len(detections), len(truth), f"detected {sorted(detections)} for {sorted(truth)}")
            for name, (position, colour) in truth.items():
                nearest = min(
                    msg.objects,
                    key=lambda o: math.dist(
                        position, (o.pose.pose.position.x, o.pose.pose.position.y, o.pose.pose.position.z)
                    ),
                )
                p = nearest.pose.pose.position
                error = math.dist(position, (p.x, p.y, p.z))
                self.assertLess(error, POSITION_BOUND, f"{name}: detection {nearest.id} {error * 1000:.1f} mm away")
                self.assertEqual(nearest.color, colour, f"{name}: colour")
            ids_per_frame.append(sorted(detections))
        self.assertEqual(ids_per_frame[0], ids_per_frame[1], "ids changed between frames")
        self.assertEqual(ids_per_frame[1], ids_per_frame[2], "ids changed between frames")
        return ids_per_frame[-1]

    def wait_scene(self, ids: list, absent: list = ()) -> None:
        deadline = time.monotonic() + 60.0
        while time.monotonic() < deadline:
            current = scene_ids()
            if all(i in current for i in ids) and not any(i in current for i in absent):
                return
            time.sleep(0.2)
        self.fail(f"planning scene {sorted(scene_ids())}: expected {ids}, not {list(absent)}")

    def test_detect_then_sort(self):
        truth = dynamic_objects()
        self.assertEqual(len(truth), 6)
        ids = self.check_layout(truth)
        self.wait_scene(ids + ["table", "red_bin_wall_x_min"])

        # A smaller layout: three objects are taken away; their ids leave the planning scene.
        delete = rospy.ServiceProxy("sixdof_sim/delete_object", DeleteObject)
        for name in ("red_sphere", "green_cube", "blue_sphere"):
            self.assertTrue(delete(name).success)
        small = dynamic_objects()
        kept = self.check_layout(small)
        self.assertTrue(set(kept) <= set(ids), f"ids changed when other objects went: {kept} vs {ids}")
        self.wait_scene(kept, absent=sorted(set(ids) - set(kept)))

        result = self.sort()
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIn("3/3 objects in their bins", result.stdout)

        # An object out of the arm's reach (the table's far corner) is reported and skipped: exit 1.
        far = SimObject(
            name="far_cube",
            shape=SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[0.04] * 3),
            mass=0.1,
            friction=0.8,
            color=ColorRGBA(0.9, 0.1, 0.1, 1.0),
        )
        far.pose.position.x, far.pose.position.y, far.pose.position.z = 0.66, 0.30, 0.02
        far.pose.orientation.w = 1.0
        self.assertTrue(rospy.ServiceProxy("sixdof_sim/spawn_object", SpawnObject)(far).success)
        result = self.sort()
        self.assertEqual(result.returncode, 1, result.stdout + result.stderr)
        self.assertIn("FAILED (unreachable", result.stdout)
        self.assertIn("far_cube", result.stdout)  # the final check names the object left out
        # Once it is gone, everything left is in its bin: nothing to sort, exit 0.
        self.assertTrue(delete("far_cube").success)
        result = self.sort()
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIn("nothing to sort", result.stdout)

    def test_bins_from_the_simulators_world(self):
        """The bins come from the simulator's ~world parameter (defaults applied); without one, sort_objects.py
        stops with exit code 2 naming the parameter."""
        world = wait_for_world(timeout=5.0)
        self.assertEqual(sorted(b.color for b in world.bins), ["blue", "green", "red"])
        self.assertTrue(all(b.wall_height > 0.0 and b.wall_thickness > 0.0 for b in world.bins))
        self.assertEqual(len([o for o in world.objects if o.bin]), 4 * len(world.bins))
        self.assertTrue(any(o.table for o in world.objects))
        self.assertTrue(world.cameras)
        result = self.sort("--ns", "/nowhere", "--world-wait", "1")
        self.assertEqual(result.returncode, 2, result.stdout + result.stderr)
        self.assertIn("/nowhere/sixdof_sim/world: no such parameter", result.stderr)

    def sort(self, *args: str) -> subprocess.CompletedProcess:
        result = subprocess.run(
            ["rosrun", "sixdof_scripts", "sort_objects.py", *args],
            capture_output=True,
            text=True,
            timeout=800,
            check=False,
        )
        print(result.stdout, result.stderr)
        return result


if __name__ == "__main__":
    rostest.rosrun("sixdof_perception", "perception_sort", PerceptionInTheStack, sys.argv)
