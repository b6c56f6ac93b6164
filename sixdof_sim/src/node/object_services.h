#pragma once
// sixdof_sim/{spawn_object, delete_object, get_object_state, set_object_state}.

#include <ros/node_handle.h>
#include <ros/service_server.h>
#include <sixdof_msgs/DeleteObject.h>
#include <sixdof_msgs/GetObjectState.h>
#include <sixdof_msgs/SetObjectState.h>
#include <sixdof_msgs/SpawnObject.h>

#include "sixdof_sim/world.h"

namespace sixdof_sim {

class ObjectServices {
 public:
  // nh: the namespace of the services (sixdof_sim).
  ObjectServices(ros::NodeHandle nh, World& world);

 private:
  bool spawn(sixdof_msgs::SpawnObject::Request& req, sixdof_msgs::SpawnObject::Response& res);
  bool remove(sixdof_msgs::DeleteObject::Request& req, sixdof_msgs::DeleteObject::Response& res);
  bool get(sixdof_msgs::GetObjectState::Request& req, sixdof_msgs::GetObjectState::Response& res);
  bool set(sixdof_msgs::SetObjectState::Request& req, sixdof_msgs::SetObjectState::Response& res);

  World& world_;
  ros::ServiceServer spawn_, delete_, get_, set_;
};

}  // namespace sixdof_sim
