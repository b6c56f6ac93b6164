#pragma once
// What the capabilities share (MoveIt's MoveGroupCapability): the context they work in and their one server.
// A capability derives as `class X : public ServiceCapability<X>` (or ActionCapability<X, Action>), inherits the
// constructor and declares `ErrorCode handle(const Request&, Response&)` (or `void execute(const GoalConstPtr&)`):
// the handler fills the response (its error code field too, where the type has one) and returns the outcome with
// its words; a failure is published on move_group/error_reports with the caller's name. Its source
// includes "move_group_capability_impl.h" and instantiates the base there (`template class
// ServiceCapability<X>;`), where the messages are complete: this header names them only through fwd.h.
// Each service is served over TCPROS by sixdof's own server (tcpros_service_server.h): a thread per client
// connection reads a request, computes the answer and writes it, with no hand-off to another thread; requests to
// one service are answered one at a time, different services concurrently. Goals and topics are served by the
// node's spinner. Neither starts before the whole node is built (MoveGroupNode::start), so a capability's own
// members are ready for them.

#include <memory>
#include <string>

#include "sixdof_planning/errors.h"
#include "sixdof_planning/fwd.h"
#include "sixdof_planning/tcpros_service_server.h"

namespace sixdof_planning {

template <class Capability>
class ServiceCapability {
 public:
  // Advertises `service` in the context's namespace, answered by Capability::handle; failures are reported.
  ServiceCapability(MoveGroupContext* context, const std::string& service);
  ServiceCapability(const ServiceCapability&) = delete;
  ServiceCapability& operator=(const ServiceCapability&) = delete;
  ~ServiceCapability();

  // Starts answering (clients that connected before wait for it); stop() closes the connections and waits for a
  // request being answered.
  void start();
  void stop();

 protected:
  MoveGroupContext* const context_;
  const std::string service_;  // also the source its error codes name

 private:
  template <class Request, class Response>
  std::unique_ptr<TcprosServiceServer> advertise(const std::string& resolved,
                                                 ErrorCode (Capability::*handle)(const Request&, Response&));

  std::unique_ptr<TcprosServiceServer> server_;
};

template <class Capability, class Action>
class ActionCapability {
 public:
  // Starts the action server `action` in the context's namespace; Capability::execute runs its goals, through
  // `executor` when they move the robot.
  ActionCapability(MoveGroupContext* context, TrajectoryExecutor* executor, const std::string& action);
  ~ActionCapability();
  ActionCapability(const ActionCapability&) = delete;
  ActionCapability& operator=(const ActionCapability&) = delete;

 protected:
  MoveGroupContext* const context_;
  TrajectoryExecutor* const executor_;
  std::unique_ptr<actionlib::SimpleActionServer<Action>> server_;
};

}  // namespace sixdof_planning
