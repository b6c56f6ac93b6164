#pragma once
// Test helper of the three collision gtests (test_collision*.cpp): the primitive arm from its URDF, probes,
// meshes written on the fly and the top-down grasp pose, all with analytic answers.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "sixdof_core/collision.h"
#include "test_collision_urdf_arm.h"
#include "test_description.h"
#include "test_shapes.h"

namespace sixdof_core {
namespace collision_test {

inline constexpr double kDistanceTolerance = 1e-4;

using sixdof_test::descriptionDir;

inline sixdof_test::UrdfArm loadArm() {
  return sixdof_test::UrdfArm(descriptionDir() + "/urdf/sixdof.urdf", descriptionDir());
}

// What the SRDF will disable: adjacent links plus the fingers, which touch when closed ("Default").
inline std::vector<std::pair<std::string, std::string>> disabledPairs(const sixdof_test::UrdfArm& arm) {
  auto pairs = arm.adjacent;
  pairs.emplace_back("finger1", "finger2");
  return pairs;
}

using sixdof_test::at;
using sixdof_test::box;
using sixdof_test::cylinder;
using sixdof_test::mesh;
using sixdof_test::sphere;

inline WorldObject object(const std::string& id, const Shape& shape, const Eigen::Isometry3d& pose) {
  WorldObject o;
  o.id = id;
  o.pose = pose;
  o.shapes.push_back(PlacedShape{shape, Eigen::Isometry3d::Identity()});
  return o;
}

// One link "probe" carrying a 5 cm sphere at its origin.
inline CollisionScene probeScene() {
  LinkGeometry probe;
  probe.link_name = "probe";
  probe.shapes.push_back(PlacedShape{sphere(0.05), Eigen::Isometry3d::Identity()});
  return CollisionScene({probe}, {});
}

inline std::vector<Eigen::Isometry3d> probeAt(double x, double y, double z) { return {at(x, y, z)}; }

// A 0.2 m cube centred at the origin, as an OBJ file.
inline std::string writeCubeObj(const std::string& name) {
  const std::string path = testing::TempDir() + name;
  std::ofstream f(path);
  for (int i = 0; i < 8; ++i) {
    f << "v " << ((i & 1) ? 0.1 : -0.1) << " " << ((i & 2) ? 0.1 : -0.1) << " " << ((i & 4) ? 0.1 : -0.1) << "\n";
  }
  // Faces as quads (assimp triangulates), outward winding.
  f << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  return path;
}

// An L-shaped prism (not convex) as ASCII STL: the union of [0,0.2]x[0,0.1]x[0,0.1] and
// [0,0.1]x[0,0.2]x[0,0.1]; the notch [0.1,0.2]x[0.1,0.2] is empty.
inline std::string writeLStl(const std::string& name) {
  const std::string path = testing::TempDir() + name;
  const std::vector<Eigen::Vector2d> outline = {{0, 0}, {0.2, 0}, {0.2, 0.1}, {0.1, 0.1}, {0.1, 0.2}, {0, 0.2}};
  std::ofstream f(path);
  f << "solid L\n";
  auto tri = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    f << "facet normal " << n.x() << " " << n.y() << " " << n.z() << "\nouter loop\n";
    for (const auto& p : {a, b, c}) f << "vertex " << p.x() << " " << p.y() << " " << p.z() << "\n";
    f << "endloop\nendfacet\n";
  };
  auto v = [&](int i, double z) { return Eigen::Vector3d(outline[i].x(), outline[i].y(), z); };
  // Bottom and top as fans from the corner (0,0) and (0.1,0.1): two convex quads each.
  const std::vector<std::array<int, 4>> quads = {{0, 1, 2, 3}, {0, 3, 4, 5}};
  for (const auto& q : quads) {
    tri(v(q[0], 0), v(q[2], 0), v(q[1], 0));
    tri(v(q[0], 0), v(q[3], 0), v(q[2], 0));
    tri(v(q[0], 0.1), v(q[1], 0.1), v(q[2], 0.1));
    tri(v(q[0], 0.1), v(q[2], 0.1), v(q[3], 0.1));
  }
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    tri(v(i, 0), v(j, 0), v(j, 0.1));
    tri(v(i, 0), v(j, 0.1), v(i, 0.1));
  }
  f << "endsolid L\n";
  return path;
}

// Joint values that put the tool (link6 z) straight down with the TCP at (x, 0, tcp_z): planar 2-link
// solution (upper arm and forearm both 0.3 m, shoulder 0.3 m high, from the design contract) with elbow up.
// The wrist-centre-to-TCP distance is the URDF's: at zero joints the tool points along +x from the wrist
// centre (link5's origin).
inline std::map<std::string, double> topDown(const sixdof_test::UrdfArm& arm, double x, double tcp_z) {
  const auto zero = arm.poses({});
  const auto at_zero = [&](const std::string& link) {
    const auto it = std::find(arm.order.begin(), arm.order.end(), link);
    return zero[it - arm.order.begin()].translation();
  };
  const double wrist_to_tcp = at_zero("tcp").x() - at_zero("link5").x();
  const double l = 0.3, shoulder = 0.3;
  const double dx = x, dz = tcp_z + wrist_to_tcp - shoulder;
  const double d = std::hypot(dx, dz);
  const double a1 = std::atan2(dz, dx) + std::acos(d / (2 * l));
  const double ex = l * std::cos(a1), ez = l * std::sin(a1);
  const double a2 = std::atan2(dz - ez, dx - ex);
  const double q2 = M_PI / 2 - a1;
  const double q3 = -a2 - q2;
  return {{"joint2", q2}, {"joint3", q3}, {"joint5", M_PI / 2 + a2}, {"finger1_joint", 0.02}};
}

inline bool hasPair(const CollisionReport& report, const std::string& a, const std::string& b) {
  for (const Contact& c : report.contacts) {
    if ((c.body1 == a && c.body2 == b) || (c.body1 == b && c.body2 == a)) return true;
  }
  return false;
}

}  // namespace collision_test
}  // namespace sixdof_core
