"""The private wire-format helper _decode_trajectory_points (used by sixdof_commander's decoder of plan answers):
the points of a serialized trajectory_msgs/JointTrajectory as objects of the given classes, ValueError for bytes
that end early. sixdof_scripts' test_plan_response compares it with genpy itself."""

from __future__ import annotations

import struct

import pytest

from sixdof_core._sixdof_core import _decode_trajectory_points


class Point:
    __slots__ = ("positions", "velocities", "accelerations", "effort", "time_from_start")

    def __init__(self) -> None:
        raise AssertionError("the helper makes points without __init__")


class Duration:
    __slots__ = ("secs", "nsecs")

    def __init__(self) -> None:
        raise AssertionError("the helper makes durations without __init__")


def float64s(values: list[float]) -> bytes:
    return struct.pack(f"<I{len(values)}d", len(values), *values)


def points_bytes(points: list[tuple[list[float], list[float], list[float], list[float], int, int]]) -> bytes:
    data = struct.pack("<I", len(points))
    for positions, velocities, accelerations, effort, secs, nsecs in points:
        data += float64s(positions) + float64s(velocities) + float64s(accelerations) + float64s(effort)
        data += struct.pack("<2i", secs, nsecs)
    return data


POINTS = [
    ([0.5, -1.25, 3.0], [0.0, 0.1, -0.2], [], [], 0, 0),
    ([1.5, float("inf"), -0.0], [], [7.0], [1.0, 2.0], 1, 250_000_000),
    ([], [], [], [], -2, -5),
]


def test_points_are_read_with_their_types_and_the_offset_after_them():
    prefix, suffix = b"\x07" * 13, b"tail"
    data = prefix + points_bytes(POINTS) + suffix
    points, end = _decode_trajectory_points(data, len(prefix), Point, Duration)
    assert end == len(data) - len(suffix)
    assert [type(p) for p in points] == [Point] * len(POINTS)
    for point, (positions, velocities, accelerations, effort, secs, nsecs) in zip(points, POINTS, strict=True):
        assert point.positions == tuple(positions)
        assert point.velocities == tuple(velocities)
        assert point.accelerations == tuple(accelerations)
        assert point.effort == tuple(effort)
        for values in (point.positions, point.velocities, point.accelerations, point.effort):
            assert type(values) is tuple
            assert all(type(v) is float for v in values)
        assert type(point.time_from_start) is Duration
        assert (point.time_from_start.secs, point.time_from_start.nsecs) == (secs, nsecs)
        assert type(point.time_from_start.secs) is int


def test_no_points_and_any_buffer():
    assert _decode_trajectory_points(struct.pack("<I", 0), 0, Point, Duration) == ([], 4)
    data = points_bytes(POINTS)
    for buffer in (bytearray(data), memoryview(data)):
        points, end = _decode_trajectory_points(buffer, 0, Point, Duration)
        assert (len(points), end) == (len(POINTS), len(data))


def test_bytes_that_end_early_raise_value_error_at_every_cut():
    data = points_bytes(POINTS)
    for cut in range(len(data)):
        with pytest.raises(ValueError):
            _decode_trajectory_points(data[:cut], 0, Point, Duration)


def test_lengths_beyond_the_buffer_raise_value_error():
    huge_count = struct.pack("<I", 0xFFFFFFFF) + points_bytes(POINTS)[4:]
    with pytest.raises(ValueError, match="the points"):
        _decode_trajectory_points(huge_count, 0, Point, Duration)
    huge_array = struct.pack("<2I", 1, 0xFFFFFFFF) + bytes(64)
    with pytest.raises(ValueError, match="float64"):
        _decode_trajectory_points(huge_array, 0, Point, Duration)
    with pytest.raises(ValueError, match="offset"):
        _decode_trajectory_points(b"\0" * 4, 5, Point, Duration)


def test_a_class_without_the_fields_raises_attribute_error():
    class Other:
        __slots__ = ("positions",)

    with pytest.raises(AttributeError):
        _decode_trajectory_points(points_bytes(POINTS), 0, Other, Duration)
