#pragma once
// The world file's cameras on ROS: per camera <name>/color/image_raw (rgb8), <name>/depth/image_raw (32FC1,
// metres, NaN: no return), a camera_info beside each, <name>/depth/points (organized PointCloud2, x y z rgb,
// in the optical frame) and static tf <parent or world> -> <name>_link -> <name>_optical_frame. Frames go
// out at each camera's rate in simulated time, stamped with the simulated time they show; a camera with no
// subscriber is not rendered.

#include <ros/node_handle.h>
#include <ros/publisher.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <memory>
#include <string>
#include <vector>

#include "sixdof_sim/camera.h"

namespace sixdof_sim {

// The node calls update() before each physics step, when the world shows the step's start time `now`. A world
// reset needs nothing: the node's clock never goes back, so the schedule stays valid.
class CameraPublisher {
 public:
  // Throws WorldError naming the camera and key on a bad camera (see CameraRenderer).
  CameraPublisher(const ros::NodeHandle& nh, const World& world, const WorldSpec& spec,
                  tf2_ros::StaticTransformBroadcaster& static_tf);
  ~CameraPublisher();

  void update(double now);

 private:
  struct Camera {
    ros::Publisher color, color_info, depth, depth_info, points;
    double next_due = 0.0;  // simulated time of the next frame
  };
  void publish(size_t index, const ros::Time& stamp);

  std::unique_ptr<CameraRenderer> renderer_;  // null without cameras: nothing is built
  std::vector<Camera> cameras_;
  CameraFrame frame_;  // reused: no allocation per frame
};

}  // namespace sixdof_sim
