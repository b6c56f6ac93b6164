#include <ros/ros.h>

#include <exception>

#include "driver_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "sixdof_control");
  // The handles outlive the try block: the last one going away shuts ROS (and its logging) down.
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  try {
    sixdof_control::DriverNode node(nh, pnh);
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM("[sixdof_control] " << e.what());
    return 1;
  }
  return 0;
}
