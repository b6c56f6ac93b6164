#include "world_parameter.h"

#include <Eigen/Geometry>
#include <string>
#include <type_traits>

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

XmlRpc::XmlRpcValue object(const ObjectSpec& spec, const std::string& conveyor) {
  XmlRpc::XmlRpcValue out;
  out["name"] = spec.name;
  forEachShapeField(spec.shape, [&out](const char* key, const auto& value) {
    if constexpr (std::is_same_v<std::decay_t<decltype(value)>, Eigen::Vector3d>) {
      out[key] = list(value);
    } else {
      out[key] = value;
    }
  });
  const Eigen::Quaterniond q(spec.pose.linear());
  out["position"] = list(spec.pose.translation());
  out["orientation"] = list(Eigen::Vector4d(q.x(), q.y(), q.z(), q.w()));
  out["static"] = spec.is_static;
  out["collision"] = spec.collision;
  out["table"] = spec.table;
  out["bin"] = spec.bin;
  out["conveyor"] = conveyor;
  out["color"] = color(spec.color);
  return out;
}

XmlRpc::XmlRpcValue conveyor(const ConveyorSpec& spec) {
  XmlRpc::XmlRpcValue out;
  const Eigen::Quaterniond q(spec.pose.linear());
  out["name"] = spec.name;
  out["size"] = list(spec.size);
  out["position"] = list(spec.pose.translation());
  out["orientation"] = list(Eigen::Vector4d(q.x(), q.y(), q.z(), q.w()));
  out["speed"] = spec.speed;
  out["direction"] = list(beltVelocity(spec, 1.0));
  out["friction"] = spec.friction;
  return out;
}

XmlRpc::XmlRpcValue source(const SourceSpec& spec) {
  XmlRpc::XmlRpcValue out;
  out["name"] = spec.name;
  out["conveyor"] = spec.conveyor;
  return out;
}

XmlRpc::XmlRpcValue sink(const SinkSpec& spec) {
  XmlRpc::XmlRpcValue out;
  out["name"] = spec.name;
  return out;
}

XmlRpc::XmlRpcValue bin(const BinSpec& spec) {
  XmlRpc::XmlRpcValue out;
  out["name"] = spec.name;
  out["color"] = color(spec.color);
  out["position"] = list(spec.position);
  out["yaw"] = spec.yaw;
  out["size"] = list(spec.size);
  out["wall_height"] = spec.wall_height;
  out["wall_thickness"] = spec.wall_thickness;
  return out;
}

XmlRpc::XmlRpcValue camera(const CameraSpec& spec) {
  XmlRpc::XmlRpcValue out;
  out["name"] = spec.name;
  out["parent_link"] = spec.parent_link;
  return out;
}

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
