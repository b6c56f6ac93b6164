"""Shared parts of the move_group rostests (test_move_group.py, test_standard_interfaces.py): message builders and a
TestCase base that connects to move_group's services and actions once and wraps the calls the tests repeat."""

import threading
import time
import unittest
import xml.etree.ElementTree as ElementTree

import actionlib
import rospy
from geometry_msgs.msg import Pose, Quaternion
from moveit_msgs.msg import (
    CollisionObject,
    Constraints,
    ExecuteTrajectoryAction,
    ExecuteTrajectoryGoal,
    JointConstraint,
    MotionPlanRequest,
    MoveGroupAction,
    MoveGroupGoal,
    MoveItErrorCodes,
    OrientationConstraint,
    PlanningScene,
    PlanningSceneComponents,
    PositionConstraint,
    PositionIKRequest,
    RobotState,
)
from moveit_msgs.srv import (
    ApplyPlanningScene,
    GetCartesianPath,
    GetMotionPlan,
    GetPlanningScene,
    GetPositionFK,
    GetPositionIK,
    GetStateValidity,
)
from scipy.spatial.transform import Rotation
from sensor_msgs.msg import JointState
from shape_msgs.msg import SolidPrimitive
from std_srvs.srv import Empty
from trajectory_msgs.msg import JointTrajectory

from sixdof_msgs.msg import ErrorReport
from sixdof_test_support.actions import wait_for_goal

ARM = ["joint1", "joint2", "joint3", "joint4", "joint5", "joint6"]
# The elbow folded back so far that the forearm (link4) hits the shoulder (link1); found by sampling the
# node's check_state_validity over joint2/joint3/joint5.
SELF_COLLIDING = {"joint1": 0.0, "joint2": 0.15, "joint3": 1.87, "joint4": 0.0, "joint5": -1.12, "joint6": 0.0}
FIXTURE = "/trajectory_fixture"


def quaternion_angle(a: Quaternion, b: Quaternion) -> float:
    """Angle (rad) of the rotation between two orientations."""
    ra, rb = (Rotation.from_quat([q.x, q.y, q.z, q.w]) for q in (a, b))
    return float((ra.inv() * rb).magnitude())


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


class ErrorReports:
    """move_group's words for this node's failed requests (sixdof_msgs/ErrorReport on move_group/error_reports)."""

    def __init__(self) -> None:
        self._reports: list[ErrorReport] = []
        self._used = 0
        self._condition = threading.Condition()
        self._subscriber = rospy.Subscriber("move_group/error_reports", ErrorReport, self._on_report, queue_size=100)
        deadline = time.monotonic() + 30.0
        while self._subscriber.get_num_connections() == 0 and time.monotonic() < deadline:
            time.sleep(0.01)
        assert self._subscriber.get_num_connections() > 0, "move_group/error_reports never connected"

    def _on_report(self, report: ErrorReport) -> None:
        if report.caller_id == rospy.get_name():
            with self._condition:
                self._reports.append(report)
                self._condition.notify_all()

    def take(self, code: int, timeout: float = 10.0) -> ErrorReport:
        """The oldest unread report with this code (the ones before it are dropped); waits for it to arrive."""
        deadline = time.monotonic() + timeout
        with self._condition:
            while True:
                for index in range(self._used, len(self._reports)):
                    if self._reports[index].error_code.val == code:
                        self._used = index + 1
                        return self._reports[index]
                remaining = deadline - time.monotonic()
                assert remaining > 0, f"no error report with code {code} within {timeout} s"
                self._condition.wait(remaining)


def pose_goal(link: str, pose: Pose, frame: str = "base_link", tolerance: float = 1e-4) -> Constraints:
    """A pose goal as MoveGroupInterface sends it: a sphere around the position, an orientation constraint."""
    goal = Constraints()
    position = PositionConstraint(link_name=link, weight=1.0)
    position.header.frame_id = frame
    position.constraint_region.primitives.append(SolidPrimitive(type=SolidPrimitive.SPHERE, dimensions=[tolerance]))
    position.constraint_region.primitive_poses.append(Pose(position=pose.position, orientation=Quaternion(w=1.0)))
    orientation = OrientationConstraint(link_name=link, orientation=pose.orientation, weight=1.0)
    orientation.header.frame_id = frame
    orientation.absolute_x_axis_tolerance = orientation.absolute_y_axis_tolerance = 1e-3
    orientation.absolute_z_axis_tolerance = 1e-3
    goal.position_constraints.append(position)
    goal.orientation_constraints.append(orientation)
    return goal


class MoveGroupTestCase(unittest.TestCase):
    """move_group's services and actions as class attributes (connected once per test class) and call helpers.

    Every test starts from the same state, whatever ran before it: setUp puts the trajectory fixture's joints back
    at its initial positions (the home pose, fingers open) and empties the planning scene.
    """

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
        cls.reports = ErrorReports()
        rospy.wait_for_service(FIXTURE + "/reset", timeout=60.0)
        cls.reset_fixture = rospy.ServiceProxy(FIXTURE + "/reset", Empty)
        cls.initial = rospy.get_param(FIXTURE + "/initial_positions")

    def setUp(self) -> None:
        self.reset_fixture()
        deadline = time.monotonic() + 10.0
        while any(abs(self.current()[n] - v) > 1e-9 for n, v in self.initial.items()):
            self.assertLess(time.monotonic(), deadline, "joint_states never showed the fixture's initial positions")
        # A full scene (is_diff false) without objects: no world objects, nothing attached.
        self.assertTrue(self.apply_scene(scene=PlanningScene(is_diff=False)).success, "the scene was not emptied")

    # --- helpers ---------------------------------------------------------------------------------------
    def assert_code(self, code: MoveItErrorCodes, expected: int, *fragments: str) -> None:
        """A service's code; a failure's words come from move_group/error_reports and must hold the fragments."""
        if code.val != MoveItErrorCodes.SUCCESS:
            report = self.reports.take(code.val)
            words = f"{report.message} (source {report.source})"
            self.assertTrue(report.source)
        else:
            words = "(no report: success)"
        self.assertEqual(code.val, expected, f"got {code.val}: {words}")
        for fragment in fragments:
            self.assertIn(fragment, words)

    def assert_refused(self, expected: int, *fragments: str) -> ErrorReport:
        """A request whose answer has no code (apply_planning_scene, check_state_validity) was refused so."""
        report = self.reports.take(expected)
        for fragment in fragments:
            self.assertIn(fragment, report.message)
        self.assertTrue(report.source)
        return report

    def assert_result(self, client: actionlib.SimpleActionClient, expected: int, *fragments: str) -> None:
        """An action's result code; its words are the goal's status text."""
        code = client.get_result().error_code
        text = client.get_goal_status_text()
        self.assertEqual(code.val, expected, f"got {code.val}: {text}")
        for fragment in fragments:
            self.assertIn(fragment, text)

    def scene(self) -> object:
        """The whole planning scene (every component)."""
        return self.get_scene(components=PlanningSceneComponents(components=1023)).scene

    def current(self) -> dict:
        msg = rospy.wait_for_message("joint_states", JointState, timeout=10.0)
        return dict(zip(msg.name, msg.position, strict=True))

    def link_pose(self, values: dict, link: str = "link6") -> Pose:
        response = self.fk(fk_link_names=[link], robot_state=robot_state(values))
        self.assert_code(response.error_code, MoveItErrorCodes.SUCCESS)
        return response.pose_stamped[0].pose

    def named_pose(self, name: str) -> Pose:
        """link6's pose (compute_fk) in the arm's named state `name`: a reachable pose goal."""
        return self.link_pose(self.states[("arm", name)])

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

    def execute_trajectory(self, trajectory: JointTrajectory, expected: int, *fragments: str) -> None:
        """Executes through execute_trajectory; the result must be `expected` with the fragments in its text."""
        goal = ExecuteTrajectoryGoal()
        goal.trajectory.joint_trajectory = trajectory
        self.execute.send_goal(goal)
        self.assertTrue(wait_for_goal(self.execute, 120.0), "no execute_trajectory result")
        self.assert_result(self.execute, expected, *fragments)

    def move_group_result(self, goal: MoveGroupGoal) -> object:
        self.move_group.send_goal(goal)
        self.assertTrue(wait_for_goal(self.move_group, 120.0), "no move_group result")
        return self.move_group.get_result()

    def move_to(self, values: dict, group: str = "arm") -> None:
        self.execute_trajectory(self.plan_to(values, group).trajectory.joint_trajectory, MoveItErrorCodes.SUCCESS)

    def assert_serving(self) -> None:
        self.link_pose(self.states[("arm", "home pose")])

    def ik_request(self, pose: Pose, group: str = "arm") -> PositionIKRequest:
        request = PositionIKRequest(group_name=group)
        request.pose_stamped.header.frame_id = "base_link"
        request.pose_stamped.pose = pose
        return request
