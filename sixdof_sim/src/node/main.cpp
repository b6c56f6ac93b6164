#include <ros/ros.h>

#include <exception>

#include "sim_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "sixdof_sim");
  // The handles outlive the try block: the last one going away shuts ROS (and its logging) down.
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  try {
    sixdof_sim::SimNode node(nh, pnh);
    node.run();
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM("[sixdof_sim] " << e.what());
    return 1;
  }
  return 0;
}
