"""ArmDriver's pure helpers (rad(), pose conversions) and the descriptions of failed calls."""

import math

import numpy as np
import pytest
from moveit_msgs.msg import MoveItErrorCodes
from sixdof_commander import ArmDriver, Gripper, MoveGroup, PlanningScene, SixdofCommanderError, rad
from sixdof_commander.arm_driver import matrix_from_pose
from sixdof_commander.error_reports import ERROR_NAMES, CallError, error_name
from sixdof_commander.goals import pose_stamped_from_target
from sixdof_commander.transforms import homogeneous, matrix_from_rpy, pose_from_matrix


def test_rad_returns_a_plain_list_of_radians():
    result = rad([-180.0, 0.688, 179.995])
    assert type(result) is list
    assert result == pytest.approx([-math.pi, math.radians(0.688), math.radians(179.995)])


def test_rad_concatenates_with_xyz_as_in_the_paper():
    xyz = [0.366, -0.000, 0.286]
    target = xyz + ArmDriver.rad([-180.000, 0.688, 179.995])
    assert len(target) == 6
    assert target[:3] == xyz
    pose_stamped_from_target(target, "base_link")


def test_rad_accepts_tuples_and_arrays():
    assert rad((90, 45)) == pytest.approx([math.pi / 2, math.pi / 4])
    assert rad(np.array([30.0])) == pytest.approx([math.pi / 6])


@pytest.mark.parametrize(
    ("value", "message"),
    [
        ("90", "list of angles"),
        (90, "list of angles"),
        ([float("nan")], "angle 0 must be finite"),
        ([0, "x"], "angle 1 must be a number"),
    ],
)
def test_rad_rejects_non_numbers(value, message):
    with pytest.raises(SixdofCommanderError, match=message):
        rad(value)


def test_pose_matrix_round_trip():
    matrix = homogeneous([0.1, -0.2, 0.3], matrix_from_rpy(0.4, -0.5, 2.9))
    np.testing.assert_allclose(matrix_from_pose(pose_from_matrix(matrix)), matrix, atol=1e-12)


def test_a_failed_call_is_described_by_its_code_name_and_words():
    error = CallError(MoveItErrorCodes.NO_IK_SOLUTION, "pose unreachable", "compute_ik")
    assert str(error) == "NO_IK_SOLUTION (-31): pose unreachable"
    assert (error.name, error.code) == ("NO_IK_SOLUTION", MoveItErrorCodes(val=-31))
    assert str(CallError(MoveItErrorCodes.SUCCESS)) == "SUCCESS (1)"
    assert str(CallError(12345)) == "unknown MoveIt error code 12345"


def test_every_moveit_error_code_has_its_name():
    # The constants of the message definition itself, one per line: "int32 NAME=value".
    constants = {}
    for line in MoveItErrorCodes._full_text.splitlines():
        words = line.split("#")[0].split()
        if len(words) == 2 and words[0] == "int32" and "=" in words[1]:
            name, value = words[1].split("=")
            constants[int(value)] = name
    assert len(constants) == 30  # moveit_msgs 0.11's codes
    assert ERROR_NAMES == constants
    assert error_name(MoveItErrorCodes.GOAL_IN_COLLISION) == "GOAL_IN_COLLISION"


@pytest.mark.parametrize("make", [lambda: MoveGroup("arm"), PlanningScene, Gripper])
def test_api_needs_an_initialised_node(make):
    with pytest.raises(SixdofCommanderError, match=r"rospy.init_node\(\) must be called"):
        make()


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"velocity_scaling": 0.0}, r"velocity_scaling must be in \(0, 1\]"),
        ({"acceleration_scaling": 1.5}, r"acceleration_scaling must be in \(0, 1\]"),
        ({"approach_distance": 0.0}, "approach_distance must be > 0"),
        ({"grasp_fix_timeout": -1.0}, "grasp_fix_timeout must be >= 0"),
    ],
)
def test_arm_driver_arguments_are_checked_before_connecting(kwargs, message):
    with pytest.raises(SixdofCommanderError, match=message):
        ArmDriver(**kwargs)
