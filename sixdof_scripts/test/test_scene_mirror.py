"""SceneMirror's decisions, from simulator and scene snapshots (no ROS master needed)."""

import math

import pytest
from geometry_msgs.msg import Pose, Vector3
from moveit_msgs.msg import CollisionObject
from shape_msgs.msg import Mesh, SolidPrimitive
from sixdof_commander.scene_mirror import (
    SceneMirror,
    SceneSnapshot,
    SimObjectState,
    orientation_angle,
    template_from_sim_object,
)

from sixdof_msgs.msg import SimObject

FINGERS = ["link6", "palm", "finger1", "finger2"]


def pose(x=0.0, y=0.0, z=0.0, yaw=0.0) -> Pose:
    p = Pose()
    p.position.x, p.position.y, p.position.z = x, y, z
    p.orientation.z, p.orientation.w = math.sin(yaw / 2.0), math.cos(yaw / 2.0)
    return p


def cube_template() -> CollisionObject:
    obj = SimObject(name="cube", shape=SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[0.04, 0.04, 0.04]))
    return template_from_sim_object(obj, load_mesh=None)


def make_mirror(grace=0.5) -> SceneMirror:
    return SceneMirror(
        shapes={"cube": cube_template()},
        planning_frame="base_link",
        touch_links=lambda link: [link] + FINGERS[1:],
        grace=grace,
    )


def scene(world=None, attached=None) -> SceneSnapshot:
    return SceneSnapshot(world=world or {}, attached=attached or {})


def test_new_object_is_added_with_its_shape_at_the_sim_pose():
    updates = make_mirror().update([SimObjectState("cube", pose(0.4, -0.15, 0.02), "")], scene(), now=0.0)
    assert updates.attached_objects == []
    (added,) = updates.world_objects
    assert added.operation == CollisionObject.ADD
    assert added.id == "cube" and added.header.frame_id == "base_link"
    assert added.pose.position.x == pytest.approx(0.4)
    assert added.primitives[0].type == SolidPrimitive.BOX
    assert list(added.primitives[0].dimensions) == [0.04, 0.04, 0.04]
    assert added.primitive_poses[0].orientation.w == 1.0


def test_objects_without_a_template_are_not_mirrored():
    updates = make_mirror().update([SimObjectState("marker", pose(), "")], scene(), now=0.0)
    assert updates.empty()


def test_small_motions_are_ignored_and_large_ones_moved():
    mirror = make_mirror()
    known = scene(world={"cube": pose(0.4, 0.0, 0.02)})
    assert mirror.update([SimObjectState("cube", pose(0.4005, 0.0, 0.02, yaw=0.005), "")], known, 0.0).empty()
    (moved,) = mirror.update([SimObjectState("cube", pose(0.402, 0.0, 0.02), "")], known, 0.0).world_objects
    assert moved.operation == CollisionObject.MOVE and moved.primitives == []
    assert moved.pose.position.x == pytest.approx(0.402)
    (turned,) = mirror.update([SimObjectState("cube", pose(0.4, 0.0, 0.02, yaw=0.05), "")], known, 0.0).world_objects
    assert turned.operation == CollisionObject.MOVE


def test_grasp_fix_attach_waits_for_the_grace_period_then_attaches_with_touch_links():
    mirror = make_mirror(grace=0.5)
    held = [SimObjectState("cube", pose(0.4, 0.0, 0.1), "link6")]
    world = scene(world={"cube": pose(0.4, 0.0, 0.02)})
    # Within the grace period nothing happens, not even a MOVE of the object that is being lifted.
    assert mirror.update(held, world, now=10.0).empty()
    assert mirror.update(held, world, now=10.4).empty()
    (attach,) = mirror.update(held, world, now=10.5).attached_objects
    assert attach.link_name == "link6"
    assert attach.touch_links == FINGERS
    assert attach.object.operation == CollisionObject.ADD
    assert attach.object.header.frame_id == "base_link"
    assert attach.object.pose.position.z == pytest.approx(0.1)
    assert len(attach.object.primitives) == 1


def test_an_attach_done_by_someone_else_is_left_alone():
    mirror = make_mirror()
    held = [SimObjectState("cube", pose(0.4, 0.0, 0.1), "link6")]
    assert mirror.update(held, scene(world={"cube": pose(0.4, 0.0, 0.02)}), now=0.0).empty()
    # The script attached it itself: no mismatch any more, and the grace timer restarts later.
    assert mirror.update(held, scene(attached={"cube": "link6"}), now=1.0).empty()
    released = [SimObjectState("cube", pose(0.4, 0.2, 0.02), "")]
    assert mirror.update(released, scene(attached={"cube": "link6"}), now=5.0).empty()
    assert mirror.update(released, scene(attached={"cube": "link6"}), now=5.3).empty()


def test_release_detaches_then_moves_to_where_the_object_fell():
    mirror = make_mirror(grace=0.0)
    released = [SimObjectState("cube", pose(0.4, 0.2, 0.02), "")]
    (detach,) = mirror.update(released, scene(attached={"cube": "link6"}), now=0.0).attached_objects
    assert detach.object.id == "cube" and detach.object.operation == CollisionObject.REMOVE
    # The planner put it back where the hand was; the mirror corrects the pose.
    (moved,) = mirror.update(released, scene(world={"cube": pose(0.4, 0.2, 0.03)}), now=0.1).world_objects
    assert moved.operation == CollisionObject.MOVE
    assert moved.pose.position.z == pytest.approx(0.02)


def test_objects_deleted_from_the_simulator_are_removed_from_the_scene():
    mirror = make_mirror()
    mirror.update([SimObjectState("cube", pose(), "")], scene(), now=0.0)
    (removal,) = mirror.update([], scene(world={"cube": pose()}), now=1.0).world_objects
    assert removal.operation == CollisionObject.REMOVE and removal.id == "cube"
    assert mirror.update([], scene(), now=2.0).empty()
    assert mirror.managed == set()


def test_an_object_a_client_removed_stays_out_until_it_leaves_the_simulator():
    mirror = make_mirror(grace=0.0)
    resting = [SimObjectState("cube", pose(0.4, 0.0, 0.02), "")]
    (added,) = mirror.update(resting, scene(), now=0.0).world_objects
    assert added.operation == CollisionObject.ADD
    assert mirror.update(resting, scene(world={"cube": pose(0.4, 0.0, 0.02)}), now=0.1).empty()
    # scene.clear() / remove_world_object: the mirror does not put it back, moved or held by the grasp fix.
    assert mirror.update(resting, scene(), now=0.2).empty()
    assert mirror.update([SimObjectState("cube", pose(0.5, 0.0, 0.02), "")], scene(), now=0.3).empty()
    assert mirror.update([SimObjectState("cube", pose(0.5, 0.0, 0.1), "link6")], scene(), now=5.0).empty()
    assert mirror.removed == {"cube"} and mirror.managed == set()
    # Gone from the simulator, then an object of that name again: mirrored like any new one.
    assert mirror.update([], scene(), now=6.0).empty()
    (again,) = mirror.update(resting, scene(), now=6.1).world_objects
    assert again.operation == CollisionObject.ADD


def test_an_add_not_yet_seen_in_the_scene_is_sent_again():
    # A refused ADD leaves the object out of the scene without anyone having removed it.
    mirror = make_mirror()
    resting = [SimObjectState("cube", pose(0.4, 0.0, 0.02), "")]
    mirror.update(resting, scene(), now=0.0)
    (again,) = mirror.update(resting, scene(), now=0.1).world_objects
    assert again.operation == CollisionObject.ADD and mirror.removed == set()


def test_objects_the_mirror_never_added_are_not_removed():
    assert make_mirror().update([], scene(world={"user_box": pose()}), now=0.0).empty()


def test_bad_settings_are_rejected():
    with pytest.raises(ValueError, match="position_threshold"):
        SceneMirror({}, "base_link", lambda link: [], position_threshold=-1.0)
    with pytest.raises(ValueError, match="grace"):
        SceneMirror({}, "base_link", lambda link: [], grace=float("nan"))
    with pytest.raises(ValueError, match="planning_frame"):
        SceneMirror({}, "", lambda link: [])


def test_templates_from_primitives_and_meshes():
    sphere = SimObject(name="ball", shape=SolidPrimitive(type=SolidPrimitive.SPHERE, dimensions=[0.025]))
    assert template_from_sim_object(sphere, None).primitives[0].dimensions == [0.025]
    loaded = []
    mesh_obj = SimObject(name="part", mesh_resource="package://p/m.stl", mesh_scale=Vector3(1.0, 2.0, 3.0))

    def load(uri, scale):
        loaded.append((uri, scale))
        return Mesh()

    template = template_from_sim_object(mesh_obj, load)
    assert loaded == [("package://p/m.stl", [1.0, 2.0, 3.0])]
    assert len(template.meshes) == 1 and template.primitives == []
    bad = SimObject(name="flat", shape=SolidPrimitive(type=SolidPrimitive.BOX, dimensions=[0.1, 0.1]))
    with pytest.raises(ValueError, match="'flat'"):
        template_from_sim_object(bad, None)


def test_orientation_angle_treats_q_and_minus_q_alike():
    a, b = pose(yaw=0.3), pose(yaw=0.3)
    b.orientation.z, b.orientation.w = -b.orientation.z, -b.orientation.w
    assert orientation_angle(a, b) == pytest.approx(0.0, abs=1e-6)
    assert orientation_angle(pose(), pose(yaw=0.3)) == pytest.approx(0.3)


def test_static_objects_are_mirrored_lowered_by_the_support_clearance():
    mirror = make_mirror()
    mirror.shapes["table"] = cube_template()
    mirror.static.add("table")
    (added,) = mirror.update([SimObjectState("table", pose(0.2, 0.0, -0.375), "")], scene(), now=0.0).world_objects
    assert added.pose.position.z == pytest.approx(-0.377)
    # The lowered pose is the mirrored one: no MOVE back and forth.
    known = scene(world={"table": added.pose})
    assert mirror.update([SimObjectState("table", pose(0.2, 0.0, -0.375), "")], known, now=1.0).empty()
