#!/usr/bin/env python3
"""rviz with the sixdof_rviz plugins and the shipped config, on the X display given by xvfb-run.

Starts rviz itself (after subscribing to /rosout, so that no early message is missed), then checks that every
plugin is live on the ROS graph, that a published DisplayTrajectory is drawn by the ghost robot at the
trajectory's final state, the planning scene's objects and the goal robot's colours, and that rviz logged no error.

The tests share one rviz (started once, as each start costs seconds under llvmpipe; again only when Mesa kills it
in its first seconds: sixdof_rviz.rviz_process) and run in their names' order
(unittest sorts them), which is the fixture: test_0 needs no rviz; test_1..test_4 each wait for the subscriptions they
use and compare screenshots against a baseline taken in the test itself, so they do not depend on each other's
drawing, except that test_2 expects no ghost robot yet (no trajectory published before it); test_5 runs last and checks
the log of the whole session.
"""

import os
import tempfile
import unittest
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import rosgraph
import rospy
import rostest
import yaml
from geometry_msgs.msg import Point, Pose, PoseStamped
from moveit_msgs.msg import (
    AttachedCollisionObject,
    CollisionObject,
    ContactInformation,
    DisplayTrajectory,
    MoveItErrorCodes,
    PlanningScene,
    RobotTrajectory,
)
from moveit_msgs.srv import (
    GetPositionIK,
    GetPositionIKResponse,
    GetStateValidity,
    GetStateValidityResponse,
)
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import JointState
from shape_msgs.msg import Mesh, MeshTriangle, SolidPrimitive
from trajectory_msgs.msg import JointTrajectoryPoint

from sixdof_msgs.msg import ErrorReport
from sixdof_rviz.rviz_process import RvizProcess
from sixdof_rviz.screenshots import channels, marker_sphere_mask, screenshot, settled_screenshot

ARM_JOINTS = ["joint1", "joint2", "joint3", "joint4", "joint5", "joint6"]
ALL_JOINTS = ARM_JOINTS + ["finger1_joint", "finger2_joint"]
# rviz prints this when the optional package media_export is missing; it is harmless.
HARMLESS = ("no such package media_export", "error while executing command")
# Hang guard only: rviz under llvmpipe maps its main window within seconds when healthy.
RVIZ_UP_TIMEOUT = 120.0


def ghost_mask(image: np.ndarray) -> np.ndarray:
    """Pixels in the PlannedPath robot's colour (220, 0, 220 in the config): red and blue alike and high,
    green low, whatever the shading. The goal robot (sky blue), the robot model (orange and grey) and the background are
    not."""
    r, g, b = channels(image)
    return (r > 70) & (b > 70) & (g * 2 < np.minimum(r, b)) & (np.abs(r - b) * 3 < np.maximum(r, b))


def world_mask(image: np.ndarray) -> np.ndarray:
    """World objects' colour (60, 170, 60 in the config)."""
    r, g, b = channels(image)
    return (g > 90) & (g * 2 > r * 3) & (g * 2 > b * 3)


def attached_mask(image: np.ndarray) -> np.ndarray:
    """Attached objects' colour (140, 60, 220 in the config): blue clearly above red, red well above green."""
    r, g, b = channels(image)
    return (b > 90) & (b * 4 > r * 5) & (r * 2 > g * 3)


def reachable_mask(image: np.ndarray) -> np.ndarray:
    """The goal robot's "reachable" colour (0, 190, 255 in the config): sky blue, red low and green between 0.4 and 1
    times blue. None of the arm's URDF materials (orange, greys) nor the other displays' colours match."""
    r, g, b = channels(image)
    return (b > 90) & (r * 3 < b) & (g * 10 > b * 4) & (g <= b)


def unreachable_mask(image: np.ndarray) -> np.ndarray:
    """The goal robot's "unreachable" colour (230, 0, 0 in the config); the arm's orange material (0.93, 0.45, 0.1) has
    half as much green as red."""
    r, g, b = channels(image)
    return (r > 90) & (g * 5 < r) & (b * 5 < r)


def box(size: float) -> SolidPrimitive:
    return SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[size, size, size])


def cube_mesh(size: float) -> Mesh:
    """A closed cube centred on its origin made of 12 triangles, each wound counter-clockwise seen from outside."""
    h = size / 2
    corners = [(x, y, z) for x in (-h, h) for y in (-h, h) for z in (-h, h)]
    triangles = []
    for axis in range(3):
        for side in (-h, h):
            # The face's corners, in the order (u0, v0), (u0, v1), (u1, v0), (u1, v1) of the other two axes.
            a, b, c, d = (i for i, corner in enumerate(corners) if corner[axis] == side)
            for triangle in ((a, b, d), (a, d, c)):
                p, q, r = (np.array(corners[i]) for i in triangle)
                outward = np.cross(q - p, r - p)[axis] * side > 0
                triangles.append(MeshTriangle(vertex_indices=list(triangle if outward else triangle[::-1])))
    return Mesh(triangles=triangles, vertices=[Point(*corner) for corner in corners])


def pose(x: float, y: float, z: float) -> Pose:
    p = Pose()
    p.position.x, p.position.y, p.position.z = x, y, z
    p.orientation.w = 1.0
    return p


def full_scene(meshes: bool = False) -> PlanningScene:
    """A table-top box beside the robot and a cube held between the fingers (0.08 m along link6's z axis).
    With `meshes`, also a mesh cube on the robot's other side (screen-right of it) and, above the box, a malformed
    mesh (a triangle's vertex index out of range), which the display skips."""
    scene = PlanningScene(name="test_scene", is_diff=False)
    obstacle = CollisionObject(id="obstacle", primitives=[box(0.15)], primitive_poses=[pose(0, 0, 0)])
    obstacle.header.frame_id = "base_link"
    obstacle.pose = pose(0.25, -0.45, 0.075)
    scene.world.collision_objects.append(obstacle)
    if meshes:
        block = CollisionObject(id="mesh_block", meshes=[cube_mesh(0.12)], mesh_poses=[pose(0, 0, 0)])
        block.header.frame_id = "base_link"
        block.pose = pose(0.25, 0.45, 0.06)
        scene.world.collision_objects.append(block)
        malformed = cube_mesh(0.12)
        malformed.triangles.append(MeshTriangle(vertex_indices=[0, 1, len(malformed.vertices)]))
        obstacle.meshes.append(malformed)
        obstacle.mesh_poses.append(pose(0, 0, 0.25))
    held = CollisionObject(id="held_cube", primitives=[box(0.04)], primitive_poses=[pose(0, 0, 0)])
    held.pose = pose(0, 0, 0.08)
    scene.robot_state.attached_collision_objects.append(
        AttachedCollisionObject(link_name="link6", object=held, touch_links=["finger1", "finger2"])
    )
    return scene


def trajectory_to(joint1: float) -> DisplayTrajectory:
    msg = DisplayTrajectory()
    msg.model_id = "sixdof"
    msg.trajectory_start.joint_state.name = ALL_JOINTS
    msg.trajectory_start.joint_state.position = [0.0] * len(ALL_JOINTS)
    trajectory = RobotTrajectory()
    trajectory.joint_trajectory.joint_names = ARM_JOINTS
    for i in range(5):
        s = i / 4.0
        point = JointTrajectoryPoint()
        point.positions = [joint1 * s, 0.5 * s, 0.3 * s, 0.0, 0.4 * s, 0.0]
        point.time_from_start = rospy.Duration(0.25 * i)
        trajectory.joint_trajectory.points.append(point)
    msg.trajectory.append(trajectory)
    return msg


def on_graph(topic: str, node: str, publishes: bool) -> bool:
    """Whether the master lists `node` among the publishers (or subscribers) of `topic`."""
    publishers, subscribers, _ = rosgraph.Master("/test_rviz_plugins").getSystemState()
    return any(name == topic and node in nodes for name, nodes in (publishers if publishes else subscribers))


class RvizPluginsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("test_rviz_plugins")
        cls.log_messages = []
        rospy.Subscriber("/rosout", Log, cls.log_messages.append, queue_size=1000)
        # The simulator is not part of this test: the current state is published here.
        cls.joint_pub = rospy.Publisher("joint_states", JointState, queue_size=1)
        cls.timer = rospy.Timer(rospy.Duration(0.1), cls.publish_joint_states)
        cls.path_pub = rospy.Publisher("move_group/display_planned_path", DisplayTrajectory, queue_size=1, latch=True)
        cls.shot_dir = os.environ.get("SIXDOF_RVIZ_SHOT_DIR") or tempfile.mkdtemp(prefix="sixdof_rviz_shots_")
        os.makedirs(cls.shot_dir, exist_ok=True)
        # rviz's rosout publisher connects to the subscribers the master knows when rviz starts.
        for _ in range(300):
            if on_graph("/rosout", rospy.get_name(), publishes=False):
                break
            rospy.sleep(0.1)
        else:
            raise AssertionError("the /rosout subscription never reached the master")
        cls.rviz_log_path = os.path.join(cls.shot_dir, "rviz.log")
        cls.rviz = RvizProcess(
            ["rosrun", "rviz", "rviz", "-d", rospy.get_param("~rviz_config"), "__name:=rviz"], Path(cls.rviz_log_path)
        )
        cls.rviz.wait_up(RVIZ_UP_TIMEOUT)

    @classmethod
    def tearDownClass(cls) -> None:
        cls.timer.shutdown()
        cls.rviz.stop()

    @classmethod
    def publish_joint_states(cls, _event) -> None:
        msg = JointState()
        msg.header.stamp = rospy.Time.now()
        msg.name = ALL_JOINTS
        msg.position = [0.0] * len(ALL_JOINTS)
        cls.joint_pub.publish(msg)

    def wait_for(self, condition, what: str, tries: int = 600) -> None:
        for _ in range(tries):
            self.assertTrue(self.rviz.alive(), self.rviz.exited())
            if condition():
                return
            rospy.sleep(0.1)
        self.fail("timed out waiting for " + what)

    def graph_has(self, topic: str, publishes: bool) -> bool:
        return on_graph(topic, "/rviz", publishes)

    def ghost_pixels(self, name: str, baseline: np.ndarray, unlike: np.ndarray) -> np.ndarray:
        """Mask of ghost-coloured pixels that were not in the baseline, once the drawing differs from `unlike`
        (the previous picture) and is still."""
        previous = None
        for _ in range(100):
            mask = ghost_mask(screenshot(save_as=os.path.join(self.shot_dir, f"{name}.png"))) & ~baseline
            changed = (mask ^ unlike).sum() > 500
            if changed and previous is not None and mask.sum() > 500 and (mask ^ previous).sum() < 50:
                return mask
            previous = mask
            rospy.sleep(0.3)
        self.fail(f"the ghost robot of {name} never settled ({0 if previous is None else previous.sum()} pixels)")

    def test_0_goal_colours_distinct(self) -> None:
        """The goal robot's configured colours match their masks, and no URDF material of the arm nor any other
        display's colour matches them, in full light or half shade: users (and the tests) tell the goal robot from
        the real one and from the planned path and the scene objects."""
        urdf = ET.fromstring(rospy.get_param("robot_description"))
        others = {
            f"material {m.get('name')}": [float(v) * 255 for v in m.find("color").get("rgba").split()[:3]]
            for m in urdf.iter("material")
            if m.find("color") is not None
        }
        self.assertGreater(len(others), 1, "the URDF has no coloured materials")
        with open(rospy.get_param("~rviz_config")) as config:
            displays = {d["Name"]: d for d in yaml.safe_load(config)["Visualization Manager"]["Displays"]}

        def rgb(text: str) -> list:
            return [float(v) for v in str(text).split(";")]

        goal = displays["Goal State"]
        others["planned path"] = rgb(displays["Planned Path"]["Robot Color"])
        others["world objects"] = rgb(displays["Planning Scene"]["World Object Color"])
        others["attached objects"] = rgb(displays["Planning Scene"]["Attached Object Color"])
        others["goal marker sphere"] = [0.9 * 255, 0.9 * 255, 0.2 * 255]

        def pixel(colour: list, shade: float) -> np.ndarray:
            return np.array([[[round(c * shade) for c in colour]]], dtype=np.uint8)

        reachable, unreachable = rgb(goal["Reachable Color"]), rgb(goal["Unreachable Color"])
        for shade in (0.5, 0.75, 1.0):
            self.assertTrue(reachable_mask(pixel(reachable, shade)).all(), shade)
            self.assertTrue(unreachable_mask(pixel(unreachable, shade)).all(), shade)
            self.assertFalse(unreachable_mask(pixel(reachable, shade)).any(), shade)
            self.assertFalse(reachable_mask(pixel(unreachable, shade)).any(), shade)
            for name, colour in others.items():
                for mask, what in ((reachable_mask, "reachable"), (unreachable_mask, "unreachable")):
                    self.assertFalse(mask(pixel(colour, shade)).any(), f"{name} {colour} looks {what} at {shade}")

    def test_1_plugins_live(self) -> None:
        # PlannedPath subscribes to the trajectory topic, GoalState publishes the goal, the panel's logic reads it.
        self.wait_for(lambda: self.graph_has("/move_group/display_planned_path", False), "PlannedPath subscription")
        self.wait_for(lambda: self.graph_has("/sixdof_rviz/goal_state", True), "GoalState goal publisher")
        self.wait_for(lambda: self.graph_has("/sixdof_rviz/goal_state", False), "panel goal subscription")
        self.wait_for(lambda: self.graph_has("/joint_states", False), "joint_states subscription")
        # The Planning Scene display takes move_group's full scenes; the panel and the goal's IK its error reports.
        self.wait_for(lambda: self.graph_has("/move_group/monitored_planning_scene", False), "scene subscription")
        self.wait_for(lambda: self.graph_has("/move_group/error_reports", False), "error report subscription")
        goal = rospy.wait_for_message("/sixdof_rviz/goal_state", JointState, timeout=60.0)
        # The goal starts at the current state (all zero here).
        self.assertEqual(sorted(goal.name), sorted(ALL_JOINTS))
        self.assertTrue(all(abs(p) < 1e-9 for p in goal.position))

    def test_2_ghost_draws_the_trajectory(self) -> None:
        self.wait_for(lambda: self.graph_has("/move_group/display_planned_path", False), "PlannedPath subscription")
        # Once the goal marker is drawn and the drawing is still, the robot model is too.
        self.wait_for_pixels("0_marker", marker_sphere_mask, np.zeros((1, 1), dtype=bool), 20)
        baseline = ghost_mask(settled_screenshot(save_as=os.path.join(self.shot_dir, "0_before.png")))
        self.assertLess(baseline.sum(), 200, "ghost colour on screen before any trajectory")
        self.path_pub.publish(trajectory_to(1.2))
        plus = self.ghost_pixels("1_joint1_plus", baseline, unlike=np.zeros_like(baseline))
        self.path_pub.publish(trajectory_to(-1.2))
        minus = self.ghost_pixels("2_joint1_minus", baseline, unlike=plus)
        # The view looks at the robot from +x with z up, so +y is screen-right: joint1 > 0 swings the arm there.
        plus_column = np.argwhere(plus)[:, 1].mean()
        minus_column = np.argwhere(minus)[:, 1].mean()
        self.assertGreater(plus_column, minus_column + 100)

    @staticmethod
    def values(state: JointState) -> dict:
        return dict(zip(state.name, state.position, strict=True))

    def wait_for_pixels(self, name: str, mask_function, baseline: np.ndarray, minimum: int) -> np.ndarray:
        for _ in range(100):
            mask = mask_function(screenshot(save_as=os.path.join(self.shot_dir, f"{name}.png"))) & ~baseline
            if mask.sum() > minimum:
                return mask
            rospy.sleep(0.3)
        self.fail(f"{name}: fewer than {minimum} new pixels")

    def test_3_planning_scene_objects(self) -> None:
        self.wait_for(lambda: self.graph_has("/move_group/display_planned_path", False), "PlannedPath subscription")
        baseline = screenshot(save_as=os.path.join(self.shot_dir, "3_scene_before.png"))
        # The marker's green arrow and the panel's icons share the world colour: only new pixels count.
        world_before, attached_before = world_mask(baseline), attached_mask(baseline)
        # Stands in for move_group's monitored_planning_scene: the full scene, latched, after each change.
        scene_pub = rospy.Publisher("move_group/monitored_planning_scene", PlanningScene, queue_size=1, latch=True)
        scene_pub.publish(full_scene())
        try:
            for _ in range(100):
                image = screenshot(save_as=os.path.join(self.shot_dir, "4_scene.png"))
                world, attached = world_mask(image) & ~world_before, attached_mask(image) & ~attached_before
                if world.sum() > 1000 and attached.sum() > 100:
                    break
                rospy.sleep(0.3)
            self.assertGreater(world.sum(), 1000, "world box not drawn")
            self.assertGreater(attached.sum(), 100, "attached cube not drawn")
            # Then the mesh cube and the malformed mesh: the cube is drawn in the world colour right of the box, the
            # malformed mesh (above the box) is not, and the rest is still drawn.
            scene_pub.publish(full_scene(meshes=True))
            self.wait_for_pixels("4_scene_meshes_appear", world_mask, world_before | world, 500)
            meshes_image = settled_screenshot(save_as=os.path.join(self.shot_dir, "4_scene_meshes.png"))
        finally:
            scene_pub.unregister()
        meshes_world = world_mask(meshes_image) & ~world_before
        mesh_cube = meshes_world & ~world
        box_columns = np.argwhere(world)[:, 1]
        mesh_columns = np.argwhere(mesh_cube)[:, 1]
        # About as many pixels as the box: fewer when the cube's far (unlit) faces cover its near ones.
        self.assertGreater(len(mesh_columns), 0.5 * world.sum(), "mesh cube not drawn, or not lit")
        self.assertGreater(mesh_columns.min(), box_columns.max(), "the malformed mesh (above the box) is drawn")
        self.assertGreater((meshes_world & world).sum(), 0.9 * world.sum(), "world box no longer drawn")
        self.assertGreater((attached_mask(meshes_image) & ~attached_before).sum(), 100, "attached cube not drawn")
        # The held cube is drawn at the gripper: next to the goal marker's sphere on link6 (at the current state).
        sphere = np.argwhere(marker_sphere_mask(image))
        self.assertGreater(len(sphere), 20, "goal marker sphere not found")
        cube_centre = np.argwhere(attached).mean(axis=0)
        gripper_distance = np.linalg.norm(cube_centre - sphere.mean(axis=0))
        box_distance = np.linalg.norm(np.argwhere(world).mean(axis=0) - sphere.mean(axis=0))
        self.assertLess(gripper_distance, 120)
        self.assertGreater(box_distance, 2 * gripper_distance)

    def test_4_goal_state_ik(self) -> None:
        self.wait_for(lambda: self.graph_has("/sixdof_rviz/goal_pose", False), "GoalState goal pose subscription")
        rospy.wait_for_message("/sixdof_rviz/goal_state", JointState, timeout=60.0)
        red_before = unreachable_mask(screenshot(save_as=os.path.join(self.shot_dir, "5_goal_before.png")))
        # Stand-ins for move_group's compute_ik / check_state_validity with scripted answers; as move_group, the
        # failed IK call's words go to move_group/error_reports before the answer.
        answers = {"ik": MoveItErrorCodes.NO_IK_SOLUTION, "valid": True}
        report_pub = rospy.Publisher("move_group/error_reports", ErrorReport, queue_size=10)
        ik_requests = []
        solution = dict(zip(ARM_JOINTS, [0.4, 0.1, 0.2, 0.0, 0.3, 0.0], strict=True))

        def compute_ik(request):
            ik_requests.append(request.ik_request)
            response = GetPositionIKResponse()
            response.error_code.val = answers["ik"]
            if answers["ik"] == MoveItErrorCodes.SUCCESS:
                response.solution.joint_state.name = list(solution)
                response.solution.joint_state.position = list(solution.values())
            else:
                report = ErrorReport(caller_id=request._connection_header["callerid"], interface="/compute_ik")
                report.header.stamp = rospy.Time.now()
                report.error_code.val = answers["ik"]
                report.message = "pose out of reach"
                report_pub.publish(report)
            return response

        def check_state_validity(_request):
            response = GetStateValidityResponse(valid=answers["valid"])
            if not answers["valid"]:
                response.contacts.append(ContactInformation(contact_body_1="link6", contact_body_2="base_link"))
            return response

        goals = []
        goal_sub = rospy.Subscriber("/sixdof_rviz/goal_state", JointState, goals.append)
        pose_pub = rospy.Publisher("sixdof_rviz/goal_pose", PoseStamped, queue_size=1)
        target = PoseStamped()
        target.header.frame_id = "base_link"
        target.pose = pose(0.3, 0.2, 0.4)
        services = [
            rospy.Service("compute_ik", GetPositionIK, compute_ik),
            rospy.Service("check_state_validity", GetStateValidity, check_state_validity),
        ]
        try:
            # Unreachable: the goal robot turns red.
            self.wait_for(lambda: pose_pub.get_num_connections() > 0, "goal pose connection")
            pose_pub.publish(target)
            self.wait_for_pixels("6_goal_no_ik", unreachable_mask, red_before, 2000)
            request = ik_requests[-1]
            self.assertEqual(request.group_name, "arm")
            self.assertEqual(request.ik_link_name, "link6")
            self.assertEqual(request.pose_stamped.header.frame_id, "base_link")
            self.assertEqual(request.pose_stamped.pose, target.pose)
            self.assertFalse(request.avoid_collisions)
            # The seed is the current state (all zero here).
            self.assertTrue(all(p == 0.0 for p in request.robot_state.joint_state.position))

            # Reachable and collision-free: sky blue at the solution, which is published as the goal.
            # (Red pixels are no measure here: rviz draws links without a URDF material red, and the goal robot
            # no longer hides the RobotModel.)
            answers["ik"] = MoveItErrorCodes.SUCCESS
            blue_no_ik = reachable_mask(screenshot(save_as=os.path.join(self.shot_dir, "6_goal_no_ik.png")))
            pose_pub.publish(target)
            self.wait_for(lambda: any(self.values(g)["joint1"] == solution["joint1"] for g in goals), "IK goal")
            goal_values = self.values(goals[-1])
            for joint, value in solution.items():
                self.assertAlmostEqual(goal_values[joint], value)
            self.assertEqual(goal_values["finger1_joint"], 0.0)  # joints outside the group keep the current state
            self.wait_for_pixels("7_goal_ok", reachable_mask, blue_no_ik, 2000)

            # Reachable but in collision: red again, and not published as a goal.
            answers["valid"] = False
            published = len(goals)
            red_ok = unreachable_mask(screenshot(save_as=os.path.join(self.shot_dir, "7_goal_ok.png")))
            pose_pub.publish(target)
            self.wait_for_pixels("8_goal_collision", unreachable_mask, red_ok, 2000)
            self.assertEqual(len(goals), published)
        finally:
            goal_sub.unregister()
            report_pub.unregister()
            for service in services:
                service.shutdown()

    def test_5_no_errors_logged(self) -> None:
        self.wait_for(lambda: self.graph_has("/move_group/display_planned_path", False), "PlannedPath subscription")
        errors = [m.msg for m in self.log_messages if m.name == "/rviz" and m.level >= Log.ERROR]
        self.assertEqual(errors, [])
        with open(self.rviz_log_path) as log:
            lines = [line.strip() for line in log if ("ERROR" in line or "FATAL" in line or "rror" in line)]
        self.assertEqual([line for line in lines if not any(h in line for h in HARMLESS)], [])


if __name__ == "__main__":
    rostest.rosrun("sixdof_rviz", "test_rviz_plugins", RvizPluginsTest)
