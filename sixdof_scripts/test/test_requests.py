"""Requests the commander sends: the move_group goal of go(), Cartesian-path requests, scene diffs."""

import math

import pytest
from geometry_msgs.msg import Pose, PoseStamped
from shape_msgs.msg import SolidPrimitive
from sixdof_commander import SixdofCommanderError
from sixdof_commander.planning_scene import (
    attach_request,
    detach_request,
    primitive_object,
    removal,
    resolve_resource,
    scene_diff,
)

from sixdof_msgs.msg import CollisionObject


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


def test_cartesian_request_carries_waypoints_link_and_scaling(builder):
    builder.set_max_velocity_scaling_factor(0.3)
    builder.set_max_acceleration_scaling_factor(0.2)
    request = builder.cartesian_path_request([pose(0.4, 0.0, 0.2), pose(0.4, 0.0, 0.1)], 0.005, 0.0, True)
    assert request.header.frame_id == "base_link"
    assert request.group_name == "arm"
    assert request.link_name == "link6"
    assert [w.position.z for w in request.waypoints] == [0.2, 0.1]
    assert request.max_step == 0.005
    assert request.jump_threshold == 0.0
    assert request.avoid_collisions is True
    assert request.start_state.is_diff is True
    assert (request.max_velocity_scaling_factor, request.max_acceleration_scaling_factor) == (0.3, 0.2)


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
