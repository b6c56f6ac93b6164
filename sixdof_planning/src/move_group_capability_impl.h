#pragma once
// The capability bases' constructors, for the capabilities' own sources (see move_group_capability.h): the server
// needs the messages, which the node's source does not include.

#include <actionlib/server/simple_action_server.h>

#include "sixdof_planning/move_group_capability.h"
#include "sixdof_planning/move_group_context.h"

namespace sixdof_planning {

template <class Capability>
ServiceCapability<Capability>::ServiceCapability(MoveGroupContext* context, const std::string& service)
    : context_(context), service_(service), server_(advertise(context->nodeHandle(), service, &Capability::handle)) {}

template <class Capability>
template <class Request, class Response>
ros::ServiceServer ServiceCapability<Capability>::advertise(ros::NodeHandle& nh, const std::string& service,
                                                            bool (Capability::*handle)(Request&, Response&)) {
  // The capability is reached through its base only when a request comes, once it is fully built.
  return nh.advertiseService<Request, Response>(service, [this, handle](Request& request, Response& response) {
    return (static_cast<Capability*>(this)->*handle)(request, response);
  });
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
