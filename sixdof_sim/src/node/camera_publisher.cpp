#include "camera_publisher.h"

#include <geometry_msgs/TransformStamped.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/PointField.h>
#include <tf2_eigen/tf2_eigen.h>

#include <cmath>
#include <cstring>

namespace sixdof_sim {
namespace {

sensor_msgs::CameraInfo cameraInfo(const CameraSpec& camera, const std_msgs::Header& header) {
  const CameraIntrinsics k = cameraIntrinsics(camera);
  sensor_msgs::CameraInfo info;
  info.header = header;
  info.width = static_cast<std::uint32_t>(camera.width);
  info.height = static_cast<std::uint32_t>(camera.height);
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  info.K = {k.fx, 0.0, k.cx, 0.0, k.fy, k.cy, 0.0, 0.0, 1.0};
  info.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  info.P = {k.fx, 0.0, k.cx, 0.0, 0.0, k.fy, k.cy, 0.0, 0.0, 0.0, 1.0, 0.0};
  return info;
}

geometry_msgs::TransformStamped transform(const std::string& parent, const std::string& child,
                                          const Eigen::Isometry3d& pose) {
  geometry_msgs::TransformStamped t = tf2::eigenToTransform(pose);
  t.header.frame_id = parent;
  t.child_frame_id = child;
  return t;
}

}  // namespace

CameraPublisher::CameraPublisher(const ros::NodeHandle& nh, const World& world, const WorldSpec& spec,
                                 tf2_ros::StaticTransformBroadcaster& static_tf) {
  if (spec.cameras.empty()) return;
  renderer_ = std::make_unique<CameraRenderer>(world, spec);
  std::vector<geometry_msgs::TransformStamped> frames;
  for (const CameraSpec& spec_camera : renderer_->cameras()) {
    ros::NodeHandle camera_nh(nh, spec_camera.name);
    Camera c;
    c.color = camera_nh.advertise<sensor_msgs::Image>("color/image_raw", 2);
    c.color_info = camera_nh.advertise<sensor_msgs::CameraInfo>("color/camera_info", 2);
    c.depth = camera_nh.advertise<sensor_msgs::Image>("depth/image_raw", 2);
    c.depth_info = camera_nh.advertise<sensor_msgs::CameraInfo>("depth/camera_info", 2);
    c.points = camera_nh.advertise<sensor_msgs::PointCloud2>("depth/points", 2);
    cameras_.push_back(c);
    const std::string link = spec_camera.name + "_link";
    frames.push_back(transform(spec_camera.parent_link.empty() ? "world" : spec_camera.parent_link, link,
                               spec_camera.pose));
    frames.push_back(transform(link, spec_camera.name + "_optical_frame", opticalInLink()));
  }
  static_tf.sendTransform(frames);
}

CameraPublisher::~CameraPublisher() = default;

void CameraPublisher::update(double now) {
  for (size_t i = 0; i < cameras_.size(); ++i) {
    Camera& c = cameras_[i];
    if (now + 1e-9 < c.next_due) continue;
    // Frame k is due at k / rate: no drift from the physics step not dividing the period.
    const double rate = renderer_->cameras()[i].rate;
    c.next_due = (std::floor(now * rate + 1e-6) + 1.0) / rate;
    if (c.color.getNumSubscribers() + c.color_info.getNumSubscribers() + c.depth.getNumSubscribers() +
            c.depth_info.getNumSubscribers() + c.points.getNumSubscribers() ==
        0) {
      continue;
    }
    publish(i, ros::Time(now));
  }
}

void CameraPublisher::publish(size_t index, const ros::Time& stamp) {
  Camera& c = cameras_[index];
  const CameraSpec& spec = renderer_->cameras()[index];
  renderer_->render(index, &frame_);
  const auto width = static_cast<std::uint32_t>(frame_.width);
  const auto height = static_cast<std::uint32_t>(frame_.height);
  const size_t pixels = static_cast<size_t>(width) * height;
  std_msgs::Header header;
  header.stamp = stamp;
  header.frame_id = spec.name + "_optical_frame";

  auto image = [&](const char* encoding, std::uint32_t bytes_per_pixel, const void* data) {
    sensor_msgs::Image msg;
    msg.header = header;
    msg.width = width;
    msg.height = height;
    msg.encoding = encoding;
    msg.step = bytes_per_pixel * width;
    msg.data.resize(bytes_per_pixel * pixels);
    std::memcpy(msg.data.data(), data, msg.data.size());
    return msg;
  };
  if (c.color.getNumSubscribers() > 0) c.color.publish(image("rgb8", 3, frame_.rgb.data()));
  if (c.depth.getNumSubscribers() > 0) c.depth.publish(image("32FC1", 4, frame_.depth.data()));
  if (c.color_info.getNumSubscribers() > 0 || c.depth_info.getNumSubscribers() > 0) {
    const sensor_msgs::CameraInfo info = cameraInfo(spec, header);
    c.color_info.publish(info);
    c.depth_info.publish(info);
  }
  if (c.points.getNumSubscribers() > 0) {
    sensor_msgs::PointCloud2 cloud;
    cloud.header = header;
    cloud.width = width;
    cloud.height = height;
    cloud.is_dense = false;  // NaN where the depth is
    cloud.is_bigendian = false;
    const char* names[] = {"x", "y", "z", "rgb"};
    for (std::uint32_t f = 0; f < 4; ++f) {
      sensor_msgs::PointField field;
      field.name = names[f];
      field.offset = 4 * f;
      field.datatype = sensor_msgs::PointField::FLOAT32;
      field.count = 1;
      cloud.fields.push_back(field);
    }
    cloud.point_step = 16;
    cloud.row_step = 16 * width;
    cloud.data.resize(16 * pixels);
    const CameraIntrinsics k = cameraIntrinsics(spec);
    auto* out = reinterpret_cast<float*>(cloud.data.data());
    for (std::uint32_t v = 0; v < height; ++v) {
      for (std::uint32_t u = 0; u < width; ++u) {
        const size_t p = static_cast<size_t>(v) * width + u;
        const float z = frame_.depth[p];
        float* point = out + 4 * p;
        point[0] = static_cast<float>((u - k.cx) / k.fx) * z;  // NaN depth -> NaN point
        point[1] = static_cast<float>((v - k.cy) / k.fy) * z;
        point[2] = z;
        // PCL's packed rgb: 0x00RRGGBB in the bits of a float.
        const std::uint32_t rgb = (static_cast<std::uint32_t>(frame_.rgb[3 * p]) << 16) |
                                  (static_cast<std::uint32_t>(frame_.rgb[3 * p + 1]) << 8) | frame_.rgb[3 * p + 2];
        std::memcpy(&point[3], &rgb, 4);
      }
    }
    c.points.publish(cloud);
  }
}

}  // namespace sixdof_sim
