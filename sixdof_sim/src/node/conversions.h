#pragma once
// Message <-> World/controller type conversions for the sixdof_sim node.

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Twist.h>
#include <sixdof_msgs/SimObject.h>

#include <string>

#include "sixdof_sim/world_types.h"

namespace sixdof_sim {

geometry_msgs::Pose toMsg(const Eigen::Isometry3d& pose);
geometry_msgs::Twist toMsg(const Twist& twist);
sixdof_msgs::SimObject toMsg(const ObjectSpec& spec);

// Returns false with `error` naming the problem (non-finite or zero-length quaternion, NaN).
bool fromMsg(const geometry_msgs::Pose& msg, Eigen::Isometry3d* pose, std::string* error);
bool fromMsg(const geometry_msgs::Twist& msg, Twist* twist, std::string* error);
// SolidPrimitive BOX [x y z], SPHERE [r], CYLINDER [height radius], or mesh_resource (mesh_scale all zero
// means 1). An all-zero color (the message default) means the World's default color.
bool fromMsg(const sixdof_msgs::SimObject& msg, ObjectSpec* spec, std::string* error);

}  // namespace sixdof_sim
