#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "protocol.h"
#include "serial_port.h"
#include "sixdof_control/hardware_interface.h"

namespace sixdof_control::dynamixel {

// Transactions on one Protocol 2.0 bus. Every reply is awaited for at most `timeout` seconds per packet. A failure
// names the servo id in its message and in `failed_id` (-1 for the bus itself).
class Bus {
 public:
  std::string open(const std::string& port, int baud, double timeout);
  void close() { port_.close(); }

  HardwareResult ping(std::uint8_t id, int& failed_id);
  HardwareResult write(std::uint8_t id, std::uint16_t address, const Bytes& data, int& failed_id);
  HardwareResult read(std::uint8_t id, std::uint16_t address, std::uint16_t size, Bytes& data, int& failed_id);
  // No status packets answer a sync write.
  HardwareResult syncWrite(std::uint16_t address, std::uint16_t size,
                           const std::vector<std::pair<std::uint8_t, Bytes>>& data, int& failed_id);
  // One status packet per id, in the ids' order; `errors` gets each one's error byte (the alert bit: a hardware
  // error).
  HardwareResult syncRead(std::uint16_t address, std::uint16_t size, const std::vector<std::uint8_t>& ids,
                          std::vector<Bytes>& data, std::vector<std::uint8_t>& errors, int& failed_id);

 private:
  HardwareResult send(const Bytes& packet, int& failed_id);
  // The next status packet, from `id`.
  HardwareResult receive(std::uint8_t id, StatusPacket& status, int& failed_id);

  SerialPort port_;
  double timeout_ = 0.02;
  Bytes buffer_;
};

}  // namespace sixdof_control::dynamixel
