"""The collision scene through the bindings: primitives and meshes added, moved and removed, attached objects,
allowed collisions, padding, collision checks with contacts, distances, random valid states."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import DATA, arm_model, translation

import sixdof_core


def folded_down(arm: sixdof_core.RobotModel) -> sixdof_core.RobotState:
    """Shoulder forward and elbow down: the flange is below the table top (z < 0)."""
    state = sixdof_core.RobotState(arm)
    state.set_group_positions("arm", [0.0, 1.5, 0.4, 0.0, 0.0, 0.0])
    assert state.link_pose("link6")[2, 3] < 0.0
    return state


def test_world_objects_make_states_collide(arm, table_scene):
    home = sixdof_core.RobotState(arm)
    home.set_to_named_state("arm", "home pose")
    assert not table_scene.is_colliding(home)
    assert sorted(table_scene.world_object_ids) == ["cube", "table"]
    down = folded_down(arm)
    report = table_scene.check_collision(down)
    assert report and report.contacts
    contact = report.contacts[0]
    assert "table" in (contact.body1, contact.body2)
    assert sixdof_core.BodyType.WORLD_OBJECT in (contact.type1, contact.type2)
    assert contact.position.shape == (3,) and contact.depth >= 0.0
    assert not table_scene.is_colliding(down, sixdof_core.CollisionScope.SELF)
    table_scene.move_object("table", translation(0.3, 0.0, -1.0))
    assert not table_scene.is_colliding(down)
    table_scene.remove_object("table")
    assert not table_scene.has_world_object("table")


def test_distances_and_padding(arm, table_scene):
    home = sixdof_core.RobotState(arm)
    home.set_to_named_state("arm", "home pose")
    clear = table_scene.distance(home, sixdof_core.CollisionScope.WORLD)
    assert clear.found and clear.distance > 0.0
    assert {clear.body1, clear.body2} & {"table", "cube"}
    np.testing.assert_allclose(np.linalg.norm(clear.point1 - clear.point2), clear.distance, atol=1e-6)
    penetrating = table_scene.distance(folded_down(arm), sixdof_core.CollisionScope.WORLD)
    assert penetrating.distance < 0.0
    table_scene.set_padding(clear.distance + 0.01)
    assert table_scene.is_colliding(home, sixdof_core.CollisionScope.WORLD)
    assert table_scene.link_padding("link6") == pytest.approx(clear.distance + 0.01)
    assert np.isnan(table_scene.link_padding("nope"))
    empty = sixdof_core.CollisionScene(arm)
    assert not empty.distance(home, sixdof_core.CollisionScope.WORLD).found


def test_meshes_spheres_cylinders_and_multi_shape_objects(arm):
    scene = sixdof_core.CollisionScene(arm)
    state = sixdof_core.RobotState(arm)
    link6 = state.link_pose("link6")
    scene.add_mesh("flange", str(DATA / "meshes" / "flange.stl"), link6, scale=[0.001, 0.001, 0.001])
    assert scene.is_colliding(state)
    scene.remove_object("flange")
    scene.add_sphere("ball", 0.05, translation(1.0, 1.0, 1.0))
    scene.add_cylinder("post", 0.02, 0.3, link6)
    parts = [sixdof_core.PlacedShape(sixdof_core.Shape.box([0.1, 0.1, 0.1]), translation(0.0, 0.0, 0.05)),
             sixdof_core.PlacedShape(sixdof_core.Shape.sphere(0.05))]
    scene.add_object("pair", parts, translation(-1.0, 0.0, 0.0))
    assert sorted(scene.world_object_ids) == ["ball", "pair", "post"]
    contacts = scene.check_collision(state).contacts
    names = {c.body1 for c in contacts} | {c.body2 for c in contacts}
    assert "post" in names and "ball" not in names and "pair" not in names
    scene.clear()
    assert scene.world_object_ids == [] and not scene.is_colliding(state)


def test_attached_objects_move_with_their_link(arm, table_scene):
    state = sixdof_core.RobotState(arm)
    state.set_to_named_state("arm", "pick pose")
    touch = ["finger1", "finger2", "palm"]
    table_scene.set_allowed("cube", "table")
    table_scene.attach_world_object("cube", "link6", state, touch_links=touch)
    assert table_scene.attached_object_ids == ["cube"] and not table_scene.has_world_object("cube")
    state.set_to_named_state("arm", "home pose")
    table_scene.detach_object("cube", state)
    assert table_scene.has_world_object("cube") and not table_scene.has_attached_object("cube")
    box = sixdof_core.PlacedShape(sixdof_core.Shape.box([0.02, 0.02, 0.3]))
    table_scene.attach_object("rod", "link6", [box], translation(0.0, 0.0, 0.25), touch_links=touch)
    down = sixdof_core.RobotState(arm)
    down.set_group_positions("arm", [0.0, 0.9, 0.6, 0.0, 1.2, 0.0])
    contacts = table_scene.check_collision(down, sixdof_core.CollisionScope.WORLD).contacts
    assert any(sixdof_core.BodyType.ATTACHED_OBJECT in (c.type1, c.type2) for c in contacts)
    table_scene.remove_attached_object("rod")
    assert table_scene.attached_object_ids == []


def test_refused_changes_raise_scene_error_with_the_status(arm, table_scene):
    with pytest.raises(sixdof_core.SceneError, match="'table': name already in use") as error:
        table_scene.add_box("table", [1.0, 1.0, 1.0])
    assert error.value.status == sixdof_core.SceneStatusCode.DUPLICATE_NAME
    with pytest.raises(sixdof_core.SceneError, match="unknown world object 'nope'") as error:
        table_scene.move_object("nope", np.eye(4))
    assert error.value.status == sixdof_core.SceneStatusCode.UNKNOWN_NAME
    with pytest.raises(sixdof_core.SceneError, match="radius") as error:
        table_scene.add_sphere("bad", -1.0)
    assert error.value.status == sixdof_core.SceneStatusCode.INVALID_SHAPE
    with pytest.raises(sixdof_core.SceneError, match="nope.stl") as error:
        table_scene.add_mesh("missing", "/nope.stl")
    assert error.value.status == sixdof_core.SceneStatusCode.MESH_LOAD_FAILED
    with pytest.raises(sixdof_core.SceneError, match="unknown link or object 'ghost'"):
        table_scene.set_allowed("ghost", "table")
    with pytest.raises(ValueError, match="unknown attached object 'cube'"):
        table_scene.detach_object("cube", sixdof_core.RobotState(arm))
    assert isinstance(error.value, ValueError)


def test_allowed_collisions_and_states_of_other_robots(arm, joint_kinds, table_scene):
    down = folded_down(arm)
    # A state of another model of the same robot is one of this robot's.
    assert table_scene.is_colliding(folded_down(arm_model()))
    assert table_scene.is_allowed(arm.root_link, "table")
    for link in table_scene.link_names:
        table_scene.set_allowed(link, "table")
    table_scene.set_default_allowed("cube")
    assert not table_scene.is_colliding(down, sixdof_core.CollisionScope.WORLD)
    with pytest.raises(ValueError, match="state of robot 'joint_kinds'"):
        table_scene.is_colliding(sixdof_core.RobotState(joint_kinds))
    copy = table_scene.copy()
    copy.add_box("extra", [0.1, 0.1, 0.1])
    assert not table_scene.has_world_object("extra")


def test_random_valid_states(arm, table_scene):
    state = sixdof_core.RobotState(arm)
    sampler = sixdof_core.StateSampler(arm, 11)
    for _ in range(10):
        assert table_scene.set_to_random_valid_positions(state, sampler, "arm")
        assert state.satisfies_bounds() and not table_scene.is_colliding(state)
    blocked = sixdof_core.CollisionScene(arm)
    blocked.add_box("everywhere", [5.0, 5.0, 5.0])
    before = state.positions
    assert not blocked.set_to_random_valid_positions(state, sampler, max_attempts=5)
    np.testing.assert_array_equal(state.positions, before)
