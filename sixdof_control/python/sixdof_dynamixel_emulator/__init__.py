"""A Dynamixel Protocol 2.0 servo bus emulated on a pseudo-terminal (X series control table), for tests and for
trying sixdof_control's dynamixel plugin without servos."""

from sixdof_dynamixel_emulator.emulator import BusEmulator, Servo
from sixdof_dynamixel_emulator.protocol import crc16, instruction_packet, stuff, unstuff

__all__ = ["BusEmulator", "Servo", "crc16", "instruction_packet", "stuff", "unstuff"]
