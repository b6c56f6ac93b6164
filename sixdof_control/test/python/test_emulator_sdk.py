"""The official Dynamixel SDK (PyPI dynamixel-sdk) as the emulator's client: if ROBOTIS's own implementation of
Protocol 2.0 talks to it, the emulator follows the real protocol (packets, CRC, byte stuffing, status packets)."""

from collections.abc import Iterator

import dynamixel_sdk as sdk
import pytest
from sixdof_dynamixel_emulator import BusEmulator, Servo
from sixdof_dynamixel_emulator.emulator import (
    GOAL_POSITION,
    HARDWARE_ERROR_STATUS,
    PRESENT_POSITION,
    TORQUE_ENABLE,
    XM430_W350,
)

IDS = [1, 2, 3]


@pytest.fixture
def bus() -> Iterator[tuple[BusEmulator, sdk.PortHandler, sdk.PacketHandler]]:
    emulator = BusEmulator([Servo(i) for i in IDS])
    port = sdk.PortHandler(emulator.port)
    assert port.openPort()
    assert port.setBaudRate(1000000)
    yield emulator, port, sdk.PacketHandler(2.0)
    port.closePort()
    emulator.close()


def test_ping_reports_the_model(bus) -> None:
    _, port, packets = bus
    for servo_id in IDS:
        model, result, error = packets.ping(port, servo_id)
        assert (result, error) == (sdk.COMM_SUCCESS, 0)
        assert model == XM430_W350
    _, result, _ = packets.ping(port, 9)
    assert result == sdk.COMM_RX_TIMEOUT


def test_write_and_read_back_with_byte_stuffing(bus) -> None:
    emulator, port, packets = bus
    result, error = packets.write1ByteTxRx(port, 2, TORQUE_ENABLE, 1)
    assert (result, error) == (sdk.COMM_SUCCESS, 0)
    assert emulator.servos[2].table[TORQUE_ENABLE] == 1
    # Goal PWM and goal current (100..103) written as FF FF FD 00: the SDK stuffs it, the emulator unstuffs it, and
    # stuffs the status packet that reads it back.
    result, error = packets.write4ByteTxRx(port, 2, 100, 0x00FDFFFF)
    assert (result, error) == (sdk.COMM_SUCCESS, 0)
    assert bytes(emulator.servos[2].table[100:104]) == b"\xff\xff\xfd\x00"
    value, result, error = packets.read4ByteTxRx(port, 2, 100)
    assert (value, result, error) == (0x00FDFFFF, sdk.COMM_SUCCESS, 0)


def test_refusals_come_back_as_instruction_errors(bus) -> None:
    _, port, packets = bus
    result, error = packets.write4ByteTxRx(port, 1, GOAL_POSITION, 5000)
    assert result == sdk.COMM_SUCCESS
    assert error & 0x7F == 0x06  # data limit error
    result, error = packets.write4ByteTxRx(port, 1, PRESENT_POSITION, 100)
    assert error & 0x7F == 0x07  # access error: read only


def test_sync_write_then_sync_read_moves_every_servo(bus) -> None:
    _, port, packets = bus
    for servo_id in IDS:
        packets.write1ByteTxRx(port, servo_id, TORQUE_ENABLE, 1)
    writer = sdk.GroupSyncWrite(port, packets, GOAL_POSITION, 4)
    goals = {1: 1000, 2: 2048, 3: 3000}
    for servo_id, goal in goals.items():
        assert writer.addParam(servo_id, list(goal.to_bytes(4, "little")))
    assert writer.txPacket() == sdk.COMM_SUCCESS
    reader = sdk.GroupSyncRead(port, packets, PRESENT_POSITION, 4)
    for servo_id in IDS:
        assert reader.addParam(servo_id)
    assert reader.txRxPacket() == sdk.COMM_SUCCESS
    for servo_id, goal in goals.items():
        assert reader.isAvailable(servo_id, PRESENT_POSITION, 4)
        assert reader.getData(servo_id, PRESENT_POSITION, 4) == goal


def test_hardware_error_sets_the_alert_bit_and_turns_the_torque_off(bus) -> None:
    emulator, port, packets = bus
    packets.write1ByteTxRx(port, 3, TORQUE_ENABLE, 1)
    emulator.servos[3].set_hardware_error(0x20)  # overload
    value, result, error = packets.read1ByteTxRx(port, 3, HARDWARE_ERROR_STATUS)
    assert result == sdk.COMM_SUCCESS
    assert error & 0x80
    assert value == 0x20
    torque, _, _ = packets.read1ByteTxRx(port, 3, TORQUE_ENABLE)
    assert torque == 0
    result, error = packets.write1ByteTxRx(port, 3, TORQUE_ENABLE, 1)
    assert error & 0x7F == 0x01  # result fail until a reboot
    assert packets.reboot(port, 3) == (sdk.COMM_SUCCESS, 0)
    assert packets.write1ByteTxRx(port, 3, TORQUE_ENABLE, 1) == (sdk.COMM_SUCCESS, 0)


def test_a_servo_that_stops_answering_times_out(bus) -> None:
    emulator, port, packets = bus
    emulator.servos[2].responding = False
    _, result, _ = packets.read4ByteTxRx(port, 2, PRESENT_POSITION)
    assert result == sdk.COMM_RX_TIMEOUT
    emulator.servos[2].responding = True
    _, result, _ = packets.read4ByteTxRx(port, 2, PRESENT_POSITION)
    assert result == sdk.COMM_SUCCESS
