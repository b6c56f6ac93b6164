#include "protocol.h"

#include <algorithm>
#include <sstream>

namespace sixdof_control::dynamixel {
namespace {

constexpr std::uint8_t kHeader[] = {0xFF, 0xFF, 0xFD, 0x00};

bool headerAt(const Bytes& b, std::size_t i) {
  return i + 4 <= b.size() && b[i] == kHeader[0] && b[i + 1] == kHeader[1] && b[i + 2] == kHeader[2] &&
         b[i + 3] == kHeader[3];
}

}  // namespace

std::string instructionErrorName(std::uint8_t error) {
  static const char* const kNames[] = {"none",
                                       "result fail",
                                       "instruction error",
                                       "CRC error",
                                       "data range error",
                                       "data length error",
                                       "data limit error",
                                       "access error"};
  const std::uint8_t code = error & 0x7F;
  return code < 8 ? kNames[code] : "error " + std::to_string(code);
}

std::string hardwareErrorNames(std::uint8_t status) {
  static const char* const kBits[] = {"input voltage",    "bit 1",    "overheating", "motor encoder",
                                      "electrical shock", "overload", "bit 6",       "bit 7"};
  std::string out;
  for (int bit = 0; bit < 8; ++bit) {
    if (status & (1u << bit)) out += (out.empty() ? "" : ", ") + std::string(kBits[bit]);
  }
  return out.empty() ? "none" : out;
}

std::uint16_t crc16(const std::uint8_t* data, std::size_t size) {
  std::uint16_t crc = 0;
  for (std::size_t i = 0; i < size; ++i) {
    crc ^= static_cast<std::uint16_t>(data[i]) << 8;
    for (int bit = 0; bit < 8; ++bit) {
      crc = (crc & 0x8000) ? static_cast<std::uint16_t>((crc << 1) ^ 0x8005) : static_cast<std::uint16_t>(crc << 1);
    }
  }
  return crc;
}

Bytes stuff(const Bytes& bytes) {
  Bytes out;
  out.reserve(bytes.size() + 4);
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    out.push_back(bytes[i]);
    if (i >= 2 && bytes[i] == 0xFD && bytes[i - 1] == 0xFF && bytes[i - 2] == 0xFF) out.push_back(0xFD);
  }
  return out;
}

Bytes unstuff(const Bytes& bytes) {
  Bytes out;
  out.reserve(bytes.size());
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    out.push_back(bytes[i]);
    if (i >= 2 && bytes[i] == 0xFD && bytes[i - 1] == 0xFF && bytes[i - 2] == 0xFF && i + 1 < bytes.size() &&
        bytes[i + 1] == 0xFD) {
      ++i;
    }
  }
  return out;
}

void appendU16(Bytes& out, std::uint16_t value) {
  out.push_back(static_cast<std::uint8_t>(value & 0xFF));
  out.push_back(static_cast<std::uint8_t>(value >> 8));
}

void appendI32(Bytes& out, std::int32_t value) {
  const auto u = static_cast<std::uint32_t>(value);
  for (int shift = 0; shift < 32; shift += 8) out.push_back(static_cast<std::uint8_t>((u >> shift) & 0xFF));
}

std::int32_t readI32(const Bytes& bytes, std::size_t offset) {
  std::uint32_t u = 0;
  for (int k = 0; k < 4; ++k) u |= static_cast<std::uint32_t>(bytes.at(offset + k)) << (8 * k);
  return static_cast<std::int32_t>(u);
}

Bytes instructionPacket(std::uint8_t id, std::uint8_t instruction, const Bytes& parameters) {
  Bytes body(parameters.size() + 1);
  body[0] = instruction;
  std::copy(parameters.begin(), parameters.end(), body.begin() + 1);
  body = stuff(body);
  Bytes packet(std::begin(kHeader), std::end(kHeader));
  packet.push_back(id);
  appendU16(packet, static_cast<std::uint16_t>(body.size() + 2));
  packet.insert(packet.end(), body.begin(), body.end());
  appendU16(packet, crc16(packet.data(), packet.size()));
  return packet;
}

std::optional<StatusPacket> takeStatusPacket(Bytes& buffer, std::string& problem) {
  problem.clear();
  std::size_t start = 0;
  while (start < buffer.size() && !headerAt(buffer, start)) ++start;
  if (start >= buffer.size()) {
    // No header: keep the last bytes, which may be the beginning of one.
    buffer.erase(buffer.begin(), buffer.end() - static_cast<std::ptrdiff_t>(std::min<std::size_t>(buffer.size(), 3)));
    return std::nullopt;
  }
  buffer.erase(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(start));
  start = 0;
  if (buffer.size() < 7) return std::nullopt;
  const std::size_t length = buffer[start + 5] | (static_cast<std::size_t>(buffer[start + 6]) << 8);
  if (start + 7 + length > buffer.size()) return std::nullopt;
  const std::size_t end = start + 7 + length;
  Bytes packet(buffer.begin() + static_cast<std::ptrdiff_t>(start), buffer.begin() + static_cast<std::ptrdiff_t>(end));
  buffer.erase(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(end));
  const std::uint16_t crc = packet[packet.size() - 2] | (packet[packet.size() - 1] << 8);
  if (length < 4 || crc16(packet.data(), packet.size() - 2) != crc) {
    std::ostringstream s;
    s << "corrupt status packet from id " << int(packet[4]) << " (CRC or length)";
    problem = s.str();
    return std::nullopt;
  }
  const Bytes body = unstuff(Bytes(packet.begin() + 7, packet.end() - 2));
  if (body.size() < 2 || body[0] != kStatus) {
    problem = "a packet from id " + std::to_string(packet[4]) + " that is not a status packet";
    return std::nullopt;
  }
  return StatusPacket{packet[4], body[1], Bytes(body.begin() + 2, body.end())};
}

}  // namespace sixdof_control::dynamixel
