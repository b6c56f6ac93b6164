// The C++ side of binding_bench.py: runs the IK and planning problems of a problem file with the core directly and
// prints, per problem, its outcome and wall-clock time, which binding_bench.py compares with the same calls made
// through the Python bindings in the same run.
//   binding_baseline PROBLEM_FILE
// Problem file (whitespace-separated, one record per line; a pose is a 4x4 matrix, 16 numbers row by row):
//   model URDF SRDF PACKAGE DIR        the robot (package:// URIs of PACKAGE resolve in DIR)
//   group NAME SOLVER                  the planning group and the IK solver of its pose goals
//   ik SOLVER TIMEOUT POSE             one IK problem (solver analytic|numeric|kdl, IkOptions.timeout)
//   padding METRES                     the scene's link padding
//   box|sphere|cylinder ID POSE DIMS   a world object (box: x y z; sphere: radius; cylinder: radius length)
//   allow A B                          an allowed collision
//   plan TIME SEGMENT STEP POSE        a pose goal of the group's tip, chained from the previous result
//                                      (allowed time s, longest_valid_segment_length, max_joint_step; seed = index)
// Output lines: "ik INDEX STATUS MICROSECONDS Q..." and "plan INDEX STATUS MICROSECONDS Q..." (Q: the solution, or
// the plan's last point; none on failure).
#include <ompl/util/Console.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "sixdof_core/collision.h"
#include "sixdof_core/ik_solver.h"
#include "sixdof_core/planning_context.h"

namespace {

using Clock = std::chrono::steady_clock;

Eigen::Isometry3d readPose(std::istream& in) {
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) in >> m(r, c);
  }
  Eigen::Isometry3d pose;
  pose.matrix() = m;
  return pose;
}

void printResult(const char* kind, int index, int status, double micros, const Eigen::VectorXd& q) {
  std::printf("%s %d %d %.3f", kind, index, status, micros);
  for (Eigen::Index i = 0; i < q.size(); ++i) std::printf(" %.17g", q[i]);
  std::printf("\n");
}

struct Problems {
  std::string urdf, srdf, package, package_dir, group, plan_solver;
  struct Ik {
    std::string solver;
    double timeout;
    Eigen::Isometry3d pose;
  };
  std::vector<Ik> ik;
  double padding = 0.0;
  std::vector<sixdof_core::WorldObject> objects;
  std::vector<std::pair<std::string, std::string>> allowed;
  struct Plan {
    double time, segment, step;
    Eigen::Isometry3d pose;
  };
  std::vector<Plan> plans;
};

sixdof_core::WorldObject readObject(const std::string& kind, std::istream& in) {
  sixdof_core::WorldObject object;
  in >> object.id;
  object.pose = readPose(in);
  sixdof_core::PlacedShape placed;
  if (kind == "box") {
    placed.shape.type = sixdof_core::ShapeType::kBox;
    in >> placed.shape.box_size.x() >> placed.shape.box_size.y() >> placed.shape.box_size.z();
  } else if (kind == "sphere") {
    placed.shape.type = sixdof_core::ShapeType::kSphere;
    in >> placed.shape.radius;
  } else {
    placed.shape.type = sixdof_core::ShapeType::kCylinder;
    in >> placed.shape.radius >> placed.shape.length;
  }
  object.shapes.push_back(placed);
  return object;
}

Problems readProblems(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error("cannot read " + path);
  Problems p;
  for (std::string line; std::getline(file, line);) {
    std::istringstream in(line);
    std::string kind;
    if (!(in >> kind)) continue;
    if (kind == "model") {
      in >> p.urdf >> p.srdf >> p.package >> p.package_dir;
    } else if (kind == "group") {
      in >> p.group >> p.plan_solver;
    } else if (kind == "ik") {
      Problems::Ik ik;
      in >> ik.solver >> ik.timeout;
      ik.pose = readPose(in);
      p.ik.push_back(ik);
    } else if (kind == "padding") {
      in >> p.padding;
    } else if (kind == "box" || kind == "sphere" || kind == "cylinder") {
      p.objects.push_back(readObject(kind, in));
    } else if (kind == "allow") {
      std::string a, b;
      in >> a >> b;
      p.allowed.emplace_back(a, b);
    } else if (kind == "plan") {
      Problems::Plan plan;
      in >> plan.time >> plan.segment >> plan.step;
      plan.pose = readPose(in);
      p.plans.push_back(plan);
    } else {
      throw std::runtime_error("unknown record '" + kind + "' in " + path);
    }
    if (in.fail()) throw std::runtime_error("malformed line in " + path + ": " + line);
  }
  return p;
}

void runIk(const sixdof_core::RobotModel& model, const Problems& p) {
  std::map<std::string, std::shared_ptr<sixdof_core::IkSolver>> solvers;
  for (size_t i = 0; i < p.ik.size(); ++i) {
    auto& solver = solvers[p.ik[i].solver];
    if (!solver) solver = sixdof_core::createIkSolver(p.ik[i].solver, model, p.group);
    sixdof_core::IkOptions options;
    options.timeout = p.ik[i].timeout;
    const auto start = Clock::now();
    const sixdof_core::IkResult result = solver->solve(p.ik[i].pose, options);
    const double micros = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
    printResult("ik", static_cast<int>(i), static_cast<int>(result.status), micros, result.solution);
  }
}

void runPlans(const sixdof_core::RobotModelConstPtr& model, const Problems& p) {
  std::vector<std::pair<std::string, std::string>> disabled;
  for (const auto& pair : model->disabledCollisionPairs()) disabled.emplace_back(pair.link1, pair.link2);
  sixdof_core::CollisionSceneOptions scene_options;
  scene_options.link_padding = p.padding;
  auto scene = std::make_shared<sixdof_core::CollisionScene>(model->collisionGeometry(), disabled, scene_options);
  for (const auto& object : p.objects) scene->addWorldObject(object);
  for (const auto& [a, b] : p.allowed) scene->setAllowed(a, b, true);
  const std::shared_ptr<const sixdof_core::IkSolver> ik = sixdof_core::createIkSolver(p.plan_solver, *model, p.group);
  const sixdof_core::PlanningContext context(model, scene, p.group, ik);
  sixdof_core::RobotState state(model);
  for (size_t i = 0; i < p.plans.size(); ++i) {
    sixdof_core::PlanningOptions options;
    options.allowed_planning_time = p.plans[i].time;
    options.longest_valid_segment_length = p.plans[i].segment;
    options.max_joint_step = p.plans[i].step;
    options.seed = static_cast<std::uint32_t>(i + 1);
    const auto start = Clock::now();
    const sixdof_core::PlanningResult result =
        context.planToPose(state, p.plans[i].pose, sixdof_core::PoseGoalOptions(), options);
    const double micros = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
    Eigen::VectorXd last;
    if (result.ok()) {
      last = result.path.back();
      state.setGroupPositions(p.group, last);
    }
    printResult("plan", static_cast<int>(i), static_cast<int>(result.status), micros, last);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: binding_baseline PROBLEM_FILE\n";
    return 2;
  }
  try {
    const Problems p = readProblems(argv[1]);
    ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
    const auto model = sixdof_core::RobotModel::fromFiles(
        p.urdf, p.srdf, sixdof_core::PackageResolver::fromMap({{p.package, p.package_dir}}));
    runIk(*model, p);
    runPlans(model, p);
  } catch (const std::exception& e) {
    std::cerr << "binding_baseline: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
