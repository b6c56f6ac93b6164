"""Requests the commander sends: the move_group goal of go() (workspace, path constraints), Cartesian-path requests,
scene diffs."""

import math
from types import SimpleNamespace

import pytest
from geometry_msgs.msg import Pose, PoseStamped
from moveit_msgs.msg import (
    CollisionObject,
    Constraints,
    JointConstraint,
    OrientationConstraint,
    PositionConstraint,
    RobotState,
    VisibilityConstraint,
)
from sensor_msgs.msg import JointState
from shape_msgs.msg import SolidPrimitive
from sixdof_commander import SixdofCommanderError
from sixdof_commander.path_constraints import check_path_constraints
from sixdof_commander.planning_scene import (
    attach_request,
    detach_request,
    primitive_object,
    removal,
    resolve_resource,
    scene_diff,
)
from sixdof_commander.targets import Targets


def pose(x, y, z):
    result = Pose()
    result.position.x, result.position.y, result.position.z = x, y, z
    result.orientation.w = 1.0
    return result


def test_go_goal_plans_and_executes_in_the_current_scene(builder):
    builder.set_named_target("home pose")
    goal = builder.move_group_goal()
    assert goal.planning_options.plan_only is False
    assert goal.planning_options.planning_scene_diff.is_diff is True
    assert goal.planning_options.planning_scene_diff.robot_state.is_diff is True
    assert goal.request.group_name == "arm"
    assert [c.joint_name for c in goal.request.goal_constraints[0].joint_constraints][0] == "joint1"


def test_request_has_moveit_s_default_workspace_until_one_is_set(builder):
    builder.set_named_target("home pose")
    workspace = builder.motion_plan_request().workspace_parameters
    assert workspace.header.frame_id == ""
    assert (workspace.min_corner.x, workspace.max_corner.z) == (0.0, 0.0)
    builder.set_workspace([-1.0, -2.0, -0.5, 1.0, 2.0, 1.5])
    workspace = builder.motion_plan_request().workspace_parameters
    assert workspace.header.frame_id == "base_link"
    corners = workspace.min_corner, workspace.max_corner
    assert [(c.x, c.y, c.z) for c in corners] == [(-1.0, -2.0, -0.5), (1.0, 2.0, 1.5)]
    # Four values are x and y (z 0), as MoveIt's set_workspace; none resets it to zero.
    builder.set_workspace([-1.0, -2.0, 1.0, 2.0])
    corners = builder.motion_plan_request().workspace_parameters.min_corner, builder.workspace.max_corner
    assert [(c.x, c.y, c.z) for c in corners] == [(-1.0, -2.0, 0.0), (1.0, 2.0, 0.0)]
    builder.set_workspace([])
    assert builder.workspace.max_corner.y == 0.0


def joint_path_constraint(name, position, tolerance):
    constraints = Constraints()
    constraints.joint_constraints.append(
        JointConstraint(
            joint_name=name, position=position, tolerance_above=tolerance, tolerance_below=tolerance, weight=1.0
        )
    )
    return constraints


def test_path_constraints_go_with_every_plan(builder):
    builder.set_named_target("home pose")
    assert builder.motion_plan_request().path_constraints == Constraints()
    builder.path_constraints = check_path_constraints(joint_path_constraint("joint4", 0.0, 0.2), "set_path_constraints")
    request = builder.move_group_goal().request
    assert [(c.joint_name, c.tolerance_above) for c in request.path_constraints.joint_constraints] == [("joint4", 0.2)]
    assert request.goal_constraints[0].joint_constraints


def test_path_constraints_move_group_refuses_are_refused_here():
    position = Constraints(position_constraints=[PositionConstraint(link_name="link6")])
    assert check_path_constraints(position, "set_path_constraints") == position
    refused = [
        (Constraints(orientation_constraints=[OrientationConstraint()]), "orientation_constraints"),
        (Constraints(visibility_constraints=[VisibilityConstraint()]), "visibility_constraints"),
    ]
    for constraints, field in refused:
        with pytest.raises(SixdofCommanderError, match=rf"set_path_constraints\(constraints with {field}\) is not"):
            check_path_constraints(constraints, "set_path_constraints")
    with pytest.raises(SixdofCommanderError, match="path_constraints must be a moveit_msgs/Constraints, got dict"):
        check_path_constraints({}, "compute_cartesian_path", "path_constraints")


def test_cartesian_request_carries_waypoints_link_and_path_constraints(builder):
    builder.set_max_velocity_scaling_factor(0.3)
    request = builder.cartesian_path_request([pose(0.4, 0.0, 0.2), pose(0.4, 0.0, 0.1)], 0.005, 0.0, True)
    assert request.header.frame_id == "base_link"
    assert request.group_name == "arm"
    assert request.link_name == "link6"
    assert [w.position.z for w in request.waypoints] == [0.2, 0.1]
    assert request.max_step == 0.005
    assert request.jump_threshold == 0.0
    assert request.avoid_collisions is True
    assert request.start_state.is_diff is True
    assert request.path_constraints == Constraints()
    assert request.max_cartesian_speed == 0.0  # timed at full speed; the commander retimes to its scaling
    constrained = joint_path_constraint("joint1", 0.0, 0.1)
    request = builder.cartesian_path_request([pose(0.4, 0.0, 0.2)], 0.005, 0.0, True, constrained)
    assert request.path_constraints == constrained


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (([], 0.01, 0.0, True), "non-empty list of geometry_msgs/Pose"),
        ((pose(0, 0, 0), 0.01, 0.0, True), "non-empty list of geometry_msgs/Pose"),
        (([PoseStamped()], 0.01, 0.0, True), "waypoint 0 must be a geometry_msgs/Pose, got PoseStamped"),
        (([pose(0, 0, 0), Pose()], 0.01, 0.0, True), "waypoint 1 orientation .* has norm 0"),
        (([pose(0, 0, float("nan"))], 0.01, 0.0, True), r"waypoint 0 position\.z must be finite"),
        (([pose(0, 0, 0)], 0.0, 0.0, True), "eef_step must be > 0"),
        (([pose(0, 0, 0)], -0.01, 0.0, True), "eef_step must be > 0"),
        (([pose(0, 0, 0)], 0.01, -1.0, True), "jump_threshold must be >= 0"),
        (([pose(0, 0, 0)], 0.01, math.inf, True), "jump_threshold must be finite"),
        (([pose(0, 0, 0)], 0.01, 0.0, "yes"), "avoid_collisions must be True or False"),
    ],
)
def test_bad_cartesian_requests_are_rejected(builder, args, message):
    with pytest.raises(SixdofCommanderError, match=message):
        builder.cartesian_path_request(*args)


def test_box_becomes_a_primitive_at_the_pose_in_the_planning_frame():
    obj = primitive_object("table", [0.5, 0.0, -0.01, 0, 0, 0], SolidPrimitive.BOX, [1.0, 1.2, 0.02], "base_link")
    assert obj.id == "table"
    assert obj.operation == CollisionObject.ADD
    assert obj.header.frame_id == "base_link"
    assert (obj.pose.position.x, obj.pose.position.z) == (0.5, -0.01)
    assert obj.primitives[0].type == SolidPrimitive.BOX
    assert list(obj.primitives[0].dimensions) == [1.0, 1.2, 0.02]
    assert obj.primitive_poses[0].orientation.w == 1.0


def test_object_in_another_frame_keeps_it():
    stamped = PoseStamped()
    stamped.header.frame_id = "link6"
    stamped.pose.orientation.w = 1.0
    obj = primitive_object("tool", stamped, SolidPrimitive.SPHERE, [0.02], "base_link")
    assert obj.header.frame_id == "link6"


def test_bad_object_names_are_rejected():
    with pytest.raises(SixdofCommanderError, match="object name must be a non-empty string"):
        primitive_object("", [0, 0, 0, 0, 0, 0], SolidPrimitive.SPHERE, [0.02], "base_link")
    with pytest.raises(SixdofCommanderError, match="object name must be a non-empty string"):
        removal(None, "base_link")


def test_attach_and_detach_requests():
    attached = attach_request("red_cube", "link6", ["link6", "finger1", "finger2"])
    assert attached.link_name == "link6"
    assert attached.object.id == "red_cube"
    assert attached.object.operation == CollisionObject.ADD
    assert attached.object.primitives == []
    assert attached.touch_links == ["link6", "finger1", "finger2"]
    detached = detach_request("red_cube")
    assert detached.object.id == "red_cube" and detached.object.operation == CollisionObject.REMOVE
    assert detach_request("").object.id == ""


def test_scene_diff_flags_and_contents():
    remove = removal("box", "base_link")
    diff = scene_diff(world_objects=[remove], attached=[detach_request("cube")])
    assert diff.is_diff is True and diff.robot_state.is_diff is True
    assert diff.world.collision_objects == [remove]
    assert diff.robot_state.attached_collision_objects[0].object.id == "cube"


def test_resource_paths():
    assert resolve_resource("/tmp/x.stl") == "/tmp/x.stl"
    with pytest.raises(SixdofCommanderError, match="package 'no_such_package_xyz' of mesh"):
        resolve_resource("package://no_such_package_xyz/meshes/x.stl")


def test_set_start_state_keeps_a_copy(builder):
    targets = Targets(SimpleNamespace(goal=builder), current=None)
    state = RobotState(joint_state=JointState(name=["joint1"], position=[0.5]), is_diff=True)
    targets.set_start_state(state)
    builder.set_named_target("home pose")
    state.joint_state.position = [1.5]
    assert builder.move_group_goal().request.start_state.joint_state.position == [0.5]
