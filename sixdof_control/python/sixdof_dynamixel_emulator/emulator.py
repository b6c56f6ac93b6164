"""Servos with an X series control table on an emulated Protocol 2.0 bus, served on a pseudo-terminal."""

from __future__ import annotations

import math
import os
import select
import threading
import time
import tty

from sixdof_dynamixel_emulator import protocol as p

# X series control table (XM430-W350): the addresses the emulator models.
MODEL_NUMBER = 0  # 2 bytes
FIRMWARE_VERSION = 6
ID = 7
OPERATING_MODE = 11
TORQUE_ENABLE = 64  # RAM starts here; EEPROM (below) is writable only with the torque off
HARDWARE_ERROR_STATUS = 70
GOAL_POSITION = 116  # 4 bytes
MOVING = 122
PRESENT_VELOCITY = 128  # 4 bytes, 0.229 rpm
PRESENT_POSITION = 132  # 4 bytes
READ_ONLY_FROM = 120  # realtime tick, moving, present values
TABLE_SIZE = 147
XM430_W350 = 1020
PULSES_PER_RAD = 4096 / (2 * math.pi)
RPM_PER_UNIT = 0.229


class Servo:
    """One servo's control table. Its present position follows the goal with a first-order lag (time constant
    `lag` s, 0 = at once) while the torque is on."""

    def __init__(self, servo_id: int, position: int = 2048, lag: float = 0.0, model: int = XM430_W350) -> None:
        self.table = bytearray(TABLE_SIZE)
        self.table[MODEL_NUMBER : MODEL_NUMBER + 2] = model.to_bytes(2, "little")
        self.table[FIRMWARE_VERSION] = 48
        self.table[ID] = servo_id
        self.table[OPERATING_MODE] = 3  # position control
        self.set(PRESENT_POSITION, 4, position)
        self.set(GOAL_POSITION, 4, position)
        self.lag = lag
        self.responding = True
        self._position = float(position)
        self._time = time.monotonic()

    @property
    def servo_id(self) -> int:
        return self.table[ID]

    def get(self, address: int, size: int) -> int:
        return int.from_bytes(self.table[address : address + size], "little", signed=size == 4)

    def set(self, address: int, size: int, value: int) -> None:
        self.table[address : address + size] = value.to_bytes(size, "little", signed=size == 4)

    def force(self, address: int, size: int, value: int) -> None:
        """Sets a value as the servo itself would not let a client (present position, a fault)."""
        self.advance()
        self.set(address, size, value)
        if address == PRESENT_POSITION:
            self._position = float(value)

    def alert(self) -> int:
        return p.ALERT if self.table[HARDWARE_ERROR_STATUS] else 0

    def set_hardware_error(self, bits: int) -> None:
        """Sets Hardware Error Status; like a real servo, the torque goes off."""
        self.table[HARDWARE_ERROR_STATUS] = bits
        if bits:
            self.table[TORQUE_ENABLE] = 0

    def advance(self) -> None:
        """Moves the present position on to now."""
        now = time.monotonic()
        dt, self._time = now - self._time, now
        before = self._position
        if self.table[TORQUE_ENABLE]:
            goal = self.get(GOAL_POSITION, 4)
            alpha = 1.0 - math.exp(-dt / self.lag) if self.lag > 0.0 else 1.0
            self._position += alpha * (goal - self._position)
        velocity = (self._position - before) / dt if dt > 0.0 else 0.0  # pulses/s
        self.set(PRESENT_POSITION, 4, round(self._position))
        self.set(PRESENT_VELOCITY, 4, round(velocity / PULSES_PER_RAD * 60.0 / (2 * math.pi) / RPM_PER_UNIT))
        self.table[MOVING] = int(abs(self.get(GOAL_POSITION, 4) - self._position) > 1.0)

    def write(self, address: int, data: bytes) -> int:
        """Writes like the servo: the instruction error (0 on success)."""
        if address + len(data) > TABLE_SIZE:
            return p.DATA_LENGTH_ERROR
        if address + len(data) > READ_ONLY_FROM or address == HARDWARE_ERROR_STATUS or address < FIRMWARE_VERSION + 1:
            return p.ACCESS_ERROR
        if address < TORQUE_ENABLE and self.table[TORQUE_ENABLE]:
            return p.ACCESS_ERROR
        if address <= GOAL_POSITION < address + len(data):
            goal = int.from_bytes(data[GOAL_POSITION - address : GOAL_POSITION - address + 4], "little", signed=True)
            if not 0 <= goal <= 4095:
                return p.DATA_LIMIT_ERROR
        if address <= TORQUE_ENABLE < address + len(data) and data[TORQUE_ENABLE - address] and self.alert():
            return p.RESULT_FAIL  # a servo with a hardware error keeps its torque off until rebooted
        self.advance()
        self.table[address : address + len(data)] = data
        return 0


class BusEmulator:
    """Serves servos on a pseudo-terminal (`port`, the device a client opens) from a thread of its own."""

    def __init__(self, servos: list[Servo]) -> None:
        self.servos = {s.servo_id: s for s in servos}
        self.lock = threading.Lock()
        self.packets = 0
        self._master, self._slave = os.openpty()
        tty.setraw(self._slave)
        self.port = os.ttyname(self._slave)
        self._running = True
        self._thread = threading.Thread(target=self._serve, daemon=True)
        self._thread.start()

    def close(self) -> None:
        """The port disappears: the client's reads and writes fail."""
        self._running = False
        self._thread.join()
        for fd in (self._master, self._slave):
            try:
                os.close(fd)
            except OSError:
                pass

    def _serve(self) -> None:
        buffer = bytearray()
        while self._running:
            ready, _, _ = select.select([self._master], [], [], 0.05)
            if not ready:
                continue
            try:
                buffer += os.read(self._master, 4096)
            except OSError:
                return
            while (packet := p.take_packet(buffer)) is not None:
                with self.lock:
                    reply = self.handle(packet)
                if reply:
                    os.write(self._master, reply)

    def handle(self, packet: p.Packet) -> bytes:
        """The status packets that answer an instruction packet (none for a sync write, a broadcast or an absent
        servo)."""
        self.packets += 1
        if packet.servo_id == p.BROADCAST_ID:
            return self._broadcast(packet)
        servo = self.servos.get(packet.servo_id)
        if servo is None or not servo.responding:
            return b""
        if not packet.crc_ok:
            return p.status_packet(servo.servo_id, p.CRC_ERROR | servo.alert())
        servo.advance()
        params = packet.parameters
        if packet.instruction == p.PING:
            return p.status_packet(servo.servo_id, servo.alert(), bytes(servo.table[0:2]) + bytes([servo.table[6]]))
        if packet.instruction == p.READ and len(params) == 4:
            address, size = int.from_bytes(params[0:2], "little"), int.from_bytes(params[2:4], "little")
            if address + size > TABLE_SIZE:
                return p.status_packet(servo.servo_id, p.DATA_LENGTH_ERROR | servo.alert())
            return p.status_packet(servo.servo_id, servo.alert(), bytes(servo.table[address : address + size]))
        if packet.instruction == p.WRITE and len(params) >= 3:
            error = servo.write(int.from_bytes(params[0:2], "little"), params[2:])
            return p.status_packet(servo.servo_id, error | servo.alert())
        if packet.instruction == p.REBOOT:
            servo.set_hardware_error(0)
            servo.table[TORQUE_ENABLE] = 0
            return p.status_packet(servo.servo_id, 0)
        return p.status_packet(servo.servo_id, p.INSTRUCTION_ERROR | servo.alert())

    def _broadcast(self, packet: p.Packet) -> bytes:
        params = packet.parameters
        if not packet.crc_ok or len(params) < 4:
            return b""
        address, size = int.from_bytes(params[0:2], "little"), int.from_bytes(params[2:4], "little")
        if packet.instruction == p.SYNC_WRITE:
            for i in range(4, len(params) - size, size + 1):
                servo = self.servos.get(params[i])
                if servo is not None and servo.responding:
                    servo.write(address, params[i + 1 : i + 1 + size])
            return b""
        if packet.instruction == p.SYNC_READ:
            replies = b""
            for servo_id in params[4:]:
                servo = self.servos.get(servo_id)
                if servo is None or not servo.responding:
                    break  # the servos after a silent one wait for its status packet: none answers
                servo.advance()
                replies += p.status_packet(servo_id, servo.alert(), bytes(servo.table[address : address + size]))
            return replies
        return b""
