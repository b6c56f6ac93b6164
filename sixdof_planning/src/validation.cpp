#include "sixdof_planning/validation.h"

#include <cmath>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include <shape_msgs/SolidPrimitive.h>
#include <sixdof_core/primitive_dimensions.h>

#include "sixdof_planning/conversions.h"

namespace sixdof_planning {

std::string formatNumber(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string joinNames(const std::vector<std::string>& names) {
  std::string result;
  for (const auto& name : names) result += (result.empty() ? "" : ", ") + ("'" + name + "'");
  return result;
}

ErrorCode validateFinite(double value, const std::string& what, const std::string& source) {
  if (!std::isfinite(value)) return makeError(ErrorCode::FAILURE, what + " is " + formatNumber(value), source);
  return makeSuccess(source);
}

ErrorCode validatePose(const geometry_msgs::Pose& pose, const std::string& what, const std::string& source) {
  const double values[] = {pose.position.x,    pose.position.y,    pose.position.z,   pose.orientation.x,
                           pose.orientation.y, pose.orientation.z, pose.orientation.w};
  const char* names[] = {"position.x",    "position.y",    "position.z",   "orientation.x",
                         "orientation.y", "orientation.z", "orientation.w"};
  for (int i = 0; i < 7; ++i) {
    ErrorCode code = validateFinite(values[i], what + "." + names[i], source);
    if (!isSuccess(code)) return code;
  }
  const double norm = std::sqrt(pose.orientation.x * pose.orientation.x + pose.orientation.y * pose.orientation.y +
                                pose.orientation.z * pose.orientation.z + pose.orientation.w * pose.orientation.w);
  if (std::abs(norm - 1.0) > kQuaternionNormTolerance) {
    return makeError(ErrorCode::FAILURE,
                     what + ".orientation is not a unit quaternion (norm " + formatNumber(norm) + ", tolerance " +
                         formatNumber(kQuaternionNormTolerance) + ")",
                     source);
  }
  return makeSuccess(source);
}

ErrorCode validateScalingFactor(double value, const std::string& what, const std::string& source,
                                double* effective) {
  if (value == 0.0) {
    *effective = 1.0;
    return makeSuccess(source);
  }
  // Tiny factors (1e-308) made the time parameterization run for ages: below kMin the request is refused.
  constexpr double kMin = 1e-3;
  if (!std::isfinite(value) || value < kMin || value > 1.0) {
    return makeError(ErrorCode::FAILURE,
                     what + " must be in [" + formatNumber(kMin) + ", 1] (0 means 1), got " + formatNumber(value),
                     source);
  }
  *effective = value;
  return makeSuccess(source);
}

ErrorCode validateScalingFactors(double velocity, double acceleration, const std::string& prefix,
                                 const std::string& source, ScalingFactors* effective) {
  const ErrorCode code =
      validateScalingFactor(velocity, prefix + "velocity_scaling_factor", source, &effective->velocity);
  if (!isSuccess(code)) return code;
  return validateScalingFactor(acceleration, prefix + "acceleration_scaling_factor", source, &effective->acceleration);
}

ErrorCode validateGroup(const sixdof_core::RobotModel& model, const std::string& group, const std::string& source) {
  if (model.findGroup(group)) return makeSuccess(source);
  std::vector<std::string> known;
  for (const auto& g : model.groups()) known.push_back(g.name);
  return makeError(ErrorCode::INVALID_GROUP_NAME,
                   "unknown planning group '" + group + "' (known groups: " + joinNames(known) + ")", source);
}

ErrorCode validateLink(const sixdof_core::RobotModel& model, const std::string& link, const std::string& source) {
  if (model.linkIndex(link) >= 0) return makeSuccess(source);
  return makeError(ErrorCode::INVALID_LINK_NAME, "unknown link '" + link + "'", source);
}

ErrorCode validateTrajectoryJoints(const sixdof_core::RobotModel& model, const std::vector<std::string>& joint_names,
                                   const std::string& source) {
  std::set<std::string> seen;
  for (const auto& name : joint_names) {
    const int index = model.jointIndex(name);
    if (index < 0) {
      return makeError(ErrorCode::INVALID_MOTION_PLAN, "trajectory names unknown joint '" + name + "'", source);
    }
    if (!model.joints()[index].isActive()) {
      return makeError(ErrorCode::INVALID_MOTION_PLAN,
                       "trajectory joint '" + name + "' is fixed or a mimic joint (give its source joint)", source);
    }
    if (!seen.insert(name).second) {
      return makeError(ErrorCode::INVALID_MOTION_PLAN, "trajectory names joint '" + name + "' twice", source);
    }
  }
  return makeSuccess(source);
}

ErrorCode validateJointState(const sixdof_core::RobotModel& model, const sensor_msgs::JointState& joint_state,
                             const std::string& source) {
  if (joint_state.position.size() != joint_state.name.size()) {
    return makeError(ErrorCode::INVALID_ROBOT_STATE,
                     "joint_state has " + std::to_string(joint_state.name.size()) + " names but " +
                         std::to_string(joint_state.position.size()) + " positions",
                     source);
  }
  std::vector<char> seen(model.joints().size(), 0);  // by joint index
  for (size_t i = 0; i < joint_state.name.size(); ++i) {
    const std::string& name = joint_state.name[i];
    const int index = model.jointIndex(name);
    if (index < 0) return makeError(ErrorCode::INVALID_ROBOT_STATE, "unknown joint '" + name + "'", source);
    if (model.joints()[index].type == sixdof_core::JointType::kFixed) {
      return makeError(ErrorCode::INVALID_ROBOT_STATE, "joint '" + name + "' is fixed and has no position", source);
    }
    if (std::exchange(seen[index], 1) != 0) {
      return makeError(ErrorCode::INVALID_ROBOT_STATE, "joint '" + name + "' appears twice", source);
    }
    if (!std::isfinite(joint_state.position[i])) {
      return makeError(ErrorCode::INVALID_ROBOT_STATE,
                       "position of joint '" + name + "' is " + formatNumber(joint_state.position[i]), source);
    }
  }
  return makeSuccess(source);
}

ErrorCode validateCollisionObject(const moveit_msgs::CollisionObject& object, const std::string& what,
                                  const std::string& source, bool shapes_required) {
  using Op = moveit_msgs::CollisionObject;
  // An empty id means "every object" for REMOVE only (MoveIt's convention).
  if (object.id.empty() && object.operation != Op::REMOVE) {
    return makeError(ErrorCode::INVALID_OBJECT_NAME, what + " has an empty id", source);
  }
  const std::string name = what + " '" + object.id + "'";
  if (object.operation != Op::ADD && object.operation != Op::REMOVE && object.operation != Op::APPEND &&
      object.operation != Op::MOVE) {
    return makeError(ErrorCode::FAILURE,
                     name + " has unknown operation " + std::to_string(static_cast<int>(object.operation)), source);
  }
  if (object.operation == Op::REMOVE) return makeSuccess(source);
  if (!object.planes.empty() || !object.plane_poses.empty()) {
    return makeError(ErrorCode::FAILURE, name + ": planes are not supported (use a thin box)", source);
  }
  if (!object.subframe_names.empty() || !object.subframe_poses.empty()) {
    return makeError(ErrorCode::FAILURE, name + ": subframes are not supported", source);
  }
  const bool shapeless = object.primitives.empty() && object.meshes.empty();
  // Attaching an existing object by id: its pose stays what the scene has, so the message's is not used.
  if (shapeless && !shapes_required && object.operation == Op::ADD) return makeSuccess(source);
  ErrorCode code = validatePose(object.pose, name + " pose", source);
  if (!isSuccess(code)) return code;
  if (object.operation == Op::MOVE) return makeSuccess(source);
  if (shapeless) return makeError(ErrorCode::FAILURE, name + " has no primitives and no meshes", source);
  if (object.primitive_poses.size() != object.primitives.size()) {
    return makeError(ErrorCode::FAILURE,
                     name + " has " + std::to_string(object.primitives.size()) + " primitives but " +
                         std::to_string(object.primitive_poses.size()) + " primitive_poses",
                     source);
  }
  if (object.mesh_poses.size() != object.meshes.size()) {
    return makeError(ErrorCode::FAILURE,
                     name + " has " + std::to_string(object.meshes.size()) + " meshes but " +
                         std::to_string(object.mesh_poses.size()) + " mesh_poses",
                     source);
  }
  for (size_t i = 0; i < object.primitives.size(); ++i) {
    const auto& primitive = object.primitives[i];
    const std::string pname = name + " primitives[" + std::to_string(i) + "]";
    const std::optional<sixdof_core::ShapeType> type = primitiveType(primitive.type);
    if (!type) {
      return makeError(ErrorCode::FAILURE,
                       pname + " has unsupported type " + std::to_string(static_cast<int>(primitive.type)) +
                           " (BOX, SPHERE and CYLINDER are supported)",
                       source);
    }
    const size_t expected = sixdof_core::primitiveDimensionCount(*type);
    if (primitive.dimensions.size() != expected) {
      return makeError(ErrorCode::FAILURE,
                       pname + " needs " + std::to_string(expected) + " dimensions, got " +
                           std::to_string(primitive.dimensions.size()),
                       source);
    }
    for (double d : primitive.dimensions) {
      if (!std::isfinite(d) || d <= 0.0) {
        return makeError(ErrorCode::FAILURE, pname + " has a non-positive dimension " + formatNumber(d),
                         source);
      }
    }
    code = validatePose(object.primitive_poses[i], name + " primitive_poses[" + std::to_string(i) + "]", source);
    if (!isSuccess(code)) return code;
  }
  for (size_t i = 0; i < object.meshes.size(); ++i) {
    const auto& mesh = object.meshes[i];
    const std::string mname = name + " meshes[" + std::to_string(i) + "]";
    if (mesh.vertices.empty() || mesh.triangles.empty()) {
      return makeError(ErrorCode::FAILURE, mname + " has no vertices or no triangles", source);
    }
    for (const auto& v : mesh.vertices) {
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
        return makeError(ErrorCode::FAILURE, mname + " has a non-finite vertex", source);
      }
    }
    for (const auto& t : mesh.triangles) {
      for (auto index : t.vertex_indices) {
        if (index >= mesh.vertices.size()) {
          return makeError(ErrorCode::FAILURE,
                           mname + " has a triangle with vertex index " + std::to_string(index) + " out of range",
                           source);
        }
      }
    }
    code = validatePose(object.mesh_poses[i], name + " mesh_poses[" + std::to_string(i) + "]", source);
    if (!isSuccess(code)) return code;
  }
  return makeSuccess(source);
}

}  // namespace sixdof_planning
