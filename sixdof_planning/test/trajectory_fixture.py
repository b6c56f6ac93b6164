#!/usr/bin/env python3
"""Test fixture standing in for the simulator's controllers: publishes joint_states and serves
arm_controller/follow_joint_trajectory and gripper_controller/follow_joint_trajectory by playing each goal's
trajectory onto the joint state (linear interpolation in time).

Knobs (private parameters, read per goal, set by the tests):
  ~initial_positions  {joint: value} at start-up and after ~reset (others 0)
  ~slowdown           plays trajectories this many times slower (1.0); > 1.2 makes move_group time out
  ~fail_with          when non-empty, aborts every goal with GOAL_TOLERANCE_VIOLATED and this error string
  ~state_lag          joint_states show the joints as they were this many seconds earlier (0.0; at most
                      HISTORY s), stamped when sent: a planner whose clock lags behind the robot's sees such states
Service ~reset (std_srvs/Empty): every joint back at ~initial_positions, the known start each test begins from.
"""

import bisect
import collections
import threading

import actionlib
import rospy
from control_msgs.msg import FollowJointTrajectoryAction, FollowJointTrajectoryResult
from sensor_msgs.msg import JointState
from std_srvs.srv import Empty, EmptyResponse

JOINTS = ["joint1", "joint2", "joint3", "joint4", "joint5", "joint6", "finger1_joint", "finger2_joint"]
CONTROLLERS = {
    "arm_controller": JOINTS[:6],
    "gripper_controller": JOINTS[6:],
}
RATE_HZ = 100.0
HISTORY = 2.0  # s of positions kept for ~state_lag


class TrajectoryFixture:
    def __init__(self) -> None:
        initial = rospy.get_param("~initial_positions", {})
        self._initial = {name: float(initial.get(name, 0.0)) for name in JOINTS}
        self._lock = threading.Lock()
        self._positions = dict(self._initial)
        self._lag = 0.0
        self._history: collections.deque = collections.deque()  # (time, positions), the last HISTORY s
        self._publisher = rospy.Publisher("joint_states", JointState, queue_size=10)
        self._reset = rospy.Service("~reset", Empty, self._on_reset)
        self._servers = []
        for controller, joints in CONTROLLERS.items():
            server = actionlib.SimpleActionServer(
                f"{controller}/follow_joint_trajectory",
                FollowJointTrajectoryAction,
                execute_cb=lambda goal, c=controller, j=joints: self._execute(c, j, goal),
                auto_start=False,
            )
            server.start()
            self._servers.append((controller, server))

    def _on_reset(self, _request: object) -> EmptyResponse:
        with self._lock:
            self._positions = dict(self._initial)
            self._lag = self._state_lag()
        return EmptyResponse()

    @staticmethod
    def _state_lag() -> float:
        lag = float(rospy.get_param("~state_lag", 0.0))
        if not 0.0 <= lag <= HISTORY:
            raise ValueError(f"~state_lag must be in [0, {HISTORY}], got {lag}")
        return lag

    def _server(self, controller: str) -> actionlib.SimpleActionServer:
        return dict(self._servers)[controller]

    def run(self) -> None:
        """Publishes joint_states until shutdown."""
        rate = rospy.Rate(RATE_HZ)
        while not rospy.is_shutdown():
            now = rospy.Time.now()
            with self._lock:
                self._history.append((now.to_sec(), dict(self._positions)))
                while self._history[0][0] < now.to_sec() - HISTORY:
                    self._history.popleft()
                shown = self._history[0][1]  # the latest positions at least ~state_lag old
                for t, positions in self._history:
                    if t > now.to_sec() - self._lag:
                        break
                    shown = positions
                msg = JointState(name=list(JOINTS), position=[shown[n] for n in JOINTS])
            msg.header.stamp = now
            self._publisher.publish(msg)
            try:
                rate.sleep()
            except rospy.ROSInterruptException:
                return

    def _execute(self, controller: str, joints: list, goal: object) -> None:
        server = self._server(controller)
        trajectory = goal.trajectory
        result = FollowJointTrajectoryResult()
        unknown = [n for n in trajectory.joint_names if n not in joints]
        if unknown or not trajectory.points:
            result.error_code = FollowJointTrajectoryResult.INVALID_JOINTS
            result.error_string = f"{controller}: unknown joints {unknown} or no points"
            server.set_aborted(result, result.error_string)
            return
        fail_with = rospy.get_param("~fail_with", "")
        lag = self._state_lag()
        with self._lock:
            self._lag = lag
        slowdown = float(rospy.get_param("~slowdown", 1.0))
        times = [p.time_from_start.to_sec() * slowdown for p in trajectory.points]
        start = rospy.Time.now()
        rate = rospy.Rate(RATE_HZ)
        while not rospy.is_shutdown():
            if server.is_preempt_requested():
                server.set_preempted(result, "preempted")
                return
            t = (rospy.Time.now() - start).to_sec()
            self._apply(trajectory, times, t)
            if fail_with and t > times[-1] / 2.0:
                result.error_code = FollowJointTrajectoryResult.GOAL_TOLERANCE_VIOLATED
                result.error_string = fail_with
                server.set_aborted(result, fail_with)
                return
            if t >= times[-1]:
                break
            rate.sleep()
        result.error_code = FollowJointTrajectoryResult.SUCCESSFUL
        server.set_succeeded(result)

    def _apply(self, trajectory: object, times: list, t: float) -> None:
        points = trajectory.points
        i = bisect.bisect_right(times, t)
        if i == 0:
            values = points[0].positions
        elif i >= len(points):
            values = points[-1].positions
        else:
            a = (t - times[i - 1]) / (times[i] - times[i - 1])
            values = [p0 + a * (p1 - p0) for p0, p1 in zip(points[i - 1].positions, points[i].positions, strict=True)]
        with self._lock:
            for name, value in zip(trajectory.joint_names, values, strict=True):
                self._positions[name] = value


def main() -> None:
    rospy.init_node("trajectory_fixture")
    TrajectoryFixture().run()


if __name__ == "__main__":
    main()
