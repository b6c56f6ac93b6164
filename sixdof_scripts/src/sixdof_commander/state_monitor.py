"""MoveGroup's view of the robot's current joint values: the latest positions on joint_states, and the whole
robot's state with mimic joints computed from their sources."""

from __future__ import annotations

import rospy
from moveit_msgs.msg import RobotState

from ._ros import JointStateMonitor
from .robot_model import RobotDescription

# Wall seconds current_state waits for joint_states stamped at or after the call, as MoveIt's getCurrentState(1.0).
CURRENT_STATE_WAIT = 1.0


class StateMonitor:
    """The current joint values of one robot, from a joint_states topic."""

    def __init__(self, topic: str, robot: RobotDescription) -> None:
        """Subscribes to `topic` (sensor_msgs/JointState); `robot` gives the mimic joints."""
        self._joint_states = JointStateMonitor(topic)
        self._robot = robot

    def positions(self, names: list[str]) -> dict[str, float]:
        """The latest positions of `names` (SixdofCommanderError when one does not arrive within 2 s)."""
        return self._joint_states.positions(names)

    def current_state(self) -> RobotState:
        """The current joint positions of the whole robot, as a RobotState: from joint_states stamped at or after
        the call (waited for up to CURRENT_STATE_WAIT wall seconds, then the latest with a warning), as MoveIt's
        getCurrentState: a simulator running faster than real time sends joint_states at most about 100 times a
        wall second, so the latest can be a tenth of a simulated second old, from before a motion that has since
        ended. A mimic joint's value is computed from its source joint, as MoveIt's RobotState does: joint_states
        reports what a physical mimic coupling measures, which may lag its source (a parallel gripper squeezing
        an object)."""
        now = rospy.get_time()
        if not self._joint_states.wait_newer(now, CURRENT_STATE_WAIT):
            rospy.logwarn(
                f"no joint state stamped at or after {now:.3f} within {CURRENT_STATE_WAIT:g} s: using the latest, "
                f"stamped {self._joint_states.stamp:.3f}"
            )
        measured = self._joint_states.joint_state()
        values = dict(zip(measured.name, measured.position, strict=True))
        state = RobotState()
        for name, position in values.items():
            joint = self._robot.joints.get(name)
            if joint is not None and joint.mimic is not None and joint.mimic in values:
                position = joint.mimic_multiplier * values[joint.mimic] + joint.mimic_offset
            state.joint_state.name.append(name)
            state.joint_state.position.append(position)
        return state
