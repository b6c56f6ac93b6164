#pragma once
// MoveIt's occupancy map monitor inside move_group: the point clouds of ~sensors (PointCloudOctomapUpdater
// semantics) go through the self filter (the robot's links, attached and known world objects, padded) into an
// occupancy map that planning, IK, Cartesian paths and check_state_validity collide against. Offers
// clear_octomap (std_srvs/Empty) and publishes the occupied cells for rviz (move_group/occupied_cells_vis_array).

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_srvs/Empty.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <sixdof_core/occupancy_map.h>

#include "sixdof_planning/config.h"

namespace sixdof_planning {

class MoveGroupContext;

class OccupancyMapMonitor {
 public:
  explicit OccupancyMapMonitor(MoveGroupContext* context);
  ~OccupancyMapMonitor();

 private:
  struct Sensor {
    OctomapSensorConfig config;
    ros::Subscriber subscriber;
    ros::Publisher filtered;
    ros::WallTime last_update;
  };

  void cloudCallback(std::size_t sensor, const sensor_msgs::PointCloud2ConstPtr& cloud);
  // Waits (wall clock, bounded) until tf can give target <- source at `stamp`.
  bool lookup(const std::string& target, const std::string& source, const ros::Time& stamp,
              Eigen::Isometry3d* pose) const;
  bool clear(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  // Hands a snapshot of the map to the planning scene and publishes the cells. Caller holds map_mutex_.
  void publishLocked(const Eigen::Isometry3d& planning_from_map);

  MoveGroupContext* context_;
  const OccupancyMapConfig config_;
  std::string frame_;  // the map's frame

  std::mutex map_mutex_;
  sixdof_core::OccupancyMap map_;
  Eigen::Isometry3d planning_from_map_ = Eigen::Isometry3d::Identity();
  ros::WallTime last_markers_;

  tf2_ros::Buffer tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  // Clouds are processed on their own thread so that a large cloud never delays a planning request.
  ros::CallbackQueue cloud_queue_;
  std::unique_ptr<ros::AsyncSpinner> cloud_spinner_;
  std::vector<std::unique_ptr<Sensor>> sensors_;
  ros::Publisher markers_pub_;
  ros::ServiceServer clear_server_;
};

}  // namespace sixdof_planning
