// Simulated cameras: a known box at a known pose lands on the pinhole model's pixels and depth, in its
// colour; optical-frame conventions; clipping and noise; bad camera configs refused with the key named.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "sixdof_sim/camera.h"
#include "test_helpers.h"

namespace sixdof_sim {
namespace {

// The box's front face is 1 m ahead of a camera looking along world +x from (2, 0, 0.5), far in front of
// the robot (at the origin, behind the camera). No ground: nothing else in view.
constexpr double kFace = 0.95;  // depth of the box's front face
const Eigen::Vector3d kBoxSize(0.1, 0.2, 0.3);
const Eigen::Vector3d kBoxCentre(3.0, 0.0, 0.5);

CameraSpec frontCamera() {
  CameraSpec c;
  c.name = "cam";
  c.pose.translation() = Eigen::Vector3d(2.0, 0.0, 0.5);
  c.width = 640;
  c.height = 480;
  c.horizontal_fov = 60.0 * M_PI / 180.0;
  c.near_clip = 0.1;
  c.far_clip = 10.0;
  return c;
}

WorldSpec boxWorld(const std::vector<CameraSpec>& cameras) {
  WorldSpec spec;
  spec.ground.enabled = false;
  ObjectSpec box;
  box.name = "box";
  box.shape.box_size = kBoxSize;
  box.pose.translation() = kBoxCentre;
  box.is_static = true;
  box.color = Color{0.9, 0.1, 0.1, 1.0};
  spec.objects.push_back(box);
  spec.cameras = cameras;
  return spec;
}

struct Scene {
  explicit Scene(const std::vector<CameraSpec>& cameras = {frontCamera()})
      : spec(boxWorld(cameras)),
        world(test::robotUrdf(), spec, test::options(false)),
        renderer(world, spec, CameraRendererOptions{2}) {}
  WorldSpec spec;
  World world;
  CameraRenderer renderer;
};

float depthAt(const CameraFrame& f, int u, int v) { return f.depth[static_cast<size_t>(v) * f.width + u]; }
const std::uint8_t* rgbAt(const CameraFrame& f, int u, int v) {
  return &f.rgb[3 * (static_cast<size_t>(v) * f.width + u)];
}

TEST(Camera, IntrinsicsAndOpticalFrame) {
  const CameraIntrinsics k = cameraIntrinsics(frontCamera());
  EXPECT_NEAR(k.fx, 640.0 / (2.0 * std::tan(M_PI / 6.0)), 1e-9);
  EXPECT_EQ(k.fx, k.fy);
  EXPECT_EQ(k.cx, 319.5);
  EXPECT_EQ(k.cy, 239.5);
  // rpy(-pi/2, 0, -pi/2) from the link frame: optical z = link x (forward), x = -link y (right),
  // y = -link z (down).
  const Eigen::Matrix3d rpy = (Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(0.0, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
  EXPECT_TRUE(opticalInLink().linear().isApprox(rpy, 1e-12));
  EXPECT_TRUE((opticalInLink().linear() * Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d::UnitX()));
  EXPECT_TRUE((opticalInLink().linear() * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitY()));
  EXPECT_TRUE((opticalInLink().linear() * Eigen::Vector3d::UnitY()).isApprox(-Eigen::Vector3d::UnitZ()));
}

TEST(Camera, KnownBoxAtTheProjectedPixelsDepthAndColour) {
  Scene s;
  CameraFrame f;
  s.renderer.render(0, &f);
  ASSERT_EQ(f.width, 640);
  ASSERT_EQ(f.height, 480);
  const CameraIntrinsics k = cameraIntrinsics(frontCamera());
  // The front face's edges projected: optical x = -world y, optical y = -(world z - 0.5).
  const double u_left = k.cx + k.fx * (-kBoxSize.y() / 2) / kFace, u_right = k.cx + k.fx * (kBoxSize.y() / 2) / kFace;
  const double v_top = k.cy + k.fy * (-kBoxSize.z() / 2) / kFace, v_bottom = k.cy + k.fy * (kBoxSize.z() / 2) / kFace;
  // The hit region's extent along the centre row and column, against the projected edges.
  int hit_left = f.width, hit_right = -1, hit_top = f.height, hit_bottom = -1;
  for (int u = 0; u < f.width; ++u) {
    if (!std::isnan(depthAt(f, u, 240))) hit_left = std::min(hit_left, u), hit_right = std::max(hit_right, u);
  }
  for (int v = 0; v < f.height; ++v) {
    if (!std::isnan(depthAt(f, 320, v))) hit_top = std::min(hit_top, v), hit_bottom = std::max(hit_bottom, v);
  }
  EXPECT_NEAR(hit_left, u_left, 1.0);
  EXPECT_NEAR(hit_right, u_right, 1.0);
  EXPECT_NEAR(hit_top, v_top, 1.0);
  EXPECT_NEAR(hit_bottom, v_bottom, 1.0);
  // Every pixel inside the projected face (1 px margin) sees the face at its depth along the optical axis
  // (not the range, which grows towards the corners); every pixel 1 px outside it sees nothing.
  int inside = 0, outside = 0;
  for (int v = 0; v < f.height; ++v) {
    for (int u = 0; u < f.width; ++u) {
      const float d = depthAt(f, u, v);
      if (u > u_left + 1 && u < u_right - 1 && v > v_top + 1 && v < v_bottom - 1) {
        ASSERT_NEAR(d, kFace, 1e-3) << "pixel " << u << ", " << v;
        ++inside;
      } else if (u < u_left - 1 || u > u_right + 1 || v < v_top - 1 || v > v_bottom + 1) {
        ASSERT_TRUE(std::isnan(d)) << "pixel " << u << ", " << v;
        ++outside;
      }
    }
  }
  EXPECT_GT(inside, 10000);
  EXPECT_GT(outside, 200000);
  // Colour: seen head-on under the headlight, the box's own colour; black where nothing is hit.
  const std::uint8_t* centre = rgbAt(f, 320, 240);
  EXPECT_NEAR(centre[0], 0.9 * 255, 1.0);
  EXPECT_NEAR(centre[1], 0.1 * 255, 1.0);
  EXPECT_NEAR(centre[2], 0.1 * 255, 1.0);
  EXPECT_EQ(rgbAt(f, 5, 5)[0] + rgbAt(f, 5, 5)[1] + rgbAt(f, 5, 5)[2], 0);
  EXPECT_TRUE(f.link_pose.isApprox(frontCamera().pose));
}

TEST(Camera, RightIsPlusUAndUpIsMinusV) {
  Scene s;
  ObjectSpec marker;
  marker.name = "right";
  marker.shape.type = ShapeType::kSphere;
  marker.shape.radius = 0.05;
  marker.is_static = true;
  marker.color = Color{0.1, 0.8, 0.1, 1.0};
  marker.pose.translation() = Eigen::Vector3d(3.0, -0.4, 0.5);  // world -y: the camera's right
  ASSERT_TRUE(s.world.spawnObject(marker).ok());
  marker.name = "up";
  marker.color = Color{0.1, 0.1, 0.9, 1.0};
  marker.pose.translation() = Eigen::Vector3d(3.0, 0.0, 0.9);  // world +z: up
  ASSERT_TRUE(s.world.spawnObject(marker).ok());
  CameraFrame f;
  s.renderer.render(0, &f);
  const CameraIntrinsics k = cameraIntrinsics(frontCamera());
  // Along the ray through a sphere's centre (0.4 off the axis at 1 m): range |c| - r, depth range / |c| * 1.
  const double d = 1.0 - 0.05 / std::sqrt(1.0 + 0.4 * 0.4);
  const int u_right = static_cast<int>(std::lround(k.cx + k.fx * 0.4 / 1.0));
  const int v_up = static_cast<int>(std::lround(k.cy - k.fy * 0.4 / 1.0));
  EXPECT_NEAR(depthAt(f, u_right, 240), d, 1e-3);
  EXPECT_GT(rgbAt(f, u_right, 240)[1], 150);  // green
  EXPECT_NEAR(depthAt(f, 320, v_up), d, 1e-3);
  EXPECT_GT(rgbAt(f, 320, v_up)[2], 150);  // blue
  // Deleted objects disappear, moved ones move.
  ASSERT_TRUE(s.world.deleteObject("up").ok());
  Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
  moved.translation() = kBoxCentre + Eigen::Vector3d(0.5, 0.0, 0.0);
  ASSERT_TRUE(s.world.setObjectState("box", moved).ok());
  s.renderer.render(0, &f);
  EXPECT_TRUE(std::isnan(depthAt(f, 320, v_up)));
  EXPECT_NEAR(depthAt(f, 320, 240), kFace + 0.5, 1e-3);
}

TEST(Camera, ClipRangeAndSeededNoise) {
  CameraSpec near_cut = frontCamera();
  near_cut.name = "near_cut";
  near_cut.near_clip = 1.0;
  CameraSpec far_cut = frontCamera();
  far_cut.name = "far_cut";
  far_cut.far_clip = 0.9;
  CameraSpec noisy = frontCamera();
  noisy.name = "noisy";
  noisy.depth_noise_stddev = 0.01;
  noisy.seed = 7;
  // Depth-proportional noise alone: its standard deviation 0.0111 * depth^2 = 0.01 m at the box's face.
  CameraSpec quadratic = frontCamera();
  quadratic.name = "quadratic";
  quadratic.depth_noise_quadratic = 0.01 / (kFace * kFace);
  quadratic.seed = 7;
  Scene s({near_cut, far_cut, noisy, quadratic});
  CameraFrame f;
  for (size_t i : {0u, 1u}) {
    s.renderer.render(i, &f);
    EXPECT_TRUE(std::isnan(depthAt(f, 320, 240))) << s.renderer.cameras()[i].name;
    EXPECT_GT(rgbAt(f, 320, 240)[0], 200);  // the colour image still shows the box
  }
  std::vector<float> first_noisy;  // camera 2's first frame
  for (size_t i : {2u, 3u}) {
    s.renderer.render(i, &f);
    if (i == 2u) first_noisy = f.depth;
    double sum = 0.0, sum2 = 0.0;
    int n = 0;
    for (int v = 200; v < 280; ++v) {
      for (int u = 290; u < 350; ++u) {
        const double e = depthAt(f, u, v) - kFace;
        sum += e, sum2 += e * e, ++n;
      }
    }
    EXPECT_NEAR(sum / n, 0.0, 1e-3) << s.renderer.cameras()[i].name;
    EXPECT_NEAR(std::sqrt(sum2 / n), 0.01, 1e-3) << s.renderer.cameras()[i].name;
  }
  // The same seed and frame index: the same noise.
  Scene again({near_cut, far_cut, noisy});
  CameraFrame g;
  again.renderer.render(2, &g);
  ASSERT_EQ(first_noisy.size(), g.depth.size());
  EXPECT_EQ(std::memcmp(first_noisy.data(), g.depth.data(), 4 * g.depth.size()), 0);
}

TEST(Camera, CameraOnALinkFollowsIt) {
  CameraSpec c = frontCamera();
  World probe(test::robotUrdf(), WorldSpec(), test::options(false));
  c.parent_link = probe.linkNames().back();
  c.pose.translation() = Eigen::Vector3d(0.01, 0.02, 0.03);
  Scene s({c});
  EXPECT_TRUE(s.renderer.linkPose(0).isApprox(test::linkPose(s.world, c.parent_link) * c.pose, 1e-12));
}

TEST(Camera, SeesTheRobotInItsMaterialColours) {
  // Looking back at the robot from 1.2 m in front of it.
  CameraSpec c = frontCamera();
  c.pose.translation() = Eigen::Vector3d(1.2, 0.0, 0.3);
  c.pose.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  WorldSpec spec;
  spec.ground.enabled = false;  // every hit is the robot
  spec.cameras = {c};
  World world(test::robotUrdf(), spec, test::options(false));
  CameraRenderer renderer(world, spec, CameraRendererOptions{2});
  CameraFrame f;
  renderer.render(0, &f);
  int robot = 0, orange = 0;
  for (int p = 0; p < f.width * f.height; ++p) {
    if (std::isnan(f.depth[p])) continue;
    ++robot;
    // The URDF's orange links (0.93, 0.45, 0.1): the hue survives the shading.
    const int r = f.rgb[3 * p], g = f.rgb[3 * p + 1], b = f.rgb[3 * p + 2];
    if (r > 60 && r > 1.6 * g && g > 2.5 * b) ++orange;
  }
  EXPECT_GT(robot, 2000);
  EXPECT_GT(orange, 500);
}

// ---- bad configs: refused with the key named ----

void expectRefused(const std::string& camera_yaml, const std::string& key) {
  try {
    parseWorldYaml("cameras:\n  - " + camera_yaml + "\n", "w.yaml");
    ADD_FAILURE() << "accepted: " << camera_yaml;
  } catch (const WorldFileError& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cameras[0]"), std::string::npos) << e.what();
  }
}

TEST(CameraConfig, ParsesEveryKey) {
  const WorldSpec spec = parseWorldYaml(R"(
cameras:
  - {name: top, position: [0.5, 0, 1], rpy: [0, 1.5707963267948966, 0], width: 320, height: 240,
     horizontal_fov_deg: 90, rate: 30, near: 0.2, far: 3, depth_noise_stddev: 0.002, depth_noise_quadratic: 0.001,
     seed: 3}
  - {name: wrist, parent: some_link, position: [0, 0, 0.05]}
)");
  ASSERT_EQ(spec.cameras.size(), 2u);
  const CameraSpec& top = spec.cameras[0];
  EXPECT_EQ(top.name, "top");
  EXPECT_TRUE(top.parent_link.empty());
  EXPECT_TRUE(top.pose.translation().isApprox(Eigen::Vector3d(0.5, 0, 1)));
  EXPECT_TRUE((top.pose.linear() * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitZ(), 1e-12));
  EXPECT_EQ(top.width, 320);
  EXPECT_EQ(top.height, 240);
  EXPECT_NEAR(top.horizontal_fov, M_PI / 2, 1e-12);
  EXPECT_EQ(top.rate, 30.0);
  EXPECT_EQ(top.near_clip, 0.2);
  EXPECT_EQ(top.far_clip, 3.0);
  EXPECT_EQ(top.depth_noise_stddev, 0.002);
  EXPECT_EQ(top.depth_noise_quadratic, 0.001);
  EXPECT_EQ(top.seed, 3u);
  EXPECT_EQ(spec.cameras[1].parent_link, "some_link");
  EXPECT_EQ(spec.cameras[1].width, 640);  // defaults
  EXPECT_EQ(spec.cameras[1].height, 480);
}

TEST(CameraConfig, BadValuesNameTheKey) {
  expectRefused("{name: c, position: [0, 0, 1], width: 0}", "'width'");
  expectRefused("{name: c, position: [0, 0, 1], height: 0}", "'height'");
  expectRefused("{name: c, position: [0, 0, 1], width: 12.5}", "'width'");
  expectRefused("{name: c, position: [0, 0, 1], horizontal_fov_deg: 0}", "'horizontal_fov_deg'");
  expectRefused("{name: c, position: [0, 0, 1], horizontal_fov_deg: 180}", "'horizontal_fov_deg'");
  expectRefused("{name: c, position: [0, 0, 1], near: 2, far: 2}", "'near' must be < 'far'");
  expectRefused("{name: c, position: [0, 0, 1], near: 0}", "'near'");
  expectRefused("{name: c, position: [0, 0, 1], rate: 0}", "'rate'");
  expectRefused("{name: c, position: [0, 0, 1], depth_noise_stddev: -1}", "'depth_noise_stddev'");
  expectRefused("{name: c, position: [0, 0, 1], depth_noise_quadratic: -0.001}", "'depth_noise_quadratic'");
  expectRefused("{name: c, position: [0, 0, 1], fov: 60}", "unknown key 'fov'");
  expectRefused("{name: 'my cam', position: [0, 0, 1]}", "'name'");
  expectRefused("{name: c}", "'position'");
  EXPECT_THROW(parseWorldYaml("cameras:\n  - {name: c, position: [0, 0, 1]}\n  - {name: c, position: [0, 0, 1]}\n"),
               WorldFileError);
}

TEST(CameraConfig, UnknownParentLinkRefusedByTheRenderer) {
  CameraSpec c = frontCamera();
  c.parent_link = "no_such_link";
  const WorldSpec spec = boxWorld({c});
  World world(test::robotUrdf(), spec, test::options(false));
  try {
    CameraRenderer renderer(world, spec, CameraRendererOptions{1});
    ADD_FAILURE() << "accepted an unknown parent link";
  } catch (const WorldError& e) {
    EXPECT_NE(std::string(e.what()).find("'parent'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no_such_link"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sixdof_sim
