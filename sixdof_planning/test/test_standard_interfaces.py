#!/usr/bin/env python3
"""rostest of move_group's moveit_msgs interfaces beyond planning and execution: path constraints, the request
fields sixdof refuses by name, workspace parameters, full and diff robot states, get_planning_scene components, the
scene topics MoveIt's move_group listens to, constraint evaluation in check_state_validity and the error reports.
Runs against the same move_group and trajectory fixture as test_move_group.py (move_group.test); every test starts
from the fixture's initial state and an empty scene (MoveGroupTestCase.setUp)."""

import sys
import time

import rospy
import rostest
from geometry_msgs.msg import Pose, Quaternion
from move_group_test_helpers import ARM, MoveGroupTestCase, box, joint_goal, robot_state
from moveit_msgs.msg import (
    AttachedCollisionObject,
    CollisionObject,
    Constraints,
    JointConstraint,
    MoveGroupGoal,
    MoveItErrorCodes,
    ObjectColor,
    OrientationConstraint,
    PlanningScene,
    PlanningSceneComponents,
    PositionConstraint,
)
from shape_msgs.msg import SolidPrimitive
from std_msgs.msg import ColorRGBA

PKG = "sixdof_planning"
C = PlanningSceneComponents


def joint_range(name: str, position: float, tolerance: float) -> JointConstraint:
    return JointConstraint(
        joint_name=name, position=position, tolerance_above=tolerance, tolerance_below=tolerance, weight=1.0
    )


class StandardInterfacesTest(MoveGroupTestCase):
    def arm_now(self) -> dict:
        return {n: v for n, v in self.current().items() if n in ARM}

    def components(self, bits: int) -> PlanningScene:
        return self.get_scene(components=C(components=bits)).scene

    def apply(self, scene: PlanningScene) -> bool:
        scene.is_diff = True
        scene.robot_state.is_diff = True
        return self.apply_scene(scene=scene).success

    # --- path constraints ------------------------------------------------------------------------------
    def test_path_joint_constraint_holds_along_the_trajectory(self) -> None:
        start = self.arm_now()
        goal = dict(start, joint1=start["joint1"] + 0.6, joint2=start["joint2"] - 0.2)
        request = self.plan_request(joint_goal(goal))
        request.path_constraints.joint_constraints.append(joint_range("joint4", start["joint4"], 0.05))
        response = self.plan(motion_plan_request=request).motion_plan_response
        self.assert_code(response.error_code, MoveItErrorCodes.SUCCESS)
        index = response.trajectory.joint_trajectory.joint_names.index("joint4")
        for point in response.trajectory.joint_trajectory.points:
            self.assertLessEqual(abs(point.positions[index] - start["joint4"]), 0.05 + 1e-6)
        # A goal outside the path constraint, and a start outside it.
        request.goal_constraints = [joint_goal(dict(goal, joint4=start["joint4"] + 0.5))]
        code = self.plan(motion_plan_request=request).motion_plan_response.error_code
        self.assert_code(code, MoveItErrorCodes.GOAL_VIOLATES_PATH_CONSTRAINTS, "joint4")
        request.goal_constraints = [joint_goal(goal)]
        request.path_constraints.joint_constraints = [joint_range("joint4", start["joint4"] + 1.0, 0.05)]
        code = self.plan(motion_plan_request=request).motion_plan_response.error_code
        self.assert_code(code, MoveItErrorCodes.START_STATE_VIOLATES_PATH_CONSTRAINTS, "joint4")

    def test_path_position_constraint_keeps_the_link_in_its_region(self) -> None:
        start = self.arm_now()
        goal = dict(start, joint1=start["joint1"] - 0.8)
        tip = self.link_pose(start).position
        region = PositionConstraint(link_name="link6", weight=1.0)
        region.header.frame_id = "base_link"
        # A box from 5 cm below the tip's height to 60 cm above it, around the whole workspace.
        region.constraint_region.primitives.append(SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[2.0, 2.0, 0.65]))
        centre = Pose(orientation=Quaternion(w=1.0))
        centre.position.z = tip.z - 0.05 + 0.325
        region.constraint_region.primitive_poses.append(centre)
        request = self.plan_request(joint_goal(goal))
        request.path_constraints.position_constraints.append(region)
        response = self.plan(motion_plan_request=request).motion_plan_response
        self.assert_code(response.error_code, MoveItErrorCodes.SUCCESS)
        trajectory = response.trajectory.joint_trajectory
        for point in trajectory.points:
            z = self.link_pose(dict(zip(trajectory.joint_names, point.positions, strict=True))).position.z
            self.assertGreaterEqual(z, tip.z - 0.05 - 1e-3)

    def test_unsupported_fields_are_refused_by_name(self) -> None:
        request = self.plan_request(joint_goal(self.arm_now()))
        request.path_constraints.orientation_constraints.append(
            OrientationConstraint(link_name="link6", orientation=Quaternion(w=1.0))
        )
        code = self.plan(motion_plan_request=request).motion_plan_response.error_code
        self.assert_code(code, MoveItErrorCodes.FAILURE, "orientation path constraints")
        request = self.plan_request(joint_goal(self.arm_now()))
        request.pipeline_id = "chomp"
        code = self.plan(motion_plan_request=request).motion_plan_response.error_code
        self.assert_code(code, MoveItErrorCodes.FAILURE, "pipeline_id 'chomp'")
        request = self.plan_request(joint_goal(self.arm_now()))
        request.trajectory_constraints.constraints.append(Constraints())
        code = self.plan(motion_plan_request=request).motion_plan_response.error_code
        self.assert_code(code, MoveItErrorCodes.FAILURE, "trajectory_constraints")
        request = self.plan_request(joint_goal(self.arm_now()))
        request.start_state.multi_dof_joint_state.joint_names = ["virtual_joint"]
        code = self.plan(motion_plan_request=request).motion_plan_response.error_code
        self.assert_code(code, MoveItErrorCodes.INVALID_ROBOT_STATE, "multi_dof_joint_state")
        goal = MoveGroupGoal(request=self.plan_request(joint_goal(self.arm_now())))
        goal.planning_options.plan_only = True
        goal.planning_options.look_around = True
        self.move_group_result(goal)
        self.assert_result(self.move_group, MoveItErrorCodes.FAILURE, "look_around")
        scene = PlanningScene()
        scene.allowed_collision_matrix.entry_names = ["link1"]
        self.assertFalse(self.apply(scene))
        self.assert_refused(MoveItErrorCodes.FAILURE, "allowed_collision_matrix")
        self.assert_serving()

    def test_workspace_parameters_are_checked_not_ignored(self) -> None:
        request = self.plan_request(joint_goal(self.arm_now()))
        # MoveGroupInterface's default workspace: a 2 m cube around the planning frame.
        request.workspace_parameters.header.frame_id = "base_link"
        request.workspace_parameters.min_corner.x = request.workspace_parameters.min_corner.y = -1.0
        request.workspace_parameters.min_corner.z = -1.0
        request.workspace_parameters.max_corner.x = request.workspace_parameters.max_corner.y = 1.0
        request.workspace_parameters.max_corner.z = 1.0
        self.assert_code(
            self.plan(motion_plan_request=request).motion_plan_response.error_code, MoveItErrorCodes.SUCCESS
        )
        request.workspace_parameters.min_corner.x = 2.0
        code = self.plan(motion_plan_request=request).motion_plan_response.error_code
        self.assert_code(code, MoveItErrorCodes.FAILURE, "workspace_parameters")

    # --- robot states ----------------------------------------------------------------------------------
    def test_full_state_replaces_attached_objects_a_diff_adds_to_them(self) -> None:
        # A long bar held by link6 that reaches down through the table-free base region into link1.
        bar = AttachedCollisionObject(link_name="link6")
        bar.object = box("bar", (0.0, 0.0, 0.0), (0.05, 0.05, 2.0), frame="link6")
        home = self.states[("arm", "home pose")]
        diff = robot_state(home)
        diff.attached_collision_objects.append(bar)
        self.assertFalse(self.validity(robot_state=diff, group_name="arm").valid)
        scene = PlanningScene()
        scene.robot_state.attached_collision_objects.append(bar)
        self.assertTrue(self.apply(scene))
        try:
            self.assertFalse(self.validity(robot_state=robot_state(home), group_name="arm").valid)
            full = robot_state(home)
            full.is_diff = False
            self.assertTrue(self.validity(robot_state=full, group_name="arm").valid)
        finally:
            bar.object.operation = CollisionObject.REMOVE
            scene = PlanningScene()
            scene.robot_state.attached_collision_objects.append(bar)
            self.assertTrue(self.apply(scene))
            scene = PlanningScene()
            scene.world.collision_objects.append(CollisionObject(id="bar", operation=CollisionObject.REMOVE))
            self.assertTrue(self.apply(scene))

    def test_check_state_validity_evaluates_constraints(self) -> None:
        home = self.states[("arm", "home pose")]
        request_state = robot_state(home)
        constraints = Constraints()
        constraints.joint_constraints.append(joint_range("joint2", home["joint2"], 0.01))
        constraints.joint_constraints.append(joint_range("joint3", home["joint3"] + 0.5, 0.01))
        link6 = self.link_pose(home)
        orientation = OrientationConstraint(link_name="link6", orientation=link6.orientation, weight=1.0)
        orientation.header.frame_id = "base_link"
        orientation.absolute_x_axis_tolerance = orientation.absolute_y_axis_tolerance = 0.01
        orientation.absolute_z_axis_tolerance = 0.01
        constraints.orientation_constraints.append(orientation)
        response = self.validity(robot_state=request_state, group_name="arm", constraints=constraints)
        self.assertEqual([r.result for r in response.constraint_result], [True, False, True])
        self.assertAlmostEqual(response.constraint_result[1].distance, 0.5, delta=1e-6)
        self.assertFalse(response.valid)
        constraints.joint_constraints[0].joint_name = "knee"
        response = self.validity(robot_state=request_state, group_name="arm", constraints=constraints)
        self.assertFalse(response.valid)
        self.assert_refused(MoveItErrorCodes.FAILURE, "'knee'")

    def test_a_hair_past_a_limit_is_on_it_further_is_not_valid(self) -> None:
        home = self.states[("arm", "home pose")]
        upper = self.states[("gripper", "open")]["finger1_joint"]  # the open fingers are at their upper limit
        for past, valid in ((1e-9, True), (0.01, False)):
            state = robot_state(dict(home, finger1_joint=upper + past, finger2_joint=upper + past))
            self.assertEqual(self.validity(robot_state=state, group_name="arm").valid, valid, f"{past} past the limit")

    # --- the planning scene ----------------------------------------------------------------------------
    def test_get_planning_scene_answers_the_components_asked_for(self) -> None:
        scene = PlanningScene()
        scene.world.collision_objects.append(box("marker", (1.0, -1.0, 0.1), (0.05, 0.05, 0.05)))
        scene.object_colors.append(ObjectColor(id="marker", color=ColorRGBA(r=1.0, a=1.0)))
        self.assertTrue(self.apply(scene))
        try:
            self.assertEqual(self.components(0).world.collision_objects, [])
            names = self.components(C.WORLD_OBJECT_NAMES).world.collision_objects
            self.assertEqual([(o.id, len(o.primitives)) for o in names], [("marker", 0)])
            geometry = self.components(C.WORLD_OBJECT_GEOMETRY).world.collision_objects
            self.assertEqual(len(geometry[0].primitives), 1)
            colors = self.components(C.OBJECT_COLORS).object_colors
            self.assertEqual([(c.id, c.color.r) for c in colors], [("marker", 1.0)])
            self.assertEqual(self.components(C.WORLD_OBJECT_NAMES).object_colors, [])
            acm = self.components(C.ALLOWED_COLLISION_MATRIX).allowed_collision_matrix
            self.assertIn("link1", acm.entry_names)
            i, j = acm.entry_names.index("base_link"), acm.entry_names.index("link1")
            self.assertTrue(acm.entry_values[i].enabled[j], "adjacent links may touch")
            self.assertTrue(self.components(C.ROBOT_STATE).robot_state.joint_state.name)
            self.assertEqual(self.components(C.TRANSFORMS).fixed_frame_transforms[0].child_frame_id, "base_link")
        finally:
            scene = PlanningScene()
            scene.world.collision_objects.append(CollisionObject(id="marker", operation=CollisionObject.REMOVE))
            self.assertTrue(self.apply(scene))

    def test_scene_topics_change_the_scene_and_report_refusals(self) -> None:
        objects = rospy.Publisher("collision_object", CollisionObject, queue_size=10)
        scenes = rospy.Publisher("planning_scene", PlanningScene, queue_size=10)
        deadline = time.monotonic() + 30.0
        while (objects.get_num_connections() == 0 or scenes.get_num_connections() == 0) and time.monotonic() < deadline:
            time.sleep(0.01)
        objects.publish(box("posted", (1.2, 1.2, 0.1), (0.05, 0.05, 0.05)))
        self.assertTrue(self.wait_for_objects(["posted"]), "the collision_object message never reached the scene")
        monitored = rospy.wait_for_message("move_group/monitored_planning_scene", PlanningScene, timeout=10.0)
        self.assertIn("posted", [o.id for o in monitored.world.collision_objects])
        bad = box("broken", (1.2, 1.2, 0.1), (0.05, 0.05, 0.05))
        bad.primitives[0].dimensions = [0.05]
        objects.publish(bad)
        report = self.assert_refused(MoveItErrorCodes.FAILURE, "'broken'")
        self.assertEqual(report.interface, rospy.resolve_name("collision_object"))
        removal = PlanningScene(is_diff=True)
        removal.robot_state.is_diff = True
        removal.world.collision_objects.append(CollisionObject(id="posted", operation=CollisionObject.REMOVE))
        scenes.publish(removal)
        self.assertTrue(self.wait_for_objects([]), "the planning_scene diff never removed the object")

    def wait_for_objects(self, ids: list, timeout: float = 10.0) -> bool:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if [o.id for o in self.components(C.WORLD_OBJECT_NAMES).world.collision_objects] == ids:
                return True
            time.sleep(0.05)
        return False

    def test_error_reports_name_caller_interface_and_source(self) -> None:
        self.plan(motion_plan_request=self.plan_request(joint_goal({"joint7": 0.0})))
        report = self.reports.take(MoveItErrorCodes.INVALID_GOAL_CONSTRAINTS)
        self.assertEqual(report.caller_id, rospy.get_name())
        self.assertEqual(report.interface, rospy.resolve_name("plan_kinematic_path"))
        self.assertIn("plan_kinematic_path", report.source)
        self.assertTrue(report.message)


if __name__ == "__main__":
    rostest.rosrun(PKG, "test_standard_interfaces", StandardInterfacesTest, sys.argv)
