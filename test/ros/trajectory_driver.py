#!/usr/bin/env python3
"""A minimal robot driver that speaks only the standard types, as a vendor's driver or a ros_control
joint_trajectory_controller would: control_msgs/FollowJointTrajectory on `<controller>/follow_joint_trajectory`
and sensor_msgs/JointState on `joint_states` (wall clock, 100 Hz). No simulator: the joints follow the commanded
trajectory exactly, interpolated linearly between its points (external_driver.py drives it through move_group).

    trajectory_driver.py CONTROLLER JOINT [JOINT ...]      (every joint starts at 0)
"""

import sys
import threading

import actionlib
import rospy
from control_msgs.msg import FollowJointTrajectoryAction, FollowJointTrajectoryFeedback, FollowJointTrajectoryResult
from sensor_msgs.msg import JointState

PERIOD = 0.01  # s between joint_states messages and trajectory steps


def interpolate(points: list[tuple[float, list[float]]], t: float) -> list[float]:
    """Positions at time t of a trajectory given as (time, positions) pairs in time order."""
    if t <= points[0][0]:
        return list(points[0][1])
    for (t0, q0), (t1, q1) in zip(points, points[1:], strict=False):
        if t <= t1:
            s = (t - t0) / (t1 - t0) if t1 > t0 else 1.0
            return [a + (b - a) * s for a, b in zip(q0, q1, strict=True)]
    return list(points[-1][1])


class Driver:
    def __init__(self, controller: str, joints: list[str]) -> None:
        self.joints = joints
        self.positions = dict.fromkeys(joints, 0.0)
        self.lock = threading.Lock()
        self.publisher = rospy.Publisher("joint_states", JointState, queue_size=10)
        self.server = actionlib.SimpleActionServer(
            f"{controller}/follow_joint_trajectory", FollowJointTrajectoryAction, self.execute, auto_start=False
        )
        self.server.start()

    def publish(self) -> None:
        with self.lock:
            state = JointState(name=self.joints, position=[self.positions[j] for j in self.joints])
        state.header.stamp = rospy.Time.now()
        self.publisher.publish(state)

    def refuse(self, code: int, why: str) -> None:
        self.server.set_aborted(FollowJointTrajectoryResult(error_code=code, error_string=why), why)

    def execute(self, goal) -> None:
        trajectory = goal.trajectory
        names = list(trajectory.joint_names)
        unknown = sorted(set(names) - set(self.joints))
        if unknown or not names:
            self.refuse(FollowJointTrajectoryResult.INVALID_JOINTS, f"joints {unknown or names} are not this driver's")
            return
        if not trajectory.points or any(len(p.positions) != len(names) for p in trajectory.points):
            self.refuse(FollowJointTrajectoryResult.INVALID_GOAL, "points missing or of the wrong length")
            return
        with self.lock:
            start = [self.positions[n] for n in names]
        points = [(0.0, start)] + [(p.time_from_start.to_sec(), list(p.positions)) for p in trajectory.points]
        began = trajectory.header.stamp if not trajectory.header.stamp.is_zero() else rospy.Time.now()
        end = points[-1][0]
        while not rospy.is_shutdown():
            if self.server.is_preempt_requested():
                self.server.set_preempted(FollowJointTrajectoryResult(), "canceled")
                return
            t = (rospy.Time.now() - began).to_sec()
            desired = interpolate(points, t)
            with self.lock:
                self.positions.update(zip(names, desired, strict=True))
            feedback = FollowJointTrajectoryFeedback(joint_names=names)
            feedback.desired.positions = feedback.actual.positions = desired
            self.server.publish_feedback(feedback)
            if t >= end:
                break
            rospy.sleep(PERIOD)
        self.server.set_succeeded(FollowJointTrajectoryResult(error_code=FollowJointTrajectoryResult.SUCCESSFUL))


def main() -> int:
    args = rospy.myargv(sys.argv)[1:]
    if len(args) < 2:
        print("usage: " + __doc__.strip().splitlines()[-1].strip(), file=sys.stderr)
        return 2
    rospy.init_node("trajectory_driver")
    driver = Driver(args[0], args[1:])
    try:
        while not rospy.is_shutdown():
            driver.publish()
            rospy.sleep(PERIOD)
    except rospy.ROSInterruptException:
        pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
