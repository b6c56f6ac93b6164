// The main of this package's rostest gtests: a ROS node named after the test executable, alive while the tests run.
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <filesystem>

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, std::filesystem::path(argv[0]).filename().string());
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
