#!/usr/bin/env python3
"""Fuzzing (issue 13 item 6): seeded random and malformed requests to every move_group service, action and
subscribed topic and to the simulator's services and controller actions. Values are drawn per field type from
the message definitions (NaN, inf, huge and tiny numbers, empty, unknown and real names, unknown frames,
unnormalised quaternions, empty, mismatched and huge arrays, negative and non-monotonic times), most of them
starting from a valid request with a few fields broken, so that the checks past the first one are reached too.
Every request must be answered (a service response, an action result) within CALL_TIMEOUT, failures must say why
where the standard puts the words (move_group's error report for a moveit_msgs service or a refused topic message,
the goal status text for move_group's actions and gripper_cmd, error_string for FollowJointTrajectory, the
sixdof_msgs services' own message), and no node may die. The count is printed. ~requests (default in
faults_headless.test) sets how many per target; ~seed the seed (`make fuzz` runs a bigger count)."""

import io
import math
import random
import re
import sys
import tempfile
import time
import unittest

import actionlib
import genpy
import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from control_msgs.msg import (
    FollowJointTrajectoryAction,
    FollowJointTrajectoryGoal,
    GripperCommandAction,
    GripperCommandGoal,
)
from control_msgs.srv import QueryTrajectoryState
from e2e import planning_scene, wait_for_action_server, wait_for_stack
from faults import bounded_call, node_pid
from moveit_msgs.msg import (
    AttachedCollisionObject,
    CollisionObject,
    MotionPlanRequest,
    MoveItErrorCodes,
    PlanningScene,
    PlanningSceneWorld,
)
from sixdof_commander import MoveGroup
from sixdof_commander.error_reports import ErrorReports
from sixdof_commander.goals import joint_constraints
from sixdof_commander.move_group_clients import MOVE_GROUP_ACTIONS, MOVE_GROUP_SERVICES
from std_srvs.srv import Empty

from sixdof_msgs.srv import DeleteObject, GetObjectState, SetObjectState, SpawnObject, StepSimulation
from sixdof_test_support.actions import wait_for_goal

TOPICS = ("planning_scene", "collision_object", "attached_collision_object")
CALL_TIMEOUT = 60.0  # s of wall time: a request unanswered by then hangs (planning alone is bounded by its time)
GOAL_TIMEOUT = 10.0  # s of wall time after which a goal still running is cancelled
NODES = ("/move_group", "/sixdof_sim", "/robot_state_publisher", "/scene_mirror")
FLOATS = (0.0, 1.0, -1.0, 0.5, math.nan, math.inf, -math.inf, 1e308, -1e308, 1e-308, 3.0e9)
INT_RANGES = {
    "int8": (-(2**7), 2**7 - 1), "uint8": (0, 2**8 - 1), "byte": (-(2**7), 2**7 - 1), "char": (0, 2**8 - 1),
    "int16": (-(2**15), 2**15 - 1), "uint16": (0, 2**16 - 1), "int32": (-(2**31), 2**31 - 1),
    "uint32": (0, 2**32 - 1), "int64": (-(2**63), 2**63 - 1), "uint64": (0, 2**64 - 1),
}


class Fuzzer:
    """Random values for message fields; `names` are the real names worth hitting (joints, links, groups, objects,
    frames, named states)."""

    def __init__(self, rng: random.Random, names: list[str]) -> None:
        self.rng = rng
        self.names = names

    def string(self) -> str:
        return self.rng.choice(
            [*self.names, *self.names, "", "unknown", "x" * 5000, "world ", "base_link/../x", "\u00e9\u2603", "a b"]
        )

    def number(self, kind: str):
        r = self.rng
        if kind in ("float32", "float64"):
            value = r.choice([*FLOATS, r.uniform(-4.0, 4.0), r.uniform(-4.0, 4.0)])
            return value if kind == "float64" or not math.isfinite(value) or abs(value) < 3e38 else math.inf
        low, high = INT_RANGES[kind]
        return r.choice([low, high, 0, 1, -1 if low < 0 else 2, r.randint(low, high), r.randint(0, 10)])

    def length(self, huge_ok: bool) -> int:
        r = self.rng.random()
        if r < 0.3:
            return 0
        if r < 0.9:
            return self.rng.randint(1, 8)
        return self.rng.choice([20000, 100000]) if huge_ok else self.rng.randint(9, 40)

    def value(self, kind: str, depth: int = 0):
        if kind.endswith("]"):
            base = kind[: kind.index("[")]
            fixed = kind[kind.index("[") + 1 : -1]
            n = int(fixed) if fixed else self.length(huge_ok=base in INT_RANGES or base.startswith("float"))
            if base in ("uint8", "char"):
                return bytes(self.rng.randint(0, 255) for _ in range(n))
            return [self.value(base, depth + 1) for _ in range(n if fixed or depth < 4 else 0)]
        if kind == "string":
            return self.string()
        if kind == "bool":
            return self.rng.random() < 0.5
        if kind in INT_RANGES or kind.startswith("float"):
            return self.number(kind)
        if kind in ("time", "duration"):
            secs = self.rng.choice([0, 1, 5, 100, 2**31 - 1] + ([-1, -100] if kind == "duration" else []))
            cls = genpy.Duration if kind == "duration" else genpy.Time
            return cls(secs, self.rng.randint(0, 999999999))
        return self.message(genpy.message.get_message_class(kind if "/" in kind else "std_msgs/" + kind), depth + 1)

    def message(self, cls, depth: int = 0):
        msg = cls()
        if depth > 6:
            return msg
        for slot, kind in zip(cls.__slots__, cls._slot_types, strict=True):
            setattr(msg, slot, self.value(kind, depth))
        return msg

    def mutate(self, msg, count: int):
        """A copy of msg with `count` randomly chosen fields (at any depth) replaced by random values."""
        msg = _copy(msg)
        for _ in range(count):
            fields = list(_fields(msg))
            if not fields:
                break
            parent, slot, kind = self.rng.choice(fields)
            setattr(parent, slot, self.value(kind, 1))
        return msg


def _copy(msg):
    buffer = io.BytesIO()
    msg.serialize(buffer)
    return type(msg)().deserialize(buffer.getvalue())


def _fields(msg):
    """(parent, slot, type) of every field, nested messages and array elements included."""
    for slot, kind in zip(msg.__slots__, msg._slot_types, strict=True):
        yield msg, slot, kind
        value = getattr(msg, slot)
        if isinstance(value, genpy.Message):
            yield from _fields(value)
        elif isinstance(value, list):
            for item in value:
                if isinstance(item, genpy.Message):
                    yield from _fields(item)


def explains_failure(response) -> str:
    """'' when a sixdof_msgs service's or FollowJointTrajectory's answer is a success or a failure that says why;
    otherwise what is wrong (move_group's answers are checked by their error reports and status texts)."""
    code = getattr(response, "error_code", None)
    if isinstance(code, int):  # FollowJointTrajectory: 0 is SUCCESSFUL, error_string says why otherwise
        return f"error code {code} without an error_string" if code != 0 and not response.error_string else ""
    if hasattr(response, "error_message"):  # sixdof_msgs services with moveit_msgs' code and words of their own
        if code.val != MoveItErrorCodes.SUCCESS and not response.error_message:
            return f"error code {code.val} without an error_message"
        return ""
    if code is not None:  # move_group's action results: their words are the goal's status text (run_action)
        return ""
    if hasattr(response, "success"):
        message = getattr(response, "status_message", getattr(response, "message", None))
        if not response.success and not message:
            return "success false without a message"
    return ""


def failed_code(response) -> bool:
    """A moveit_msgs service's answer with a MoveItErrorCodes other than SUCCESS."""
    return response.error_code.val != MoveItErrorCodes.SUCCESS


# Per moveit_msgs service: which of its answers are failures whose words move_group must report.
MOVEIT_FAILURES = {
    "plan_kinematic_path": lambda r: failed_code(r.motion_plan_response),
    "compute_cartesian_path": failed_code,
    "compute_fk": failed_code,
    "compute_ik": failed_code,
    "get_planning_scene": lambda _r: False,
    "apply_planning_scene": lambda r: not r.success,
}


class Fuzz(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_fuzz")
        wait_for_stack()
        cls.seed = int(rospy.get_param("~seed", 13))
        cls.requests = int(rospy.get_param("~requests", 100))
        cls.pids = {name: node_pid(name) for name in NODES}
        urdf = rospy.get_param("robot_description")
        srdf = rospy.get_param("robot_description_semantic")
        names = set(re.findall(r'<(?:joint|link)\s+name="([^"]+)"', urdf))
        names |= set(re.findall(r'<(?:group|group_state)\s+name="([^"]+)"', srdf))
        names |= {o.id for o in planning_scene().world.collision_objects} | {"world"}
        cls.names = sorted(names)
        cls.reports = ErrorReports()
        cls.topic_reports = []  # move_group's reports of refused topic messages
        for topic in TOPICS:
            cls.reports.listen(topic, cls.topic_reports.append)

    def dump(self, target: str, i: int, message) -> str:
        """Writes a request that failed to a file (for replaying it) and names it."""
        path = f"{tempfile.gettempdir()}/fuzz_{target.replace('/', '_')}_{self.seed}_{i}"
        with open(path + ".bin", "wb") as out:
            buffer = io.BytesIO()
            message.serialize(buffer)
            out.write(buffer.getvalue())
        with open(path + ".txt", "w") as out:
            out.write(str(message))
        return f"{type(message)._type} in {path}.txt/.bin"

    def check_nodes(self):
        for name, pid in self.pids.items():
            self.assertEqual(node_pid(name), pid, f"{name} died or was restarted")

    def problem(self, name, response) -> str:
        """'' when the answer is a success or says why it failed, where the standard puts the words."""
        if name == "check_state_validity":
            # 'Not valid' is an answer, not a failure; a refused request is reported, and then with words.
            report = self.reports.take(name, timeout=0.2)
            return "an error report without a message" if report is not None and not report.message else ""
        if name not in MOVEIT_FAILURES:
            return explains_failure(response)
        if not MOVEIT_FAILURES[name](response):
            return ""
        report = self.reports.take(name)
        if report is None:
            return "a failure without an error report on move_group/error_reports"
        return "" if report.message else "an error report without a message"

    def run_service(self, name, srv_class, base, rng, count, refusal_is_an_error=False):
        """refusal_is_an_error: the service refuses a request by failing the call (control_msgs/QueryTrajectoryState,
        as joint_trajectory_controller): such an error answer counts as answered."""
        proxy = rospy.ServiceProxy(name, srv_class)
        fuzzer = Fuzzer(rng, self.names)
        request_class = srv_class._request_class
        answered = 0
        for i in range(count):
            if i % 4 == 0:
                request = fuzzer.message(request_class)
            else:
                request = fuzzer.mutate(base, rng.randint(1, 3))
            self.reports.forget(name)
            try:
                response = bounded_call(proxy, request, timeout=CALL_TIMEOUT, what=f"{name} request {i}")
            except rospy.ServiceException as exc:
                if refusal_is_an_error and "responded with an error" in str(exc):
                    answered += 1
                    continue
                self.fail(f"{name} request {i}: no response ({exc}): {self.dump(name, i, request)}")
            except AssertionError as exc:
                self.fail(f"{name} request {i}: no response ({exc}): {self.dump(name, i, request)}")
            problem = self.problem(name, response)
            if problem:
                self.fail(f"{name} request {i}: {problem}: {self.dump(name, i, request)}")
            answered += 1
        return answered

    def run_action(self, name, action_class, goal_class, base, rng, count):
        client = actionlib.SimpleActionClient(name, action_class)
        wait_for_action_server(client, 30.0, name)
        fuzzer = Fuzzer(rng, self.names)
        answered = 0
        for i in range(count):
            goal = fuzzer.message(goal_class) if i % 4 == 0 else fuzzer.mutate(base, rng.randint(1, 3))
            client.send_goal(goal)
            if not wait_for_goal(client, GOAL_TIMEOUT):
                # A goal may legitimately run long (a trajectory starting in a year): cancelled, it must end.
                client.cancel_goal()
                if not wait_for_goal(client, CALL_TIMEOUT):
                    self.fail(f"{name} goal {i} cancelled: not within {CALL_TIMEOUT} s: {self.dump(name, i, goal)}")
            result = client.get_result()
            self.assertIsNotNone(result, f"{name} goal {i}: no result message")
            problem = explains_failure(result)
            # move_group's actions and gripper_cmd say why in the goal's status text (set_aborted(result, text));
            # FollowJointTrajectory in error_string (explains_failure).
            code = getattr(result, "error_code", None)
            if hasattr(code, "val"):
                failed = code.val != MoveItErrorCodes.SUCCESS
            else:
                failed = code is None and client.get_state() in (GoalStatus.ABORTED, GoalStatus.REJECTED)
            if not problem and failed and not client.get_goal_status_text():
                problem = f"a failure (state {client.get_state()}) without a goal status text"
            if problem:
                self.fail(f"{name} goal {i}: {problem}: {self.dump(name, i, goal)}")
            answered += 1
        return answered

    def run_topic(self, name, msg_class, base, rng, count):
        """Publishes random and broken messages on a topic move_group subscribes to; what it refuses it reports,
        with words (the reports are checked after the run, by the caller)."""
        publisher = rospy.Publisher(name, msg_class, queue_size=count)
        deadline = time.monotonic() + 30.0
        while publisher.get_num_connections() == 0 and time.monotonic() < deadline:
            time.sleep(0.05)
        self.assertGreater(publisher.get_num_connections(), 0, f"nobody subscribes to {name}")
        fuzzer = Fuzzer(rng, self.names)
        for i in range(count):
            publisher.publish(fuzzer.message(msg_class) if i % 4 == 0 else fuzzer.mutate(base, rng.randint(1, 3)))
            time.sleep(0.01)
        publisher.unregister()
        return count

    def test_every_request_is_answered_and_no_node_dies(self):
        rng = random.Random(self.seed)
        n = self.requests
        arm = "arm" if "arm" in self.names else self.names[0]
        group = MoveGroup(arm, wait_for_servers=60.0)
        goal = joint_constraints(group.get_named_target_values("home pose"), 1e-4)
        valid_plan = MotionPlanRequest(group_name=arm, goal_constraints=[goal], allowed_planning_time=1.0)
        valid_plan.start_state.is_diff = True
        planner = rospy.ServiceProxy("plan_kinematic_path", MOVE_GROUP_SERVICES["plan_kinematic_path"])
        plan = bounded_call(planner, valid_plan, timeout=CALL_TIMEOUT, what="a valid plan").motion_plan_response
        trajectory = plan.trajectory
        counts = {}
        valid_fields = {  # per move_group service, the fields of a valid request (the others keep their defaults)
            "plan_kinematic_path": {"motion_plan_request": valid_plan},
            "compute_cartesian_path": {"group_name": arm},
            "compute_fk": {"fk_link_names": self.names[:2]},
            "check_state_validity": {"group_name": arm},
        }
        services = [
            (name, srv_class, srv_class._request_class(**valid_fields.get(name, {})))
            for name, srv_class in MOVE_GROUP_SERVICES.items()
        ] + [
            ("sixdof_sim/spawn_object", SpawnObject, SpawnObject._request_class()),
            ("sixdof_sim/get_object_state", GetObjectState, GetObjectState._request_class()),
            ("sixdof_sim/set_object_state", SetObjectState, SetObjectState._request_class()),
            ("sixdof_sim/delete_object", DeleteObject, DeleteObject._request_class()),
            ("sixdof_sim/step", StepSimulation, StepSimulation._request_class()),
        ]
        start = time.monotonic()
        for name, srv_class, base in services:
            counts[name] = self.run_service(name, srv_class, base, rng, n)
            self.check_nodes()
        counts["arm_controller/query_state"] = self.run_service(
            "arm_controller/query_state", QueryTrajectoryState, QueryTrajectoryState._request_class(), rng, n, True
        )
        self.check_nodes()
        valid_goals = {"move_group": {"request": valid_plan}, "execute_trajectory": {"trajectory": trajectory}}
        actions = [
            (name, action_class, goal_class, goal_class(**valid_goals[name]))
            for name, (action_class, goal_class) in MOVE_GROUP_ACTIONS.items()
        ] + [
            ("arm_controller/follow_joint_trajectory", FollowJointTrajectoryAction, FollowJointTrajectoryGoal,
             FollowJointTrajectoryGoal(trajectory=trajectory.joint_trajectory)),
            ("gripper_controller/gripper_cmd", GripperCommandAction, GripperCommandGoal, GripperCommandGoal()),
        ]
        for name, action_class, goal_class, base in actions:
            counts[name] = self.run_action(name, action_class, goal_class, base, rng, max(n // 4, 1))
            self.check_nodes()
        box = CollisionObject(id="fuzz_box", operation=CollisionObject.ADD)
        box.header.frame_id = "world"
        diff = PlanningScene(is_diff=True, world=PlanningSceneWorld(collision_objects=[box]))
        topics = [
            ("planning_scene", PlanningScene, diff),
            ("collision_object", CollisionObject, box),
            ("attached_collision_object", AttachedCollisionObject, AttachedCollisionObject(object=box)),
        ]
        for name, msg_class, base in topics:
            counts[name] = self.run_topic(name, msg_class, base, rng, max(n // 4, 1))
        # move_group still answers, and every refusal it reported said why.
        bounded_call(planning_scene, timeout=CALL_TIMEOUT, what="get_planning_scene after the topics")
        self.check_nodes()
        silent = [r for r in self.topic_reports if not r.message]
        self.assertEqual(silent, [], "refused topic messages reported without words")
        # The simulator's world is put back for whatever runs next on this stack.
        rospy.ServiceProxy("sixdof_sim/reset_world", Empty)()
        total = sum(counts.values())
        print(f"fuzz: {total} requests answered in {time.monotonic() - start:.0f} s (seed {self.seed}): {counts}")
        rospy.loginfo("fuzz: %d requests answered (seed %d): %s", total, self.seed, counts)


if __name__ == "__main__":
    rostest.rosrun("sixdof_tests", "test_fuzz", Fuzz, sys.argv)
