"""ROS plumbing shared by the API classes: names, parameters, waiting for servers, joint states."""

from __future__ import annotations

import math
import threading
import time
import xmlrpc.client

import actionlib
import rosgraph
import rospy
from actionlib_msgs.msg import GoalStatusArray
from sensor_msgs.msg import JointState

from sixdof_msgs.srv import GetRobotModel, GetRobotModelRequest

from ._service import SERVICE_TIMEOUT, call_service
from .exceptions import SixdofCommanderError
from .robot_model import RobotDescription, SemanticDescription, model_from_response


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
    # rospy's rosout handler reads this parameter from the master, with no timeout, on the first message it logs
    # (on every message while the parameter is unset: robot_host.launch sets it). Read now, while the master
    # answers, so that an error logged during a network outage (the commander reporting that move_group stopped
    # answering) does not block on the unreachable master.
    try:
        rospy.get_param_cached("/rosout_disable_topics_generation", False)
    except (OSError, rospy.ROSException):
        pass


def load_robot_model(
    ns: str, robot_description: str = "robot_description", timeout: float = 5.0
) -> tuple[RobotDescription, SemanticDescription]:
    """The robot model, from move_group's `get_robot_model` service (query_robot_model).

    The one place the commander gets the robot model: every class gets its groups, joints, limits and named
    states from here. move_group serves the model it loaded from its `robot_description` and
    `robot_description`_semantic parameters; a client cannot choose other parameters (SixdofCommanderError).
    """
    if not isinstance(robot_description, str) or not robot_description:
        raise SixdofCommanderError(f"robot_description must be a parameter name, got {robot_description!r}")
    if robot_description != "robot_description":
        raise SixdofCommanderError(
            f"robot_description '{robot_description}': the robot model comes from move_group's get_robot_model "
            "(the model of move_group's 'robot_description'); other parameters are not supported"
        )
    return query_robot_model(ns, timeout)


def query_robot_model(
    ns: str, timeout: float = 5.0, collision_geometry: bool = False
) -> tuple[RobotDescription, SemanticDescription]:
    """The robot model move_group plans with, from its `get_robot_model` service (sixdof_msgs/GetRobotModel).

    move_group's core RobotModel is the project's only URDF/SRDF reader: groups, joint order, limits (continuous
    joints unbounded), named states and end effectors come from it, as moveit_commander gets them from MoveIt's
    C++ RobotModel; with `collision_geometry`, also every link's collision shapes (RobotDescription.collision).
    Waits up to `timeout` wall-clock seconds (0: forever) for the service; SixdofCommanderError names it when
    move_group is not there, and move_group's error when it cannot describe the geometry.
    """
    name = resolve(ns, "get_robot_model")
    waiter = ServerWaiter(check_timeout(timeout, "timeout"))
    waiter.service(name)
    waiter.check("robot model")
    try:
        request = GetRobotModelRequest(include_collision_geometry=bool(collision_geometry))
        response = call_service(rospy.ServiceProxy(name, GetRobotModel), request, SERVICE_TIMEOUT)
    except (rospy.ServiceException, rospy.ROSException) as err:
        raise SixdofCommanderError(f"robot model: call to '{rospy.resolve_name(name)}' failed: {err}") from err
    if response.error_code.val != response.error_code.SUCCESS:
        raise SixdofCommanderError(f"robot model: '{rospy.resolve_name(name)}' failed: {response.error_message}")
    return model_from_response(response, collision=bool(collision_geometry))


def server_connected(client: actionlib.SimpleActionClient) -> bool:
    """True while the action server's status and result topics are connected to this client.

    When the server's node dies, its TCP connections close and rospy drops them at once, whatever the ROS
    clock does (with use_sim_time and a stopped simulator, time-based checks would never fire).
    """
    impl = client.action_client
    return impl.status_sub.get_num_connections() > 0 and impl.result_sub.get_num_connections() > 0


# How long (wall clock) an action server may stay disconnected before a waiting call gives up on it: long enough
# to ride out a reconnect, short enough that a dead node is noticed within a few seconds.
SERVER_LOST_AFTER = 2.0
# A network outage closes no connection: the server's status messages (actionlib publishes them at 5 Hz) just
# stop. After this long without one (wall clock) the server's node is asked for its pid; one that does not
# answer within PING_TIMEOUT is unreachable. A node that answers is waited for: with a stopped /clock (a paused
# or dead simulator) its status stops too, and move_group's execution watchdog ends the motion instead.
SERVER_SILENT_AFTER = 2.0
PING_TIMEOUT = 1.0


class _TimeoutTransport(xmlrpc.client.Transport):
    def __init__(self, timeout: float) -> None:
        super().__init__()
        self._timeout = timeout

    def make_connection(self, host):  # noqa: ANN001, ANN201 (xmlrpc.client's signature)
        connection = super().make_connection(host)
        connection.timeout = self._timeout
        return connection


def node_answers(uri: str, timeout: float = PING_TIMEOUT) -> bool:
    """True if the node at XML-RPC uri answers getPid within timeout (wall clock)."""
    try:
        xmlrpc.client.ServerProxy(uri, transport=_TimeoutTransport(timeout)).getPid(rospy.get_name())
        return True
    except (OSError, xmlrpc.client.Error):
        return False


def wait_for_done(client: actionlib.SimpleActionClient, done: threading.Event, timeout: float = 0.0) -> str:
    """Waits until `done` is set (the goal finished). '' then; otherwise why it gave up: the server was lost
    (disconnected for SERVER_LOST_AFTER s), `timeout` wall-clock seconds passed (0: no limit), or ROS shut down."""
    start = time.monotonic()
    lost_since = None
    last_ping = 0.0
    while not done.wait(0.05):
        now = time.monotonic()
        if rospy.is_shutdown():
            return "ROS shut down while waiting for the result"
        if server_connected(client):
            lost_since = None
        elif lost_since is None:
            lost_since = now
        elif now - lost_since >= SERVER_LOST_AFTER:
            return f"the action server was lost (disconnected for {SERVER_LOST_AFTER:g} s: did its node die?)"
        # Still connected but silent: a network outage (a dead node's connections close, handled above).
        silent = client.silent_for(now, start) if isinstance(client, ActionClient) and lost_since is None else 0.0
        if silent >= SERVER_SILENT_AFTER and now - last_ping >= PING_TIMEOUT:
            last_ping = now
            if client.server_uri and not node_answers(client.server_uri):
                return (
                    f"the action server stopped answering (no status for {silent:.1f} s and its node did not "
                    f"answer within {PING_TIMEOUT:g} s: is the network to it down?)"
                )
        if timeout and now - start >= timeout:
            return f"no result within {timeout:g} s"
    return ""


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
        # The server's heartbeat: when its last status arrived, and its node's XML-RPC URI (looked up once, while
        # the master is reachable) to ask whether it is still there when the status stops.
        self._last_status: float | None = None
        self.server_uri = ""
        self._heartbeat = rospy.Subscriber(
            rospy.remap_name(ns) + "/status", GoalStatusArray, self._on_status, queue_size=1
        )

    def _on_status(self, msg: GoalStatusArray) -> None:
        self._last_status = time.monotonic()
        if not self.server_uri:
            caller = (getattr(msg, "_connection_header", None) or {}).get("callerid", "")
            try:
                self.server_uri = rosgraph.Master(rospy.get_name()).lookupNode(caller) if caller else ""
            except (OSError, rosgraph.MasterException):
                pass

    def silent_for(self, now: float, since: float) -> float:
        """Wall seconds without a status message from the server, counted from `since` (the start of the wait) at
        the earliest: a call gets its own grace after an outage (0 before the first status)."""
        return now - max(self._last_status, since) if self._last_status is not None else 0.0

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

    def subscriber(self, publisher: rospy.Publisher) -> None:
        """Waits until the publisher's topic has a subscriber (a message published earlier would be lost)."""
        while publisher.get_num_connections() == 0:
            remaining = self._remaining()
            if (remaining is not None and remaining <= 0.001) or rospy.is_shutdown():
                self.missing.append(f"subscriber of topic '{publisher.resolved_name}'")
                return
            time.sleep(0.01)

    def check(self, who: str) -> None:
        if self.missing:
            raise SixdofCommanderError(
                f"{who}: {', '.join(self.missing)} not available after {self.timeout:g} s "
                "(is the node running, in this namespace?)"
            )


class JointStateMonitor:
    """Keeps the latest position of every joint seen on joint_states, and the largest stamp seen (a message's arrival
    time when unstamped). When ROS time goes backwards (a restarted simulator, a replayed bag starting over), the
    stamps seen before are of another timeline: they are forgotten, as MoveIt's state monitor does on a jump back."""

    def __init__(self, topic: str) -> None:
        self.topic = topic
        self._positions: dict[str, float] = {}
        self._stamp = -math.inf
        self._clock = -math.inf  # the latest ROS time seen, to notice a jump back
        self._condition = threading.Condition()
        self._subscriber = rospy.Subscriber(topic, JointState, self._callback, queue_size=10)

    def _note_time(self, now: float) -> None:
        """With the condition held: forget the stamps when ROS time `now` is earlier than the latest seen."""
        if now < self._clock:
            rospy.logwarn(f"ROS time moved back from {self._clock:.3f} to {now:.3f}: joint_states stamps reset")
            self._stamp = -math.inf
        self._clock = now

    def _callback(self, msg: JointState) -> None:
        now = rospy.get_time()
        stamp = msg.header.stamp.to_sec() if not msg.header.stamp.is_zero() else now
        with self._condition:
            self._note_time(now)
            self._positions.update(zip(msg.name, msg.position, strict=False))
            self._stamp = max(self._stamp, stamp)
            self._condition.notify_all()

    def wait_newer(self, stamp: float, timeout: float) -> bool:
        """Waits up to `timeout` s (wall clock) for a message stamped at or after `stamp` (ROS time, s) since ROS time
        last went backwards; whether one arrived."""
        end = time.monotonic() + timeout
        with self._condition:
            self._note_time(rospy.get_time())
            while self._stamp < stamp:
                remaining = end - time.monotonic()
                if remaining <= 0.0 or rospy.is_shutdown():
                    return False
                self._condition.wait(remaining)
            return True

    @property
    def stamp(self) -> float:
        """The largest stamp seen since ROS time last went backwards (ROS time, s); -inf before the first."""
        with self._condition:
            return self._stamp

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
