#include "serial_port.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

namespace sixdof_control::dynamixel {
namespace {

speed_t baudConstant(int baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 1000000:
      return B1000000;
    case 2000000:
      return B2000000;
    case 3000000:
      return B3000000;
    case 4000000:
      return B4000000;
    default:
      return 0;
  }
}

}  // namespace

SerialPort::~SerialPort() { close(); }

std::string SerialPort::open(const std::string& path, int baud) {
  close();
  path_ = path;
  const speed_t speed = baudConstant(baud);
  if (speed == 0) {
    return "baud " + std::to_string(baud) + " is not one of 9600, 57600, 115200, 1000000, 2000000, 3000000, 4000000";
  }
  fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
  if (fd_ < 0) return "cannot open port '" + path + "': " + std::strerror(errno);
  termios tio{};
  if (tcgetattr(fd_, &tio) != 0) {
    const std::string why = "port '" + path + "' is not a serial port: " + std::strerror(errno);
    close();
    return why;
  }
  cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~(CSTOPB | PARENB | CRTSCTS);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  cfsetispeed(&tio, speed);
  cfsetospeed(&tio, speed);
  if (tcsetattr(fd_, TCSANOW, &tio) != 0) {
    const std::string why = "cannot configure port '" + path + "': " + std::strerror(errno);
    close();
    return why;
  }
  flushInput();
  return "";
}

void SerialPort::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void SerialPort::flushInput() {
  if (fd_ >= 0) tcflush(fd_, TCIFLUSH);
}

std::string SerialPort::write(const Bytes& bytes, bool& lost) {
  lost = false;
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
    } else if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
      pollfd p{fd_, POLLOUT, 0};
      ::poll(&p, 1, 10);
    } else {
      lost = true;
      return "port '" + path_ + "' write failed: " + std::strerror(errno);
    }
  }
  return "";
}

std::string SerialPort::readSome(Bytes& out, double timeout_s, bool& lost) {
  lost = false;
  pollfd p{fd_, POLLIN, 0};
  const int r = ::poll(&p, 1, static_cast<int>(std::ceil(timeout_s * 1000.0)));
  if (r == 0) return "";
  if (r < 0) return errno == EINTR ? "" : "port '" + path_ + "' poll failed: " + std::strerror(errno);
  std::uint8_t chunk[512];
  const ssize_t n = ::read(fd_, chunk, sizeof(chunk));
  if (n > 0) {
    out.insert(out.end(), chunk, chunk + n);
    return "";
  }
  if (n < 0 && (errno == EAGAIN || errno == EINTR)) return "";
  lost = true;
  return "port '" + path_ + "' is gone (" + (n == 0 ? std::string("hang-up") : std::strerror(errno)) + ")";
}

}  // namespace sixdof_control::dynamixel
