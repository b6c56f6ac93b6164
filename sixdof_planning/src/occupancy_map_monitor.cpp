#include "sixdof_planning/occupancy_map_monitor.h"

#include <algorithm>
#include <cmath>

#include <sensor_msgs/point_cloud2_iterator.h>
#include <tf2_eigen/tf2_eigen.h>
#include <visualization_msgs/MarkerArray.h>

#include "sixdof_planning/move_group_context.h"

namespace sixdof_planning {

namespace {

// How long a cloud waits for tf to reach its stamp (the robot's link transforms come a little after the cloud).
constexpr double kTfWaitSeconds = 0.5;
// rviz needs no more; building the markers of a large map is not free.
constexpr double kMarkerPeriodSeconds = 0.5;

visualization_msgs::MarkerArray cellMarkers(const sixdof_core::OccupancyMap& map, const std::string& frame) {
  visualization_msgs::MarkerArray markers;
  visualization_msgs::Marker clear_all;
  clear_all.header.frame_id = frame;
  clear_all.action = visualization_msgs::Marker::DELETEALL;
  markers.markers.push_back(clear_all);
  // One cube list per cell size (octomap_server's occupied_cells_vis_array layout), coloured by height.
  std::vector<sixdof_core::OccupiedCell> cells = map.occupiedCells();
  std::sort(cells.begin(), cells.end(), [](const auto& a, const auto& b) { return a.size < b.size; });
  double lo = 0.0, hi = 0.0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    lo = i == 0 ? cells[i].center.z() : std::min(lo, cells[i].center.z());
    hi = i == 0 ? cells[i].center.z() : std::max(hi, cells[i].center.z());
  }
  for (const auto& cell : cells) {
    if (markers.markers.size() == 1 || std::abs(markers.markers.back().scale.x - cell.size) > 1e-9) {
      visualization_msgs::Marker marker;
      marker.header.frame_id = frame;
      marker.ns = "occupied_cells";
      marker.id = static_cast<int>(markers.markers.size());
      marker.type = visualization_msgs::Marker::CUBE_LIST;
      marker.action = visualization_msgs::Marker::ADD;
      marker.pose.orientation.w = 1.0;
      marker.scale.x = marker.scale.y = marker.scale.z = cell.size;
      marker.color.a = 1.0;
      markers.markers.push_back(marker);
    }
    auto& marker = markers.markers.back();
    geometry_msgs::Point p;
    p.x = cell.center.x();
    p.y = cell.center.y();
    p.z = cell.center.z();
    marker.points.push_back(p);
    // Blue (low) to red (high), as octomap_server's height map.
    const double t = hi > lo ? (cell.center.z() - lo) / (hi - lo) : 0.5;
    std_msgs::ColorRGBA color;
    color.r = static_cast<float>(t);
    color.g = static_cast<float>(1.0 - std::abs(2.0 * t - 1.0));
    color.b = static_cast<float>(1.0 - t);
    color.a = 1.0f;
    marker.colors.push_back(color);
  }
  return markers;
}

}  // namespace

OccupancyMapMonitor::OccupancyMapMonitor(MoveGroupContext* context)
    : context_(context),
      config_(context->config().occupancy_map),
      frame_(config_.octomap_frame.empty() ? context->planningFrame() : config_.octomap_frame),
      map_(config_.octomap_resolution) {
  ros::NodeHandle& nh = context_->nodeHandle();
  markers_pub_ = nh.advertise<visualization_msgs::MarkerArray>("move_group/occupied_cells_vis_array", 1, true);
  clear_server_ = nh.advertiseService("clear_octomap", &OccupancyMapMonitor::clear, this);
  if (config_.sensors.empty()) return;
  tf_listener_ = std::make_unique<tf2_ros::TransformListener>(tf_buffer_);
  ros::NodeHandle cloud_nh(nh);
  cloud_nh.setCallbackQueue(&cloud_queue_);
  for (std::size_t i = 0; i < config_.sensors.size(); ++i) {
    auto sensor = std::make_unique<Sensor>();
    sensor->config = config_.sensors[i];
    if (!sensor->config.filtered_cloud_topic.empty()) {
      sensor->filtered = nh.advertise<sensor_msgs::PointCloud2>(sensor->config.filtered_cloud_topic, 1);
    }
    sensor->subscriber = cloud_nh.subscribe<sensor_msgs::PointCloud2>(
        sensor->config.point_cloud_topic, 1,
        [this, i](const sensor_msgs::PointCloud2ConstPtr& cloud) { cloudCallback(i, cloud); });
    ROS_INFO_STREAM("occupancy map: " << sensor->config.sensor_plugin << " on " << sensor->subscriber.getTopic()
                                      << ", map in '" << frame_ << "' at " << config_.octomap_resolution << " m");
    sensors_.push_back(std::move(sensor));
  }
  cloud_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &cloud_queue_);
  cloud_spinner_->start();
}

OccupancyMapMonitor::~OccupancyMapMonitor() {
  if (cloud_spinner_) cloud_spinner_->stop();
}

bool OccupancyMapMonitor::lookup(const std::string& target, const std::string& source, const ros::Time& stamp,
                                 Eigen::Isometry3d* pose) const {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(kTfWaitSeconds);
  std::string error;
  while (!tf_buffer_.canTransform(target, source, stamp, &error)) {
    if (ros::WallTime::now() > deadline || !ros::ok()) {
      ROS_WARN_STREAM_THROTTLE(5.0, "occupancy map: no transform " << target << " <- " << source << " at "
                                                                   << stamp << ": " << error << " (cloud skipped)");
      return false;
    }
    ros::WallDuration(0.005).sleep();
  }
  *pose = tf2::transformToEigen(tf_buffer_.lookupTransform(target, source, stamp));
  return true;
}

void OccupancyMapMonitor::cloudCallback(std::size_t index, const sensor_msgs::PointCloud2ConstPtr& cloud) {
  Sensor& sensor = *sensors_[index];
  const OctomapSensorConfig& config = sensor.config;
  const ros::WallTime start = ros::WallTime::now();
  if (config.max_update_rate > 0.0 && (start - sensor.last_update).toSec() < 1.0 / config.max_update_rate) return;
  const std::string& planning = context_->planningFrame();
  const ros::Time& stamp = cloud->header.stamp;
  Eigen::Isometry3d map_from_sensor, map_from_planning;
  if (!lookup(frame_, cloud->header.frame_id, stamp, &map_from_sensor) ||
      !lookup(frame_, planning, stamp, &map_from_planning)) {
    return;
  }
  // The self filter at the cloud's time: every link's pose from tf, attached objects with their links, known world
  // objects where the scene has them.
  const auto scene = context_->scene();
  const auto& collision = *scene->collision();
  std::vector<Eigen::Isometry3d> link_poses;
  for (const auto& link : collision.linkNames()) {
    link_poses.emplace_back();
    if (!lookup(planning, link, stamp, &link_poses.back())) return;
  }
  sixdof_core::ShapeMask mask(config.padding_scale, config.padding_offset);
  for (const auto& placed : collision.bodyShapes(link_poses)) {
    const sixdof_core::SceneStatus status = mask.addShape(placed.shape, map_from_planning * placed.origin);
    if (!status.ok()) ROS_WARN_STREAM_THROTTLE(10.0, "occupancy map: self filter shape skipped: " << status.message);
  }
  const Eigen::Vector3d origin = map_from_sensor.translation();
  std::vector<Eigen::Vector3d> hits, clipped, masked;
  std::vector<Eigen::Vector3f> kept;  // sensor frame, for filtered_cloud_topic
  const bool publish_filtered = sensor.filtered && sensor.filtered.getNumSubscribers() > 0;
  try {
    sensor_msgs::PointCloud2ConstIterator<float> x(*cloud, "x"), y(*cloud, "y"), z(*cloud, "z");
    const std::size_t count = static_cast<std::size_t>(cloud->width) * cloud->height;
    for (std::size_t i = 0; i < count; ++i, ++x, ++y, ++z) {
      if (i % static_cast<std::size_t>(config.point_subsample) != 0) continue;
      const Eigen::Vector3f p(*x, *y, *z);
      if (!p.allFinite()) continue;
      const double range = p.cast<double>().norm();
      const Eigen::Vector3d point = map_from_sensor * p.cast<double>();
      if (range > config.max_range) {
        clipped.push_back(origin + (point - origin) * (config.max_range / range));
      } else if (mask.contains(point)) {
        masked.push_back(point);
      } else {
        hits.push_back(point);
        if (publish_filtered) kept.push_back(p);
      }
    }
  } catch (const std::exception& e) {
    ROS_WARN_STREAM_THROTTLE(5.0, "occupancy map: cloud on " << sensor.subscriber.getTopic() << " skipped: " << e.what());
    return;
  }
  {
    std::lock_guard<std::mutex> lock(map_mutex_);
    map_.insertScan(origin, hits, clipped, masked);
    planning_from_map_ = map_from_planning.inverse();
    publishLocked(planning_from_map_);
  }
  sensor.last_update = start;
  if (publish_filtered) {
    sensor_msgs::PointCloud2 filtered;
    filtered.header = cloud->header;
    sensor_msgs::PointCloud2Modifier modifier(filtered);
    modifier.setPointCloud2FieldsByString(1, "xyz");
    modifier.resize(kept.size());
    sensor_msgs::PointCloud2Iterator<float> out(filtered, "x");
    for (const auto& p : kept) {
      out[0] = p.x();
      out[1] = p.y();
      out[2] = p.z();
      ++out;
    }
    sensor.filtered.publish(filtered);
  }
  ROS_DEBUG_STREAM("occupancy map: cloud of " << cloud->width * cloud->height << " points (" << hits.size()
                                              << " hits, " << masked.size() << " masked, " << clipped.size()
                                              << " beyond range) in " << (ros::WallTime::now() - start).toSec() * 1e3
                                              << " ms");
}

void OccupancyMapMonitor::publishLocked(const Eigen::Isometry3d& planning_from_map) {
  context_->setOccupancyMap(std::make_shared<const sixdof_core::OccupancyMap>(map_), planning_from_map);
  const ros::WallTime now = ros::WallTime::now();
  if ((now - last_markers_).toSec() < kMarkerPeriodSeconds && !map_.empty()) return;
  last_markers_ = now;
  markers_pub_.publish(cellMarkers(map_, frame_));
}

bool OccupancyMapMonitor::clear(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  std::lock_guard<std::mutex> lock(map_mutex_);
  map_.clear();
  publishLocked(planning_from_map_);
  ROS_INFO("occupancy map cleared (clear_octomap)");
  return true;
}

}  // namespace sixdof_planning
