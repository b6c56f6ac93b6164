#pragma once
// What the capabilities share (MoveIt's MoveGroupCapability): the context they work in and their one server.
// A capability derives as `class X : public ServiceCapability<X>` (or ActionCapability<X, Action>), inherits the
// constructor and declares `ErrorCode handle(const Request&, Response&)` (or `void execute(const GoalConstPtr&)`):
// the handler fills the response (its error code field too, where the type has one) and returns the outcome with
// its words; a failure is published on move_group/error_reports with the caller's name. Its source
// includes "move_group_capability_impl.h" and instantiates the base there (`template class
// ServiceCapability<X>;`), where the messages are complete: this header names them only through fwd.h.
// Each service is answered by a thread of its own, in the order its requests arrive (the response is written by
// the thread that computed it, which then reads a request already waiting on a kept connection itself: no other
// thread is woken and the connection is not polled for writing in the meantime); different services run
// concurrently. Goals and topics are served by the node's spinner. Neither starts before the whole node is built
// (MoveGroupNode::start), so a capability's own members are ready for them.

#include <memory>
#include <string>

#include <ros/callback_queue.h>
#include <ros/forwards.h>
#include <ros/service_server.h>
#include <ros/spinner.h>

#include "sixdof_planning/errors.h"
#include "sixdof_planning/fwd.h"

namespace sixdof_planning {

template <class Capability>
class ServiceCapability {
 public:
  // Advertises `service` in the context's namespace, answered by Capability::handle; failures are reported.
  ServiceCapability(MoveGroupContext* context, const std::string& service);
  ServiceCapability(const ServiceCapability&) = delete;
  ServiceCapability& operator=(const ServiceCapability&) = delete;
  ~ServiceCapability();

  // Starts answering (requests that came before wait for it); stop() waits for a request being answered.
  void start();
  void stop();

 protected:
  MoveGroupContext* const context_;
  const std::string service_;  // also the source its error codes name

 private:
  template <class Request, class Response>
  ros::ServiceServer advertise(ros::NodeHandle& nh, const std::string& service,
                               ErrorCode (Capability::*handle)(const Request&, Response&));

  ros::CallbackQueue queue_;
  ros::ServiceServer server_;
  std::unique_ptr<ros::AsyncSpinner> thread_;
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
