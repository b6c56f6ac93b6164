#include "world_parameter.h"

#include <Eigen/Geometry>
#include <initializer_list>
#include <string>
#include <type_traits>
#include <utility>

#include "sixdof_sim/conveyor.h"
#include "sixdof_sim/world_file.h"

namespace sixdof_sim {
namespace {

template <class Vector>
XmlRpc::XmlRpcValue list(const Vector& values) {
  XmlRpc::XmlRpcValue out;
  out.setSize(static_cast<int>(values.size()));
  for (int i = 0; i < static_cast<int>(values.size()); ++i) out[i] = static_cast<double>(values[i]);
  return out;
}

XmlRpc::XmlRpcValue color(const Color& c) { return list(Eigen::Vector4d(c.r, c.g, c.b, c.a)); }

// An entry's members after its name: key and value.
using Members = std::initializer_list<std::pair<const char*, XmlRpc::XmlRpcValue>>;

// An entry of a list: a struct with its name and these members.
XmlRpc::XmlRpcValue named(const std::string& name, Members members = {}) {
  XmlRpc::XmlRpcValue out;
  out["name"] = name;
  for (const auto& [key, value] : members) out[key] = value;
  return out;
}

// A named entry with its pose (position, orientation as a quaternion x, y, z, w): objects and conveyors.
XmlRpc::XmlRpcValue placed(const std::string& name, const Eigen::Isometry3d& pose, Members members) {
  const Eigen::Quaterniond q(pose.linear());
  XmlRpc::XmlRpcValue out = named(name, members);
  out["position"] = list(pose.translation());
  out["orientation"] = list(Eigen::Vector4d(q.x(), q.y(), q.z(), q.w()));
  return out;
}

XmlRpc::XmlRpcValue object(const ObjectSpec& spec, const std::string& conveyor) {
  XmlRpc::XmlRpcValue out = placed(spec.name, spec.pose,
                                   {{"static", spec.is_static},
                                    {"collision", spec.collision},
                                    {"table", spec.table},
                                    {"bin", spec.bin},
                                    {"conveyor", conveyor},
                                    {"color", color(spec.color)}});
  forEachShapeField(spec.shape, [&out](const char* key, const auto& value) {
    if constexpr (std::is_same_v<std::decay_t<decltype(value)>, Eigen::Vector3d>) {
      out[key] = list(value);
    } else {
      out[key] = value;
    }
  });
  return out;
}

XmlRpc::XmlRpcValue conveyor(const ConveyorSpec& spec) {
  return placed(spec.name, spec.pose,
                {{"size", list(spec.size)},
                 {"speed", spec.speed},
                 {"direction", list(beltVelocity(spec, 1.0))},
                 {"friction", spec.friction}});
}

XmlRpc::XmlRpcValue source(const SourceSpec& spec) { return named(spec.name, {{"conveyor", spec.conveyor}}); }

XmlRpc::XmlRpcValue sink(const SinkSpec& spec) { return named(spec.name); }

XmlRpc::XmlRpcValue bin(const BinSpec& spec) {
  return named(spec.name, {{"color", color(spec.color)},
                           {"position", list(spec.position)},
                           {"yaw", spec.yaw},
                           {"size", list(spec.size)},
                           {"wall_height", spec.wall_height},
                           {"wall_thickness", spec.wall_thickness}});
}

XmlRpc::XmlRpcValue camera(const CameraSpec& spec) { return named(spec.name, {{"parent_link", spec.parent_link}}); }

template <class Spec, class Convert>
XmlRpc::XmlRpcValue array(const std::vector<Spec>& specs, const Convert& convert) {
  XmlRpc::XmlRpcValue out;
  out.setSize(static_cast<int>(specs.size()));  // an empty list stays a list
  for (int i = 0; i < static_cast<int>(specs.size()); ++i) out[i] = convert(specs[i]);
  return out;
}

}  // namespace

XmlRpc::XmlRpcValue worldParameter(const WorldSpec& world) {
  XmlRpc::XmlRpcValue out;
  out["name"] = world.name;
  std::vector<ObjectSpec> objects = world.objects;
  for (const ConveyorSpec& c : world.conveyors) objects.push_back(beltObject(c));
  XmlRpc::XmlRpcValue object_list = array(objects, [&](const ObjectSpec& spec) {
    const bool belt = &spec - objects.data() >= static_cast<std::ptrdiff_t>(world.objects.size());
    return object(spec, belt ? spec.name : "");
  });
  out["objects"] = object_list;
  out["conveyors"] = array(world.conveyors, conveyor);
  out["sources"] = array(world.sources, source);
  out["sinks"] = array(world.sinks, sink);
  out["bins"] = array(world.bins, bin);
  out["cameras"] = array(world.cameras, camera);
  return out;
}

}  // namespace sixdof_sim
