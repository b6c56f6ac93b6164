// Full-state collision checks per second: self collision plus a table-top world of 6 objects, on
// random arm configurations (link poses precomputed, so only collision checking is timed).
//   collision_bench [seconds per query type (default 2)] [path to sixdof.urdf]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "../test/test_collision_urdf_arm.h"
#include "bench_paths.h"
#include "sixdof_core/collision.h"

namespace {

using sixdof_core::CollisionScene;
using sixdof_core::CollisionScope;
using sixdof_core::PlacedShape;
using sixdof_core::Shape;
using sixdof_core::WorldObject;

WorldObject object(const std::string& id, Shape::Type type, const Eigen::Vector3d& position,
                   const Eigen::Vector3d& dims) {
  WorldObject o;
  o.id = id;
  o.pose.translation() = position;
  PlacedShape placed;
  placed.shape.type = type;
  if (type == Shape::Type::kBox) placed.shape.box_size = dims;
  placed.shape.radius = dims.x();
  placed.shape.length = dims.z();
  o.shapes.push_back(placed);
  return o;
}

template <typename F>
double rate(double seconds, F&& query) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  long count = 0;
  double elapsed = 0.0;
  while (elapsed < seconds) {
    for (int i = 0; i < 500; ++i) query(count++);
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  }
  return count / elapsed;
}

}  // namespace

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 2.0;
  const std::string description = sixdof_core::bench::descriptionDir();
  const std::string urdf = argc > 2 ? argv[2] : sixdof_core::bench::defaultUrdf();
  if (!(seconds > 0.0)) {
    std::fprintf(stderr, "usage: collision_bench [seconds > 0] [urdf]\n");
    return 2;
  }

  const sixdof_test::UrdfArm arm(urdf, description);
  auto disabled = arm.adjacent;
  disabled.emplace_back("finger1", "finger2");  // touching when closed (the SRDF's "Default" pair)
  CollisionScene scene(arm.links, disabled);

  using T = Shape::Type;
  for (const WorldObject& o : {object("table", T::kBox, {0.3, 0.0, -0.025}, {1.2, 1.2, 0.05}),
                               object("red_cube", T::kBox, {0.40, -0.15, 0.02}, {0.04, 0.04, 0.04}),
                               object("cylinder", T::kCylinder, {0.35, 0.25, 0.06}, {0.03, 0.0, 0.12}),
                               object("sphere", T::kSphere, {0.50, 0.0, 0.04}, {0.04, 0.0, 0.0}),
                               object("obstacle", T::kBox, {0.25, -0.35, 0.10}, {0.10, 0.10, 0.20}),
                               object("post", T::kCylinder, {-0.30, 0.30, 0.25}, {0.05, 0.0, 0.50})}) {
    const auto status = scene.addWorldObject(o);
    if (!status.ok()) {
      std::fprintf(stderr, "%s\n", status.message.c_str());
      return 1;
    }
  }
  scene.setAllowed("base_link", "table", true);  // the robot stands on the table

  const std::vector<std::vector<Eigen::Isometry3d>> states = arm.randomPoses(4096, 42);
  long colliding = 0;
  for (const auto& s : states) colliding += scene.isColliding(s);

  volatile bool sink = false;
  const double full = rate(seconds, [&](long i) { sink = scene.isColliding(states[i & 4095]); });
  const double self =
      rate(seconds / 2, [&](long i) { sink = scene.isColliding(states[i & 4095], CollisionScope::kSelf); });
  const double report = rate(seconds / 2, [&](long i) { sink = scene.checkCollision(states[i & 4095]).colliding; });
  const double dist = rate(seconds / 2, [&](long i) { sink = scene.distance(states[i & 4095]).found; });
  (void)sink;
  std::printf("links %zu, world objects %zu, colliding states %.1f%%\n", scene.numLinks(),
              scene.worldObjectIds().size(), 100.0 * colliding / states.size());
  std::printf("isColliding (self + world): %.0f checks/s (target >= 50000: %s)\n", full,
              full >= 50000.0 ? "met" : "NOT MET");
  std::printf("isColliding (self only):    %.0f checks/s\n", self);
  std::printf("checkCollision (report):    %.0f checks/s\n", report);
  std::printf("distance (self + world):    %.0f queries/s\n", dist);
  return 0;
}
