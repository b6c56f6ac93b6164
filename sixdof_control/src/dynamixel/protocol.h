#pragma once
// Dynamixel Protocol 2.0 packets (ROBOTIS e-Manual, "DYNAMIXEL Protocol 2.0"): header FF FF FD 00, id, length (LE,
// the bytes after it), instruction, parameters (byte-stuffed), CRC-16 (LE). Status packets carry instruction 0x55
// and an error byte before their parameters.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace sixdof_control::dynamixel {

using Bytes = std::vector<std::uint8_t>;

constexpr std::uint8_t kBroadcastId = 0xFE;

enum Instruction : std::uint8_t {
  kPing = 0x01,
  kRead = 0x02,
  kWrite = 0x03,
  kReboot = 0x08,
  kStatus = 0x55,
  kSyncRead = 0x82,
  kSyncWrite = 0x83,
};

// The status packet's error byte: bit 7 says the servo's Hardware Error Status is set; bits 0..6 are the result of
// the instruction (0 = none).
constexpr std::uint8_t kAlertBit = 0x80;
// The instruction error's name ("result fail", "instruction error", "CRC error", "data range error", "data length
// error", "data limit error", "access error").
std::string instructionErrorName(std::uint8_t error);
// The names of the Hardware Error Status bits set (input voltage, overheating, motor encoder, electrical shock,
// overload), comma-separated.
std::string hardwareErrorNames(std::uint8_t status);

// X series control table (e.g. XM430-W350, XL430-W250): the addresses and sizes used here.
namespace address {
constexpr std::uint16_t kTorqueEnable = 64;         // 1 byte
constexpr std::uint16_t kHardwareErrorStatus = 70;  // 1 byte
constexpr std::uint16_t kGoalPosition = 116;        // 4 bytes, signed, pulses
constexpr std::uint16_t kPresentVelocity = 128;     // 4 bytes, signed, 0.229 rpm
constexpr std::uint16_t kPresentPosition = 132;     // 4 bytes, signed, pulses
}  // namespace address
constexpr double kPulsesPerRevolution = 4096.0;  // 0.088 degrees per pulse
constexpr double kCentrePulse = 2048.0;          // the middle of one turn (180 degrees)
constexpr double kVelocityUnitRpm = 0.229;

// CRC-16 of Protocol 2.0 (polynomial 0x8005, initial value 0, no reflection) over the bytes.
std::uint16_t crc16(const std::uint8_t* data, std::size_t size);

// Inserts 0xFD after every FF FF FD in the bytes (the instruction and parameter fields of a packet).
Bytes stuff(const Bytes& bytes);
// The inverse: drops the 0xFD after every FF FF FD.
Bytes unstuff(const Bytes& bytes);

// A complete instruction packet.
Bytes instructionPacket(std::uint8_t id, std::uint8_t instruction, const Bytes& parameters);

struct StatusPacket {
  std::uint8_t id = 0;
  std::uint8_t error = 0;
  Bytes parameters;
};

// Finds the first complete status packet in `buffer` (dropping garbage before a header) and removes it and what came
// before it. nullopt while no complete packet is there yet; a packet with a wrong CRC or instruction gives `problem`.
std::optional<StatusPacket> takeStatusPacket(Bytes& buffer, std::string& problem);

// Little-endian fields.
void appendU16(Bytes& out, std::uint16_t value);
void appendI32(Bytes& out, std::int32_t value);
std::int32_t readI32(const Bytes& bytes, std::size_t offset);

}  // namespace sixdof_control::dynamixel
