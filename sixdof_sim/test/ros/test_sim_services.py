#!/usr/bin/env python3
"""rostest: the simulator's world services (pause/step/unpause, reset, objects), /clock and state topics."""

import unittest

import actionlib
import rospy
import rostest
import tf2_ros
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import FollowJointTrajectoryAction, GripperCommand, GripperCommandAction, GripperCommandGoal
from control_msgs.srv import QueryTrajectoryState
from rosgraph_msgs.msg import Clock
from shape_msgs.msg import SolidPrimitive
from sim_test_util import (
    FINGER_JOINTS,
    JointStateListener,
    at_rest,
    sim_service,
    trajectory_goal,
    wait_for_servers,
    wait_until,
)
from std_srvs.srv import Empty

from sixdof_msgs.msg import ObjectStates, SimObject
from sixdof_msgs.srv import (
    DeleteObject,
    GetObjectState,
    SetObjectState,
    SpawnObject,
    StepSimulation,
)
from sixdof_test_support.actions import wait_for_goal

TIMEOUT = 60.0


class SimServicesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("test_sim_services")
        cls.step = sim_service("step", StepSimulation, TIMEOUT)
        cls.reset_world = sim_service("reset_world", Empty, TIMEOUT)
        cls.pause = sim_service("pause_physics", Empty, TIMEOUT)
        cls.unpause = sim_service("unpause_physics", Empty, TIMEOUT)
        cls.spawn = sim_service("spawn_object", SpawnObject, TIMEOUT)
        cls.delete = sim_service("delete_object", DeleteObject, TIMEOUT)
        cls.get_object = sim_service("get_object_state", GetObjectState, TIMEOUT)
        cls.set_object = sim_service("set_object_state", SetObjectState, TIMEOUT)
        cls.fingers = actionlib.SimpleActionClient(
            "gripper_controller/follow_joint_trajectory", FollowJointTrajectoryAction
        )
        cls.gripper = actionlib.SimpleActionClient("gripper_controller/gripper_cmd", GripperCommandAction)
        wait_for_servers((cls.fingers, cls.gripper), TIMEOUT)
        cls.joints = JointStateListener()
        cls.tf_buffer = tf2_ros.Buffer()
        cls.tf_listener = tf2_ros.TransformListener(cls.tf_buffer)

    def setUp(self) -> None:
        self.unpause()
        self.reset_world()

    def clock(self) -> float:
        return rospy.wait_for_message("/clock", Clock, TIMEOUT).clock.to_sec()

    def settled_clock(self) -> float:
        """/clock once it stops changing: rospy may still deliver messages published before a pause."""
        previous = self.clock()
        for _ in range(50):
            rospy.rostime.wallsleep(0.1)
            current = self.clock()
            if current == previous:
                return current
            previous = current
        raise AssertionError("/clock keeps advancing while paused")

    def test_pause_step_unpause(self) -> None:
        response = self.step(10)
        self.assertFalse(response.success)
        self.assertIn("pause_physics", response.status_message)
        self.pause()
        paused_at = self.settled_clock()
        response = self.step(250)
        self.assertTrue(response.success, response.status_message)
        self.assertAlmostEqual(self.settled_clock(), paused_at + 0.25, delta=1e-6)
        self.assertFalse(self.step(0).success)
        self.unpause()
        rospy.sleep(0.1)  # the behaviour under test: returns only because simulated time runs again
        self.assertGreater(self.clock(), paused_at + 0.25)

    def test_reset_keeps_the_clock_monotonic_and_restores_objects(self) -> None:
        cube = self.get_object("red_cube")
        self.assertTrue(cube.success, cube.status_message)
        initial_x = cube.object.pose.position.x
        moved = cube.object.pose
        moved.position.x = initial_x + 0.1
        self.assertTrue(self.set_object("red_cube", moved, cube.twist).success)
        before = self.clock()
        self.reset_world()
        self.assertGreaterEqual(self.clock(), before)
        self.assertAlmostEqual(self.get_object("red_cube").object.pose.position.x, initial_x, 6)

    def test_spawn_get_delete(self) -> None:
        ball = SimObject(name="ball", shape=SolidPrimitive(type=SolidPrimitive.SPHERE, dimensions=[0.02]), mass=0.05)
        ball.pose.position.x, ball.pose.position.y, ball.pose.position.z = 0.3, 0.35, 0.3
        ball.pose.orientation.w = 1.0
        ball.friction = 0.5
        self.assertTrue(self.spawn(ball).success)
        duplicate = self.spawn(ball)
        self.assertFalse(duplicate.success)
        self.assertIn("ball", duplicate.status_message)
        self.assertTrue(wait_until(lambda: at_rest(self.get_object("ball")), TIMEOUT), "the ball did not come to rest")
        state = self.get_object("ball")
        self.assertTrue(state.success)
        self.assertEqual(state.object.shape.type, SolidPrimitive.SPHERE)
        self.assertLess(state.object.pose.position.z, 0.1)  # fell onto the table
        states = rospy.wait_for_message("sixdof_sim/object_states", ObjectStates, TIMEOUT)
        self.assertIn("ball", states.name)
        self.assertIn("red_cube", states.name)
        transform = self.tf_buffer.lookup_transform("world", "ball", rospy.Time(0), rospy.Duration(10.0))
        self.assertAlmostEqual(transform.transform.translation.x, 0.3, delta=0.05)
        self.assertTrue(self.delete("ball").success)
        self.assertFalse(self.get_object("ball").success)
        missing = self.delete("ball")
        self.assertFalse(missing.success)
        self.assertIn("ball", missing.status_message)

    def test_latest_gripper_goal_owns_the_fingers(self) -> None:
        self.fingers.send_goal(trajectory_goal(FINGER_JOINTS, [([0.01, 0.01], 3.0)]))
        self.assertTrue(wait_until(lambda: self.fingers.get_state() == GoalStatus.ACTIVE, TIMEOUT), "fingers goal")
        self.gripper.send_goal(GripperCommandGoal(command=GripperCommand(position=0.035)))
        self.assertTrue(wait_for_goal(self.gripper, TIMEOUT))
        self.assertEqual(self.gripper.get_state(), GoalStatus.SUCCEEDED)
        self.assertTrue(wait_for_goal(self.fingers, TIMEOUT))
        self.assertEqual(self.fingers.get_state(), GoalStatus.PREEMPTED)
        self.assertTrue(self.joints.wait_near(FINGER_JOINTS, [0.035, 0.035], 0.0025))
        rospy.sleep(1.0)  # the behaviour under test: for 1 s the preempted trajectory towards 0.01 drives nothing
        self.assertTrue(self.joints.wait_near(FINGER_JOINTS, [0.035, 0.035], 0.0025, timeout=0.0))
        # The trajectory controller cannot say what it commands: it commands nothing now, and (as
        # joint_trajectory_controller) the call fails.
        query = rospy.ServiceProxy("gripper_controller/query_state", QueryTrajectoryState)
        with self.assertRaises(rospy.ServiceException):
            query(rospy.Time.now())


if __name__ == "__main__":
    rostest.rosrun("sixdof_sim", "test_sim_services", SimServicesTest)
