"""Protocol 2.0 packets (ROBOTIS e-Manual, "DYNAMIXEL Protocol 2.0"): header FF FF FD 00, id, length (little endian,
the bytes after it), instruction, byte-stuffed parameters, CRC-16 (little endian)."""

from __future__ import annotations

from dataclasses import dataclass

HEADER = bytes([0xFF, 0xFF, 0xFD, 0x00])
BROADCAST_ID = 0xFE

PING = 0x01
READ = 0x02
WRITE = 0x03
REBOOT = 0x08
STATUS = 0x55
SYNC_READ = 0x82
SYNC_WRITE = 0x83

# The status packet's error field: the instruction's result in bits 0..6, the alert bit for a hardware error.
RESULT_FAIL = 0x01
INSTRUCTION_ERROR = 0x02
CRC_ERROR = 0x03
DATA_RANGE_ERROR = 0x04
DATA_LENGTH_ERROR = 0x05
DATA_LIMIT_ERROR = 0x06
ACCESS_ERROR = 0x07
ALERT = 0x80


def crc16(data: bytes) -> int:
    """CRC-16 with polynomial 0x8005, initial value 0, no reflection."""
    crc = 0
    for byte in data:
        crc ^= byte << 8
        for _ in range(8):
            crc = ((crc << 1) ^ 0x8005) if crc & 0x8000 else crc << 1
            crc &= 0xFFFF
    return crc


def stuff(body: bytes) -> bytes:
    """Inserts 0xFD after every FF FF FD (the instruction and parameter fields)."""
    out = bytearray()
    for byte in body:
        out.append(byte)
        if out[-3:] == b"\xff\xff\xfd":
            out.append(0xFD)
    return bytes(out)


def unstuff(body: bytes) -> bytes:
    """Drops the 0xFD that follows every FF FF FD."""
    out = bytearray()
    i = 0
    while i < len(body):
        out.append(body[i])
        if out[-3:] == b"\xff\xff\xfd" and body[i + 1 : i + 2] == b"\xfd":
            i += 1
        i += 1
    return bytes(out)


def _packet(servo_id: int, body: bytes) -> bytes:
    body = stuff(body)
    packet = HEADER + bytes([servo_id]) + (len(body) + 2).to_bytes(2, "little") + body
    return packet + crc16(packet).to_bytes(2, "little")


def instruction_packet(servo_id: int, instruction: int, parameters: bytes = b"") -> bytes:
    return _packet(servo_id, bytes([instruction]) + parameters)


def status_packet(servo_id: int, error: int, parameters: bytes = b"") -> bytes:
    return _packet(servo_id, bytes([STATUS, error]) + parameters)


@dataclass
class Packet:
    """A received packet: its id, instruction (or STATUS) and unstuffed parameters; crc_ok False for a bad CRC."""

    servo_id: int
    instruction: int
    parameters: bytes
    crc_ok: bool = True


def take_packet(buffer: bytearray) -> Packet | None:
    """Removes the first complete packet (and any garbage before it) from the buffer; None while incomplete."""
    start = buffer.find(HEADER)
    if start < 0:
        del buffer[: max(0, len(buffer) - 3)]
        return None
    del buffer[:start]
    if len(buffer) < 7:
        return None
    length = int.from_bytes(buffer[5:7], "little")
    if len(buffer) < 7 + length:
        return None
    raw = bytes(buffer[: 7 + length])
    del buffer[: 7 + length]
    if length < 3:
        return Packet(raw[4], 0, b"", crc_ok=False)
    crc_ok = crc16(raw[:-2]) == int.from_bytes(raw[-2:], "little")
    body = unstuff(raw[7:-2])
    return Packet(raw[4], body[0] if body else 0, body[1:], crc_ok)
