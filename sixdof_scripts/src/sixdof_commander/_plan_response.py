"""A fast decoder of plan_kinematic_path's answer (moveit_msgs/GetMotionPlan's response) from its bytes on the wire.

genpy's generated deserializer builds every trajectory point through the message constructors, a struct per array
and a slice of the buffer per field, which costs more than the rest of the answer together. This decoder reads the
answer's fields in order and builds the same message objects without genpy's constructors (which check every
keyword), field for field the values and types genpy gives (tuples for float64[], lists for string[] and message
arrays, genpy.Time and genpy.Duration). The trajectory's points, most of the answer, are read in C++ by sixdof_core's
private wire-format helper `_decode_trajectory_points`. It reads the answers move_group gives: a start state without
multi-DOF joints or attached objects, and a trajectory without multi-DOF points. Any other answer (or bytes that do
not parse) is decoded by genpy itself.
"""

from __future__ import annotations

import struct

import genpy
from moveit_msgs.msg import MotionPlanResponse, MoveItErrorCodes, RobotState, RobotTrajectory
from moveit_msgs.srv import GetMotionPlanResponse
from sensor_msgs.msg import JointState, MultiDOFJointState
from std_msgs.msg import Header
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint, MultiDOFJointTrajectory

from sixdof_core._sixdof_core import _decode_trajectory_points

_U32 = struct.Struct("<I")
_HEADER = struct.Struct("<3I")
_TAIL = struct.Struct("<di")  # planning_time, error_code.val


class _UnusualAnswerError(Exception):
    """The bytes are not an answer of the shape this decoder reads."""


class _Reader:
    """Reads the fields of a serialized message in order."""

    __slots__ = ("data", "at")

    def __init__(self, data: bytes) -> None:
        self.data = data
        self.at = 0

    def u32(self) -> int:
        (value,) = _U32.unpack_from(self.data, self.at)
        self.at += 4
        return value

    def string(self) -> str:
        size = self.u32()
        end = self.at + size
        if end > len(self.data):
            raise _UnusualAnswerError
        value = self.data[self.at : end].decode("utf-8")
        self.at = end
        return value

    def strings(self) -> list[str]:
        return [self.string() for _ in range(self.u32())]

    def float64s(self) -> tuple[float, ...]:
        count = self.u32()
        values = struct.unpack_from(f"<{count}d", self.data, self.at)
        self.at += 8 * count
        return values

    def header(self) -> Header:
        seq, secs, nsecs = _HEADER.unpack_from(self.data, self.at)
        self.at += 12
        return _message(Header, seq=seq, stamp=_stamp(genpy.Time, secs, nsecs), frame_id=self.string())

    def empty(self) -> None:
        """An array that must be empty (a shape this decoder does not read otherwise)."""
        if self.u32():
            raise _UnusualAnswerError


def _message(kind: type, **fields: object) -> genpy.Message:
    """A message of type `kind` holding `fields` (every field of the type), made without genpy's constructor, which
    checks each keyword and fills in defaults."""
    msg = kind.__new__(kind)
    for name, value in fields.items():
        setattr(msg, name, value)
    return msg


def _stamp(kind: type, secs: int, nsecs: int) -> genpy.TVal:
    """A genpy.Time or genpy.Duration holding the values as read (genpy's deserializers do not normalize them)."""
    value = kind.__new__(kind)
    value.secs = secs
    value.nsecs = nsecs
    return value


def _points(reader: _Reader) -> list[JointTrajectoryPoint]:
    """The trajectory's points, read in C++ (sixdof_core's wire-format helper); ValueError for bytes that end early."""
    points, reader.at = _decode_trajectory_points(reader.data, reader.at, JointTrajectoryPoint, genpy.Duration)
    return points


def _decode(reader: _Reader) -> GetMotionPlanResponse:
    joint_state = _message(
        JointState,
        header=reader.header(),
        name=reader.strings(),
        position=reader.float64s(),
        velocity=reader.float64s(),
        effort=reader.float64s(),
    )
    multi_dof_header = reader.header()
    for _ in range(4):  # joint_names, transforms, twist, wrench
        reader.empty()
    reader.empty()  # attached_collision_objects
    is_diff = bool(reader.data[reader.at])
    reader.at += 1
    start = _message(
        RobotState,
        joint_state=joint_state,
        multi_dof_joint_state=_message(
            MultiDOFJointState, header=multi_dof_header, joint_names=[], transforms=[], twist=[], wrench=[]
        ),
        attached_collision_objects=[],
        is_diff=is_diff,
    )
    group_name = reader.string()
    joint_trajectory = _message(
        JointTrajectory, header=reader.header(), joint_names=reader.strings(), points=_points(reader)
    )
    multi_dof = _message(MultiDOFJointTrajectory, header=reader.header(), joint_names=reader.strings(), points=[])
    reader.empty()  # multi_dof_joint_trajectory.points
    planning_time, code = _TAIL.unpack_from(reader.data, reader.at)
    if reader.at + _TAIL.size != len(reader.data):
        raise _UnusualAnswerError
    return _message(
        GetMotionPlanResponse,
        motion_plan_response=_message(
            MotionPlanResponse,
            trajectory_start=start,
            group_name=group_name,
            trajectory=_message(
                RobotTrajectory, joint_trajectory=joint_trajectory, multi_dof_joint_trajectory=multi_dof
            ),
            planning_time=planning_time,
            error_code=_message(MoveItErrorCodes, val=code),
        ),
    )


def decode_plan_response(data: bytes) -> GetMotionPlanResponse:
    """The GetMotionPlan response serialized in `data`, as genpy's deserialize gives it (genpy.DeserializationError
    when the bytes are not one)."""
    try:
        return _decode(_Reader(data))
    except (_UnusualAnswerError, struct.error, IndexError, ValueError):  # UnicodeDecodeError is a ValueError
        return GetMotionPlanResponse().deserialize(data)
