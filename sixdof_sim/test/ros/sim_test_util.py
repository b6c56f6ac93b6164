"""Helpers shared by the sixdof_sim rostests: trajectory goals, state listeners, a top-down arm IK."""

import math
import threading
import time
import xml.etree.ElementTree as ET

import rospy
from control_msgs.msg import FollowJointTrajectoryGoal
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectoryPoint

from sixdof_msgs.msg import GraspEvent

ARM_JOINTS = [f"joint{i}" for i in range(1, 7)]
FINGER_JOINTS = ["finger1_joint", "finger2_joint"]


def wait_for_servers(clients: tuple, timeout: float) -> None:
    """Until each action client's server is up (an assertion fails after `timeout` wall-clock seconds for one: a
    free-running simulator's clock would spend a simulated timeout in a fraction of that)."""
    for client in clients:
        deadline = time.monotonic() + timeout
        while not client.wait_for_server(rospy.Duration(0.05)):
            assert time.monotonic() < deadline and not rospy.is_shutdown(), "action server missing"


def sim_service(name: str, service_type: type, timeout: float) -> rospy.ServiceProxy:
    """A proxy of the simulator's service sixdof_sim/<name>, once it is up."""
    rospy.wait_for_service("sixdof_sim/" + name, timeout)
    return rospy.ServiceProxy("sixdof_sim/" + name, service_type)


def trajectory_goal(
    joints: list[str], points: list[tuple[list[float], float]], with_velocities: bool = True
) -> FollowJointTrajectoryGoal:
    """A goal through (positions, time_from_start) points, at rest at each point when with_velocities."""
    goal = FollowJointTrajectoryGoal()
    goal.trajectory.joint_names = list(joints)
    for positions, t in points:
        point = JointTrajectoryPoint(positions=list(positions), time_from_start=rospy.Duration(t))
        if with_velocities:
            point.velocities = [0.0] * len(positions)
        goal.trajectory.points.append(point)
    return goal


def wait_until(condition, timeout: float) -> bool:
    """Whether condition() holds within `timeout` simulated seconds (polled every 10 ms of wall time)."""
    deadline = rospy.Time.now() + rospy.Duration(timeout)
    while not rospy.is_shutdown():
        if condition():
            return True
        if rospy.Time.now() > deadline:
            return False
        rospy.rostime.wallsleep(0.01)
    return False


def at_rest(state, speed: float = 1e-3) -> bool:
    """Whether a get_object_state answer's linear (m/s) and angular (rad/s) speeds are below `speed`."""
    v, w = state.twist.linear, state.twist.angular
    return max(math.hypot(v.x, v.y, v.z), math.hypot(w.x, w.y, w.z)) < speed


class JointStateListener:
    """Keeps the latest joint_states message. A free-running simulator publishes far faster than rospy
    delivers, so the latest message may lag: checks wait for a condition instead of reading once."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self._msg = None
        self._sub = rospy.Subscriber("joint_states", JointState, self._callback, queue_size=1)

    def _callback(self, msg: JointState) -> None:
        with self._lock:
            self._msg = msg

    def positions(self, joints: list[str]) -> list[float]:
        return self.reading(joints)[1]

    def reading(self, joints: list[str]) -> tuple[rospy.Time, list[float]]:
        """The latest message's stamp and the joints' positions in it."""
        deadline = rospy.Time.now() + rospy.Duration(30.0)
        while self._msg is None and rospy.Time.now() < deadline and not rospy.is_shutdown():
            rospy.rostime.wallsleep(0.01)
        with self._lock:
            msg = self._msg
        by_name = dict(zip(msg.name, msg.position, strict=True))
        return msg.header.stamp, [by_name[j] for j in joints]

    def wait_near(self, joints: list[str], target: list[float], tolerance: float, timeout: float = 10.0) -> bool:
        """Whether all joints come within tolerance of target within timeout simulated seconds."""
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        while not rospy.is_shutdown():
            if all(abs(a - t) < tolerance for a, t in zip(self.positions(joints), target, strict=True)):
                return True
            if rospy.Time.now() > deadline:
                return False
            rospy.rostime.wallsleep(0.01)
        return False

    def settled(self, joints: list[str], still: float = 1e-4, timeout: float = 10.0) -> list[float]:
        """Positions once two messages stamped at least 0.2 simulated seconds apart differ by less than `still`
        (messages, not reads: a free-running simulator publishes at most about publish_rate messages per wall-clock
        second, so two reads 0.2 simulated seconds apart may see the same message)."""
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        stamp, previous = self.reading(joints)
        while rospy.Time.now() < deadline and not rospy.is_shutdown():
            rospy.rostime.wallsleep(0.005)
            current_stamp, current = self.reading(joints)
            if (current_stamp - stamp).to_sec() < 0.2:
                continue
            if all(abs(a - b) < still for a, b in zip(current, previous, strict=True)):
                return current
            stamp, previous = current_stamp, current
        raise AssertionError(f"joints {joints} did not come to rest")


class GraspEventListener:
    """Records grasp_events."""

    def __init__(self) -> None:
        self.events: list[GraspEvent] = []
        self._sub = rospy.Subscriber("grasp_events", GraspEvent, self.events.append, queue_size=100)

    def wait_for(self, event: int, obj: str, timeout: float) -> bool:
        deadline = rospy.Time.now() + rospy.Duration(timeout)
        while rospy.Time.now() < deadline and not rospy.is_shutdown():
            if any(e.event == event and e.object == obj for e in self.events):
                return True
            rospy.rostime.wallsleep(0.01)
        return False


def arm_geometry(urdf_xml: str) -> dict[str, float]:
    """Lengths of the arm's planar chain, read from the URDF's joint origins (docs/design.md layout)."""
    origins = {}
    for joint in ET.fromstring(urdf_xml).findall("joint"):
        origin = joint.find("origin")
        xyz = [float(v) for v in origin.get("xyz").split()] if origin is not None else [0.0, 0.0, 0.0]
        origins[joint.get("name")] = xyz
    return {
        "shoulder_height": origins["joint1"][2] + origins["joint2"][2],
        "upper_arm": origins["joint3"][2],
        "forearm": origins["joint4"][0] + origins["joint5"][0],
        "flange": origins["joint6"][0],
        "tcp": origins["tcp_joint"][2],
    }


def top_down_ik(geometry: dict[str, float], x: float, y: float, z: float) -> list[float]:
    """Arm joints putting the tcp at (x, y, z) with the tool axis pointing down (elbow up, joint4 = joint6 = 0)."""
    q1 = math.atan2(y, x)
    r = math.hypot(x, y)
    wrist_z = z + geometry["flange"] + geometry["tcp"]
    dz = wrist_z - geometry["shoulder_height"]
    a2, d4 = geometry["upper_arm"], geometry["forearm"]
    cos_bend = (r * r + dz * dz - a2 * a2 - d4 * d4) / (2.0 * a2 * d4)
    if abs(cos_bend) > 1.0:
        raise ValueError(f"({x}, {y}, {z}) is out of reach")
    bend = -math.acos(cos_bend)  # forearm angle minus upper-arm angle (from the horizontal)
    upper = math.atan2(dz, r) - math.atan2(d4 * math.sin(bend), a2 + d4 * math.cos(bend))
    fore = upper + bend
    q2 = math.pi / 2.0 - upper
    q3 = -fore - q2
    q5 = math.pi / 2.0 + fore
    return [q1, q2, q3, 0.0, q5, 0.0]
