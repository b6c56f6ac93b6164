#pragma once
// A ROS service served over TCPROS (the protocol of roscpp's and rospy's service clients) by a thread per client
// connection: the thread that reads a request computes its answer and writes it. roscpp's own servers hand each
// request from the node's poll thread to a callback queue and wake the poll thread again for every write (the
// connection is polled for writing while the answer goes out); on two cores those hand-offs cost more than a
// small request's handling. The service is registered with the master under the node's name like roscpp's, so
// every client, rosservice and `rosnode info` see an ordinary service.
//
// Wire behaviour, as roscpp's ServiceClientLink: the client's connection header must name this service, a caller
// and an md5sum (this service's or "*"); otherwise the answer is a header holding only `error=...` and the
// connection is closed. The server's header holds callerid, md5sum, type, request_type and response_type (a probe,
// as rospy's wait_for_service sends, reads it and closes). Each request is its length (uint32) and bytes; each
// answer an ok byte, a length and the serialized response (ok 1) or an error text (ok 0, for a request the handler
// could not read). A connection whose header asked for persistent=1 is kept for further requests, any other is
// closed after its answer. Requests to one server are handled one at a time (in the order their connections'
// threads reach it); a request longer than 1 GB ends the connection, as in roscpp. It listens on every address of
// the host (only the loopback when the node's host is it), over IPv6 when ROS_IPV6 is on.

#include <atomic>
#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace sixdof_planning {

struct TcprosServiceType {
  std::string type;  // e.g. moveit_msgs/GetMotionPlan
  std::string md5sum;
  std::string request_type;
  std::string response_type;
};

class TcprosServiceServer {
 public:
  // Where a handler writes the serialized response in its output: after TCPROS's ok byte and length.
  static constexpr std::size_t kResponseOffset = 5;
  // Answers one request: its bytes and the caller's name (the connection header's callerid) in; out resized to
  // kResponseOffset + the response's length with the response from kResponseOffset on. Throws std::exception for
  // a request it cannot read: the answer is then TCPROS's error answer with its words.
  using Handler =
      std::function<void(const uint8_t* request, uint32_t size, const std::string& caller, std::vector<uint8_t>* out)>;

  // Listens on a port of its own and registers `resolved_name` with the master; std::runtime_error naming the
  // service when either fails. Connections wait (in the listen queue) until start().
  TcprosServiceServer(const std::string& resolved_name, TcprosServiceType type, Handler handler);
  ~TcprosServiceServer();
  TcprosServiceServer(const TcprosServiceServer&) = delete;
  TcprosServiceServer& operator=(const TcprosServiceServer&) = delete;

  // Starts accepting connections.
  void start();
  // Stops accepting, closes every connection and waits for their threads (a request being handled is answered
  // first). The service stays registered until destruction.
  void stop();

  const std::string& uri() const { return uri_; }  // rosrpc://host:port

  // Runs `work` once the answer to the request this thread is handling has been written (still before the next
  // request is handled), or at once on a thread that is not handling a server's request: what the client need
  // not wait for (notifications, freeing what the request built). An exception it throws is logged.
  static void afterAnswer(std::function<void()> work);

 private:
  struct Connection {
    int fd = -1;
    std::thread thread;
    std::atomic<bool> done{false};
  };

  void acceptLoop();
  void serve(Connection* connection);
  // Reads and checks the connection header and sends the server's; false when the connection is to be closed.
  bool handshake(int fd, std::string* caller, bool* persistent) const;
  void reap(bool all);
  // The master call `method` (registerService, unregisterService) for this service: the node's name, the service's
  // name and URI, and to register the node's XML-RPC URI; waits for the master when asked. True when it answered.
  bool callMaster(const char* method, bool with_node_api, bool wait_for_master) const;
  // The answer's work deferred by afterAnswer, run under handling_.
  static void runDeferred(std::vector<std::function<void()>>* work);

  const std::string name_;
  const TcprosServiceType type_;
  const Handler handler_;
  std::string uri_;
  int listen_fd_ = -1;
  bool registered_ = false;
  std::mutex handling_;  // one request at a time
  std::mutex connections_mutex_;
  std::list<Connection> connections_;
  std::thread accept_thread_;
  std::atomic<bool> stopping_{false};
};

}  // namespace sixdof_planning
