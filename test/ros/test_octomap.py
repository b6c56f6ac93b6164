#!/usr/bin/env python3
"""The occupancy map in the live stack (octomap.test): an obstacle spawned into the simulator only (no scene
message ever names it) is seen by the camera, blocks a straight joint motion through it, and the planned motion
avoids it without touching it in the simulator; the robot's own links never enter the map; get_planning_scene
gives the map (component OCTOMAP); clear_octomap empties it. One stack, the checks in order (each needs the state
the previous one left)."""

from __future__ import annotations

import math
import sys
import time
import unittest
import xml.etree.ElementTree as ET

import actionlib
import rospy
import rostest
from e2e import STARTUP_TIMEOUT, case, object_state, wait_for_action_server
from geometry_msgs.msg import Pose
from moveit_msgs.msg import (
    CollisionObject,
    Constraints,
    ExecuteTrajectoryAction,
    ExecuteTrajectoryGoal,
    JointConstraint,
    MoveItErrorCodes,
    PlanningScene,
    PlanningSceneComponents,
    PlanningSceneWorld,
    RobotState,
)
from moveit_msgs.srv import (
    ApplyPlanningScene,
    GetMotionPlan,
    GetPlanningScene,
    GetPlanningSceneRequest,
    GetPositionFK,
    GetStateValidity,
)
from sensor_msgs.msg import JointState
from shape_msgs.msg import SolidPrimitive
from std_srvs.srv import Empty
from visualization_msgs.msg import MarkerArray

from sixdof_msgs.msg import SimObject
from sixdof_msgs.srv import SpawnObject
from sixdof_test_support.actions import wait_for_goal

OCTOMAP_BODY = "<octomap>"
GROUP = "arm"
# Hang guards only: the camera publishes at 15 Hz of simulated time and the map updates at 5 Hz.
MAP_TIMEOUT = 60.0
SWEEP = 0.9  # rad the first joint turns either way from the middle state
STEPS = 24  # states checked along a straight joint motion
OBSTACLE = "octomap_wall"
# The wall's thickness as a fraction of the map's cell: inside one layer of cells with a margin each side.
WALL_CELL_FRACTION = 0.8
# How far (m) the obstacle may move while the robot passes it: any touch moves a light wall far more.
UNTOUCHED = 0.003


def group_joints(srdf: str, group: str, state: str) -> tuple[list[str], list[float], str]:
    """The group's joints and values in the named state, and the tip link of its chain (from the SRDF)."""
    root = ET.fromstring(srdf)
    tip = next(g.find("chain").get("tip_link") for g in root.findall("group") if g.get("name") == group)
    named = next(s for s in root.findall("group_state") if s.get("group") == group and s.get("name") == state)
    names = [j.get("name") for j in named.findall("joint")]
    values = [float(j.get("value")) for j in named.findall("joint")]
    return names, values, tip


class OccupancyMapTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_octomap")
        for name in ("check_state_validity", "plan_kinematic_path", "compute_fk", "apply_planning_scene",
                     "clear_octomap", "sixdof_sim/spawn_object", "sixdof_sim/pause_physics"):
            rospy.wait_for_service(name, timeout=STARTUP_TIMEOUT)
        cls.validity = rospy.ServiceProxy("check_state_validity", GetStateValidity)
        cls.plan = rospy.ServiceProxy("plan_kinematic_path", GetMotionPlan)
        cls.fk = rospy.ServiceProxy("compute_fk", GetPositionFK)
        cls.clear = rospy.ServiceProxy("clear_octomap", Empty)
        cls.pause = rospy.ServiceProxy("sixdof_sim/pause_physics", Empty)
        cls.unpause = rospy.ServiceProxy("sixdof_sim/unpause_physics", Empty)
        cls.execute = actionlib.SimpleActionClient("execute_trajectory", ExecuteTrajectoryAction)
        wait_for_action_server(cls.execute, STARTUP_TIMEOUT, "execute_trajectory")
        # The sweep of the first joint through the pick pose, its tip low over the table in the camera's view.
        cls.joints, pick, cls.tip = group_joints(rospy.get_param("robot_description_semantic"), GROUP, "pick pose")
        cls.middle = [0.0] + pick[1:]
        cls.start = [-SWEEP] + pick[1:]
        cls.goal = [SWEEP] + pick[1:]
        cls.markers = None
        cls.marker_updates = 0
        rospy.Subscriber("move_group/occupied_cells_vis_array", MarkerArray, cls._on_markers, queue_size=1)
        # The table is a known object (as scene_mirror or perception would make it): the map leaves it out. 2 mm
        # lower, as scene_mirror puts it, so that the robot standing on it does not collide with it.
        table = CollisionObject()
        table.header.frame_id = ""
        table.id = "table"
        table.operation = CollisionObject.ADD
        table.primitives.append(SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[1.0, 1.2, 0.75]))
        table.pose.position.x, table.pose.position.z, table.pose.orientation.w = 0.2, -0.377, 1.0
        identity = Pose()
        identity.orientation.w = 1.0
        table.primitive_poses.append(identity)
        response = rospy.ServiceProxy("apply_planning_scene", ApplyPlanningScene)(
            PlanningScene(is_diff=True, world=PlanningSceneWorld(collision_objects=[table]))
        )
        assert response.success, "apply_planning_scene refused the table"
        # Cells the camera put on the table before it was known go with the next clouds; clearing is quicker.
        cls.clear()

    @classmethod
    def _on_markers(cls, msg: MarkerArray) -> None:
        cls.markers = msg
        cls.marker_updates += 1

    def state(self, values: list[float]) -> RobotState:
        return RobotState(joint_state=JointState(name=self.joints, position=values), is_diff=True)

    def octomap_contacts(self, values: list[float]) -> list:
        response = self.validity(robot_state=self.state(values), group_name=GROUP)
        # Not valid with no contact to say why: move_group refused the request (its words are in its error report).
        self.assertTrue(response.valid or response.contacts, "check_state_validity refused the state")
        return [c for c in response.contacts if OCTOMAP_BODY in (c.contact_body_1, c.contact_body_2)]

    def straight(self, k: int) -> list[float]:
        return [a + (b - a) * k / STEPS for a, b in zip(self.start, self.goal, strict=True)]

    def blocked_states(self) -> list[int]:
        return [k for k in range(STEPS + 1) if self.octomap_contacts(self.straight(k))]

    def wait_until(self, predicate, what: str) -> None:
        deadline = time.monotonic() + MAP_TIMEOUT
        while not predicate():
            self.assertLess(time.monotonic(), deadline, f"timed out waiting until {what}")
            time.sleep(0.2)

    def move_to(self, values: list[float]) -> list:
        """Plans a joint goal (the planner checks it against the map at its resolution) and executes it; returns the
        waypoints."""
        goal = Constraints(joint_constraints=[
            JointConstraint(joint_name=n, position=v, tolerance_above=1e-3, tolerance_below=1e-3, weight=1.0)
            for n, v in zip(self.joints, values, strict=True)
        ])
        request = GetMotionPlan._request_class()
        request.motion_plan_request.group_name = GROUP
        request.motion_plan_request.start_state.is_diff = True
        request.motion_plan_request.goal_constraints = [goal]
        request.motion_plan_request.num_planning_attempts = 1
        request.motion_plan_request.allowed_planning_time = 10.0
        response = self.plan(request).motion_plan_response
        self.assertEqual(response.error_code.val, MoveItErrorCodes.SUCCESS, "plan_kinematic_path")
        trajectory = response.trajectory
        names = trajectory.joint_trajectory.joint_names
        points = trajectory.joint_trajectory.points
        waypoints = [[dict(zip(names, p.positions, strict=True))[j] for j in self.joints] for p in points]
        self.execute.send_goal(ExecuteTrajectoryGoal(trajectory=trajectory))
        self.assertTrue(wait_for_goal(self.execute, 120.0), "execution did not finish")
        result = self.execute.get_result()
        self.assertEqual(result.error_code.val, MoveItErrorCodes.SUCCESS, self.execute.get_goal_status_text())
        return waypoints

    def cell_count(self) -> int:
        msg = self.markers
        return -1 if msg is None else sum(len(m.points) for m in msg.markers)

    def test_occupancy_map(self):
        # 1. No obstacle yet: the robot goes to the start; the map (of what the camera sees) has no cell on the
        #    robot at either end, and the straight joint motion through the middle is free.
        self.move_to(self.start)
        # The map was cleared and the table is masked: it may stay empty, so wait for updates instead of cells.
        updates = self.marker_updates
        self.wait_until(lambda: self.marker_updates >= updates + 2, "the map is updated from the camera")
        with case(step="self filter at the start"):
            self.assertEqual(self.octomap_contacts(self.start), [], "the robot's own links are in the map")
        with case(step="straight motion before the obstacle"):
            self.assertEqual(self.blocked_states(), [])

        # 2. A thin wall facing the camera, in the simulator only, where the middle state's tip passes. The map
        #    knows nothing behind a surface: the cells of the visible face hold the whole wall only if its
        #    thickness lies inside one layer of cells, so it is thinner than a cell and centred in the layer
        #    around the tip (the map's grid has a cell boundary at every multiple of the resolution). A wall
        #    reaching behind that layer leaves a slab the planner may pass through.
        fk = self.fk(fk_link_names=[self.tip], robot_state=self.state(self.middle))
        self.assertEqual(fk.error_code.val, MoveItErrorCodes.SUCCESS, "compute_fk")
        tip = fk.pose_stamped[0].pose.position
        resolution = rospy.get_param("move_group/octomap_resolution")
        height = tip.z + 0.12
        wall = SimObject(name=OBSTACLE, mass=0.3, friction=0.8)
        wall.shape = SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[WALL_CELL_FRACTION * resolution, 0.16, height])
        wall.pose.position.x = (math.floor(tip.x / resolution) + 0.5) * resolution
        wall.pose.position.y, wall.pose.position.z = tip.y, height / 2
        wall.pose.orientation.w = 1.0
        wall.color.r, wall.color.a = 0.8, 1.0
        spawned = rospy.ServiceProxy("sixdof_sim/spawn_object", SpawnObject)(object=wall)
        self.assertTrue(spawned.success, spawned.status_message)
        self.wait_until(lambda: self.octomap_contacts(self.middle), "the middle state collides with the map")
        with case(step="straight motion after the obstacle was seen"):
            blocked = self.blocked_states()
            self.assertIn(STEPS // 2, blocked)
            self.assertNotIn(0, blocked)
            self.assertNotIn(STEPS, blocked)
        with case(step="the map in get_planning_scene"):
            request = GetPlanningSceneRequest()
            request.components.components = PlanningSceneComponents.OCTOMAP
            octomap = rospy.ServiceProxy("get_planning_scene", GetPlanningScene)(request).scene.world.octomap
            self.assertEqual((octomap.octomap.id, octomap.octomap.binary), ("OcTree", True))
            self.assertTrue(octomap.octomap.data, "the map holds the wall's cells")
            self.assertGreater(octomap.octomap.resolution, 0.0)

        # 3. The planned motion goes around it, and executing it in the simulator leaves the wall untouched.
        before = object_state(OBSTACLE).object.pose.position
        waypoints = self.move_to(self.goal)
        after = object_state(OBSTACLE).object.pose.position
        with case(step="planned motion"):
            deviation = max(
                max(abs(q[i] - self.start[i]) for i in range(1, len(q))) for q in waypoints
            )
            self.assertGreater(deviation, 0.05, "the plan is the blocked straight motion")
            moved = math.dist((before.x, before.y, before.z), (after.x, after.y, after.z))
            self.assertLess(moved, UNTOUCHED, f"the robot touched the obstacle (it moved {moved:.4f} m)")
        with case(step="self filter at the goal"):
            self.assertEqual(self.octomap_contacts(self.goal), [], "the robot's own links are in the map")

        # 4. clear_octomap empties the map (the simulator paused: no new cloud refills it meanwhile); the camera
        #    brings the wall back once the simulator runs again.
        self.pause()
        try:
            time.sleep(1.0)  # a cloud already in flight is inserted before the clear
            self.clear()
            with case(step="cleared"):
                self.wait_until(lambda: self.cell_count() == 0, "the published map is empty")
                self.assertEqual(self.octomap_contacts(self.middle), [])
        finally:
            self.unpause()
        self.wait_until(lambda: self.octomap_contacts(self.middle), "the camera refills the map")


if __name__ == "__main__":
    rostest.rosrun("sixdof_tests", "test_octomap", OccupancyMapTest, sys.argv)
