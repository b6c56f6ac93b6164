"""_wire's codecs read and write what genpy reads and writes: the same objects field for field and type for type, the
same bytes, and genpy's own outcome (its values or its errors) for every input the C++ codec does not take."""

from __future__ import annotations

import io
import math
import random

import genpy
import genpy.dynamic
import numpy as np
import pytest
import rospy
from geometry_msgs.msg import Transform
from moveit_msgs.msg import AttachedCollisionObject, MoveItErrorCodes, PlanningScene
from moveit_msgs.srv import (
    GetCartesianPathRequest,
    GetCartesianPathResponse,
    GetMotionPlanRequest,
    GetMotionPlanResponse,
    GetPositionIKRequest,
    GetPositionIKResponse,
)
from sensor_msgs.msg import CameraInfo, PointCloud2
from sixdof_commander import _wire
from sixdof_commander._wire import WireCodec, codec
from std_msgs.msg import Duration as DurationMsg
from std_msgs.msg import Time as TimeMsg
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint, MultiDOFJointTrajectoryPoint
from visualization_msgs.msg import MarkerArray

# A message with a field of every kind in every shape (genpy.dynamic builds its class as genpy's generator does).
EVERY_KIND = """
bool a_bool
int8 an_int8
uint8 a_uint8
char a_char
byte a_byte
int16 an_int16
uint16 a_uint16
int32 an_int32
uint32 a_uint32
int64 an_int64
uint64 a_uint64
float32 a_float32
float64 a_float64
string a_string
time a_time
duration a_duration
Part a_part
bool[] bools
int8[] int8s
uint8[] uint8s
char[] chars
int16[] int16s
uint16[] uint16s
int32[] int32s
uint32[] uint32s
int64[] int64s
uint64[] uint64s
float32[] float32s
float64[] float64s
string[] strings
time[] times
duration[] durations
Part[] parts
bool[2] two_bools
uint8[3] three_uint8s
int16[2] two_int16s
float64[3] three_float64s
string[2] two_strings
time[2] two_times
Part[2] two_parts
================================================================================
MSG: test_wire/Part
string name
float32[] values
duration[] waits
"""
DYNAMIC = genpy.dynamic.generate_dynamic("test_wire/EveryKind", EVERY_KIND)
EveryKind = DYNAMIC["test_wire/EveryKind"]
# Found by name as the classes of installed packages are (genpy.message.get_message_class, whose cache this is).
genpy.message._message_class_cache.update(DYNAMIC)

INTEGER_RANGES = {
    "int8": (-(2**7), 2**7 - 1),
    "byte": (-(2**7), 2**7 - 1),
    "uint8": (0, 2**8 - 1),
    "char": (0, 2**8 - 1),
    "int16": (-(2**15), 2**15 - 1),
    "uint16": (0, 2**16 - 1),
    "int32": (-(2**31), 2**31 - 1),
    "uint32": (0, 2**32 - 1),
    "int64": (-(2**63), 2**63 - 1),
    "uint64": (0, 2**64 - 1),
}


def random_value(slot_type: str, rng: random.Random) -> object:
    """A random value genpy serializes for a field of slot_type (as a user would set it: lists for arrays)."""
    base, count = _wire._parse(slot_type)
    if count != _wire._SCALAR:
        size = rng.randint(0, 4) if count == _wire._VARIABLE else count
        if base in ("uint8", "char"):
            return bytes(rng.randint(0, 255) for _ in range(size))
        return [random_value(base, rng) for _ in range(size)]
    if base == "bool":
        return rng.random() < 0.5
    if base in INTEGER_RANGES:
        return rng.randint(*INTEGER_RANGES[base])
    if base == "float32":
        return float(np.float32(rng.uniform(-1e6, 1e6)))
    if base == "float64":
        return rng.choice([rng.uniform(-1e9, 1e9), 0.0, -0.0, math.inf, 5e-324])
    if base == "string":
        return rng.choice(["", "arm", "übung", "joint_" * rng.randint(1, 5)])
    if base == "time":
        return genpy.Time(rng.randint(0, 2**32 - 1), rng.randint(0, 999_999_999))
    if base == "duration":
        return genpy.Duration(rng.randint(-(2**31), 2**31 - 1), rng.randint(-999_999_999, 999_999_999))
    return random_message(genpy.message.get_message_class(base), rng)


def random_message(message_class: type, rng: random.Random) -> genpy.Message:
    return message_class(
        **{
            name: random_value(slot_type, rng)
            for name, slot_type in zip(message_class.__slots__, message_class._slot_types, strict=True)
        }
    )


def wire(msg: genpy.Message) -> bytes:
    buffer = io.BytesIO()
    msg.serialize(buffer)
    return buffer.getvalue()


def assert_same_objects(got: object, want: object, where: str = "") -> None:
    """got and want are equal and of the same type, down to every field and element."""
    assert type(got) is type(want), f"{where}: {type(got).__name__} is not {type(want).__name__}"
    if isinstance(want, genpy.Message):
        for name in want.__slots__:
            assert_same_objects(getattr(got, name), getattr(want, name), f"{where}.{name}")
    elif isinstance(want, genpy.TVal):
        assert (got.secs, got.nsecs) == (want.secs, want.nsecs), where
    elif isinstance(want, list | tuple):
        assert len(got) == len(want), where
        for i, (a, b) in enumerate(zip(got, want, strict=True)):
            assert_same_objects(a, b, f"{where}[{i}]")
    elif isinstance(want, float) and math.isnan(want):
        assert math.isnan(got), where
    else:
        assert got == want, where


def assert_as_genpy(message_class: type, data: bytes) -> None:
    """The codec decodes data to what genpy gives (or raises genpy's error), and writes it back as genpy does."""
    try:
        want = message_class().deserialize(data)
    except genpy.DeserializationError:
        with pytest.raises(genpy.DeserializationError):
            codec(message_class).decode(data)
        return
    got = codec(message_class).decode(data)
    assert_same_objects(got, want)
    assert codec(message_class).encode(got) == wire(want)


CLASSES = [
    EveryKind,
    GetMotionPlanRequest,
    GetMotionPlanResponse,
    GetPositionIKRequest,
    GetPositionIKResponse,
    GetCartesianPathRequest,
    GetCartesianPathResponse,
    PlanningScene,
    PointCloud2,
    CameraInfo,
    MarkerArray,
    TimeMsg,
    DurationMsg,
]


@pytest.mark.parametrize("message_class", CLASSES, ids=lambda c: c._type)
def test_random_messages_of_every_kind_read_and_write_as_genpy_does(message_class):
    rng = random.Random(7)
    for _ in range(25):
        msg = random_message(message_class, rng)
        data = wire(msg)
        assert codec(message_class).encode(msg) == data
        assert_as_genpy(message_class, data)


def test_the_codec_reads_and_writes_in_cpp():
    msg = random_message(EveryKind, random.Random(3))
    data = wire(msg)
    assert codec(EveryKind)._codec.encode(msg) == data  # no genpy fallback taken
    assert_same_objects(codec(EveryKind)._codec.decode(data), EveryKind().deserialize(data))


def test_a_messages_own_times_are_normalized_as_genpy_does_and_nested_ones_kept_as_read():
    data = (5).to_bytes(4, "little") + (2_500_000_000).to_bytes(4, "little")  # nsecs over a second
    got = codec(TimeMsg).decode(data)
    assert_same_objects(got, TimeMsg().deserialize(data))
    assert (got.data.secs, got.data.nsecs) == (7, 500_000_000)
    point = JointTrajectoryPoint(time_from_start=genpy.Duration(0, 0))
    point.time_from_start.nsecs = 1_500_000_000
    data = wire(JointTrajectory(points=[point]))
    got = codec(JointTrajectory).decode(data)
    assert got.points[0].time_from_start.nsecs == 1_500_000_000
    assert_same_objects(got, JointTrajectory().deserialize(data))


def plan_answer(points: int, joints: int = 6, seed: int = 1) -> GetMotionPlanResponse:
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


@pytest.mark.parametrize("points", [0, 1, 62, 500])
def test_plans_read_as_genpy_reads_them(points):
    assert_as_genpy(GetMotionPlanResponse, wire(plan_answer(points)))


def test_multi_dof_parts_and_attached_objects_read_as_genpy_reads_them():
    msg = plan_answer(3)
    response = msg.motion_plan_response
    response.trajectory_start.attached_collision_objects.append(AttachedCollisionObject(link_name="tcp"))
    response.trajectory_start.multi_dof_joint_state.joint_names = ["base"]
    response.trajectory_start.multi_dof_joint_state.transforms = [Transform()]
    response.trajectory.multi_dof_joint_trajectory.joint_names = ["base"]
    response.trajectory.multi_dof_joint_trajectory.points.append(MultiDOFJointTrajectoryPoint(transforms=[Transform()]))
    assert_as_genpy(GetMotionPlanResponse, wire(msg))


def test_bytes_cut_anywhere_or_extended_read_or_raise_as_genpy_does():
    data = wire(random_message(EveryKind, random.Random(5)))
    for cut in range(1, len(data) + 1):
        assert_as_genpy(EveryKind, data[:-cut])
    assert_as_genpy(EveryKind, data + b"extra")  # genpy reads no further than the message
    plan = wire(plan_answer(3))
    for cut in range(1, len(plan) + 1, 7):
        assert_as_genpy(GetMotionPlanResponse, plan[:-cut])


def test_counts_beyond_the_bytes_raise_as_genpy_raises():
    data = bytearray(wire(plan_answer(3)))
    points_count = data.index(b"joint6", data.index(b"joint6") + 1) + len(b"joint6")
    data[points_count : points_count + 4] = (2**32 - 1).to_bytes(4, "little")
    assert_as_genpy(GetMotionPlanResponse, bytes(data))


def test_a_string_that_is_not_utf8_is_replaced_as_genpy_replaces_it():
    msg = plan_answer(1)
    msg.motion_plan_response.group_name = "a" * 7
    data = wire(msg).replace(b"aaaaaaa", b"a\xffa\xfeaaa")
    assert_as_genpy(GetMotionPlanResponse, data)
    assert codec(GetMotionPlanResponse).decode(data).motion_plan_response.group_name == "a\ufffda\ufffdaaa"


NEGATIVE_TIME = genpy.Time()
NEGATIVE_TIME.secs = -1  # out of a time's uint32 (genpy.Time's constructor refuses it)


def same_outcome_as_genpy(msg: genpy.Message) -> None:
    """encode(msg) gives genpy's bytes, or raises what genpy raises."""
    try:
        want = wire(msg)
    except Exception as err:  # genpy's error, whatever it is
        with pytest.raises(type(err)):
            codec(type(msg)).encode(msg)
        return
    assert codec(type(msg)).encode(msg) == want


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("a_float64", "1.0"),
        ("a_float64", None),
        ("a_float64", 3),  # an int where a float goes: struct.pack takes it
        ("a_float64", np.float32(0.1)),
        ("a_float32", 1e39),  # too large for a float32
        ("a_float32", math.inf),
        ("an_int8", 128),
        ("a_uint8", -1),
        ("an_int32", 2.0),
        ("an_int32", np.int64(-5)),
        ("a_uint64", 2**64),
        ("an_int64", -(2**63) - 1),
        ("a_bool", 2),  # written as the byte 2, as genpy writes it
        ("a_string", b"bytes"),
        ("a_string", "\ud800"),  # a lone surrogate: not encodable
        ("float64s", np.array([1.0, 2.5])),
        ("float64s", (x / 3 for x in range(3))),  # no length
        ("int32s", [1, 2.5]),
        ("uint8s", [1, 2, 300]),
        ("uint8s", [1, 2, 3]),
        ("uint8s", bytearray(b"abc")),
        ("uint8s", "text"),
        ("three_uint8s", b"ab"),  # genpy pads fixed-length bytes
        ("three_uint8s", b"abcd"),  # and cuts them
        ("three_float64s", [1.0, 2.0]),
        ("two_strings", ["a"]),
        ("two_parts", []),
        ("a_time", rospy.Time(3, 4)),
        ("a_time", NEGATIVE_TIME),
        ("a_duration", 1.5),
        ("a_part", None),
        ("parts", [None]),
        ("a_part", TimeMsg()),
    ],
)
def test_values_genpy_writes_or_refuses_have_genpys_outcome(field, value):
    msg = random_message(EveryKind, random.Random(11))
    setattr(msg, field, value)
    same_outcome_as_genpy(msg)


def test_a_message_of_another_class_is_written_by_its_own_serializer():
    point = JointTrajectoryPoint(positions=[1.0])
    assert codec(MultiDOFJointTrajectoryPoint).encode(point) == wire(point)


def test_each_class_has_one_codec():
    assert codec(GetMotionPlanResponse) is codec(GetMotionPlanResponse)
    assert isinstance(codec(GetMotionPlanResponse), WireCodec)
