"""Shared parts of the move_group rostest (test_move_group.py): the paper's poses, message builders and a TestCase
base that connects to move_group's services and actions once and wraps the calls the tests repeat."""

import math
import unittest
import xml.etree.ElementTree as ElementTree

import actionlib
import rospy
from geometry_msgs.msg import Pose, Quaternion
from sensor_msgs.msg import JointState
from shape_msgs.msg import SolidPrimitive
from trajectory_msgs.msg import JointTrajectory

from sixdof_msgs.msg import (
    CollisionObject,
    Constraints,
    ExecuteTrajectoryAction,
    ExecuteTrajectoryGoal,
    JointConstraint,
    MotionPlanRequest,
    MoveGroupAction,
    MoveGroupGoal,
    MoveItErrorCodes,
    PositionIKRequest,
    RobotState,
)
from sixdof_msgs.srv import (
    ApplyPlanningScene,
    GetCartesianPath,
    GetMotionPlan,
    GetPlanningScene,
    GetPositionFK,
    GetPositionIK,
    GetStateValidity,
)

ARM = ["joint1", "joint2", "joint3", "joint4", "joint5", "joint6"]
# The paper's poses of link6 in base_link (rpy fixed axes, degrees).
PAPER_HOME = ((0.366, 0.000, 0.286), (-180.0, 0.688, 179.995))
PAPER_TARGET = ((-0.568, 0.058, 0.396), (-133.151, 35.219, 1.048))
# The elbow folded back so far that the forearm (link4) hits the shoulder (link1); found by sampling the
# node's check_state_validity over joint2/joint3/joint5.
SELF_COLLIDING = {"joint1": 0.0, "joint2": 0.15, "joint3": 1.87, "joint4": 0.0, "joint5": -1.12, "joint6": 0.0}
FIXTURE = "/trajectory_fixture"


def quaternion_from_rpy(roll: float, pitch: float, yaw: float) -> Quaternion:
    """Fixed-axes roll/pitch/yaw (tf2 setRPY) as a quaternion."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return Quaternion(
        x=sr * cp * cy - cr * sp * sy,
        y=cr * sp * cy + sr * cp * sy,
        z=cr * cp * sy - sr * sp * cy,
        w=cr * cp * cy + sr * sp * sy,
    )


def paper_pose(which: tuple) -> Pose:
    xyz, rpy = which
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = xyz
    pose.orientation = quaternion_from_rpy(*[math.radians(a) for a in rpy])
    return pose


def quaternion_angle(a: Quaternion, b: Quaternion) -> float:
    dot = abs(a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w)
    return 2.0 * math.acos(min(1.0, dot))


def named_states() -> dict:
    """{(group, name): {joint: value}} from the SRDF on the parameter server."""
    root = ElementTree.fromstring(rospy.get_param("robot_description_semantic"))
    states = {}
    for state in root.findall("group_state"):
        values = {j.get("name"): float(j.get("value")) for j in state.findall("joint")}
        states[(state.get("group"), state.get("name"))] = values
    return states


def robot_state(values: dict) -> RobotState:
    state = RobotState()
    state.joint_state.name = list(values)
    state.joint_state.position = [values[n] for n in values]
    state.is_diff = True
    return state


def joint_goal(values: dict, tolerance: float = 1e-4) -> Constraints:
    goal = Constraints()
    for name, value in values.items():
        goal.joint_constraints.append(
            JointConstraint(
                joint_name=name, position=value, tolerance_above=tolerance, tolerance_below=tolerance, weight=1
            )
        )
    return goal


def box(name: str, position: tuple, size: tuple, frame: str = "base_link") -> CollisionObject:
    obj = CollisionObject()
    obj.header.frame_id = frame
    obj.id = name
    obj.pose.position.x, obj.pose.position.y, obj.pose.position.z = position
    obj.pose.orientation.w = 1.0
    obj.primitives.append(SolidPrimitive(type=SolidPrimitive.BOX, dimensions=list(size)))
    identity = Pose()
    identity.orientation.w = 1.0
    obj.primitive_poses.append(identity)
    obj.operation = CollisionObject.ADD
    return obj


class MoveGroupTestCase(unittest.TestCase):
    """move_group's services and actions as class attributes (connected once per test class) and call helpers."""

    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("test_move_group")
        services = {
            "fk": ("compute_fk", GetPositionFK),
            "ik": ("compute_ik", GetPositionIK),
            "plan": ("plan_kinematic_path", GetMotionPlan),
            "cartesian": ("compute_cartesian_path", GetCartesianPath),
            "validity": ("check_state_validity", GetStateValidity),
            "get_scene": ("get_planning_scene", GetPlanningScene),
            "apply_scene": ("apply_planning_scene", ApplyPlanningScene),
        }
        for attribute, (name, service_type) in services.items():
            rospy.wait_for_service(name, timeout=60.0)
            setattr(cls, attribute, rospy.ServiceProxy(name, service_type))
        cls.execute = actionlib.SimpleActionClient("execute_trajectory", ExecuteTrajectoryAction)
        cls.move_group = actionlib.SimpleActionClient("move_group", MoveGroupAction)
        assert cls.execute.wait_for_server(rospy.Duration(60.0))
        assert cls.move_group.wait_for_server(rospy.Duration(60.0))
        cls.states = named_states()
        cls.limits = rospy.get_param("robot_description_planning/joint_limits")

    # --- helpers ---------------------------------------------------------------------------------------
    def assert_code(self, code: MoveItErrorCodes, expected: int, *fragments: str) -> None:
        self.assertEqual(code.val, expected, f"got {code.val}: {code.message} (source {code.source})")
        for fragment in fragments:
            self.assertIn(fragment, code.message)
        self.assertTrue(code.source)

    def current(self) -> dict:
        msg = rospy.wait_for_message("joint_states", JointState, timeout=10.0)
        return dict(zip(msg.name, msg.position, strict=True))

    def link_pose(self, values: dict, link: str = "link6") -> Pose:
        response = self.fk(fk_link_names=[link], robot_state=robot_state(values))
        self.assert_code(response.error_code, MoveItErrorCodes.SUCCESS)
        return response.pose_stamped[0].pose

    def plan_request(self, goal: Constraints, group: str = "arm") -> MotionPlanRequest:
        request = MotionPlanRequest()
        request.group_name = group
        request.goal_constraints.append(goal)
        request.allowed_planning_time = 5.0
        request.start_state.is_diff = True
        return request

    def plan_to(self, values: dict, group: str = "arm") -> object:
        response = self.plan(motion_plan_request=self.plan_request(joint_goal(values), group)).motion_plan_response
        self.assert_code(response.error_code, MoveItErrorCodes.SUCCESS)
        return response

    def execute_trajectory(self, trajectory: JointTrajectory) -> MoveItErrorCodes:
        goal = ExecuteTrajectoryGoal()
        goal.trajectory.joint_trajectory = trajectory
        self.execute.send_goal(goal)
        self.assertTrue(self.execute.wait_for_result(rospy.Duration(120.0)))
        return self.execute.get_result().error_code

    def move_group_result(self, goal: MoveGroupGoal) -> object:
        self.move_group.send_goal(goal)
        self.assertTrue(self.move_group.wait_for_result(rospy.Duration(120.0)))
        return self.move_group.get_result()

    def move_to(self, values: dict, group: str = "arm") -> None:
        code = self.execute_trajectory(self.plan_to(values, group).trajectory.joint_trajectory)
        self.assert_code(code, MoveItErrorCodes.SUCCESS)

    def assert_serving(self) -> None:
        self.link_pose(self.states[("arm", "home pose")])

    def ik_request(self, pose: Pose, group: str = "arm") -> PositionIKRequest:
        request = PositionIKRequest(group_name=group)
        request.pose_stamped.header.frame_id = "base_link"
        request.pose_stamped.pose = pose
        return request
