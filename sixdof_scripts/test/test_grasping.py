"""Top-down grasp and place geometry for boxes, cylinders and spheres."""

import math

import numpy as np
import pytest
from shape_msgs.msg import SolidPrimitive
from sixdof_commander import SixdofCommanderError
from sixdof_commander.grasping import (
    GraspSpec,
    grasp_tcp_pose,
    object_geometry,
    place_tcp_pose,
    preferred_yaw,
    raised,
    tip_pose,
    wrap_angle,
)
from sixdof_commander.transforms import homogeneous, matrix_from_rpy

# The fixture robot's hand: tcp 0.1 m along link6's z axis, fingers closing along link6's y axis.
SPEC = GraspSpec(
    tcp_in_tip=homogeneous([0.0, 0.0, 0.1], np.eye(3)), finger_axis=np.array([0.0, 1.0, 0.0]), max_width=0.08
)


def shape(kind, *dimensions):
    return SolidPrimitive(type=kind, dimensions=list(dimensions))


def at(x, y, z, yaw=0.0):
    return homogeneous([x, y, z], matrix_from_rpy(0.0, 0.0, yaw))


def finger_direction(tcp):
    return tcp[:3, :3] @ SPEC.finger_axis


def test_cube_grasp_centres_the_tcp_tool_down_fingers_across_a_face():
    geometry = object_geometry(at(0.40, -0.15, 0.02), shape(SolidPrimitive.BOX, 0.04, 0.04, 0.04))
    tcp, width = grasp_tcp_pose(geometry, SPEC)
    np.testing.assert_allclose(tcp[:3, 3], [0.40, -0.15, 0.02], atol=1e-12)
    np.testing.assert_allclose(tcp[:3, 2], [0.0, 0.0, -1.0], atol=1e-12)
    assert width == 0.04
    fingers = finger_direction(tcp)
    assert max(abs(fingers[0]), abs(fingers[1])) == pytest.approx(1.0)


def test_grasp_yaw_is_the_square_symmetry_nearest_the_unwound_wrist():
    geometry = object_geometry(at(0.40, -0.15, 0.02, yaw=0.3), shape(SolidPrimitive.BOX, 0.04, 0.04, 0.04))
    tcp, _ = grasp_tcp_pose(geometry, SPEC)
    yaw = math.atan2(tcp[1, 0], tcp[0, 0])
    offset = wrap_angle(yaw - preferred_yaw(0.40, -0.15))
    assert abs(offset) <= math.pi / 4 + 1e-9
    # A multiple of 90 degrees away from the cube's yaw.
    assert wrap_angle(4 * (yaw - 0.3)) == pytest.approx(0.0, abs=1e-9)


def test_long_box_is_squeezed_across_its_narrow_side():
    geometry = object_geometry(at(0.3, 0.2, 0.03, yaw=0.5), shape(SolidPrimitive.BOX, 0.2, 0.05, 0.06))
    tcp, width = grasp_tcp_pose(geometry, SPEC)
    assert width == 0.05
    narrow_axis = np.array([-math.sin(0.5), math.cos(0.5), 0.0])
    assert abs(float(finger_direction(tcp) @ narrow_axis)) == pytest.approx(1.0)


def test_tall_object_is_grasped_near_its_top():
    geometry = object_geometry(at(0.3, 0.0, 0.1), shape(SolidPrimitive.CYLINDER, 0.2, 0.02))
    tcp, width = grasp_tcp_pose(geometry, SPEC)
    assert width == 0.04
    assert tcp[2, 3] == pytest.approx(0.2 - SPEC.max_grasp_depth)
    assert math.atan2(tcp[1, 0], tcp[0, 0]) == pytest.approx(preferred_yaw(0.3, 0.0))


def test_sphere_grasp_at_its_centre():
    tcp, width = grasp_tcp_pose(object_geometry(at(0.35, 0.1, 0.025), shape(SolidPrimitive.SPHERE, 0.025)), SPEC)
    np.testing.assert_allclose(tcp[:3, 3], [0.35, 0.1, 0.025])
    assert width == 0.05


@pytest.mark.parametrize(
    ("geometry_args", "message"),
    [
        ((at(0.3, 0, 0.05), shape(SolidPrimitive.BOX, 0.1, 0.09, 0.1)), "all exceed the gripper's opening"),
        ((at(0.3, 0, 0.05), shape(SolidPrimitive.SPHERE, 0.05)), "exceeds the gripper's opening"),
        ((at(0.3, 0, 0.05), shape(SolidPrimitive.CONE, 0.1, 0.02)), "only box, cylinder, sphere"),
        ((at(0.3, 0, 0.05), shape(SolidPrimitive.BOX, 0.1, 0.02)), "box needs 3 positive dimensions"),
        (
            (
                homogeneous([0.3, 0, 0.02], matrix_from_rpy(math.pi / 2, 0, 0)),
                shape(SolidPrimitive.CYLINDER, 0.1, 0.02),
            ),
            "not upright",
        ),
        (
            (homogeneous([0.3, 0, 0.02], matrix_from_rpy(0.5, 0.4, 0)), shape(SolidPrimitive.BOX, 0.04, 0.04, 0.04)),
            "tilted",
        ),
    ],
)
def test_ungraspable_objects_are_rejected(geometry_args, message):
    with pytest.raises(SixdofCommanderError, match=message):
        grasp_tcp_pose(object_geometry(*geometry_args), SPEC)


def test_tip_pose_puts_the_tcp_on_target():
    tcp = homogeneous([0.4, -0.15, 0.02], matrix_from_rpy(math.pi, 0.0, 2.0))
    tip = tip_pose(tcp, SPEC)
    np.testing.assert_allclose(tip @ SPEC.tcp_in_tip, tcp, atol=1e-12)
    # Tool pointing down: the tip is above the tcp by the tcp offset.
    assert tip[2, 3] == pytest.approx(0.12)


def test_raised_moves_only_up():
    pose = at(0.1, 0.2, 0.3, 1.0)
    np.testing.assert_allclose(raised(pose, 0.05)[:3, 3], [0.1, 0.2, 0.35])
    np.testing.assert_allclose(raised(pose, 0.05)[:3, :3], pose[:3, :3])


def test_place_pose_puts_the_held_object_on_target():
    object_in_tcp = np.array([0.004, -0.002, -0.01, 1.0])
    target = np.array([0.40, 0.20, 0.02])
    tcp = place_tcp_pose(target, object_in_tcp, clearance=0.005)
    np.testing.assert_allclose((tcp @ object_in_tcp)[:3], target + [0.0, 0.0, 0.005], atol=1e-12)
    np.testing.assert_allclose(tcp[:3, 2], [0.0, 0.0, -1.0], atol=1e-12)


def test_place_pose_stands_an_object_leaning_in_the_hand_upright():
    # A cube held 12 mm below the tcp (whose z points down), leaning 20 deg about the closing axis (the tcp's y)
    # and turned 30 deg.
    upright_in_tcp = matrix_from_rpy(math.pi, 0.0, 0.0)
    lean = homogeneous([0.0, 0.0, 0.012], upright_in_tcp @ matrix_from_rpy(0.0, math.radians(20.0), math.radians(30.0)))
    target = np.array([0.40, 0.20, 0.02])
    tcp = place_tcp_pose(target, lean, clearance=0.005)
    held = tcp @ lean
    np.testing.assert_allclose(held[:3, 3], target + [0.0, 0.0, 0.005], atol=1e-12)
    np.testing.assert_allclose(held[:3, 2], [0.0, 0.0, 1.0], atol=1e-12)
    # The tool leans by as much, at the wrist yaw preferred at the target.
    assert math.degrees(math.acos(-tcp[2, 2])) == pytest.approx(20.0)
    # Lying on a side face, it is stood on that face: the least turn.
    side = homogeneous([0.0, 0.0, 0.0], upright_in_tcp @ matrix_from_rpy(math.radians(85.0), 0.0, 0.0))
    tcp = place_tcp_pose(target, side, clearance=0.005)
    assert abs((tcp @ side)[2, 1]) == pytest.approx(1.0)
    assert math.degrees(math.acos(-tcp[2, 2])) == pytest.approx(5.0)


def test_low_object_grasp_keeps_the_fingertips_above_the_support():
    # Fingertips 15 mm beyond the tcp: a 3 cm cube is gripped 10 mm deep, fingertips 5 mm above the table.
    spec = GraspSpec(tcp_in_tip=SPEC.tcp_in_tip, finger_axis=SPEC.finger_axis, max_width=0.08, reach=0.015)
    tcp, _ = grasp_tcp_pose(object_geometry(at(0.3, 0.0, 0.015), shape(SolidPrimitive.BOX, 0.03, 0.03, 0.03)), spec)
    assert tcp[2, 3] == pytest.approx(0.02)
    assert tcp[2, 3] - spec.reach == pytest.approx(spec.clearance)
    # A 6 cm cube is gripped as deep as the spec allows.
    tcp, _ = grasp_tcp_pose(object_geometry(at(0.3, 0.0, 0.03), shape(SolidPrimitive.BOX, 0.06, 0.06, 0.06)), spec)
    assert tcp[2, 3] == pytest.approx(0.06 - spec.max_grasp_depth)


def test_fingers_reaching_far_beyond_the_tcp_grip_a_low_object_along_their_pads():
    # Pads 27.5 mm on either side of the tcp: the tcp stays above a 3 cm cube, the pads cover it from 5 mm up.
    spec = GraspSpec(tcp_in_tip=SPEC.tcp_in_tip, finger_axis=SPEC.finger_axis, max_width=0.08, reach=0.0275)
    tcp, _ = grasp_tcp_pose(object_geometry(at(0.3, 0.0, 0.015), shape(SolidPrimitive.BOX, 0.03, 0.03, 0.03)), spec)
    assert tcp[2, 3] == pytest.approx(0.0325)


def test_a_tall_object_stays_clear_of_the_palm():
    # The palm 2 cm behind the tcp: a 6 cm cube is held with its top 5 mm below the palm.
    spec = GraspSpec(tcp_in_tip=SPEC.tcp_in_tip, finger_axis=SPEC.finger_axis, max_width=0.08, palm_depth=0.02)
    tcp, _ = grasp_tcp_pose(object_geometry(at(0.3, 0.0, 0.03), shape(SolidPrimitive.BOX, 0.06, 0.06, 0.06)), spec)
    assert tcp[2, 3] == pytest.approx(0.06 - 0.02 + spec.clearance)


def test_object_too_low_to_grip_is_refused():
    spec = GraspSpec(tcp_in_tip=SPEC.tcp_in_tip, finger_axis=SPEC.finger_axis, max_width=0.08, reach=0.03)
    with pytest.raises(SixdofCommanderError, match="too low for a top-down grasp"):
        grasp_tcp_pose(object_geometry(at(0.3, 0.0, 0.004), shape(SolidPrimitive.BOX, 0.03, 0.03, 0.008)), spec)
