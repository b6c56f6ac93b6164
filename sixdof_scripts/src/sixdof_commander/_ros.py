"""ROS plumbing shared by the API classes: names, parameters, waiting for servers, joint states."""

from __future__ import annotations

import math
import threading
import time

import actionlib
import rospy
from sensor_msgs.msg import JointState

from .exceptions import SixdofCommanderError
from .robot_model import RobotDescription, SemanticDescription, parse_srdf, parse_urdf


def resolve(ns: str, name: str) -> str:
    """name inside namespace ns ('' keeps the node's namespace)."""
    return rospy.names.ns_join(ns, name) if ns else name


def check_timeout(value: float, what: str = "wait_for_servers") -> float:
    """A server-wait timeout in seconds: finite and >= 0 (0 waits forever, as in MoveIt)."""
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value) or value < 0:
        raise SixdofCommanderError(f"{what} must be a finite number of seconds >= 0, got {value!r}")
    return float(value)


def require_node() -> None:
    """The API needs rospy.init_node first (clients, subscribers and the clock need a node)."""
    if not rospy.core.is_initialized():
        raise SixdofCommanderError("rospy.init_node() must be called before using sixdof_commander")


def load_robot_model(ns: str) -> tuple[RobotDescription, SemanticDescription]:
    """URDF and SRDF from the parameter server (robot_description, robot_description_semantic)."""
    texts = []
    for name in ("robot_description", "robot_description_semantic"):
        param = resolve(ns, name)
        try:
            texts.append(rospy.get_param(param))
        except KeyError:
            raise SixdofCommanderError(
                f"parameter '{rospy.resolve_name(param)}' is not set (load the description first)"
            ) from None
        except OSError as err:
            raise SixdofCommanderError(f"cannot reach the ROS master to read '{param}': {err}") from err
    return parse_urdf(texts[0]), parse_srdf(texts[1])


class ActionClient(actionlib.SimpleActionClient):
    """actionlib's SimpleActionClient without its send_goal race (ros/actionlib#206).

    The server's first status or feedback for a new goal can arrive before SimpleActionClient.send_goal has
    stored the new goal handle; it then logs "Got a transition callback on a goal handle that we're not
    tracking" and drops the update (an early feedback message is lost). Here those callbacks wait until
    send_goal has stored the handle. They run on rospy's subscriber threads, and send_goal only publishes,
    so the wait is short and cannot deadlock.
    """

    def __init__(self, ns: str, action_spec: type) -> None:
        super().__init__(ns, action_spec)
        self._sending = threading.Lock()

    def send_goal(self, goal, done_cb=None, active_cb=None, feedback_cb=None) -> None:
        with self._sending:
            super().send_goal(goal, done_cb=done_cb, active_cb=active_cb, feedback_cb=feedback_cb)

    def _handle_transition(self, gh) -> None:
        with self._sending:
            pass
        super()._handle_transition(gh)

    def _handle_feedback(self, gh, feedback) -> None:
        with self._sending:
            pass
        super()._handle_feedback(gh, feedback)


class ServerWaiter:
    """Waits for several services and actions under one wall-clock deadline; names every missing one.

    Wall clock, because with use_sim_time and no simulator running ROS time does not advance (actionlib's
    own timeout would then never expire).
    """

    def __init__(self, timeout: float) -> None:
        self.timeout = check_timeout(timeout)
        self.deadline = None if self.timeout == 0.0 else time.monotonic() + self.timeout
        self.missing: list[str] = []

    def _remaining(self) -> float | None:
        if self.deadline is None:
            return None
        return max(self.deadline - time.monotonic(), 0.001)

    def service(self, name: str) -> None:
        try:
            rospy.wait_for_service(name, timeout=self._remaining())
        except rospy.ROSException:
            self.missing.append(f"service '{rospy.resolve_name(name)}'")

    def action(self, client: ActionClient, name: str) -> None:
        ready = threading.Event()

        def wait() -> None:
            if client.wait_for_server():
                ready.set()

        threading.Thread(target=wait, daemon=True).start()
        if not ready.wait(self._remaining()):
            self.missing.append(f"action '{rospy.resolve_name(name)}'")

    def check(self, who: str) -> None:
        if self.missing:
            raise SixdofCommanderError(
                f"{who}: {', '.join(self.missing)} not available after {self.timeout:g} s "
                "(is the node running, in this namespace?)"
            )


class JointStateMonitor:
    """Keeps the latest position of every joint seen on joint_states."""

    def __init__(self, topic: str) -> None:
        self.topic = topic
        self._positions: dict[str, float] = {}
        self._condition = threading.Condition()
        self._subscriber = rospy.Subscriber(topic, JointState, self._callback, queue_size=10)

    def _callback(self, msg: JointState) -> None:
        with self._condition:
            self._positions.update(zip(msg.name, msg.position, strict=False))
            self._condition.notify_all()

    def _wait_for(self, names: list[str], timeout: float) -> dict[str, float]:
        end = time.monotonic() + timeout
        with self._condition:
            while not self._positions or any(name not in self._positions for name in names):
                remaining = end - time.monotonic()
                if remaining <= 0.0 or rospy.is_shutdown():
                    missing = [n for n in names if n not in self._positions] or ["any joint"]
                    raise SixdofCommanderError(
                        f"no position of {missing} received on '{rospy.resolve_name(self.topic)}' "
                        f"within {timeout:g} s"
                    )
                self._condition.wait(remaining)
            return dict(self._positions)

    def positions(self, names: list[str], timeout: float = 2.0) -> dict[str, float]:
        """Latest positions of `names`; waits up to `timeout` s (wall clock) for them to appear."""
        known = self._wait_for(names, timeout)
        return {name: known[name] for name in names}

    def joint_state(self, timeout: float = 2.0) -> JointState:
        """The latest position of every joint seen, as a JointState."""
        known = self._wait_for([], timeout)
        msg = JointState()
        msg.name = list(known)
        msg.position = list(known.values())
        return msg
