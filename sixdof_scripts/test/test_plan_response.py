"""The fast decoder of plan_kinematic_path's answer gives what genpy's deserializer gives, field for field and type
for type, for the answers it reads and (through genpy) for every other one."""

import io
import random

import genpy
import pytest
from geometry_msgs.msg import Transform
from moveit_msgs.msg import AttachedCollisionObject, MoveItErrorCodes
from moveit_msgs.srv import GetMotionPlanResponse
from sixdof_commander._plan_response import decode_plan_response
from trajectory_msgs.msg import JointTrajectoryPoint, MultiDOFJointTrajectoryPoint


def answer(points: int, joints: int = 6, seed: int = 1) -> GetMotionPlanResponse:
    """An answer as move_group gives it: a start state and a timed trajectory of `points` points."""
    rng = random.Random(seed)
    names = [f"joint{i}" for i in range(1, joints + 1)]
    msg = GetMotionPlanResponse()
    response = msg.motion_plan_response
    start = response.trajectory_start.joint_state
    start.header.frame_id = "base_link"
    start.header.stamp = genpy.Time(12, 345)
    start.name = names + ["finger_joint"]
    start.position = [rng.uniform(-3, 3) for _ in start.name]
    response.group_name = "arm"
    trajectory = response.trajectory.joint_trajectory
    trajectory.header.frame_id = "base_link"
    trajectory.joint_names = names
    for i in range(points):
        trajectory.points.append(
            JointTrajectoryPoint(
                positions=[rng.uniform(-3, 3) for _ in names],
                velocities=[rng.uniform(-1, 1) for _ in names],
                accelerations=[rng.uniform(-1, 1) for _ in names],
                time_from_start=genpy.Duration(i // 10, (i % 10) * 100_000_000),
            )
        )
    response.planning_time = 0.000412
    response.error_code.val = MoveItErrorCodes.SUCCESS
    return msg


def wire(msg: GetMotionPlanResponse) -> bytes:
    buffer = io.BytesIO()
    msg.serialize(buffer)
    return buffer.getvalue()


def assert_same(decoded: GetMotionPlanResponse, data: bytes) -> None:
    expected = GetMotionPlanResponse().deserialize(data)
    assert decoded == expected
    points = decoded.motion_plan_response.trajectory.joint_trajectory.points
    for got, want in zip(points, expected.motion_plan_response.trajectory.joint_trajectory.points, strict=True):
        for field in JointTrajectoryPoint.__slots__:
            assert type(getattr(got, field)) is type(getattr(want, field)), field
    assert wire(decoded) == data


@pytest.mark.parametrize("points", [0, 1, 2, 62, 500])
def test_a_plan_decodes_as_genpy_decodes_it(points):
    data = wire(answer(points))
    assert_same(decode_plan_response(data), data)


def test_a_failed_plan_decodes_as_genpy_decodes_it():
    msg = GetMotionPlanResponse()
    msg.motion_plan_response.error_code.val = MoveItErrorCodes.GOAL_IN_COLLISION
    data = wire(msg)
    assert_same(decode_plan_response(data), data)


def test_points_of_different_shapes_decode_as_genpy_decodes_them():
    msg = answer(5)
    points = msg.motion_plan_response.trajectory.joint_trajectory.points
    points[3].velocities = []
    points[4].effort = [1.0] * 6
    data = wire(msg)
    assert_same(decode_plan_response(data), data)


def test_multi_dof_parts_and_attached_objects_decode_as_genpy_decodes_them():
    msg = answer(3)
    response = msg.motion_plan_response
    response.trajectory_start.attached_collision_objects.append(AttachedCollisionObject(link_name="tcp"))
    response.trajectory_start.multi_dof_joint_state.joint_names = ["base"]
    response.trajectory_start.multi_dof_joint_state.transforms = [Transform()]
    response.trajectory.multi_dof_joint_trajectory.joint_names = ["base"]
    response.trajectory.multi_dof_joint_trajectory.points.append(MultiDOFJointTrajectoryPoint(transforms=[Transform()]))
    data = wire(msg)
    assert_same(decode_plan_response(data), data)


@pytest.mark.parametrize("cut", [1, 9, 200])
def test_truncated_bytes_raise_as_genpy_raises(cut):
    data = wire(answer(4))[:-cut]
    with pytest.raises(genpy.DeserializationError):
        decode_plan_response(data)


def decodes_as_genpy(data: bytes) -> None:
    """decode_plan_response(data) gives what genpy gives, or raises genpy.DeserializationError as genpy does."""
    try:
        GetMotionPlanResponse().deserialize(data)
    except genpy.DeserializationError:
        with pytest.raises(genpy.DeserializationError):
            decode_plan_response(data)
        return
    decoded = decode_plan_response(data)
    expected = GetMotionPlanResponse().deserialize(data)
    assert decoded == expected


def test_negative_and_large_durations_and_odd_values_decode_as_genpy_decodes_them():
    msg = answer(4)
    points = msg.motion_plan_response.trajectory.joint_trajectory.points
    points[0].time_from_start = genpy.Duration(-3, -7)  # genpy keeps the values as read
    points[1].time_from_start = genpy.Duration(2**31 - 1, 999_999_999)
    points[2].positions = [float("inf"), -0.0, 1e-308, -1e308, 0.0, 5e-324]
    points[3].accelerations = []
    data = wire(msg)
    assert_same(decode_plan_response(data), data)


def test_bytes_cut_anywhere_in_the_points_decode_or_raise_as_genpy_does():
    data = wire(answer(3))
    for cut in range(1, 3 * (4 * 4 + 3 * 6 * 8 + 8) + 30):
        decodes_as_genpy(data[:-cut])


def test_odd_bytes_fall_back_to_genpy():
    data = wire(answer(3))
    decodes_as_genpy(data + b"extra")  # genpy reads no further than the message
    trajectory_points = data.index(b"joint6", data.index(b"joint6") + 1) + len(b"joint6")
    too_many = bytearray(data)
    too_many[trajectory_points : trajectory_points + 4] = (1000).to_bytes(4, "little")
    decodes_as_genpy(bytes(too_many))


def test_the_points_are_read_by_the_wire_format_helper_and_its_errors_fall_back_to_genpy(monkeypatch):
    from sixdof_commander import _plan_response

    calls = []
    helper = _plan_response._decode_trajectory_points

    def spy(*args):
        calls.append(args[2:])
        return helper(*args)

    monkeypatch.setattr(_plan_response, "_decode_trajectory_points", spy)
    data = wire(answer(5))
    assert_same(decode_plan_response(data), data)
    assert calls == [(JointTrajectoryPoint, genpy.Duration)]

    def failing(*args):
        raise ValueError("bytes end early")

    monkeypatch.setattr(_plan_response, "_decode_trajectory_points", failing)
    assert_same(decode_plan_response(data), data)
