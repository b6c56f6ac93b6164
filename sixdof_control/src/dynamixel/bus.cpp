#include "bus.h"

#include <chrono>
#include <sstream>

namespace sixdof_control::dynamixel {
namespace {

HardwareResult failure(HardwareStatus status, int id, const std::string& why, int& failed_id) {
  failed_id = id;
  return HardwareResult::failure(status, (id >= 0 ? "id " + std::to_string(id) + ": " : "") + why);
}

}  // namespace

std::string Bus::open(const std::string& port, int baud, double timeout) {
  timeout_ = timeout;
  buffer_.clear();
  return port_.open(port, baud);
}

HardwareResult Bus::send(const Bytes& packet, int& failed_id) {
  port_.flushInput();
  buffer_.clear();
  bool lost = false;
  const std::string why = port_.write(packet, lost);
  if (!why.empty()) return failure(HardwareStatus::kDeviceLost, -1, why, failed_id);
  return {};
}

HardwareResult Bus::receive(std::uint8_t id, StatusPacket& status, int& failed_id) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_);
  std::string problem;
  while (true) {
    if (std::optional<StatusPacket> packet = takeStatusPacket(buffer_, problem)) {
      if (packet->id != id) {
        return failure(HardwareStatus::kCommunicationError, id,
                       "a status packet from id " + std::to_string(packet->id) + " came instead", failed_id);
      }
      if (packet->error & 0x7F) {
        return failure(HardwareStatus::kCommunicationError, id, instructionErrorName(packet->error), failed_id);
      }
      status = std::move(*packet);
      return {};
    }
    if (!problem.empty()) return failure(HardwareStatus::kCommunicationError, id, problem, failed_id);
    const double left = std::chrono::duration<double>(deadline - Clock::now()).count();
    if (left <= 0.0) {
      std::ostringstream s;
      s << "no status packet within " << timeout_ * 1000.0 << " ms";
      return failure(HardwareStatus::kTimeout, id, s.str(), failed_id);
    }
    bool lost = false;
    const std::string why = port_.readSome(buffer_, left, lost);
    if (!why.empty()) return failure(HardwareStatus::kDeviceLost, -1, why, failed_id);
  }
}

HardwareResult Bus::ping(std::uint8_t id, int& failed_id) {
  HardwareResult r = send(instructionPacket(id, kPing, {}), failed_id);
  StatusPacket status;
  if (r.ok()) r = receive(id, status, failed_id);
  if (r.status == HardwareStatus::kTimeout) r.status = HardwareStatus::kDeviceNotFound;
  return r;
}

HardwareResult Bus::write(std::uint8_t id, std::uint16_t address, const Bytes& data, int& failed_id) {
  Bytes parameters;
  appendU16(parameters, address);
  parameters.insert(parameters.end(), data.begin(), data.end());
  HardwareResult r = send(instructionPacket(id, kWrite, parameters), failed_id);
  StatusPacket status;
  if (r.ok()) r = receive(id, status, failed_id);
  return r;
}

HardwareResult Bus::read(std::uint8_t id, std::uint16_t address, std::uint16_t size, Bytes& data, int& failed_id) {
  Bytes parameters;
  appendU16(parameters, address);
  appendU16(parameters, size);
  HardwareResult r = send(instructionPacket(id, kRead, parameters), failed_id);
  StatusPacket status;
  if (r.ok()) r = receive(id, status, failed_id);
  if (r.ok() && status.parameters.size() != size) {
    return failure(HardwareStatus::kCommunicationError, id,
                   "read returned " + std::to_string(status.parameters.size()) + " bytes for " + std::to_string(size),
                   failed_id);
  }
  data = std::move(status.parameters);
  return r;
}

HardwareResult Bus::syncWrite(std::uint16_t address, std::uint16_t size,
                              const std::vector<std::pair<std::uint8_t, Bytes>>& data, int& failed_id) {
  Bytes parameters;
  appendU16(parameters, address);
  appendU16(parameters, size);
  for (const auto& [id, bytes] : data) {
    parameters.push_back(id);
    parameters.insert(parameters.end(), bytes.begin(), bytes.end());
  }
  return send(instructionPacket(kBroadcastId, kSyncWrite, parameters), failed_id);
}

HardwareResult Bus::syncRead(std::uint16_t address, std::uint16_t size, const std::vector<std::uint8_t>& ids,
                             std::vector<Bytes>& data, std::vector<std::uint8_t>& errors, int& failed_id) {
  Bytes parameters;
  appendU16(parameters, address);
  appendU16(parameters, size);
  parameters.insert(parameters.end(), ids.begin(), ids.end());
  HardwareResult r = send(instructionPacket(kBroadcastId, kSyncRead, parameters), failed_id);
  data.assign(ids.size(), {});
  errors.assign(ids.size(), 0);
  for (std::size_t i = 0; i < ids.size() && r.ok(); ++i) {
    StatusPacket status;
    r = receive(ids[i], status, failed_id);
    if (r.ok() && status.parameters.size() != size) {
      r = failure(
          HardwareStatus::kCommunicationError, ids[i],
          "sync read returned " + std::to_string(status.parameters.size()) + " bytes for " + std::to_string(size),
          failed_id);
    }
    data[i] = std::move(status.parameters);
    errors[i] = status.error;
  }
  return r;
}

}  // namespace sixdof_control::dynamixel
