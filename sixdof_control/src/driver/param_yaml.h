#pragma once
// Parameter-server values as YAML, for what reads YAML (hardware plugins' init, loadJointLimits): hardware.yaml and
// joint_limits.yaml are loaded with rosparam and reach the driver as XmlRpc values.

#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcValue.h>
#include <yaml-cpp/yaml.h>

#include <string>

namespace sixdof_control {

// Scalars, lists and dictionaries; a double keeps its full precision. Throws std::runtime_error naming `where` for a
// value YAML cannot hold (base64, date/time).
YAML::Node toYaml(XmlRpc::XmlRpcValue& value, const std::string& where);

// The parameter `key` of nh as YAML; a null node when it is not set.
YAML::Node paramYaml(const ros::NodeHandle& nh, const std::string& key);

}  // namespace sixdof_control
