"""The private wire-format helper _MessageCodec (used by sixdof_commander's _wire): a message class's objects to and
from ROS 1's serialized layout, described by (class, fields). Made here with plain slotted classes; sixdof_scripts'
test_wire compares it with genpy itself."""

from __future__ import annotations

import struct

import pytest

from sixdof_core._sixdof_core import _MessageCodec


class Made:
    """A class whose instances the codec makes: without __init__, every field set."""

    __slots__ = ()

    def __init__(self) -> None:
        raise AssertionError("the codec makes messages without __init__")


class Stamp(Made):
    __slots__ = ("secs", "nsecs")


class Wait(Made):
    __slots__ = ("secs", "nsecs")


class Point(Made):
    __slots__ = ("positions", "names", "flags", "blob", "time_from_start")


class Trajectory(Made):
    __slots__ = ("stamp", "count", "ratio", "name", "points", "fixed")


POINT = (
    Point,
    (
        ("positions", "float64", -1, None),
        ("names", "string", -1, None),
        ("flags", "bool", -1, None),
        ("blob", "uint8", -1, None),
        ("time_from_start", "duration", -2, Wait),
    ),
)
TRAJECTORY = (
    Trajectory,
    (
        ("stamp", "time", -2, Stamp),
        ("count", "int16", -2, None),
        ("ratio", "float32", -2, None),
        ("name", "string", -2, None),
        ("points", "message", -1, POINT),
        ("fixed", "int32", 2, None),
    ),
)


def string(text: str) -> bytes:
    data = text.encode()
    return struct.pack("<I", len(data)) + data


def point_bytes(positions, names, flags, blob, secs, nsecs) -> bytes:
    return (
        struct.pack(f"<I{len(positions)}d", len(positions), *positions)
        + struct.pack("<I", len(names))
        + b"".join(string(n) for n in names)
        + struct.pack(f"<I{len(flags)}B", len(flags), *flags)
        + struct.pack("<I", len(blob))
        + blob
        + struct.pack("<2i", secs, nsecs)
    )


DATA = (
    struct.pack("<2Ihf", 17, 999, -3, 0.5)
    + string("arm")
    + struct.pack("<I", 2)
    + point_bytes([0.5, -1.25], ["a", "bé"], [1, 0, 1], b"\x00\xff", 1, 250_000_000)
    + point_bytes([], [], [], b"", -2, -5)
    + struct.pack("<2i", 7, -8)
)


def test_messages_are_read_with_their_types():
    message = _MessageCodec(TRAJECTORY).decode(DATA)
    assert type(message) is Trajectory
    assert type(message.stamp) is Stamp and (message.stamp.secs, message.stamp.nsecs) == (17, 999)
    assert (message.count, message.ratio, message.name, message.fixed) == (-3, 0.5, "arm", (7, -8))
    assert type(message.points) is list and [type(p) for p in message.points] == [Point, Point]
    first, second = message.points
    assert first.positions == (0.5, -1.25) and type(first.positions) is tuple
    assert first.names == ["a", "bé"]
    assert first.flags == [True, False, True] and all(type(f) is bool for f in first.flags)
    assert first.blob == b"\x00\xff" and type(first.blob) is bytes
    assert type(first.time_from_start) is Wait
    assert (first.time_from_start.secs, first.time_from_start.nsecs) == (1, 250_000_000)
    assert (second.positions, second.names, second.flags, second.blob) == ((), [], [], b"")
    assert (second.time_from_start.secs, second.time_from_start.nsecs) == (-2, -5)


class LoggedStamp(Made):
    """Fields set through its own __setattr__, which the codec must call."""

    __slots__ = ("secs", "nsecs", "log")

    def __setattr__(self, name: str, value: object) -> None:
        if name != "log":
            if not hasattr(self, "log"):
                object.__setattr__(self, "log", [])
            self.log.append(name)
        object.__setattr__(self, name, value)


class Clamped(Made):
    """A field that is a property (not a slot): set through it."""

    __slots__ = ("_count", "name")

    @property
    def count(self) -> int:
        return self._count

    @count.setter
    def count(self, value: int) -> None:
        self._count = value * 10


def test_fields_that_are_not_plain_slots_are_set_through_setattr():
    stamp = _MessageCodec((LoggedStamp, (("secs", "uint32", -2, None), ("nsecs", "uint32", -2, None)))).decode(
        struct.pack("<2I", 3, 4)
    )
    assert (stamp.secs, stamp.nsecs, stamp.log) == (3, 4, ["secs", "nsecs"])
    clamped = _MessageCodec((Clamped, (("count", "int32", -2, None), ("name", "string", -2, None)))).decode(
        struct.pack("<i", 7) + string("x")
    )
    assert (clamped.count, clamped.name) == (70, "x")


def test_a_bool_is_any_byte_but_zero():
    codec = _MessageCodec(POINT)
    assert codec.decode(point_bytes([], [], [0, 1, 2, 255], b"", 0, 0)).flags == [False, True, True, True]


def test_any_buffer_is_read_and_bytes_beyond_the_message_are_not():
    codec = _MessageCodec(TRAJECTORY)
    for buffer in (bytearray(DATA), memoryview(DATA), DATA + b"tail"):
        assert codec.encode(codec.decode(buffer)) == DATA


def test_messages_are_written_back_to_the_same_bytes():
    codec = _MessageCodec(TRAJECTORY)
    assert codec.encode(codec.decode(DATA)) == DATA
    assert codec.type is Trajectory


def test_bytes_that_end_early_raise_value_error_naming_the_field_at_every_cut():
    codec = _MessageCodec(TRAJECTORY)
    for cut in range(len(DATA)):
        with pytest.raises(ValueError, match=r"(Trajectory|Point)\.\w+ needs \d+ bytes at offset \d+"):
            codec.decode(DATA[:cut])


def test_counts_beyond_the_bytes_raise_before_anything_is_sized_by_them():
    codec = _MessageCodec(POINT)
    with pytest.raises(ValueError, match=r"Point\.positions needs 34359738360 bytes"):
        codec.decode(struct.pack("<I", 0xFFFFFFFF) + bytes(64))
    with pytest.raises(ValueError, match=r"Point\.names needs"):
        codec.decode(struct.pack("<2I", 0, 0xFFFFFFFF) + bytes(64))


def test_a_string_that_is_not_utf8_raises_unicode_decode_error():
    codec = _MessageCodec((Stamp, (("secs", "string", -2, None), ("nsecs", "string", -2, None))))
    with pytest.raises(UnicodeDecodeError):
        codec.decode(string("a") + struct.pack("<I", 1) + b"\xff")


def values(**fields):
    message = Trajectory.__new__(Trajectory)
    point = Point.__new__(Point)
    point.positions, point.names, point.flags, point.blob = [1.0], ["x"], [True], [1, 2]
    point.time_from_start = Wait.__new__(Wait)
    point.time_from_start.secs, point.time_from_start.nsecs = 0, 5
    message.stamp = Stamp.__new__(Stamp)
    message.stamp.secs, message.stamp.nsecs = 1, 2
    message.count, message.ratio, message.name, message.points, message.fixed = 0, 0.0, "", [point], [1, 2]
    for name, value in fields.items():
        setattr(message, name, value)
    return message


def test_values_of_another_kind_raise_type_error_naming_the_field():
    codec = _MessageCodec(TRAJECTORY)
    assert codec.decode(codec.encode(values())).points[0].blob == b"\x01\x02"  # a list of ints is written as bytes
    for fields, where in [
        ({"count": 2**15}, r"Trajectory\.count is out of the type's range"),
        ({"count": 1.0}, r"Trajectory\.count is not an integer"),
        ({"ratio": 1e39}, r"Trajectory\.ratio is too large for a float32"),
        ({"ratio": "1"}, r"Trajectory\.ratio is not a float"),
        ({"name": b"arm"}, r"Trajectory\.name is not a str"),
        ({"fixed": [1]}, r"Trajectory\.fixed holds 1 values, not 2"),
        ({"points": 3}, r"Trajectory\.points has no length"),
        ({"points": [None]}, r"Trajectory\.points Point\.positions: no such attribute"),
        ({"stamp": None}, r"Trajectory\.stamp has no secs and nsecs"),
    ]:
        with pytest.raises(TypeError, match=where):
            codec.encode(values(**fields))
    message = values()
    message.points[0].blob = "text"
    with pytest.raises(TypeError, match=r"Point\.blob is neither bytes nor a list or tuple"):
        codec.encode(message)


def test_layouts_that_are_not_one_raise_naming_the_problem():
    with pytest.raises(ValueError, match="unknown kind 'float128'"):
        _MessageCodec((Stamp, (("secs", "float128", -2, None),)))
    with pytest.raises(TypeError, match="starts with its class"):
        _MessageCodec(("Stamp", ()))
    with pytest.raises(TypeError, match="names its class"):
        _MessageCodec((Stamp, (("secs", "time", -2, None),)))
    with pytest.raises(ValueError, match="count"):
        _MessageCodec((Stamp, (("secs", "int32", -3, None),)))
