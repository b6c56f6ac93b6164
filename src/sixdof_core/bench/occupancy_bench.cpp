// The occupancy map's cost per depth cloud, as move_group's occupancy map monitor pays it: a 640x480 cloud of
// the sorting world's camera (table_cam: 60 deg horizontal fov, 1.1 m above the table's front edge, pitched down
// 54.5 deg) seeing the table, five small boxes and a wall, in the sensor's optical frame; per cloud the self filter
// is built from the arm's collision shapes (padding 3 cm, sensors_3d.yaml), every point is moved into the map frame,
// range-checked and tested against it, and the cloud goes into the octree (insertScan). The analytic ray caster is
// not timed.
// Then the same update at 0.025 m for images of 80x60 to 1280x960: its cost against the cloud's size.
//   occupancy_bench [clouds per resolution and size (default 30)] [path to sixdof.urdf]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

#include "../test/test_collision_urdf_arm.h"
#include "bench_paths.h"
#include "sixdof_core/occupancy_map.h"

namespace {

struct Box {
  Eigen::Vector3d min, max;
};

// Distance along a unit ray to an axis-aligned box (infinity when it misses).
double hitBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Box& box) {
  double t_near = 0.0, t_far = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-12) {
      if (o[i] < box.min[i] || o[i] > box.max[i]) return std::numeric_limits<double>::infinity();
      continue;
    }
    double t1 = (box.min[i] - o[i]) / d[i], t2 = (box.max[i] - o[i]) / d[i];
    if (t1 > t2) std::swap(t1, t2);
    t_near = std::max(t_near, t1);
    t_far = std::min(t_far, t2);
  }
  return t_near <= t_far ? t_near : std::numeric_limits<double>::infinity();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double percentile95(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(0.95 * (v.size() - 1) + 0.5))];
}

// The sorting world's camera (sixdof_sim/worlds/sorting.yaml's table_cam) and what it sees.
struct Camera {
  Eigen::Vector3d origin{0.95, 0.0, 0.80};
  Eigen::Isometry3d map_from_sensor = Eigen::Isometry3d::Identity();  // optical frame: z forward, x right, y down
  std::vector<Box> boxes;

  Camera() {
    const double pitch = 0.951;
    const Eigen::Vector3d forward(-std::cos(pitch), 0.0, -std::sin(pitch));
    const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
    map_from_sensor.linear().col(0) = right;
    map_from_sensor.linear().col(1) = forward.cross(right);
    map_from_sensor.linear().col(2) = forward;
    map_from_sensor.translation() = origin;
    const Box table{{-0.3, -0.6, -0.75}, {0.7, 0.6, 0.0}};
    const Box floor{{-10.0, -10.0, -1.75}, {10.0, 10.0, -0.75}};
    boxes = {table, floor, {{0.25, 0.30, 0.0}, {0.30, 0.50, 0.30}}};  // a wall beside the arm
    for (int i = 0; i < 5; ++i) {
      const Eigen::Vector3d c(0.30 + 0.05 * i, -0.20 + 0.08 * i, 0.02);
      boxes.push_back({c - Eigen::Vector3d::Constant(0.02), c + Eigen::Vector3d::Constant(0.02)});
    }
  }

  // The organized cloud of a width x height image with the camera's 60 deg horizontal fov, in the sensor frame
  // (NaN where nothing is hit within the 3 m far clip).
  std::vector<Eigen::Vector3f> cloud(int width, int height) const {
    const Eigen::Vector3d right = map_from_sensor.linear().col(0), down = map_from_sensor.linear().col(1);
    const Eigen::Vector3d forward = map_from_sensor.linear().col(2);
    const double f = (width / 2.0) / std::tan(M_PI / 6.0);
    const Eigen::Isometry3d sensor_from_map = map_from_sensor.inverse();
    std::vector<Eigen::Vector3f> points;
    points.reserve(static_cast<std::size_t>(width) * height);
    for (int v = 0; v < height; ++v) {
      for (int u = 0; u < width; ++u) {
        const Eigen::Vector3d d =
            (forward * f + (u - (width - 1) / 2.0) * right + (v - (height - 1) / 2.0) * down).normalized();
        double t = std::numeric_limits<double>::infinity();
        for (const Box& b : boxes) t = std::min(t, hitBox(origin, d, b));
        const Eigen::Vector3f point = (sensor_from_map * (origin + t * d)).cast<float>();
        points.push_back(std::isfinite(t) && t < 3.0 ? point : Eigen::Vector3f::Constant(std::nanf("")));
      }
    }
    return points;
  }
};

struct Updates {
  std::vector<double> filter_ms, insert_ms, total_ms;  // per cloud
  std::size_t hits = 0, masked = 0;                    // of the last cloud
  std::size_t occupied = 0;                            // cells after the last cloud
};

// `clouds` updates of a map at `resolution` with one cloud, as move_group's occupancy map monitor does them: the
// self filter from the arm's shapes, every point moved into the map frame, range-checked and tested against it, then
// the cloud into the octree (insertScan).
bool update(const Camera& camera, const std::vector<Eigen::Vector3f>& cloud, const sixdof_test::UrdfArm& arm,
            double resolution, int clouds, Updates* out) {
  const auto link_poses = arm.poses({});  // the arm at its zero configuration (any URDF: no joint names here)
  const double max_range = 2.0, padding = 0.03;
  using Clock = std::chrono::steady_clock;
  sixdof_core::OccupancyMap map(resolution);
  for (int k = 0; k < clouds; ++k) {
    const auto t0 = Clock::now();
    sixdof_core::ShapeMask mask(1.0, padding);
    for (std::size_t i = 0; i < arm.links.size(); ++i) {
      for (const auto& placed : arm.links[i].shapes) {
        if (!mask.addShape(placed.shape, link_poses[i] * placed.origin).ok()) {
          std::fprintf(stderr, "self filter: cannot add a shape of %s\n", arm.links[i].link_name.c_str());
          return false;
        }
      }
    }
    std::vector<Eigen::Vector3d> hits, clipped, masked;
    for (const Eigen::Vector3f& p : cloud) {
      if (!p.allFinite()) continue;
      const double range = p.cast<double>().norm();
      const Eigen::Vector3d point = camera.map_from_sensor * p.cast<double>();
      if (range > max_range) {
        clipped.push_back(camera.origin + (point - camera.origin) * (max_range / range));
      } else if (mask.contains(point)) {
        masked.push_back(point);
      } else {
        hits.push_back(point);
      }
    }
    const auto t1 = Clock::now();
    map.insertScan(camera.origin, hits, clipped, masked);
    const auto t2 = Clock::now();
    out->filter_ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    out->insert_ms.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
    out->total_ms.push_back(std::chrono::duration<double, std::milli>(t2 - t0).count());
    out->hits = hits.size();
    out->masked = masked.size();
  }
  out->occupied = map.occupiedCells().size();
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const int clouds = argc > 1 ? std::atoi(argv[1]) : 30;
  const std::string description = sixdof_core::bench::descriptionDir();
  const std::string urdf = argc > 2 ? argv[2] : sixdof_core::bench::defaultUrdf();
  if (clouds < 1) {
    std::fprintf(stderr, "usage: occupancy_bench [clouds >= 1] [urdf]\n");
    return 2;
  }
  const Camera camera;
  const sixdof_test::UrdfArm arm(urdf, description);
  std::printf("occupancy_bench: 640x480 cloud of the sorting world's table_cam, %zu arm collision links in the self "
              "filter (padding 0.03 m), max_range 2.0 m, %d clouds per resolution\n",
              arm.links.size(), clouds);
  std::printf("\n| resolution | points in range | hits | masked | self filter + transform, median ms | insertScan, "
              "median ms | per cloud, median ms | per cloud, p95 ms | occupied cells |\n");
  std::printf("|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  const std::vector<Eigen::Vector3f> full = camera.cloud(640, 480);
  for (const double resolution : {0.025, 0.01}) {
    Updates u;
    if (!update(camera, full, arm, resolution, clouds, &u)) return 1;
    std::printf("| %.3f m | %zu | %zu | %zu | %.1f | %.1f | %.1f | %.1f | %zu |\n", resolution, u.hits + u.masked,
                u.hits, u.masked, median(u.filter_ms), median(u.insert_ms), median(u.total_ms),
                percentile95(u.total_ms), u.occupied);
  }
  // The same scene seen at other image sizes: the cost of one update against the cloud's size.
  std::printf("\nupdate time vs cloud size (0.025 m)\n\n| image | points in range | per cloud, median ms | per cloud, "
              "p95 ms |\n|---:|---:|---:|---:|\n");
  for (const int width : {80, 160, 320, 640, 1280}) {
    Updates u;
    if (!update(camera, camera.cloud(width, width * 3 / 4), arm, 0.025, clouds, &u)) return 1;
    std::printf("| %dx%d | %zu | %.2f | %.2f |\n", width, width * 3 / 4, u.hits + u.masked, median(u.total_ms),
                percentile95(u.total_ms));
  }
  return 0;
}
