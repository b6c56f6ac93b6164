// Protocol 2.0 packets: CRC, byte stuffing, instruction packets, status packet parsing.
#include <gtest/gtest.h>

#include <string>

#include "../src/dynamixel/protocol.h"

namespace sixdof_control::dynamixel {
namespace {

TEST(DynamixelProtocol, Crc16IsTheProtocolsOne) {
  const std::string check = "123456789";
  EXPECT_EQ(crc16(reinterpret_cast<const std::uint8_t*>(check.data()), check.size()), 0xFEE8);
  // The e-Manual's ping of id 1.
  EXPECT_EQ(instructionPacket(1, kPing, {}), (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x03, 0x00, 0x01, 0x19, 0x4E}));
}

TEST(DynamixelProtocol, ByteStuffingRoundTrips) {
  const Bytes raw{0x03, 0xFF, 0xFF, 0xFD, 0x00, 0xFF, 0xFF, 0xFD, 0xFD};
  const Bytes stuffed = stuff(raw);
  EXPECT_EQ(stuffed, (Bytes{0x03, 0xFF, 0xFF, 0xFD, 0xFD, 0x00, 0xFF, 0xFF, 0xFD, 0xFD, 0xFD}));
  EXPECT_EQ(unstuff(stuffed), raw);
  // The length field counts the stuffed bytes.
  const Bytes packet = instructionPacket(2, kWrite, {0x74, 0x00, 0xFF, 0xFF, 0xFD, 0x00});
  EXPECT_EQ(packet[5] | (packet[6] << 8), 1 + 7 + 2);
}

TEST(DynamixelProtocol, StatusPacketsAreFoundInAStream) {
  // A status packet as a servo sends it: id 1, error 0x80 (alert), parameters FF FF FD (stuffed on the wire).
  Bytes body = stuff(Bytes{kStatus, 0x80, 0xFF, 0xFF, 0xFD});
  Bytes packet{0xFF, 0xFF, 0xFD, 0x00, 0x01};
  appendU16(packet, static_cast<std::uint16_t>(body.size() + 2));
  packet.insert(packet.end(), body.begin(), body.end());
  appendU16(packet, crc16(packet.data(), packet.size()));

  Bytes stream{0x00, 0x12};  // garbage first
  for (std::size_t i = 0; i + 3 < packet.size(); ++i) stream.push_back(packet[i]);
  std::string problem;
  EXPECT_FALSE(takeStatusPacket(stream, problem));  // incomplete
  EXPECT_TRUE(problem.empty());
  for (std::size_t i = packet.size() - 3; i < packet.size(); ++i) stream.push_back(packet[i]);
  const auto status = takeStatusPacket(stream, problem);
  ASSERT_TRUE(status) << problem;
  EXPECT_EQ(status->id, 1);
  EXPECT_EQ(status->error, kAlertBit);
  EXPECT_EQ(status->parameters, (Bytes{0xFF, 0xFF, 0xFD}));
  EXPECT_TRUE(stream.empty());

  Bytes corrupt = packet;
  corrupt[8] ^= 0x01;
  EXPECT_FALSE(takeStatusPacket(corrupt, problem));
  EXPECT_NE(problem.find("corrupt"), std::string::npos) << problem;
}

TEST(DynamixelProtocol, ErrorsAreNamed) {
  EXPECT_EQ(instructionErrorName(0x03), "CRC error");
  EXPECT_EQ(hardwareErrorNames(0x24), "overheating, overload");
  EXPECT_EQ(readI32(Bytes{0xFF, 0xFF, 0xFF, 0xFF}, 0), -1);
}

}  // namespace
}  // namespace sixdof_control::dynamixel
