#pragma once
// sim_bench's workload, shared with the benchmarks that compare it with another simulator: the joint trajectory,
// the extra boxes on the table, and the whole run written as JSON for bench/pybullet_world.py to repeat.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "sixdof_sim/world.h"
#include "sixdof_sim/world_file.h"

namespace sixdof_sim::bench {

// A joint swinging about the middle of its range (0 when unbounded): by a quarter of the range, at most 0.4 rad
// (or m), at 0.25 Hz, each joint 0.7 rad further in phase than the one before. The arm stays clear of the table.
struct JointSwing {
  std::string joint;
  double centre = 0.0;
  double amplitude = 0.0;
  double omega = 2.0 * M_PI * 0.25;
  double phase = 0.0;

  double position(double t) const { return centre + amplitude * std::sin(omega * t + phase); }
  double velocity(double t) const { return amplitude * omega * std::cos(omega * t + phase); }
};

// Every actuated joint that is not a mimic joint (mimic joints follow their master).
inline std::vector<JointSwing> jointSwings(const std::vector<JointInfo>& joints) {
  std::vector<JointSwing> swings;
  for (const JointInfo& info : joints) {
    if (!info.mimic_of.empty()) continue;
    JointSwing s;
    s.joint = info.name;
    s.centre = info.bounded ? 0.5 * (info.lower + info.upper) : 0.0;
    s.amplitude = info.bounded ? std::min(0.4, 0.25 * (info.upper - info.lower)) : 0.4;
    s.phase = 0.7 * static_cast<double>(swings.size());
    swings.push_back(s);
  }
  return swings;
}

// Adds 3 x 3 x 5 cm boxes of 80 g standing on the table (the largest static box) until the world has `dynamic`
// dynamic objects: on an 8 cm grid, farthest from the robot (at the origin) first, 0.3 m or more from it and 8 cm
// or more from every other object. Returns the number of dynamic objects, or -1 and `error`.
inline int addTableBoxes(WorldSpec* spec, int dynamic, std::string* error) {
  int count = 0;
  const ObjectSpec* table = nullptr;
  for (const ObjectSpec& o : spec->objects) {
    count += o.is_static ? 0 : 1;
    const bool candidate = o.is_static && o.collision && o.shape.type == ShapeType::kBox;
    if (candidate && (table == nullptr || o.shape.box_size.head<2>().prod() > table->shape.box_size.head<2>().prod())) {
      table = &o;
    }
  }
  if (count >= dynamic) return count;
  if (table == nullptr) {
    *error = "world '" + spec->name + "' has no table (static box) for the extra objects";
    return -1;
  }
  constexpr double kSpacing = 0.08;
  constexpr double kEdge = 0.05;
  const Eigen::Vector3d box(0.03, 0.03, 0.05);
  const Eigen::Vector3d half = table->shape.box_size / 2.0;
  std::vector<Eigen::Vector3d> free;
  for (double x = half.x() - kEdge; x >= -half.x() + kEdge; x -= kSpacing) {
    for (double y = -half.y() + kEdge; y <= half.y() - kEdge; y += kSpacing) {
      const Eigen::Vector3d p = table->pose * Eigen::Vector3d(x, y, half.z() + box.z() / 2.0);
      bool clear = p.head<2>().norm() >= 0.3;
      for (const ObjectSpec& o : spec->objects) {
        if (&o != table && (o.pose.translation() - p).head<2>().norm() < kSpacing) clear = false;
      }
      if (clear) free.push_back(p);
    }
  }
  const std::string table_name = table->name;
  const Eigen::Matrix3d orientation = table->pose.linear();
  if (static_cast<int>(free.size()) < dynamic - count) {
    *error = "table '" + table_name + "' has room for " + std::to_string(free.size()) + " extra objects, not " +
             std::to_string(dynamic - count);
    return -1;
  }
  for (size_t k = 0; count < dynamic; ++k, ++count) {
    ObjectSpec o;
    o.name = "bench_box_" + std::to_string(k);
    o.shape.box_size = box;
    o.mass = 0.08;
    o.pose.linear() = orientation;
    o.pose.translation() = free[k];
    spec->objects.push_back(o);
  }
  return count;
}

struct Timing {
  std::uint64_t steps = 0;
  double wall = 0.0;  // s
  double cpu = 0.0;   // s
  std::uint64_t settled_steps = 0;  // the steps after the objects settled, and their wall-clock time
  double settled_wall = 0.0;
};

// A minimal JSON writer: strings, numbers, arrays of numbers, nested objects and arrays.
class Json {
 public:
  explicit Json(std::ostream& out) : out_(out) { out_.precision(17); }
  Json& key(const std::string& k) {
    comma();
    out_ << quote(k) << ": ";
    fresh_ = true;
    return *this;
  }
  Json& value(const std::string& v) { return raw(quote(v)); }
  Json& value(const char* v) { return raw(quote(v)); }
  Json& value(double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return raw(s.str());
  }
  Json& value(bool v) { return raw(v ? "true" : "false"); }
  Json& integer(long long v) { return raw(std::to_string(v)); }
  Json& value(const Eigen::Vector3d& v) { return numbers({v.x(), v.y(), v.z()}); }
  Json& numbers(const std::vector<double>& values) {
    begin('[');
    for (double v : values) value(v);
    return end(']');
  }
  Json& begin(char bracket) {
    comma();
    out_ << bracket;
    fresh_ = true;
    return *this;
  }
  Json& end(char bracket) {
    out_ << bracket;
    fresh_ = false;
    return *this;
  }

 private:
  Json& raw(const std::string& text) {
    comma();
    out_ << text;
    fresh_ = false;
    return *this;
  }
  void comma() {
    if (!fresh_) out_ << ", ";
    fresh_ = true;
  }
  static std::string quote(const std::string& s) {
    std::string q = "\"";
    for (char c : s) {
      if (c == '"' || c == '\\') q += '\\';
      q += c;
    }
    return q + "\"";
  }

  std::ostream& out_;
  bool fresh_ = true;
};

inline void writeShape(Json& json, const Shape& shape) {
  forEachShapeField(shape, [&json](const char* key, const auto& value) { json.key(key).value(value); });
}

// The run as JSON: robot, package roots, physics settings of WorldOptions, ground, objects (the shape's centre and
// orientation as a quaternion x, y, z, w), the joints and their swings, and the timings.
inline void writeScenario(std::ostream& out, const std::string& urdf_path, const WorldOptions& options,
                          const WorldSpec& spec, const World& world, const std::vector<JointSwing>& swings,
                          const Timing& timing) {
  Json json(out);
  json.begin('{');
  json.key("urdf").value(urdf_path).key("package_roots").begin('[');
  for (const std::string& root : options.package_search_roots) json.value(root);
  json.end(']');
  json.key("time_step").value(options.time_step).key("solver_iterations").integer(options.solver_iterations);
  json.key("position_gain").value(options.position_gain).key("gravity").value(spec.gravity);
  json.key("ground").begin('{').key("enabled").value(spec.ground.enabled).key("z").value(spec.ground.z);
  json.key("friction").value(spec.ground.friction).key("restitution").value(spec.ground.restitution).end('}');
  json.key("objects").begin('[');
  for (const ObjectSpec& o : spec.objects) {
    const Eigen::Quaterniond q(o.pose.linear());
    json.begin('{').key("name").value(o.name);
    writeShape(json, o.shape);
    json.key("position").value(Eigen::Vector3d(o.pose.translation()));
    json.key("quaternion").numbers({q.x(), q.y(), q.z(), q.w()});
    json.key("mass").value(o.mass).key("static").value(o.is_static).key("collision").value(o.collision);
    json.key("friction").value(o.friction).key("restitution").value(o.restitution).end('}');
  }
  json.end(']').key("joints").begin('[');
  for (const JointInfo& j : world.joints()) {
    json.begin('{').key("name").value(j.name).key("max_effort").value(j.max_effort);
    json.key("mimic_of").value(j.mimic_of).key("mimic_multiplier").value(j.mimic_multiplier);
    json.key("mimic_offset").value(j.mimic_offset).end('}');
  }
  json.end(']').key("swings").begin('[');
  for (const JointSwing& s : swings) {
    json.begin('{').key("joint").value(s.joint).key("centre").value(s.centre).key("amplitude").value(s.amplitude);
    json.key("omega").value(s.omega).key("phase").value(s.phase).end('}');
  }
  json.end(']').key("steps").integer(static_cast<long long>(timing.steps)).key("wall").value(timing.wall);
  json.key("cpu").value(timing.cpu).key("settled_steps").integer(static_cast<long long>(timing.settled_steps));
  json.key("settled_wall").value(timing.settled_wall).end('}');
  out << "\n";
}

}  // namespace sixdof_sim::bench
