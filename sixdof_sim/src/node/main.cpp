#include <ros/ros.h>

#include <exception>
#include <memory>
#include <string>

#include "sim_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "sixdof_sim");
  // The handles outlive the try blocks: the last one going away shuts ROS (and its logging) down.
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  std::unique_ptr<sixdof_sim::SimNode> node;
  try {
    node = std::make_unique<sixdof_sim::SimNode>(nh, pnh);
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM("[sixdof_sim] " << e.what());
    // The simulator could not start (bad URDF, world or parameters): sixdof_bringup's startup_watch ends the launch
    // with this message instead of leaving the other nodes waiting for a clock.
    pnh.setParam("startup_error", std::string(e.what()));
    return 1;
  }
  try {
    node->run();
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM("[sixdof_sim] " << e.what());
    return 1;
  }
  return 0;
}
