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
