#pragma once
// The capability bases' constructors, for the capabilities' own sources (see move_group_capability.h): the server
// needs the messages, which the node's source does not include.

#include <actionlib/server/simple_action_server.h>
#include <ros/service_traits.h>
#include <ros/serialization.h>

#include "sixdof_planning/move_group_capability.h"
#include "sixdof_planning/move_group_context.h"

namespace sixdof_planning {

template <class Capability>
ServiceCapability<Capability>::ServiceCapability(MoveGroupContext* context, const std::string& service)
    : context_(context), service_(service) {
  server_ = advertise(context->nodeHandle().resolveName(service), &Capability::handle);
}

template <class Capability>
ServiceCapability<Capability>::~ServiceCapability() {
  stop();
}

template <class Capability>
void ServiceCapability<Capability>::start() {
  server_->start();
}

template <class Capability>
void ServiceCapability<Capability>::stop() {
  server_->stop();
}

template <class Capability>
template <class Request, class Response>
std::unique_ptr<TcprosServiceServer> ServiceCapability<Capability>::advertise(
    const std::string& resolved, ErrorCode (Capability::*handle)(const Request&, Response&)) {
  // Generated requests carry their service's type and md5sum (service_traits).
  TcprosServiceType type{ros::service_traits::datatype<Request>(), ros::service_traits::md5sum<Request>(),
                         ros::message_traits::datatype<Request>(), ros::message_traits::datatype<Response>()};
  // The capability is reached through its base only when a request comes, once it is fully built.
  return std::make_unique<TcprosServiceServer>(
      resolved, std::move(type),
      [this, handle, resolved](const uint8_t* data, uint32_t size, const std::string& caller,
                               std::vector<uint8_t>* out) {
        namespace ser = ros::serialization;
        // The messages are freed once the answer is written.
        auto messages = std::make_shared<std::pair<Request, Response>>();
        Request& request = messages->first;
        try {
          ser::IStream in(const_cast<uint8_t*>(data), size);
          ser::deserialize(in, request);
        } catch (const ser::StreamOverrunException& e) {
          throw std::runtime_error("a request of " + std::to_string(size) + " bytes is not a " +
                                   ros::message_traits::datatype<Request>() + " (" + e.what() + ")");
        }
        Response& response = messages->second;
        const ErrorCode code = (static_cast<Capability*>(this)->*handle)(request, response);
        if (!isSuccess(code)) context_->reportError(caller, resolved, code);
        const uint32_t length = ser::serializationLength(response);
        out->resize(TcprosServiceServer::kResponseOffset + length);
        ser::OStream stream(out->data() + TcprosServiceServer::kResponseOffset, length);
        ser::serialize(stream, response);
        TcprosServiceServer::afterAnswer([messages = std::move(messages)]() mutable { messages.reset(); });
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
