#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "protocol.h"

namespace sixdof_control::dynamixel {

// A serial port in raw mode (8N1, no flow control) at a standard baud rate: a U2D2 or any USB-RS485 adapter, or a
// pseudo-terminal.
class SerialPort {
 public:
  SerialPort() = default;
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  // Empty on success, else why (naming the port).
  std::string open(const std::string& path, int baud);
  void close();
  bool isOpen() const { return fd_ >= 0; }

  // Drops unread input.
  void flushInput();
  // Empty on success; "lost" problems set `lost`.
  std::string write(const Bytes& bytes, bool& lost);
  // Appends what arrives within timeout_s (at least one byte, or none at the timeout) to `out`. Empty on success or
  // timeout, else why (the port went away: `lost`).
  std::string readSome(Bytes& out, double timeout_s, bool& lost);

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace sixdof_control::dynamixel
