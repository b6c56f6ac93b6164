"""ROS messages to and from their bytes on the wire, as genpy's generated (de)serializers write and read them, by
sixdof_core's private C++ codec `_MessageCodec`.

genpy's deserializer builds every nested message through its constructor (which checks every keyword and fills in
defaults that are then replaced) and slices the buffer per field; for a planned trajectory (~70 points) that costs
more than the rest of a plan() call's client side together. The codec reads and writes the same layout from a
description of the message class made once here from genpy's own slots (`__slots__`, `_slot_types`), and makes
the same objects: every message made without __init__ and every field set, float and integer arrays as tuples,
uint8[] as bytes, bool[] and string[] and message arrays as lists, genpy.Time and genpy.Duration as read (a
message's own time fields then normalized, as genpy does).

What the codec does not read or write as genpy would goes to genpy itself, so the outcome is genpy's in every case:
bytes that end early (genpy.DeserializationError) or hold a string that is not UTF-8 (genpy replaces the bytes and
logs once); a value of another type, a number out of its type's range, a fixed-length array of another length
(genpy's errors, or its padding of fixed-length bytes).
"""

from __future__ import annotations

import functools
import io

import genpy

from sixdof_core._sixdof_core import _MessageCodec

# ROS's primitive types by the codec's names (char and byte are ROS 1's aliases of uint8 and int8).
_KINDS = {
    "bool": "bool",
    "int8": "int8",
    "byte": "int8",
    "uint8": "uint8",
    "char": "uint8",
    "int16": "int16",
    "uint16": "uint16",
    "int32": "int32",
    "uint32": "uint32",
    "int64": "int64",
    "uint64": "uint64",
    "float32": "float32",
    "float64": "float64",
    "string": "string",
    "time": "time",
    "duration": "duration",
}
_TIME_CLASSES = {"time": genpy.Time, "duration": genpy.Duration}
_SCALAR, _VARIABLE = -2, -1


def _parse(slot_type: str) -> tuple[str, int]:
    """A slot type's base type and count (_SCALAR, _VARIABLE or the fixed length): 'float64[]' -> ('float64', -1)."""
    if not slot_type.endswith("]"):
        return slot_type, _SCALAR
    base, _, length = slot_type[:-1].partition("[")
    return base, int(length) if length else _VARIABLE


def _layout(message_class: type) -> tuple:
    """The codec's description of message_class: (class, ((name, kind, count, sub), ...))."""
    fields = []
    for name, slot_type in zip(message_class.__slots__, message_class._slot_types, strict=True):
        base, count = _parse(slot_type)
        kind = _KINDS.get(base)
        if kind is None:
            nested = genpy.message.get_message_class(base)
            if nested is None:
                raise ValueError(f"{message_class._type}.{name}: no message class {base} is installed")
            fields.append((name, "message", count, _layout(nested)))
        else:
            fields.append((name, kind, count, _TIME_CLASSES.get(kind)))
    return message_class, tuple(fields)


class WireCodec:
    """A message class's objects to and from their serialized bytes (without TCPROS's length before them), with
    genpy's outcome for every input."""

    def __init__(self, message_class: type) -> None:
        self.message_class = message_class
        self._codec = _MessageCodec(_layout(message_class))
        # genpy's deserializer normalizes the message's own time and duration fields (not nested ones).
        self._own_times = [
            name
            for name, slot_type in zip(message_class.__slots__, message_class._slot_types, strict=True)
            if slot_type in _TIME_CLASSES
        ]

    def decode(self, data: bytes) -> genpy.Message:
        """The message serialized in data, as message_class().deserialize(data) gives it (and raises)."""
        try:
            message = self._codec.decode(data)
        except ValueError:  # bytes that end early, or a string that is not UTF-8 (UnicodeDecodeError)
            return self.message_class().deserialize(data)
        for name in self._own_times:
            getattr(message, name).canon()
        return message

    def encode(self, message: genpy.Message) -> bytes:
        """message's bytes, as message.serialize() writes them (and raises)."""
        if type(message) is self.message_class:
            try:
                return self._codec.encode(message)
            except TypeError:  # a value the codec does not write as genpy would
                pass
        buffer = io.BytesIO()
        message.serialize(buffer)
        return buffer.getvalue()


@functools.cache
def codec(message_class: type) -> WireCodec:
    """The WireCodec of message_class (made once per class)."""
    return WireCodec(message_class)
