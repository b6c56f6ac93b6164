#include "sixdof_planning/tcpros_service_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <map>

#include <ros/master.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <ros/xmlrpc_manager.h>

namespace sixdof_planning {
namespace {

// roscpp's bound on a message's predicted length: anything longer means the stream is out of step.
constexpr uint32_t kMaxRequest = 1000000000;
// A connection header is a few short fields.
constexpr uint32_t kMaxHeader = 1 << 20;
// Connections served at once; a connection beyond them is closed at once.
constexpr std::size_t kMaxConnections = 128;

bool readAll(int fd, void* buffer, std::size_t size) {
  auto* at = static_cast<char*>(buffer);
  while (size > 0) {
    const ssize_t got = ::recv(fd, at, size, 0);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;
    at += got;
    size -= static_cast<std::size_t>(got);
  }
  return true;
}

bool writeAll(int fd, const void* buffer, std::size_t size) {
  const auto* at = static_cast<const char*>(buffer);
  while (size > 0) {
    const ssize_t sent = ::send(fd, at, size, MSG_NOSIGNAL);
    if (sent < 0 && errno == EINTR) continue;
    if (sent <= 0) return false;
    at += sent;
    size -= static_cast<std::size_t>(sent);
  }
  return true;
}

void putU32(std::string* out, uint32_t value) {
  const uint32_t little = value;  // TCPROS is little-endian, as this machine
  out->append(reinterpret_cast<const char*>(&little), 4);
}

// A connection header: its fields (each a length and "key=value") after the header's length.
bool sendHeader(int fd, const std::map<std::string, std::string>& fields) {
  std::string body;
  for (const auto& [key, value] : fields) {
    putU32(&body, static_cast<uint32_t>(key.size() + 1 + value.size()));
    body += key + "=" + value;
  }
  std::string frame;
  putU32(&frame, static_cast<uint32_t>(body.size()));
  frame += body;
  return writeAll(fd, frame.data(), frame.size());
}

// The fields of a received header; false when they do not parse.
bool parseHeader(const std::vector<char>& data, std::map<std::string, std::string>* fields) {
  std::size_t at = 0;
  while (at < data.size()) {
    if (data.size() - at < 4) return false;
    uint32_t size = 0;
    std::memcpy(&size, data.data() + at, 4);
    at += 4;
    if (size > data.size() - at) return false;
    const std::string field(data.data() + at, size);
    at += size;
    const std::size_t equals = field.find('=');
    if (equals == std::string::npos) return false;
    (*fields)[field.substr(0, equals)] = field.substr(equals + 1);
  }
  return true;
}

std::string errnoText() { return std::strerror(errno); }

// The work afterAnswer defers on a thread handling a request (null elsewhere).
thread_local std::vector<std::function<void()>>* t_after_answer = nullptr;

}  // namespace

namespace {

void runLogged(const std::function<void()>& work) {
  try {
    work();
  } catch (const std::exception& e) {
    ROS_ERROR_STREAM("work after a service's answer failed: " << e.what());
  }
}

}  // namespace

void TcprosServiceServer::afterAnswer(std::function<void()> work) {
  if (t_after_answer) {
    t_after_answer->push_back(std::move(work));
  } else {
    runLogged(work);
  }
}

void TcprosServiceServer::runDeferred(std::vector<std::function<void()>>* work) {
  for (const auto& item : *work) runLogged(item);
  work->clear();
}

TcprosServiceServer::TcprosServiceServer(const std::string& resolved_name, TcprosServiceType type, Handler handler)
    : name_(resolved_name), type_(std::move(type)), handler_(std::move(handler)) {
  const std::string& host = ros::network::getHost();
  // As roscpp: IPv6 (dual stack) when ROS_IPV6 is on, and a node whose host is the loopback accepts only local
  // connections.
  const char* ipv6_setting = std::getenv("ROS_IPV6");
  const bool ipv6 = ipv6_setting && std::string(ipv6_setting) == "on";
  const bool local_only = host == "localhost" || host.rfind("127.", 0) == 0 || host == "::1";
  listen_fd_ = ::socket(ipv6 ? AF_INET6 : AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (listen_fd_ < 0) throw std::runtime_error("service " + name_ + ": socket: " + errnoText());
  sockaddr_storage address{};
  socklen_t length = 0;
  if (ipv6) {
    auto* in6 = reinterpret_cast<sockaddr_in6*>(&address);
    in6->sin6_family = AF_INET6;
    in6->sin6_addr = local_only ? in6addr_loopback : in6addr_any;
    length = sizeof(sockaddr_in6);
  } else {
    auto* in4 = reinterpret_cast<sockaddr_in*>(&address);
    in4->sin_family = AF_INET;
    in4->sin_addr.s_addr = htonl(INADDR_ANY);
    // A loopback host listens on that address itself (127.0.0.1 for "localhost").
    if (local_only && ::inet_pton(AF_INET, host.c_str(), &in4->sin_addr) != 1) {
      in4->sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    }
    length = sizeof(sockaddr_in);
  }
  if (::bind(listen_fd_, reinterpret_cast<sockaddr*>(&address), length) != 0 || ::listen(listen_fd_, 64) != 0 ||
      ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
    const std::string why = errnoText();
    ::close(listen_fd_);
    throw std::runtime_error("service " + name_ + ": cannot listen: " + why);
  }
  const uint16_t port = ipv6 ? reinterpret_cast<sockaddr_in6*>(&address)->sin6_port
                             : reinterpret_cast<sockaddr_in*>(&address)->sin_port;
  uri_ = "rosrpc://" + host + ":" + std::to_string(ntohs(port));
  if (!callMaster("registerService", true, true)) {
    ::close(listen_fd_);
    throw std::runtime_error("service " + name_ + ": the master refused its registration");
  }
  registered_ = true;
}

TcprosServiceServer::~TcprosServiceServer() {
  stop();
  // Without a master (shut down first) the registration is gone with it.
  if (registered_) callMaster("unregisterService", false, false);
  if (listen_fd_ >= 0) ::close(listen_fd_);
}

bool TcprosServiceServer::callMaster(const char* method, bool with_node_api, bool wait_for_master) const {
  XmlRpc::XmlRpcValue request, response, payload;
  request[0] = ros::this_node::getName();
  request[1] = name_;
  request[2] = uri_;
  if (with_node_api) request[3] = ros::XMLRPCManager::instance()->getServerURI();
  return ros::master::execute(method, request, response, payload, wait_for_master);
}

void TcprosServiceServer::start() {
  if (accept_thread_.joinable() || stopping_) return;
  accept_thread_ = std::thread([this] { acceptLoop(); });
}

void TcprosServiceServer::stop() {
  if (stopping_.exchange(true)) return;
  // accept() returns once the socket is shut down; the descriptor is closed by the destructor.
  ::shutdown(listen_fd_, SHUT_RDWR);
  if (accept_thread_.joinable()) accept_thread_.join();
  {
    std::lock_guard<std::mutex> lock(connections_mutex_);
    // Each thread's recv returns (descriptors are closed only once their thread is joined).
    for (Connection& connection : connections_) ::shutdown(connection.fd, SHUT_RDWR);
  }
  reap(true);
}

void TcprosServiceServer::reap(bool all) {
  std::list<Connection> finished;
  {
    std::lock_guard<std::mutex> lock(connections_mutex_);
    for (auto it = connections_.begin(); it != connections_.end();) {
      auto next = std::next(it);
      if (all || it->done) finished.splice(finished.end(), connections_, it);
      it = next;
    }
  }
  for (Connection& connection : finished) {
    connection.thread.join();
    ::close(connection.fd);
  }
}

void TcprosServiceServer::acceptLoop() {
  while (!stopping_) {
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0) {
      if (errno == EINTR || errno == ECONNABORTED) continue;
      if (!stopping_) ROS_ERROR_STREAM("service " << name_ << ": accept: " << errnoText());
      return;
    }
    reap(false);
    std::lock_guard<std::mutex> lock(connections_mutex_);
    if (stopping_ || connections_.size() >= kMaxConnections) {
      if (!stopping_) ROS_WARN_STREAM("service " << name_ << ": " << kMaxConnections << " connections open, refused one");
      ::close(fd);
      continue;
    }
    connections_.emplace_back();
    Connection* connection = &connections_.back();
    connection->fd = fd;
    connection->thread = std::thread([this, connection] {
      serve(connection);
      // The client sees the end of the stream now; the descriptor is closed once the thread is joined (reap), so
      // that stop() never shuts down a descriptor number already reused.
      ::shutdown(connection->fd, SHUT_RDWR);
      connection->done = true;
    });
  }
}

bool TcprosServiceServer::handshake(int fd, std::string* caller, bool* persistent) const {
  uint32_t size = 0;
  if (!readAll(fd, &size, 4)) return false;
  if (size > kMaxHeader) {
    ROS_WARN_STREAM("service " << name_ << ": a connection header of " << size << " bytes, closed");
    return false;
  }
  std::vector<char> data(size);
  std::map<std::string, std::string> fields;
  if (!readAll(fd, data.data(), size)) return false;
  std::string error;
  if (!parseHeader(data, &fields)) {
    error = "the connection header does not parse";
  } else if (!fields.count("md5sum") || !fields.count("service") || !fields.count("callerid")) {
    error = "bogus tcpros header. did not have required elements: md5sum, service, callerid";
  } else if (fields["service"] != name_) {
    error = "received a tcpros connection for a nonexistent service [" + fields["service"] + "]";
  } else if (fields["md5sum"] != "*" && fields["md5sum"] != type_.md5sum) {
    error = "client wants service " + name_ + " to have md5sum " + fields["md5sum"] + ", but it has " +
            type_.md5sum + ". Dropping connection.";
  }
  if (!error.empty()) {
    ROS_WARN_STREAM("service " << name_ << ": " << error);
    sendHeader(fd, {{"error", error}});
    return false;
  }
  *caller = fields["callerid"];
  *persistent = fields["persistent"] == "1" || fields["persistent"] == "true";
  return sendHeader(fd, {{"callerid", ros::this_node::getName()},
                         {"md5sum", type_.md5sum},
                         {"request_type", type_.request_type},
                         {"response_type", type_.response_type},
                         {"type", type_.type}});
}

void TcprosServiceServer::serve(Connection* connection) {
  const int fd = connection->fd;
  const int one = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));
  std::string caller;
  bool persistent = false;
  if (!handshake(fd, &caller, &persistent)) return;
  std::vector<uint8_t> request;
  std::vector<uint8_t> answer;
  std::vector<std::function<void()>> after_answer;
  for (;;) {
    uint32_t size = 0;
    if (!readAll(fd, &size, 4)) return;  // the client closed the connection (or stop())
    if (size > kMaxRequest) {
      ROS_ERROR_STREAM("service " << name_ << ": a request of " << size << " bytes from " << caller
                                  << " (over 1 GB): the stream is out of step, connection closed");
      return;
    }
    request.resize(size);
    if (!readAll(fd, request.data(), size)) return;
    uint8_t ok = 1;
    std::unique_lock<std::mutex> lock(handling_);
    t_after_answer = &after_answer;
    try {
      handler_(request.data(), size, caller, &answer);
    } catch (const std::exception& e) {
      ok = 0;
      const std::string text = std::string("exception: ") + e.what();
      answer.resize(kResponseOffset + text.size());
      std::memcpy(answer.data() + kResponseOffset, text.data(), text.size());
      ROS_WARN_STREAM("service " << name_ << ": request from " << caller << " not read: " << e.what());
    }
    t_after_answer = nullptr;
    const auto length = static_cast<uint32_t>(answer.size() - kResponseOffset);
    answer[0] = ok;
    std::memcpy(answer.data() + 1, &length, 4);
    const bool written = writeAll(fd, answer.data(), answer.size());
    runDeferred(&after_answer);
    lock.unlock();
    if (!written || !persistent) return;
  }
}

}  // namespace sixdof_planning
