#pragma once
// The capability bases' constructors, for the capabilities' own sources (see move_group_capability.h): the server
// needs the messages, which the node's source does not include.

#include <actionlib/server/simple_action_server.h>

#include "sixdof_planning/move_group_capability.h"
#include "sixdof_planning/move_group_context.h"

namespace sixdof_planning {

template <class Capability>
ServiceCapability<Capability>::ServiceCapability(MoveGroupContext* context, const std::string& service)
    : context_(context), service_(service) {
  ros::NodeHandle nh(context->nodeHandle());
  nh.setCallbackQueue(&queue_);
  server_ = advertise(nh, service, &Capability::handle);
}

template <class Capability>
ServiceCapability<Capability>::~ServiceCapability() {
  stop();
  server_.shutdown();
}

template <class Capability>
void ServiceCapability<Capability>::start() {
  if (thread_) return;
  thread_ = std::make_unique<ros::AsyncSpinner>(1, &queue_);
  thread_->start();
}

template <class Capability>
void ServiceCapability<Capability>::stop() {
  thread_.reset();  // the spinner's destructor stops its thread and waits for it
}

template <class Capability>
template <class Request, class Response>
ros::ServiceServer ServiceCapability<Capability>::advertise(ros::NodeHandle& nh, const std::string& service,
                                                            ErrorCode (Capability::*handle)(const Request&,
                                                                                            Response&)) {
  using Event = ros::ServiceEvent<Request, Response>;
  // The capability is reached through its base only when a request comes, once it is fully built.
  const std::string resolved = nh.resolveName(service);
  return nh.advertiseService<Event>(service, boost::function<bool(Event&)>([this, handle, resolved](Event& event) {
    const ErrorCode code = (static_cast<Capability*>(this)->*handle)(event.getRequest(), event.getResponse());
    if (!isSuccess(code)) context_->reportError(event.getCallerName(), resolved, code);
    return true;
  }));
}

template <class Capability, class Action>
ActionCapability<Capability, Action>::ActionCapability(MoveGroupContext* context, TrajectoryExecutor* executor,
                                                       const std::string& action)
    : context_(context),
      executor_(executor),
      server_(std::make_unique<actionlib::SimpleActionServer<Action>>(
          context->nodeHandle(), action, [this](const auto& goal) { static_cast<Capability*>(this)->execute(goal); },
          false)) {
  server_->start();
}

template <class Capability, class Action>
ActionCapability<Capability, Action>::~ActionCapability() = default;

}  // namespace sixdof_planning
