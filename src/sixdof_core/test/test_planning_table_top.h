#pragma once
// Test and benchmark fixture: the arm (URDF + SRDF) on the default table-top world of docs/design.md (table top
// at z = 0, the red cube at (0.40, -0.15), the place location at (0.40, 0.20), a cylinder and a sphere as
// obstacles), with the arm group's IK, wrapped in a PlanningContext.
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "sixdof_core/collision.h"
#include "sixdof_core/ik_analytic.h"
#include "sixdof_core/ik_solver.h"
#include "sixdof_core/kinematics.h"
#include "sixdof_core/planning_context.h"
#include "sixdof_core/robot_model.h"

namespace sixdof_test {

inline sixdof_core::WorldObject tableTopObject(const std::string& id, sixdof_core::Shape::Type type,
                                               const Eigen::Vector3d& position, const Eigen::Vector3d& size) {
  sixdof_core::WorldObject o;
  o.id = id;
  o.pose.translation() = position;
  sixdof_core::PlacedShape placed;
  placed.shape.type = type;
  placed.shape.box_size = size;     // kBox: full extents
  placed.shape.radius = size.x();   // kSphere, kCylinder
  placed.shape.length = size.z();   // kCylinder
  o.shapes.push_back(placed);
  return o;
}

struct TableTop {
  sixdof_core::RobotModelConstPtr model;
  std::shared_ptr<sixdof_core::CollisionScene> scene;  // true geometry: what paths are re-checked against
  std::shared_ptr<const sixdof_core::IkSolver> ik;
  std::string ik_note;  // which solver, and why if not the analytic one
  std::unique_ptr<sixdof_core::PlanningContext> context;  // plans in `scene` with the links padded
  Eigen::Isometry3d tcp_in_tip = Eigen::Isometry3d::Identity();

  // link6 pose that puts the tcp at tcp_pose.
  Eigen::Isometry3d tipFor(const Eigen::Isometry3d& tcp_pose) const { return tcp_pose * tcp_in_tip.inverse(); }

  // Top-down tcp pose (tool z pointing down) at a point, rotated by yaw about the vertical.
  static Eigen::Isometry3d topDown(double x, double y, double z, double yaw = 0.0) {
    return sixdof_core::poseFromXyzRpy(x, y, z, M_PI, 0.0, yaw);
  }

  bool colliding(const sixdof_core::RobotState& state) const {
    return scene->isColliding(context->sceneLinkPoses(state));
  }
};

// padding: link padding (m) of the scene the planner sees; discrete motion checks may cut corners by a few mm.
// extra: more world objects (e.g. clutter on the table).
inline TableTop makeTableTop(const std::string& urdf_path, const std::string& srdf_path,
                             const std::string& description_dir, double padding,
                             const std::vector<sixdof_core::WorldObject>& extra = {}) {
  using sixdof_core::Shape;
  TableTop t;
  t.model = sixdof_core::RobotModel::fromFiles(
      urdf_path, srdf_path,
      sixdof_core::PackageResolver::fromMap({{"sixdof_description", description_dir}}));
  std::vector<std::pair<std::string, std::string>> disabled;
  for (const auto& pair : t.model->disabledCollisionPairs()) disabled.emplace_back(pair.link1, pair.link2);
  t.scene = std::make_shared<sixdof_core::CollisionScene>(t.model->collisionGeometry(), disabled);
  t.scene->addWorldObject(tableTopObject("table", Shape::Type::kBox, {0.3, 0.0, -0.025}, {1.2, 1.2, 0.05}));
  t.scene->addWorldObject(tableTopObject("red_cube", Shape::Type::kBox, {0.40, -0.15, 0.02}, {0.04, 0.04, 0.04}));
  t.scene->addWorldObject(tableTopObject("post", Shape::Type::kCylinder, {0.42, 0.03, 0.15}, {0.025, 0.0, 0.30}));
  t.scene->addWorldObject(tableTopObject("ball", Shape::Type::kSphere, {0.20, 0.30, 0.06}, {0.06, 0.0, 0.0}));
  // The robot stands on the table.
  t.scene->setAllowed("base_link", "table", true);
  for (const sixdof_core::WorldObject& object : extra) {
    const sixdof_core::SceneStatus status = t.scene->addWorldObject(object);
    if (!status.ok()) throw std::invalid_argument("table top: " + status.message);
  }

  try {
    t.ik = sixdof_core::createIkSolver("analytic", *t.model, "arm");
    t.ik_note = "analytic";
  } catch (const sixdof_core::AnalyticIkUnsupported& e) {
    t.ik = sixdof_core::createIkSolver("kdl", *t.model, "arm");
    t.ik_note = std::string("kdl (analytic unsupported: ") + e.what() + ")";
  }

  auto padded = std::make_shared<sixdof_core::CollisionScene>(*t.scene);
  padded->setPadding(padding);
  t.context = std::make_unique<sixdof_core::PlanningContext>(t.model, padded, "arm", t.ik);

  sixdof_core::RobotState state(t.model);
  t.tcp_in_tip = state.linkTransform("link6").inverse() * state.linkTransform("tcp");
  return t;
}

}  // namespace sixdof_test
