#include <ros/ros.h>

#include "sixdof_planning/move_group_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "move_group");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  std::unique_ptr<sixdof_planning::MoveGroupNode> node;
  try {
    node = std::make_unique<sixdof_planning::MoveGroupNode>(nh, private_nh);
  } catch (const sixdof_planning::ConfigError& e) {
    ROS_FATAL_STREAM("move_group: bad configuration: " << e.what());
    return 1;
  }
  // Planning, execution and scene requests are served concurrently (executions block their action's thread).
  ros::AsyncSpinner spinner(4);
  spinner.start();
  ROS_INFO("move_group: ready");
  ros::waitForShutdown();
  return 0;
}
