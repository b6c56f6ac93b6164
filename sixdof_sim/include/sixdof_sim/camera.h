#pragma once
// Simulated RGB-D cameras: ray casting (Embree) of a World's robot links (URDF visuals in their material
// colours; collision shapes for links without visuals), objects, tables and ground plane. ROS-free.
//
// Conventions:
//   camera link frame     REP 103 body frame: x forward, y left, z up (CameraSpec::pose places it)
//   optical frame         z forward, x right, y down: link * rpy(-pi/2, 0, -pi/2) (opticalInLink())
//   pinhole               fx = fy = W / (2 tan(hfov / 2)), cx = (W - 1) / 2, cy = (H - 1) / 2: pixel (u, v)
//                         (column u, row v) is the ray through optical-frame point ((u - cx) / fx, (v - cy) / fy, 1)
//   depth                 metres along the optical z axis; NaN where nothing is hit or the hit is outside
//                         [near_clip, far_clip]
//   colour                rgb8; Lambert shading under a headlight (the light sits at the camera), so a surface
//                         keeps its hue and saturation and only its brightness changes with the viewing angle;
//                         black where nothing is hit. Alpha is ignored (translucent markers render opaque).

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sixdof_sim/world.h"
#include "sixdof_sim/world_types.h"

namespace sixdof_sim {

struct CameraIntrinsics {
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
};

CameraIntrinsics cameraIntrinsics(const CameraSpec& camera);

// The optical frame in the camera link frame: rpy(-pi/2, 0, -pi/2).
Eigen::Isometry3d opticalInLink();

// Checks a camera's own values (name, finite pose, size, field of view, rate, clip range, noise); the
// message names the key, e.g. "camera 'front': 'horizontal_fov_deg' must be in (0, 180)". The parent
// link is checked against the robot by CameraRenderer.
Result validateCameraSpec(const CameraSpec& camera);

struct CameraFrame {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, 3 bytes (r, g, b) per pixel
  std::vector<float> depth;       // row-major, metres along the optical axis, NaN: no return
  Eigen::Isometry3d link_pose = Eigen::Isometry3d::Identity();  // camera link frame in the world frame
  double sim_time = 0.0;                                         // World::simTime() the frame shows
};

struct CameraRendererOptions {
  int threads = 0;  // render threads; 0: one per hardware thread
};

// One ray-casting scene of a World, shared by its cameras. Every mesh and primitive is built once
// (one bounding-volume hierarchy per shape); each render moves the instances to the world's current link
// and object poses (objects spawned or deleted since the last render are added or removed).
// Not thread-safe; the World must outlive the renderer and must not step during render().
class CameraRenderer {
 public:
  // `world` was built from `spec`; the renderer takes the robot's visuals from the world's robot model
  // (World::robotModel), the cameras and the ground plane from the spec and the objects (with their current poses)
  // from the world, their meshes resolved with World::packageResolver. Throws WorldError naming the camera and key
  // on an invalid camera (validateCameraSpec), a parent link the robot does not have, duplicate camera names or a
  // camera frame name that is a robot link; and on unreadable meshes.
  CameraRenderer(const World& world, const WorldSpec& spec,
                 const CameraRendererOptions& options = CameraRendererOptions());
  ~CameraRenderer();
  CameraRenderer(const CameraRenderer&) = delete;
  CameraRenderer& operator=(const CameraRenderer&) = delete;

  const std::vector<CameraSpec>& cameras() const;
  // The camera link frame in the world frame as the world is now.
  Eigen::Isometry3d linkPose(size_t camera) const;
  // Renders camera `camera` (index into cameras()) as the world is now. Depth noise (when the camera has
  // some) is drawn from a generator seeded by the camera's seed and the frame's index: the same frames
  // of the same world give the same images.
  void render(size_t camera, CameraFrame* frame);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sixdof_sim
