#include <ros/ros.h>

#include <exception>

#include "sim_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "sixdof_sim");
  try {
    sixdof_sim::SimNode node{ros::NodeHandle(), ros::NodeHandle("~")};
    node.run();
  } catch (const std::exception& e) {
    ROS_FATAL_STREAM("[sixdof_sim] " << e.what());
    return 1;
  }
  return 0;
}
