#!/usr/bin/env python3
"""End-to-end: scripts written for MoveIt run unchanged. A MoveIt-tutorial-style script (sixdof_scripts'
moveit_tutorial.py) runs as a user would run it; then, on the same stack, what MoveIt's own commander tests check:
target setting in every form, planning (the Noetic 4-tuple), go with every argument form, a stale plan refused,
path constraints, Cartesian paths in both signatures, retiming, the planning scene synchronous and asynchronous,
RobotCommander, the planned path display, and upstream's exceptions for bad input."""

import copy
import subprocess
import sys
import time
import unittest

import moveit_commander
import moveit_msgs.msg
import numpy as np
import roslib.packages
import rospy
import rostest
from e2e import case, settled_joint_state, wait_for_stack
from geometry_msgs.msg import PoseStamped
from moveit_commander import MoveItCommanderException
from moveit_msgs.msg import (
    Constraints,
    JointConstraint,
    MoveItErrorCodes,
    OrientationConstraint,
    RobotState,
    RobotTrajectory,
)
from moveit_msgs.srv import GetPositionFK
from sensor_msgs.msg import JointState

HANG_GUARD = 120.0  # outcome bound for calls that must return (not a speed claim)


def wait_until(condition, timeout: float = 20.0) -> bool:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if condition():
            return True
        time.sleep(0.05)
    return condition()


class MoveItCommanderEndToEnd(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        moveit_commander.roscpp_initialize(sys.argv)
        rospy.init_node("test_moveit_commander")
        wait_for_stack()
        cls.robot = moveit_commander.RobotCommander()
        cls.arm = moveit_commander.MoveGroupCommander("arm", wait_for_servers=60.0)
        cls.arm.set_max_velocity_scaling_factor(0.5)
        cls.arm.set_max_acceleration_scaling_factor(0.5)
        cls.home = cls.arm.get_named_target_values("home pose")

    def setUp(self):
        self.arm.clear_pose_targets()
        self.arm.set_start_state_to_current_state()

    def assert_at(self, values, tolerance=0.01):
        """The arm's settled joint positions are within tolerance of values (a list in active-joint order)."""
        msg = settled_joint_state()
        positions = dict(zip(msg.name, msg.position, strict=True))
        for joint, value in zip(self.arm.get_active_joints(), values, strict=True):
            self.assertAlmostEqual(positions[joint], value, delta=tolerance, msg=joint)

    def home_values(self):
        return [self.home[j] for j in self.arm.get_active_joints()]

    # The tutorial, as a user runs it -----------------------------------------------------------------
    def test_a_tutorial_script_runs_unchanged(self):
        self.assertTrue(self.arm.go("home pose", wait=True), self.arm.last_error.message)
        # As `rosrun sixdof_scripts moveit_tutorial.py` finds it (the first match: source and install spaces may
        # both hold it), with this interpreter (the venv's: the script's shebang needs it on PATH).
        script = roslib.packages.find_node("sixdof_scripts", "moveit_tutorial.py")[0]
        run = subprocess.run([sys.executable, script], capture_output=True, text=True, timeout=600)
        print(run.stdout, run.stderr)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        self.assertIn("all steps succeeded", run.stdout)
        scene = moveit_commander.PlanningSceneInterface(synchronous=True)
        self.assertNotIn("tutorial_box", scene.get_known_object_names())
        self.assertEqual(scene.get_attached_objects(), {})

    # go() and plan() ---------------------------------------------------------------------------------
    def test_go_accepts_every_argument_form(self):
        home = self.home_values()
        shifted = list(home)
        shifted[0] += 0.25
        names = self.arm.get_active_joints()
        joint_state = JointState(name=names, position=shifted)
        self.assertTrue(self.arm.go("home pose"), self.arm.last_error.message)
        pose = self.arm.get_current_pose()
        self.arm.remember_joint_values("shifted", shifted)
        # Each form moves the arm (shifted <-> home); pose forms are checked by the pose reached (IK may pick
        # another joint configuration of the same pose).
        forms = [
            ("list", shifted, shifted),
            ("tuple", tuple(home), home),
            ("ndarray", np.array(shifted), shifted),
            ("dict (partial)", {names[0]: home[0]}, home),
            ("JointState", joint_state, shifted),
            ("Pose", pose.pose, pose),
            ("remembered name", "shifted", shifted),
            ("PoseStamped", pose, pose),
            ("list", shifted, shifted),
            ("SRDF name", "home pose", home),
        ]
        for form, argument, expected in forms:
            with case(form=form):
                self.assertTrue(self.arm.go(argument, wait=True), self.arm.last_error.message)
                if isinstance(expected, PoseStamped):
                    settled_joint_state()
                    reached = self.arm.get_current_pose()
                    self.assertLess(np.linalg.norm(np.subtract(_xyz(reached), _xyz(expected))), 0.002)
                else:
                    self.assert_at(expected)
        with case(form="bool means wait"):
            self.arm.set_joint_value_target(shifted)
            self.assertTrue(self.arm.go(True))
            self.assert_at(shifted)
            self.arm.set_joint_value_target(home)
            self.assertTrue(self.arm.go(wait=False))
            self.assertTrue(wait_until(lambda: self.arm.get_current_joint_values()[0] < home[0] + 0.01, HANG_GUARD))
            self.assert_at(home)

    def test_plan_returns_the_noetic_tuple_and_a_stale_plan_is_refused(self):
        self.assertTrue(self.arm.go("home pose"), self.arm.last_error.message)
        target = self.home_values()
        target[0] -= 0.3
        success, plan, planning_time, error_code = self.arm.plan(target)
        self.assertIs(success, True)
        self.assertIsInstance(plan, moveit_msgs.msg.RobotTrajectory)
        self.assertIsInstance(planning_time, float)
        self.assertIsInstance(error_code, MoveItErrorCodes)
        self.assertEqual(error_code.val, MoveItErrorCodes.SUCCESS)
        self.assertTrue(self.arm.execute(plan, wait=True), self.arm.last_error.message)
        self.assert_at(target)
        # The same plan again: it starts where the arm no longer is, so execution refuses it.
        self.assertFalse(self.arm.execute(plan, wait=True))
        self.assertNotEqual(self.arm.last_error.val, MoveItErrorCodes.SUCCESS)
        self.assertTrue(self.arm.last_error.message)
        # plan() with no argument plans to the target already set.
        self.arm.set_named_target("home pose")
        success, plan, _, _ = self.arm.plan()
        self.assertTrue(success)
        last = dict(zip(plan.joint_trajectory.joint_names, plan.joint_trajectory.points[-1].positions, strict=True))
        for joint, value in self.home.items():
            self.assertAlmostEqual(last[joint], value, delta=1e-3, msg=joint)

    # Targets -----------------------------------------------------------------------------------------
    def test_joint_value_target_forms(self):
        names = self.arm.get_active_joints()
        home = self.home_values()
        self.arm.set_joint_value_target(home)
        self.assertEqual(self.arm.get_joint_value_target(), home)
        self.arm.set_joint_value_target(names[0], 0.5)
        self.assertAlmostEqual(self.arm.get_joint_value_target()[0], 0.5)
        state = RobotState()
        state.joint_state.name = names
        state.joint_state.position = home
        self.arm.set_joint_value_target(state)
        self.assertEqual(self.arm.get_joint_value_target(), home)
        # A pose, solved by IK (compute_ik) for the end-effector link, exact and with approx.
        self.assertTrue(self.arm.go("home pose"), self.arm.last_error.message)
        pose = self.arm.get_current_pose()
        for extra in ((), (True,), (self.arm.get_end_effector_link(),), (self.arm.get_end_effector_link(), True)):
            with case(arguments=extra):
                self.arm.set_joint_value_target(pose, *extra)
                solution = self.arm.get_joint_value_target()
                fk = self._fk(self.arm.get_end_effector_link(), self._state(solution))
                self.assertLess(np.linalg.norm(np.subtract(_xyz(fk), _xyz(pose))), 1e-3)
        with self.assertRaisesRegex(MoveItCommanderException, "no IK solution"):
            far = PoseStamped()
            far.header.frame_id = self.arm.get_planning_frame()
            far.pose.position.x, far.pose.orientation.w = 3.0, 1.0
            self.arm.set_joint_value_target(far)

    def _fk(self, link, state):
        """link's pose in the planning frame at `state` (move_group's compute_fk)."""
        response = rospy.ServiceProxy("compute_fk", GetPositionFK)(fk_link_names=[link], robot_state=state)
        self.assertEqual(response.error_code.val, MoveItErrorCodes.SUCCESS, f"compute_fk of '{link}'")
        return response.pose_stamped[0]

    def _state(self, values):
        state = RobotState()
        state.is_diff = True
        state.joint_state.name = self.arm.get_active_joints()
        state.joint_state.position = values
        return state

    def test_bad_input_raises_upstreams_exceptions_naming_the_problem(self):
        names = self.arm.get_active_joints()
        with self.assertRaisesRegex(MoveItCommanderException, "6 names but 5 positions"):
            self.arm.set_joint_value_target(JointState(name=names, position=[0.0] * 5))
        with self.assertRaisesRegex(MoveItCommanderException, "must have 6 values"):
            self.arm.set_joint_value_target([0.0] * 5)
        with self.assertRaisesRegex(MoveItCommanderException, "6 elements .* or 7 .* got 5"):
            self.arm.set_pose_target([0.3, 0.0, 0.3, 0.0, 0.0])
        with self.assertRaisesRegex(MoveItCommanderException, "unknown named target 'nowhere'"):
            self.arm.set_named_target("nowhere")
        with self.assertRaisesRegex(MoveItCommanderException, "unknown named target 'nowhere'"):
            self.arm.go("nowhere")
        with self.assertRaisesRegex(RuntimeError, "no group 'manipulator'"):
            moveit_commander.MoveGroupCommander("manipulator")
        with self.assertRaisesRegex(MoveItCommanderException, "no group 'manipulator'"):
            self.robot.get_group("manipulator")
        with self.assertRaisesRegex(MoveItCommanderException, "outside its limits"):
            self.arm.set_joint_value_target(names[1], 10.0)
        # What sixdof cannot honour is refused by name, never silently ignored.
        orientation = Constraints(orientation_constraints=[OrientationConstraint(link_name="link6")])
        for call, name in (
            (lambda: self.arm.set_path_constraints(orientation), "set_path_constraints"),
            (lambda: self.arm.set_path_constraints("upright"), "set_path_constraints"),
            (lambda: self.arm.allow_replanning(True), "allow_replanning"),
            (lambda: self.arm.set_orientation_target([0, 0, 0, 1]), "set_orientation_target"),
            (lambda: self.arm.pick("red_cube"), "pick"),
        ):
            with case(method=name), self.assertRaisesRegex(MoveItCommanderException, f"{name}.* not available"):
                call()
        self.arm.allow_replanning(False)
        self.arm.set_path_constraints(None)
        self.arm.clear_path_constraints()
        self.assertEqual(self.arm.get_known_constraints(), [])

    def test_path_constraints_keep_a_joint_in_its_range(self):
        self.assertTrue(self.arm.go("home pose"), self.arm.last_error.message)
        names = self.arm.get_active_joints()
        home = self.home_values()
        target = list(home)
        target[0] += 0.4
        # joint4 (the wrist roll) kept within 0.05 rad of home along the whole path, joint1 free to move.
        kept = JointConstraint(joint_name=names[3], position=home[3], tolerance_above=0.05, tolerance_below=0.05)
        self.arm.set_path_constraints(Constraints(joint_constraints=[kept], name="wrist kept"))
        try:
            self.assertEqual(self.arm.get_path_constraints().joint_constraints[0].joint_name, names[3])
            success, plan, _, code = self.arm.plan(target)
            self.assertTrue(success, self.arm.last_error)
            column = plan.joint_trajectory.joint_names.index(names[3])
            for point in plan.joint_trajectory.points:
                self.assertLessEqual(abs(point.positions[column] - home[3]), 0.05 + 1e-6)
            # A goal outside the range cannot be reached: the failure comes with move_group's words.
            outside = list(home)
            outside[3] += 0.5
            success, _, _, code = self.arm.plan(outside)
            self.assertFalse(success)
            self.assertNotEqual(code.val, MoveItErrorCodes.SUCCESS)
            self.assertTrue(self.arm.last_error.message, self.arm.last_error)
        finally:
            self.arm.clear_path_constraints()
        self.assertEqual(self.arm.get_path_constraints(), Constraints())

    # Cartesian paths and retiming --------------------------------------------------------------------
    def test_cartesian_path_in_both_signatures_and_retiming(self):
        self.assertTrue(self.arm.go("home pose"), self.arm.last_error.message)
        start = self.arm.get_current_pose().pose
        waypoint = start.__class__()
        waypoint.position.x, waypoint.position.y = start.position.x, start.position.y
        waypoint.position.z = start.position.z + 0.05
        waypoint.orientation = start.orientation
        for arguments in ((), (True,), (0.0,), (0.0, True)):
            with case(arguments=arguments):
                plan, fraction = self.arm.compute_cartesian_path([waypoint], 0.01, *arguments)
                self.assertEqual(fraction, 1.0, self.arm.last_error.message)
        plan, fraction = self.arm.compute_cartesian_path([waypoint], 0.01, avoid_collisions=True)
        self.assertEqual(fraction, 1.0)
        duration = plan.joint_trajectory.points[-1].time_from_start.to_sec()
        slow = self.arm.retime_trajectory(self.robot.get_current_state(), plan, 0.2, 0.2)
        fast = self.arm.retime_trajectory(self.robot.get_current_state(), plan, 1.0, 1.0)
        end_slow, end_fast = (t.joint_trajectory.points[-1].time_from_start for t in (slow, fast))
        self.assertGreater(end_slow, end_fast)
        self.assertEqual(len(slow.joint_trajectory.points), len(plan.joint_trajectory.points))
        self.assertGreater(duration, 0.0)
        # Time-optimal (move_group's retime_trajectory service): the same path, slower at smaller factors.
        optimal = {
            factor: self.arm.retime_trajectory(
                self.robot.get_current_state(), plan, factor, factor, algorithm="time_optimal_trajectory_generation"
            )
            for factor in (0.2, 1.0)
        }
        for retimed in optimal.values():
            self.assertEqual(retimed.joint_trajectory.joint_names, plan.joint_trajectory.joint_names)
            last, expected = retimed.joint_trajectory.points[-1], plan.joint_trajectory.points[-1]
            for a, b in zip(last.positions, expected.positions, strict=True):
                self.assertAlmostEqual(a, b, places=6)
        self.assertGreater(optimal[0.2].joint_trajectory.points[-1].time_from_start,
                           optimal[1.0].joint_trajectory.points[-1].time_from_start)
        unknown = RobotTrajectory()
        unknown.joint_trajectory = copy.deepcopy(plan.joint_trajectory)
        unknown.joint_trajectory.joint_names[0] = "no_such_joint"
        with self.assertRaisesRegex(MoveItCommanderException, "unknown joint 'no_such_joint'"):
            self.arm.retime_trajectory(RobotState(), unknown, algorithm="time_optimal_trajectory_generation")
        self.assertTrue(self.arm.execute(slow, wait=True), self.arm.last_error.message)
        self.assertLess(abs(self.arm.get_current_pose().pose.position.z - waypoint.position.z), 0.005)

    # Planning scene ----------------------------------------------------------------------------------
    def test_planning_scene_synchronous_and_asynchronous(self):
        link = self.arm.get_end_effector_link()
        pose = PoseStamped()
        pose.header.frame_id = self.arm.get_planning_frame()
        pose.pose.position.x, pose.pose.position.y, pose.pose.position.z = 0.1, 0.4, 0.3
        pose.pose.orientation.w = 1.0
        for synchronous in (True, False):
            scene = moveit_commander.PlanningSceneInterface(synchronous=synchronous)
            name = f"box_{'sync' if synchronous else 'async'}"

            def known(n=name, s=scene):
                return n in s.get_known_object_names()

            def attached(n=name, s=scene):
                return n in s.get_attached_objects([n])

            with case(synchronous=synchronous):
                scene.add_box(name, pose, size=(0.05, 0.05, 0.05))
                self.assertTrue(known() if synchronous else wait_until(known))
                self.assertIn(name, scene.get_objects([name]))
                self.assertAlmostEqual(scene.get_object_poses([name])[name].position.y, 0.4, places=6)
                self.assertIn(name, scene.get_known_object_names_in_roi(0.0, 0.3, 0.2, 0.2, 0.5, 0.4))
                self.assertNotIn(name, scene.get_known_object_names_in_roi(0.5, 0.3, 0.2, 0.7, 0.5, 0.4))
                scene.attach_box(link, name, touch_links=self.robot.get_link_names(group="gripper"))
                self.assertTrue(attached() if synchronous else wait_until(attached))
                self.assertFalse(known())
                self.assertEqual(scene.get_attached_objects([name])[name].link_name, link)
                scene.remove_attached_object(link, name=name)
                self.assertTrue(known() if synchronous else wait_until(known))
                scene.remove_world_object(name)
                self.assertTrue(not known() if synchronous else wait_until(lambda: not known()))
                # A new box attached directly (with a pose), then detached by link, then removed.
                scene.attach_box(link, name, pose=pose, size=(0.02, 0.02, 0.02), touch_links=[link])
                self.assertTrue(attached() if synchronous else wait_until(attached))
                scene.remove_attached_object(link)
                self.assertTrue(known() if synchronous else wait_until(known))
                scene.remove_world_object(name)
                self.assertTrue(not known() if synchronous else wait_until(lambda: not known()))

    # RobotCommander and the display ------------------------------------------------------------------
    def test_robot_commander(self):
        robot = self.robot
        self.assertEqual(robot.get_group_names(), ["arm", "gripper"])
        self.assertEqual(robot.get_planning_frame(), "world")
        self.assertEqual(robot.get_root_link(), "base_link")
        self.assertEqual(robot.get_joint_names("arm"), self.arm.get_active_joints())
        self.assertEqual(robot.get_active_joint_names("gripper"), ["finger1_joint"])
        self.assertIn("finger2_joint", robot.get_joint_names())
        self.assertIn("link6", robot.get_link_names())
        self.assertEqual(robot.get_link_names()[0], "base_link")
        self.assertEqual(robot.get_joint("joint2").bounds(), [-1.92, 1.92])
        values = robot.get_current_variable_values()
        self.assertAlmostEqual(robot.get_joint("joint1").value(), values["joint1"], delta=0.05)
        self.assertEqual(robot.arm.get_name(), "arm")
        self.assertIs(robot.arm, robot.get_group("arm"))
        self.assertEqual(set(robot.get_current_state().joint_state.name), set(values))
        link6 = robot.get_link("link6").pose()
        self.assertEqual(link6.header.frame_id, "world")
        current = self.arm.get_current_pose("link6")
        self.assertLess(np.linalg.norm(np.subtract(_xyz(link6), _xyz(current))), 0.01)
        with self.assertRaisesRegex(MoveItCommanderException, "no joint named 'joint9'"):
            robot.get_joint("joint9")
        with self.assertRaises(AttributeError):
            robot.no_such_thing  # noqa: B018
        jac = self.arm.get_jacobian_matrix(self.home_values())
        self.assertEqual(jac.shape, (6, 6))
        self.assertEqual(self.arm.get_random_pose().header.frame_id, "world")
        bounded = self.arm.enforce_bounds(self._state([0.0, 5.0, 0.0, 0.0, 0.0, 0.0]))
        self.assertEqual(bounded.joint_state.position[1], 1.92)
        for _ in range(20):
            for joint, value in zip(self.arm.get_active_joints(), self.arm.get_random_joint_values(), strict=True):
                low, high = robot.get_joint(joint).bounds()
                self.assertTrue(low <= value <= high, f"{joint} {value}")
        self.arm.set_workspace([-1.0, -1.0, -1.0, 1.0, 1.0, 1.0])
        self.arm.set_workspace([])
        with self.assertRaisesRegex(MoveItCommanderException, "a minimum exceeds its maximum"):
            self.arm.set_workspace([1.0, 0.0, 0.0, 0.0])
        self.arm.shift_pose_target(2, 0.05)
        self.assertAlmostEqual(self.arm.get_pose_target().pose.position.z, current.pose.position.z + 0.05, delta=0.01)
        self.arm.clear_pose_targets()

    def test_planned_path_reaches_the_rviz_display_topic(self):
        received = []
        subscriber = rospy.Subscriber(
            "/move_group/display_planned_path", moveit_msgs.msg.DisplayTrajectory, received.append
        )
        try:
            # sixdof_rviz's Planned Path display subscribes to exactly this type.
            self.assertEqual(moveit_msgs.msg.DisplayTrajectory._type, "moveit_msgs/DisplayTrajectory")
            self.assertTrue(wait_until(lambda: subscriber.get_num_connections() > 0))
            self.arm.set_named_target("home pose")
            success, plan, _, _ = self.arm.plan()
            self.assertTrue(success)
            self.assertTrue(wait_until(lambda: any(
                m.trajectory and m.trajectory[0].joint_trajectory.points == plan.joint_trajectory.points
                for m in received)))
        finally:
            subscriber.unregister()

    def test_z_clear_removes_every_object(self):
        # Last (tests run in name order): it also removes the simulator's mirrored objects from the planning scene.
        scene = moveit_commander.PlanningSceneInterface(synchronous=True)
        link = self.arm.get_end_effector_link()
        pose = PoseStamped()
        pose.header.frame_id = link
        pose.pose.orientation.w = 1.0
        scene.attach_box(link, "held_box", pose=pose, size=(0.01, 0.01, 0.01))
        self.assertIn("held_box", scene.get_attached_objects())
        self.assertTrue(scene.get_known_object_names())
        self.assertTrue(scene.clear())
        self.assertEqual(scene.get_known_object_names(), [])
        self.assertEqual(scene.get_attached_objects(), {})


def _xyz(pose):
    p = pose.pose.position if isinstance(pose, PoseStamped) else pose.position
    return [p.x, p.y, p.z]


if __name__ == "__main__":
    rostest.rosrun("sixdof_tests", "test_moveit_commander", MoveItCommanderEndToEnd, sys.argv)
