#!/usr/bin/env python3
"""rostest of the move_group node against the real robot description and a FollowJointTrajectory fixture
(trajectory_fixture.py) that plays trajectories onto joint_states."""

import itertools
import math
import sys
import time

import rospy
import rostest
from actionlib_msgs.msg import GoalStatus
from geometry_msgs.msg import Pose, Quaternion
from move_group_test_helpers import (
    ARM,
    FIXTURE,
    SELF_COLLIDING,
    MoveGroupTestCase,
    box,
    joint_goal,
    pose_goal,
    quaternion_angle,
    robot_state,
)
from moveit_msgs.msg import (
    AttachedCollisionObject,
    CollisionObject,
    Constraints,
    DisplayTrajectory,
    ExecuteTrajectoryGoal,
    MotionPlanRequest,
    MoveGroupGoal,
    MoveItErrorCodes,
    PlanningScene,
    RobotState,
)
from moveit_msgs.srv import GetCartesianPathRequest
from scipy.spatial.transform import Rotation
from shape_msgs.msg import Plane
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint
from visualization_msgs.msg import Marker, MarkerArray

from sixdof_test_support.actions import wait_for_goal

PKG = "sixdof_planning"


class MoveGroupTest(MoveGroupTestCase):
    # --- kinematics ----------------------------------------------------------------------------------
    def test_01_fk_at_zero_matches_the_design(self) -> None:
        # docs/design.md: at zero the wrist centre is 0.30 ahead of the shoulder (0.30 up, + the 0.30 upper arm),
        # link6's flange 0.08 further along +x, its z axis along +x and its x axis down.
        pose = self.link_pose(dict.fromkeys(ARM, 0.0))
        self.assertAlmostEqual(pose.position.x, 0.38, delta=1e-6)
        self.assertAlmostEqual(pose.position.y, 0.0, delta=1e-6)
        self.assertAlmostEqual(pose.position.z, 0.60, delta=1e-6)
        x, y, z, w = Rotation.from_euler("xyz", (0.0, math.pi / 2, 0.0)).as_quat()
        self.assertLess(quaternion_angle(pose.orientation, Quaternion(x=x, y=y, z=z, w=w)), 1e-4)

    def test_02_ik_of_named_state_poses_round_trips(self) -> None:
        for name in ("home pose", "place pose"):
            request = self.ik_request(self.named_pose(name))
            request.avoid_collisions = True
            response = self.ik(ik_request=request)
            self.assert_code(response.error_code, MoveItErrorCodes.SUCCESS)
            values = dict(zip(response.solution.joint_state.name, response.solution.joint_state.position, strict=True))
            pose = self.link_pose({n: values[n] for n in ARM})
            target = request.pose_stamped.pose
            self.assertAlmostEqual(pose.position.x, target.position.x, delta=1e-4)
            self.assertAlmostEqual(pose.position.y, target.position.y, delta=1e-4)
            self.assertAlmostEqual(pose.position.z, target.position.z, delta=1e-4)
            self.assertLess(quaternion_angle(pose.orientation, target.orientation), 1e-3)

    # --- planning ------------------------------------------------------------------------------------
    def test_10_plan_to_named_state_starts_at_current_state(self) -> None:
        goal_values = self.states[("arm", "pick pose")]
        current = self.current()
        response = self.plan_to(goal_values)
        trajectory = response.trajectory.joint_trajectory
        self.assertEqual(trajectory.joint_names, ARM)
        self.assertGreater(len(trajectory.points), 2)
        for name, value in zip(trajectory.joint_names, trajectory.points[0].positions, strict=True):
            self.assertAlmostEqual(value, current[name], delta=1e-6)
        for name, value in zip(trajectory.joint_names, trajectory.points[-1].positions, strict=True):
            self.assertAlmostEqual(value, goal_values[name], delta=1e-3)
        times = [p.time_from_start.to_sec() for p in trajectory.points]
        self.assertEqual(times[0], 0.0)
        self.assertTrue(all(b > a for a, b in itertools.pairwise(times)), "times must increase strictly")
        # Points every ~trajectory_sample_period (the last one at the end, sooner).
        period = rospy.get_param("/move_group/trajectory_sample_period", 0.1)
        for a, b in itertools.pairwise(times[:-1]):
            self.assertAlmostEqual(b - a, period, delta=1e-6)
        self.assertLessEqual(times[-1] - times[-2], period + 1e-6)
        for point in trajectory.points:
            self.assertEqual(len(point.velocities), len(ARM))
            for name, velocity in zip(trajectory.joint_names, point.velocities, strict=True):
                self.assertLessEqual(abs(velocity), self.limits[name]["max_velocity"] * 1.01)
        start = dict(
            zip(response.trajectory_start.joint_state.name, response.trajectory_start.joint_state.position, strict=True)
        )
        for name in ARM:
            self.assertAlmostEqual(start[name], current[name], delta=1e-6)

    def test_11_plan_to_a_pose(self) -> None:
        target = self.named_pose("after place pose")
        response = self.plan(motion_plan_request=self.plan_request(pose_goal("link6", target))).motion_plan_response
        self.assert_code(response.error_code, MoveItErrorCodes.SUCCESS)
        last = dict(zip(ARM, response.trajectory.joint_trajectory.points[-1].positions, strict=True))
        pose = self.link_pose(last)
        self.assertAlmostEqual(pose.position.x, target.position.x, delta=1e-3)
        self.assertAlmostEqual(pose.position.z, target.position.z, delta=1e-3)

    def test_12_cartesian_path_fraction(self) -> None:
        start = self.link_pose({n: v for n, v in self.current().items() if n in ARM})
        down = Pose(position=start.position, orientation=start.orientation)
        down.position.z -= 0.05
        request = GetCartesianPathRequest(group_name="arm", waypoints=[down], max_step=0.005, avoid_collisions=True)
        request.header.frame_id = "base_link"
        request.start_state.is_diff = True
        response = self.cartesian(request)
        self.assert_code(response.error_code, MoveItErrorCodes.SUCCESS)
        self.assertAlmostEqual(response.fraction, 1.0, delta=1e-9)
        self.assertGreaterEqual(len(response.solution.joint_trajectory.points), 10)
        end = self.link_pose(dict(zip(ARM, response.solution.joint_trajectory.points[-1].positions, strict=True)))
        self.assertAlmostEqual(end.position.z, down.position.z, delta=1e-4)
        # Half of the path leads out of reach: the fraction stops short of 1 and the call still succeeds.
        far = Pose(orientation=start.orientation)
        far.position.x, far.position.y, far.position.z = 2.0, 0.0, start.position.z
        request.waypoints = [down, far]
        response = self.cartesian(request)
        self.assert_code(response.error_code, MoveItErrorCodes.SUCCESS)
        self.assertGreaterEqual(response.fraction, 0.5)
        self.assertLess(response.fraction, 1.0)

    def test_13_check_state_validity_detects_self_collision(self) -> None:
        response = self.validity(robot_state=robot_state(SELF_COLLIDING), group_name="arm")
        self.assertFalse(response.valid)
        self.assertTrue(response.contacts)
        robot_links = {"base_link", "link1", "link2", "link3", "link4", "link5", "link6", "palm", "finger1", "finger2"}
        contact = response.contacts[0]
        self.assertIn(contact.contact_body_1, robot_links)
        self.assertIn(contact.contact_body_2, robot_links)
        response = self.validity(robot_state=robot_state(self.states[("arm", "home pose")]), group_name="arm")
        self.assertTrue(response.valid, response.contacts)

    def test_14_box_at_goal_gives_goal_in_collision(self) -> None:
        goal_values = self.states[("arm", "place pose")]
        tcp = self.link_pose(goal_values, "link6").position
        scene = PlanningScene(is_diff=True)
        scene.world.collision_objects.append(box("blocker", (tcp.x, tcp.y, tcp.z), (0.08, 0.08, 0.08)))
        self.assertTrue(self.apply_scene(scene=scene).success)
        objects = self.scene().world.collision_objects
        self.assertEqual([o.id for o in objects], ["blocker"])
        markers = rospy.wait_for_message("move_group/planning_scene_markers", MarkerArray, timeout=10.0)
        self.assertIn(("blocker", Marker.CUBE), {(m.ns, m.type) for m in markers.markers})
        plan = self.plan(motion_plan_request=self.plan_request(joint_goal(goal_values))).motion_plan_response
        self.assert_code(plan.error_code, MoveItErrorCodes.GOAL_IN_COLLISION)
        validity = self.validity(robot_state=robot_state(goal_values), group_name="arm")
        self.assertFalse(validity.valid)
        self.assertIn("blocker", {validity.contacts[0].contact_body_1, validity.contacts[0].contact_body_2})
        removal = CollisionObject(id="blocker", operation=CollisionObject.REMOVE)
        scene = PlanningScene(is_diff=True)
        scene.world.collision_objects.append(removal)
        self.assertTrue(self.apply_scene(scene=scene).success)
        plan = self.plan(motion_plan_request=self.plan_request(joint_goal(goal_values))).motion_plan_response
        self.assert_code(plan.error_code, MoveItErrorCodes.SUCCESS)
        display = rospy.wait_for_message("move_group/display_planned_path", DisplayTrajectory, timeout=10.0)
        self.assertEqual(display.trajectory[0].joint_trajectory, plan.trajectory.joint_trajectory)

    def test_15_attach_and_detach_an_object(self) -> None:
        tcp = self.link_pose({n: v for n, v in self.current().items() if n in ARM}, "tcp").position
        scene = PlanningScene(is_diff=True)
        scene.world.collision_objects.append(box("held", (tcp.x, tcp.y, tcp.z), (0.02, 0.02, 0.02)))
        self.assertTrue(self.apply_scene(scene=scene).success)
        attach = AttachedCollisionObject(link_name="link6", touch_links=["palm", "finger1", "finger2", "tcp"])
        attach.object.id = "held"
        attach.object.operation = CollisionObject.ADD
        scene = PlanningScene(is_diff=True)
        scene.robot_state.is_diff = True
        scene.robot_state.attached_collision_objects.append(attach)
        self.assertTrue(self.apply_scene(scene=scene).success)
        current = self.scene()
        self.assertEqual(current.world.collision_objects, [])
        self.assertEqual([a.object.id for a in current.robot_state.attached_collision_objects], ["held"])
        # Held between the fingers (touch links), the object does not make the state invalid.
        self.assertTrue(self.validity(robot_state=RobotState(is_diff=True)).valid)
        attach.object.operation = CollisionObject.REMOVE
        self.assertTrue(self.apply_scene(scene=scene).success)
        current = self.scene()
        self.assertEqual([o.id for o in current.world.collision_objects], ["held"])
        self.assertAlmostEqual(current.world.collision_objects[0].pose.position.z, tcp.z, delta=1e-9)
        scene = PlanningScene(is_diff=True)
        scene.world.collision_objects.append(CollisionObject(id="held", operation=CollisionObject.REMOVE))
        self.assertTrue(self.apply_scene(scene=scene).success)

    # --- execution -----------------------------------------------------------------------------------
    def test_20_execute_trajectory_reaches_the_goal(self) -> None:
        goal_values = self.states[("arm", "after pick pose")]
        self.move_to(goal_values)
        current = self.current()
        for name in ARM:
            self.assertAlmostEqual(current[name], goal_values[name], delta=1e-3)
        # The gripper group: finger2_joint mimics finger1_joint and is sent to the gripper controller too.
        self.move_to({"finger1_joint": 0.03}, group="gripper")
        current = self.current()
        self.assertAlmostEqual(current["finger1_joint"], 0.03, delta=1e-4)
        self.assertAlmostEqual(current["finger2_joint"], 0.03, delta=1e-4)

    def test_21_trajectory_spanning_both_controllers_is_split(self) -> None:
        current = self.current()
        trajectory = JointTrajectory(joint_names=["joint1", "finger1_joint"])
        start = [current["joint1"], current["finger1_joint"]]
        end = [current["joint1"] + 0.1, 0.01]
        for t, values in ((0.0, start), (1.0, end)):
            trajectory.points.append(JointTrajectoryPoint(positions=values, time_from_start=rospy.Duration(t)))
        self.execute_trajectory(trajectory, MoveItErrorCodes.SUCCESS)
        current = self.current()
        self.assertAlmostEqual(current["joint1"], end[0], delta=1e-4)
        self.assertAlmostEqual(current["finger1_joint"], 0.01, delta=1e-4)
        self.assertAlmostEqual(current["finger2_joint"], 0.01, delta=1e-4)

    def test_22_start_state_deviation_is_rejected(self) -> None:
        current = self.current()
        trajectory = JointTrajectory(joint_names=ARM)
        first = [current[n] for n in ARM]
        first[1] += 0.05
        for t in (0.0, 1.0):
            trajectory.points.append(JointTrajectoryPoint(positions=first, time_from_start=rospy.Duration(t)))
        self.execute_trajectory(trajectory, MoveItErrorCodes.CONTROL_FAILED, "deviates", "joint2")

    def test_22b_the_next_motion_starts_where_an_execution_ended(self) -> None:
        # joint_states half a second behind the motion, stamped when sent: what move_group sees of a simulator faster
        # than real time when its own /clock lags behind. An execution ends once they show its end, so the next
        # motion from there passes the start check.
        current = self.current()
        start = [current[n] for n in ARM]
        end = [start[0] + 0.4, *start[1:]]
        there, back = JointTrajectory(joint_names=ARM), JointTrajectory(joint_names=ARM)
        for t, a, b in ((0.0, start, end), (0.8, end, start)):
            there.points.append(JointTrajectoryPoint(positions=a, time_from_start=rospy.Duration(t)))
            back.points.append(JointTrajectoryPoint(positions=b, time_from_start=rospy.Duration(t)))
        rospy.set_param(FIXTURE + "/state_lag", 0.5)
        try:
            self.execute_trajectory(there, MoveItErrorCodes.SUCCESS)
            self.execute_trajectory(back, MoveItErrorCodes.SUCCESS)
        finally:
            rospy.set_param(FIXTURE + "/state_lag", 0.0)

    def test_23_slow_controller_times_out(self) -> None:
        trajectory = self.plan_to(self.states[("arm", "after pick pose")]).trajectory.joint_trajectory
        rospy.set_param(FIXTURE + "/slowdown", 4.0)
        try:
            self.execute_trajectory(trajectory, MoveItErrorCodes.TIMED_OUT, "Controller is taking too long")
        finally:
            rospy.set_param(FIXTURE + "/slowdown", 1.0)

    def test_24_controller_error_is_reported(self) -> None:
        trajectory = self.plan_to(self.states[("arm", "pick pose")]).trajectory.joint_trajectory
        rospy.set_param(FIXTURE + "/fail_with", "fixture says joint3 missed its goal")
        try:
            self.execute_trajectory(
                trajectory,
                MoveItErrorCodes.CONTROL_FAILED,
                "fixture says joint3 missed its goal",
                "GOAL_TOLERANCE_VIOLATED",
                "arm_controller",
            )
        finally:
            rospy.set_param(FIXTURE + "/fail_with", "")

    def test_24b_execution_can_be_preempted(self) -> None:
        trajectory = self.plan_to(self.states[("arm", "place pose")]).trajectory.joint_trajectory
        rospy.set_param(FIXTURE + "/slowdown", 10.0)
        try:
            goal = ExecuteTrajectoryGoal()
            goal.trajectory.joint_trajectory = trajectory
            self.execute.send_goal(goal)
            # Wait (bounded, wall clock) until the server executes the goal. Not for its MONITOR feedback:
            # rospy's SimpleActionClient drops feedback that arrives before send_goal has returned.
            deadline = time.monotonic() + 60.0
            while self.execute.get_state() != GoalStatus.ACTIVE and time.monotonic() < deadline:
                time.sleep(0.01)
            self.assertEqual(self.execute.get_state(), GoalStatus.ACTIVE, "execute_trajectory goal never became active")
            self.execute.cancel_goal()
            self.assertTrue(wait_for_goal(self.execute, 120.0), "no execute_trajectory result")
        finally:
            rospy.set_param(FIXTURE + "/slowdown", 1.0)
        self.assert_result(self.execute, MoveItErrorCodes.PREEMPTED)

    def test_25_move_group_action_plans_and_executes(self) -> None:
        goal = MoveGroupGoal()
        goal.request = self.plan_request(joint_goal(self.states[("arm", "pick pose")]))
        goal.planning_options.plan_only = True
        result = self.move_group_result(goal)
        self.assert_result(self.move_group, MoveItErrorCodes.SUCCESS)
        self.assertTrue(result.planned_trajectory.joint_trajectory.points)
        self.assertFalse(result.executed_trajectory.joint_trajectory.points)
        goal.planning_options.plan_only = False
        result = self.move_group_result(goal)
        self.assert_result(self.move_group, MoveItErrorCodes.SUCCESS)
        self.assertTrue(result.executed_trajectory.joint_trajectory.points)
        current = self.current()
        for name in ARM:
            self.assertAlmostEqual(current[name], self.states[("arm", "pick pose")][name], delta=1e-3)

    # --- bad input: an error code and a message naming the problem; the node keeps serving ------------
    def test_30_ik_rejects_nan_and_non_unit_quaternions(self) -> None:
        pose = self.named_pose("home pose")
        pose.position.y = float("nan")
        code = self.ik(ik_request=self.ik_request(pose)).error_code
        self.assert_code(code, MoveItErrorCodes.FAILURE, "position.y", "nan")
        pose = self.named_pose("home pose")
        pose.position.z = float("inf")
        self.assert_code(self.ik(ik_request=self.ik_request(pose)).error_code, MoveItErrorCodes.FAILURE, "inf")
        pose = self.named_pose("home pose")
        pose.orientation.w *= 1.1
        pose.orientation.x *= 1.1
        pose.orientation.y *= 1.1
        pose.orientation.z *= 1.1
        code = self.ik(ik_request=self.ik_request(pose)).error_code
        self.assert_code(code, MoveItErrorCodes.FAILURE, "unit quaternion")
        # Within the 1e-3 tolerance the quaternion is accepted.
        pose = self.named_pose("home pose")
        pose.orientation.w *= 1.0004
        self.assert_code(self.ik(ik_request=self.ik_request(pose)).error_code, MoveItErrorCodes.SUCCESS)
        self.assert_serving()

    def test_31_unknown_group_link_joint_and_state(self) -> None:
        code = self.ik(ik_request=self.ik_request(self.named_pose("home pose"), group="leg")).error_code
        self.assert_code(code, MoveItErrorCodes.INVALID_GROUP_NAME, "'leg'", "'arm'")
        code = self.fk(fk_link_names=["link9"], robot_state=RobotState()).error_code
        self.assert_code(code, MoveItErrorCodes.INVALID_LINK_NAME, "'link9'")
        request = self.ik_request(self.named_pose("home pose"))
        request.ik_link_name = "link3"
        self.assert_code(self.ik(ik_request=request).error_code, MoveItErrorCodes.INVALID_LINK_NAME, "'link3'")
        response = self.plan(motion_plan_request=self.plan_request(Constraints(name="home pose")))
        self.assert_code(
            response.motion_plan_response.error_code, MoveItErrorCodes.INVALID_GOAL_CONSTRAINTS, "no constraints"
        )
        response = self.plan(motion_plan_request=self.plan_request(joint_goal({"joint7": 0.0})))
        self.assert_code(
            response.motion_plan_response.error_code, MoveItErrorCodes.INVALID_GOAL_CONSTRAINTS, "'joint7'"
        )
        response = self.plan(motion_plan_request=self.plan_request(joint_goal({"finger1_joint": 0.0})))
        self.assert_code(
            response.motion_plan_response.error_code,
            MoveItErrorCodes.INVALID_GOAL_CONSTRAINTS,
            "'finger1_joint'",
            "'arm'",
        )
        code = self.fk(fk_link_names=["link6"], robot_state=robot_state({"elbow": 1.0})).error_code
        self.assert_code(code, MoveItErrorCodes.INVALID_ROBOT_STATE, "'elbow'")
        code = self.fk(fk_link_names=["link6"], robot_state=robot_state({"joint2": float("nan")})).error_code
        self.assert_code(code, MoveItErrorCodes.INVALID_ROBOT_STATE, "'joint2'")
        request = MotionPlanRequest(group_name="wing")
        request.goal_constraints.append(Constraints(name="home pose"))
        code = self.plan(motion_plan_request=request).motion_plan_response.error_code
        self.assert_code(code, MoveItErrorCodes.INVALID_GROUP_NAME, "'wing'")
        self.assert_serving()

    def test_32_scaling_factors_outside_zero_one(self) -> None:
        for field in ("max_velocity_scaling_factor", "max_acceleration_scaling_factor"):
            for value in (1.5, -0.1, float("nan"), 1e-308):
                request = self.plan_request(joint_goal(self.states[("arm", "home pose")]))
                setattr(request, field, value)
                code = self.plan(motion_plan_request=request).motion_plan_response.error_code
                self.assert_code(code, MoveItErrorCodes.FAILURE, field, "[0.001, 1]")
        request = GetCartesianPathRequest(group_name="arm", waypoints=[self.named_pose("home pose")], max_step=0.01)
        request.max_cartesian_speed = 0.2
        self.assert_code(self.cartesian(request).error_code, MoveItErrorCodes.FAILURE, "max_cartesian_speed")
        self.assert_serving()

    def test_33_cartesian_path_bad_requests(self) -> None:
        request = GetCartesianPathRequest(group_name="arm", waypoints=[], max_step=0.01)
        self.assert_code(self.cartesian(request).error_code, MoveItErrorCodes.FAILURE, "waypoints is empty")
        home = self.named_pose("home pose")
        pose = self.named_pose("home pose")
        pose.orientation.w = 0.0
        pose.orientation.x = pose.orientation.y = pose.orientation.z = 0.0
        request = GetCartesianPathRequest(group_name="arm", waypoints=[home, pose], max_step=0.01)
        self.assert_code(
            self.cartesian(request).error_code, MoveItErrorCodes.FAILURE, "waypoints[1]", "unit quaternion"
        )
        request = GetCartesianPathRequest(group_name="arm", waypoints=[self.named_pose("home pose")], max_step=0.0)
        self.assert_code(self.cartesian(request).error_code, MoveItErrorCodes.FAILURE, "max_step")
        request = GetCartesianPathRequest(group_name="gripper", waypoints=[self.named_pose("home pose")], max_step=0.01)
        self.assert_code(self.cartesian(request).error_code, MoveItErrorCodes.NO_IK_SOLUTION, "'gripper'")
        self.assert_serving()

    def test_34_malformed_collision_objects(self) -> None:
        def refused(obj: CollisionObject, code: int, *fragments: str) -> None:
            scene = PlanningScene(is_diff=True)
            scene.world.collision_objects.append(obj)
            self.assertFalse(self.apply_scene(scene=scene).success)
            self.assert_refused(code, *fragments)

        obj = box("flat", (1.0, 1.0, 0.5), (0.1, 0.1, 0.1))
        obj.primitives[0].dimensions = [0.1, 0.1]
        refused(obj, MoveItErrorCodes.FAILURE, "'flat'", "3 dimensions")
        obj = box("negative", (1.0, 1.0, 0.5), (0.1, -0.1, 0.1))
        refused(obj, MoveItErrorCodes.FAILURE, "'negative'", "non-positive")
        obj = box("", (1.0, 1.0, 0.5), (0.1, 0.1, 0.1))
        refused(obj, MoveItErrorCodes.INVALID_OBJECT_NAME, "empty id")
        obj = box("posed", (1.0, 1.0, 0.5), (0.1, 0.1, 0.1))
        obj.primitive_poses = []
        refused(obj, MoveItErrorCodes.FAILURE, "'posed'", "primitive_poses")
        obj = box("tilted", (1.0, 1.0, 0.5), (0.1, 0.1, 0.1))
        obj.pose.orientation.w = 2.0
        refused(obj, MoveItErrorCodes.FAILURE, "'tilted'", "unit quaternion")
        obj = box("shapeless", (1.0, 1.0, 0.5), (0.1, 0.1, 0.1))
        obj.primitives, obj.primitive_poses = [], []
        refused(obj, MoveItErrorCodes.FAILURE, "'shapeless'", "no primitives")
        obj = box("elsewhere", (1.0, 1.0, 0.5), (0.1, 0.1, 0.1), frame="moon")
        refused(obj, MoveItErrorCodes.FRAME_TRANSFORM_FAILURE, "'moon'")
        obj = CollisionObject(id="ghost", operation=CollisionObject.REMOVE)
        refused(obj, MoveItErrorCodes.INVALID_OBJECT_NAME, "'ghost'")
        obj = box("planar", (1.0, 1.0, 0.5), (0.1, 0.1, 0.1))
        obj.planes.append(Plane(coef=[0.0, 0.0, 1.0, 0.0]))
        obj.plane_poses.append(Pose(orientation=Quaternion(w=1.0)))
        refused(obj, MoveItErrorCodes.FAILURE, "'planar'", "planes are not supported")
        # Nothing of the rejected requests reached the scene.
        self.assertEqual(self.scene().world.collision_objects, [])
        self.assert_serving()

    def test_35_execute_rejects_malformed_trajectories(self) -> None:
        trajectory = JointTrajectory(joint_names=["joint1", "knee"])
        trajectory.points.append(JointTrajectoryPoint(positions=[0.0, 0.0], time_from_start=rospy.Duration(0.0)))
        self.execute_trajectory(trajectory, MoveItErrorCodes.INVALID_MOTION_PLAN, "'knee'")
        self.execute_trajectory(JointTrajectory(joint_names=ARM), MoveItErrorCodes.INVALID_MOTION_PLAN)
        self.assert_serving()

    def test_36_cartesian_start_a_hair_past_a_limit(self) -> None:
        # The home pose with the wrist flipped: joint4 at +pi, read a hair past it (under load the measured joint4
        # read 3.1416). As for planning, the path starts on the limit, so the controller accepts its first point.
        home = {"joint1": 0.0, "joint2": 0.487674, "joint3": 0.237739, "joint5": -0.833376, "joint6": -math.pi}
        start = dict(home, joint4=math.pi + 5e-4)
        pose = self.link_pose(dict(home, joint4=math.pi))
        down = Pose(position=pose.position, orientation=pose.orientation)
        down.position.z -= 0.03
        request = GetCartesianPathRequest(group_name="arm", waypoints=[down], max_step=0.005, avoid_collisions=True)
        request.header.frame_id = "base_link"
        request.start_state = robot_state(start)
        response = self.cartesian(request)
        self.assert_code(response.error_code, MoveItErrorCodes.SUCCESS)
        self.assertAlmostEqual(response.fraction, 1.0, delta=1e-9)
        first = dict(zip(ARM, response.solution.joint_trajectory.points[0].positions, strict=True))
        self.assertEqual(first["joint4"], math.pi)


if __name__ == "__main__":
    rostest.rosrun(PKG, "test_move_group", MoveGroupTest, sys.argv)
