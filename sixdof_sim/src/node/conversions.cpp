#include "conversions.h"

#include <shape_msgs/SolidPrimitive.h>
#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <optional>
#include <sstream>

#include "sixdof_core/primitive_dimensions.h"

namespace sixdof_sim {
namespace {

// The primitives a SimObject may be, for both directions; the dimension order is sixdof_core's.
struct Primitive {
  uint8_t msg_type;
  ShapeType type;
  const char* name;
  const char* dimensions;  // as the error message spells them
};
constexpr Primitive kPrimitives[] = {
    {shape_msgs::SolidPrimitive::BOX, ShapeType::kBox, "BOX", "[x, y, z]"},
    {shape_msgs::SolidPrimitive::SPHERE, ShapeType::kSphere, "SPHERE", "[radius]"},
    {shape_msgs::SolidPrimitive::CYLINDER, ShapeType::kCylinder, "CYLINDER", "[height, radius]"},
};

}  // namespace

geometry_msgs::Pose toMsg(const Eigen::Isometry3d& pose) { return tf2::toMsg(pose); }

geometry_msgs::Twist toMsg(const Twist& twist) {
  geometry_msgs::Twist msg;
  tf2::toMsg(twist.linear, msg.linear);
  tf2::toMsg(twist.angular, msg.angular);
  return msg;
}

sixdof_msgs::SimObject toMsg(const ObjectSpec& spec) {
  sixdof_msgs::SimObject msg;
  msg.name = spec.name;
  if (spec.shape.type == ShapeType::kMesh) {
    msg.mesh_resource = spec.shape.mesh_resource;
    msg.mesh_scale.x = spec.shape.mesh_scale.x();
    msg.mesh_scale.y = spec.shape.mesh_scale.y();
    msg.mesh_scale.z = spec.shape.mesh_scale.z();
  }
  for (const Primitive& primitive : kPrimitives) {
    if (primitive.type == spec.shape.type) msg.shape.type = primitive.msg_type;
  }
  msg.shape.dimensions = sixdof_core::primitiveDimensions(spec.shape);
  msg.pose = tf2::toMsg(spec.pose);
  msg.mass = spec.mass;
  msg.friction = spec.friction;
  msg.restitution = spec.restitution;
  msg.color.r = static_cast<float>(spec.color.r);
  msg.color.g = static_cast<float>(spec.color.g);
  msg.color.b = static_cast<float>(spec.color.b);
  msg.color.a = static_cast<float>(spec.color.a);
  msg.is_static = spec.is_static;
  return msg;
}

bool fromMsg(const geometry_msgs::Pose& msg, Eigen::Isometry3d* pose, std::string* error) {
  const Eigen::Vector3d p(msg.position.x, msg.position.y, msg.position.z);
  Eigen::Quaterniond q(msg.orientation.w, msg.orientation.x, msg.orientation.y, msg.orientation.z);
  if (!p.allFinite() || !q.coeffs().allFinite()) {
    *error = "pose has a non-finite (NaN or inf) value";
    return false;
  }
  if (std::abs(q.norm() - 1.0) > 1e-3) {
    std::ostringstream s;
    s << "pose orientation is not a unit quaternion (norm " << q.norm() << ")";
    *error = s.str();
    return false;
  }
  // tf2_eigen converts the quaternion as it is: normalising first keeps the rotation orthonormal.
  geometry_msgs::Pose unit = msg;
  unit.orientation = tf2::toMsg(q.normalized());
  tf2::fromMsg(unit, *pose);
  return true;
}

bool fromMsg(const geometry_msgs::Twist& msg, Twist* twist, std::string* error) {
  twist->linear = Eigen::Vector3d(msg.linear.x, msg.linear.y, msg.linear.z);
  twist->angular = Eigen::Vector3d(msg.angular.x, msg.angular.y, msg.angular.z);
  if (!twist->linear.allFinite() || !twist->angular.allFinite()) {
    *error = "twist has a non-finite (NaN or inf) value";
    return false;
  }
  return true;
}

bool fromMsg(const sixdof_msgs::SimObject& msg, ObjectSpec* spec, std::string* error) {
  ObjectSpec out;
  out.name = msg.name;
  if (!msg.mesh_resource.empty()) {
    out.shape.type = ShapeType::kMesh;
    out.shape.mesh_resource = msg.mesh_resource;
    const Eigen::Vector3d scale(msg.mesh_scale.x, msg.mesh_scale.y, msg.mesh_scale.z);
    out.shape.mesh_scale = scale.isZero(0.0) ? Eigen::Vector3d::Ones() : scale;
  } else {
    const auto primitive = std::find_if(std::begin(kPrimitives), std::end(kPrimitives),
                                        [&](const Primitive& p) { return p.msg_type == msg.shape.type; });
    if (primitive == std::end(kPrimitives)) {
      *error = "object '" + msg.name + "': shape type " + std::to_string(msg.shape.type) +
               " is not supported (BOX=1, SPHERE=2, CYLINDER=3, or set mesh_resource)";
      return false;
    }
    const std::optional<Shape> shape = sixdof_core::primitiveShape(primitive->type, msg.shape.dimensions);
    if (!shape) {
      std::ostringstream s;
      s << "object '" << msg.name << "': a " << primitive->name << " needs dimensions " << primitive->dimensions
        << ", got " << msg.shape.dimensions.size() << " values";
      *error = s.str();
      return false;
    }
    out.shape = *shape;
  }
  if (!fromMsg(msg.pose, &out.pose, error)) {
    *error = "object '" + msg.name + "': " + *error;
    return false;
  }
  out.mass = msg.mass;
  out.friction = msg.friction;
  out.restitution = msg.restitution;
  out.is_static = msg.is_static;
  if (msg.color.r != 0.0f || msg.color.g != 0.0f || msg.color.b != 0.0f || msg.color.a != 0.0f) {
    out.color = {msg.color.r, msg.color.g, msg.color.b, msg.color.a};
  }
  *spec = out;
  return true;
}

}  // namespace sixdof_sim
