#include "object_services.h"

#include <ros/console.h>

#include "conversions.h"

namespace sixdof_sim {

namespace {

// Fills a response's success/status_message; failures are logged so they show up next to the node's output.
template <class Response>
bool respond(Response& res, const Result& r, const std::string& what) {
  res.success = r.ok();
  res.status_message = r.ok() ? what : r.message;
  if (!r.ok()) {
    ROS_WARN_STREAM("[sixdof_sim] " << r.message);
  }
  return true;
}

}  // namespace

ObjectServices::ObjectServices(ros::NodeHandle nh, World& world)
    : world_(world),
      spawn_(nh.advertiseService("spawn_object", &ObjectServices::spawn, this)),
      delete_(nh.advertiseService("delete_object", &ObjectServices::remove, this)),
      get_(nh.advertiseService("get_object_state", &ObjectServices::get, this)),
      set_(nh.advertiseService("set_object_state", &ObjectServices::set, this)) {}

bool ObjectServices::spawn(sixdof_msgs::SpawnObject::Request& req, sixdof_msgs::SpawnObject::Response& res) {
  ObjectSpec spec;
  std::string error;
  if (!fromMsg(req.object, &spec, &error)) {
    return respond(res, {Status::kInvalidArgument, error}, "");
  }
  return respond(res, world_.spawnObject(spec), "spawned '" + spec.name + "'");
}

bool ObjectServices::remove(sixdof_msgs::DeleteObject::Request& req, sixdof_msgs::DeleteObject::Response& res) {
  return respond(res, world_.deleteObject(req.name), "deleted '" + req.name + "'");
}

bool ObjectServices::get(sixdof_msgs::GetObjectState::Request& req, sixdof_msgs::GetObjectState::Response& res) {
  ObjectState state;
  const Result r = world_.objectState(req.name, &state);
  if (r.ok()) {
    res.object = toMsg(state.spec);
    res.twist = toMsg(state.twist);
    res.attached_to = state.attached_to;
  }
  return respond(res, r, "");
}

bool ObjectServices::set(sixdof_msgs::SetObjectState::Request& req, sixdof_msgs::SetObjectState::Response& res) {
  Eigen::Isometry3d pose;
  Twist twist;
  std::string error;
  if (!fromMsg(req.pose, &pose, &error) || !fromMsg(req.twist, &twist, &error)) {
    return respond(res, {Status::kInvalidArgument, "object '" + req.name + "': " + error}, "");
  }
  return respond(res, world_.setObjectState(req.name, pose, twist), "moved '" + req.name + "'");
}

}  // namespace sixdof_sim
