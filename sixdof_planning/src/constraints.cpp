#include "sixdof_planning/constraints.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include <shape_msgs/SolidPrimitive.h>
#include <sixdof_core/primitive_dimensions.h>

#include "sixdof_planning/conversions.h"
#include "sixdof_planning/scene_store.h"
#include "sixdof_planning/validation.h"

namespace sixdof_planning {

namespace {

// One checked joint constraint.
struct JointRange {
  std::string joint;
  double position = 0.0;
  double below = 0.0;
  double above = 0.0;
  bool continuous = false;

  double error(const sixdof_core::RobotState& state) const {
    const double delta = state.jointPosition(joint) - position;
    return continuous ? std::remainder(delta, 2.0 * M_PI) : delta;
  }
  bool satisfied(const sixdof_core::RobotState& state) const {
    const double e = error(state);
    return e >= -below && e <= above;
  }
};

// One checked position constraint: the link's point inside any of the region's primitives.
struct PositionRegion {
  std::string link;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  std::string frame;
  std::vector<shape_msgs::SolidPrimitive> primitives;
  std::vector<Eigen::Isometry3d> poses;  // in `frame`

  // Distance from the point to the nearest primitive centre; *inside when the point lies in any primitive.
  double evaluate(const sixdof_core::RobotState& state, bool* inside) const {
    Eigen::Isometry3d frame_pose;
    *inside = false;
    if (!isSuccess(SceneStore::frameTransform(state, frame, "", &frame_pose))) return std::numeric_limits<double>::max();
    const Eigen::Vector3d point = state.linkTransform(link) * offset;
    double nearest = std::numeric_limits<double>::max();
    for (size_t i = 0; i < primitives.size(); ++i) {
      const Eigen::Vector3d p = (frame_pose * poses[i]).inverse() * point;
      nearest = std::min(nearest, p.norm());
      const auto& d = primitives[i].dimensions;
      using P = shape_msgs::SolidPrimitive;
      if (primitives[i].type == P::BOX) {
        *inside = *inside || (std::abs(p.x()) <= d[0] / 2 && std::abs(p.y()) <= d[1] / 2 && std::abs(p.z()) <= d[2] / 2);
      } else if (primitives[i].type == P::SPHERE) {
        *inside = *inside || p.norm() <= d[0];
      } else {
        *inside = *inside || (std::abs(p.z()) <= d[0] / 2 && p.head<2>().norm() <= d[1]);
      }
    }
    return nearest;
  }
};

ErrorCode fail(const std::string& message, const std::string& source) {
  return makeError(ErrorCode::FAILURE, message, source);
}

ErrorCode checkJoint(const sixdof_core::RobotModel& model, const moveit_msgs::JointConstraint& c,
                     const std::string& what, const std::string& source, JointRange* range) {
  const int index = model.jointIndex(c.joint_name);
  if (index < 0) return fail(what + ": unknown joint '" + c.joint_name + "'", source);
  const auto& joint = model.joints()[index];
  if (joint.type == sixdof_core::JointType::kFixed) return fail(what + ": joint '" + c.joint_name + "' is fixed", source);
  if (!std::isfinite(c.position) || !std::isfinite(c.tolerance_above) || !std::isfinite(c.tolerance_below) ||
      c.tolerance_above < 0.0 || c.tolerance_below < 0.0) {
    return fail(what + ": position must be finite and tolerances finite and >= 0 (joint '" + c.joint_name + "')",
                source);
  }
  *range = JointRange{c.joint_name, c.position, c.tolerance_below, c.tolerance_above, !joint.limits.bounded};
  return makeSuccess(source);
}

ErrorCode checkPosition(const sixdof_core::RobotModel& model, const moveit_msgs::PositionConstraint& c,
                        const std::string& what, const std::string& source, PositionRegion* region) {
  ErrorCode code = validateLink(model, c.link_name, source);
  if (!isSuccess(code)) {
    code.message = what + ": " + code.message;
    return code;
  }
  const auto& o = c.target_point_offset;
  if (!std::isfinite(o.x) || !std::isfinite(o.y) || !std::isfinite(o.z)) {
    return fail(what + ".target_point_offset is not finite", source);
  }
  const auto& volume = c.constraint_region;
  if (!volume.meshes.empty() || !volume.mesh_poses.empty()) {
    return fail(what + ".constraint_region: meshes are not supported (use boxes, spheres or cylinders)", source);
  }
  if (volume.primitives.empty()) return fail(what + ".constraint_region has no primitives", source);
  if (volume.primitive_poses.size() != volume.primitives.size()) {
    return fail(what + ".constraint_region has " + std::to_string(volume.primitives.size()) + " primitives but " +
                    std::to_string(volume.primitive_poses.size()) + " primitive_poses",
                source);
  }
  region->link = c.link_name;
  region->offset = Eigen::Vector3d(o.x, o.y, o.z);
  region->frame = c.header.frame_id;
  for (size_t i = 0; i < volume.primitives.size(); ++i) {
    const auto& primitive = volume.primitives[i];
    const std::string pwhat = what + ".constraint_region.primitives[" + std::to_string(i) + "]";
    const auto type = primitiveType(primitive.type);
    if (!type) return fail(pwhat + ": only BOX, SPHERE and CYLINDER are supported", source);
    if (primitive.dimensions.size() != sixdof_core::primitiveDimensionCount(*type)) {
      return fail(pwhat + " needs " + std::to_string(sixdof_core::primitiveDimensionCount(*type)) + " dimensions",
                  source);
    }
    for (double d : primitive.dimensions) {
      if (!std::isfinite(d) || d < 0.0) return fail(pwhat + " has a negative or non-finite dimension", source);
    }
    code = validatePose(volume.primitive_poses[i], what + ".constraint_region.primitive_poses[" + std::to_string(i) + "]",
                        source);
    if (!isSuccess(code)) return code;
    region->primitives.push_back(primitive);
    region->poses.push_back(poseToEigen(volume.primitive_poses[i]));
  }
  return makeSuccess(source);
}

// Checks each constraint of `list` (named list_name[i]) with `check` into a Value, then hands the Value to `use`;
// the first error of either ends the walk.
template <class Value, class Msg, class Check, class Use>
ErrorCode forEachChecked(const sixdof_core::RobotModel& model, const std::vector<Msg>& list,
                         const std::string& list_name, const std::string& source, Check check, Use use) {
  for (size_t i = 0; i < list.size(); ++i) {
    Value value;
    ErrorCode code = check(model, list[i], list_name + "[" + std::to_string(i) + "]", source, &value);
    if (!isSuccess(code)) return code;
    code = use(value);
    if (!isSuccess(code)) return code;
  }
  return makeSuccess(source);
}

}  // namespace

bool constraintsEmpty(const moveit_msgs::Constraints& c) {
  return c.joint_constraints.empty() && c.position_constraints.empty() && c.orientation_constraints.empty() &&
         c.visibility_constraints.empty();
}

ErrorCode toPathConstraints(const sixdof_core::RobotModel& model, const std::string& group,
                            const moveit_msgs::Constraints& constraints, const std::string& what,
                            const std::string& source, sixdof_core::PathConstraints* out) {
  if (!constraints.orientation_constraints.empty()) {
    return fail(what + ".orientation_constraints: orientation path constraints are not supported", source);
  }
  if (!constraints.visibility_constraints.empty()) {
    return fail(what + ".visibility_constraints: visibility constraints are not supported", source);
  }
  const auto* joint_group = model.findGroup(group);
  std::vector<JointRange> joints;
  ErrorCode code = forEachChecked<JointRange>(
      model, constraints.joint_constraints, what + ".joint_constraints", source, checkJoint,
      [&](const JointRange& range) {
        const auto& active = joint_group->active_joints;
        if (std::find(active.begin(), active.end(), range.joint) != active.end()) {
          out->joint_bounds.push_back({range.joint, range.position - range.below, range.position + range.above, false});
        }
        joints.push_back(range);
        return makeSuccess(source);
      });
  if (!isSuccess(code)) return code;
  std::vector<PositionRegion> regions;
  code = forEachChecked<PositionRegion>(model, constraints.position_constraints, what + ".position_constraints", source,
                                        checkPosition, [&](const PositionRegion& region) {
                                          regions.push_back(region);
                                          return makeSuccess(source);
                                        });
  if (!isSuccess(code)) return code;
  if (joints.empty() && regions.empty()) return makeSuccess(source);
  auto shared_joints = std::make_shared<const std::vector<JointRange>>(std::move(joints));
  auto shared_regions = std::make_shared<const std::vector<PositionRegion>>(std::move(regions));
  out->state = [shared_joints, shared_regions](const sixdof_core::RobotState& state) {
    for (const auto& j : *shared_joints) {
      if (!j.satisfied(state)) return false;
    }
    for (const auto& r : *shared_regions) {
      bool inside = false;
      r.evaluate(state, &inside);
      if (!inside) return false;
    }
    return true;
  };
  out->explain = [shared_joints, shared_regions, what](const sixdof_core::RobotState& state) -> std::string {
    for (size_t i = 0; i < shared_joints->size(); ++i) {
      const auto& j = (*shared_joints)[i];
      if (!j.satisfied(state)) {
        return "joint '" + j.joint + "' = " + formatNumber(state.jointPosition(j.joint)) + " violates " + what +
               ".joint_constraints[" + std::to_string(i) + "] [" + formatNumber(j.position - j.below) + ", " +
               formatNumber(j.position + j.above) + "]";
      }
    }
    for (size_t i = 0; i < shared_regions->size(); ++i) {
      bool inside = false;
      (*shared_regions)[i].evaluate(state, &inside);
      if (!inside) {
        return "link '" + (*shared_regions)[i].link + "' leaves the region of " + what + ".position_constraints[" +
               std::to_string(i) + "]";
      }
    }
    return "";
  };
  return makeSuccess(source);
}

ErrorCode evaluateConstraints(const sixdof_core::RobotState& state, const moveit_msgs::Constraints& constraints,
                              const std::string& what, const std::string& source,
                              std::vector<moveit_msgs::ConstraintEvalResult>* results) {
  const auto& model = state.model();
  if (!constraints.visibility_constraints.empty()) {
    return fail(what + ".visibility_constraints: visibility constraints are not supported", source);
  }
  const auto add = [results](bool satisfied, double distance) {
    moveit_msgs::ConstraintEvalResult result;
    result.result = satisfied;
    result.distance = distance;
    results->push_back(result);
  };
  ErrorCode code = forEachChecked<JointRange>(model, constraints.joint_constraints, what + ".joint_constraints", source,
                                              checkJoint, [&](const JointRange& range) {
                                                add(range.satisfied(state), std::abs(range.error(state)));
                                                return makeSuccess(source);
                                              });
  if (!isSuccess(code)) return code;
  code = forEachChecked<PositionRegion>(model, constraints.position_constraints, what + ".position_constraints", source,
                                        checkPosition, [&](const PositionRegion& region) {
                                          Eigen::Isometry3d frame;
                                          const ErrorCode frame_code =
                                              SceneStore::frameTransform(state, region.frame, source, &frame);
                                          if (!isSuccess(frame_code)) return frame_code;
                                          bool inside = false;
                                          const double distance = region.evaluate(state, &inside);
                                          add(inside, distance);
                                          return makeSuccess(source);
                                        });
  if (!isSuccess(code)) return code;
  for (size_t i = 0; i < constraints.orientation_constraints.size(); ++i) {
    const auto& c = constraints.orientation_constraints[i];
    const std::string owhat = what + ".orientation_constraints[" + std::to_string(i) + "]";
    code = validateLink(model, c.link_name, source);
    if (!isSuccess(code)) {
      code.message = owhat + ": " + code.message;
      return code;
    }
    geometry_msgs::Pose pose;
    pose.orientation = c.orientation;
    code = validatePose(pose, owhat, source);
    if (!isSuccess(code)) return code;
    const double tolerances[] = {c.absolute_x_axis_tolerance, c.absolute_y_axis_tolerance, c.absolute_z_axis_tolerance};
    for (double t : tolerances) {
      if (!std::isfinite(t) || t < 0.0) return fail(owhat + ": axis tolerances must be finite and >= 0", source);
    }
    if (c.parameterization != moveit_msgs::OrientationConstraint::XYZ_EULER_ANGLES &&
        c.parameterization != moveit_msgs::OrientationConstraint::ROTATION_VECTOR) {
      return fail(owhat + ": unknown parameterization " + std::to_string(c.parameterization), source);
    }
    Eigen::Isometry3d frame;
    code = SceneStore::frameTransform(state, c.header.frame_id, source, &frame);
    if (!isSuccess(code)) return code;
    const Eigen::Matrix3d desired = frame.rotation() * poseToEigen(pose).rotation();
    const Eigen::Matrix3d error = desired.transpose() * state.linkTransform(c.link_name).rotation();
    Eigen::Vector3d angles;
    if (c.parameterization == moveit_msgs::OrientationConstraint::ROTATION_VECTOR) {
      const Eigen::AngleAxisd aa(error);
      angles = aa.angle() * aa.axis();
    } else {
      // MoveIt's XYZ Euler angles of the error rotation (intrinsic x, y, z).
      angles = error.eulerAngles(0, 1, 2);
      // eulerAngles returns x in [0, pi]: the equivalent set with the smallest angles is the one to compare.
      const Eigen::Vector3d alternative(angles.x() - M_PI, M_PI - angles.y(), angles.z() - M_PI);
      const auto wrap = [](const Eigen::Vector3d& v) {
        return Eigen::Vector3d(std::remainder(v.x(), 2 * M_PI), std::remainder(v.y(), 2 * M_PI),
                               std::remainder(v.z(), 2 * M_PI));
      };
      const Eigen::Vector3d a = wrap(angles);
      const Eigen::Vector3d b = wrap(alternative);
      angles = a.cwiseAbs().sum() <= b.cwiseAbs().sum() ? a : b;
    }
    const bool satisfied = std::abs(angles.x()) <= tolerances[0] + 1e-9 && std::abs(angles.y()) <= tolerances[1] + 1e-9 &&
                           std::abs(angles.z()) <= tolerances[2] + 1e-9;
    add(satisfied, angles.cwiseAbs().maxCoeff());
  }
  return makeSuccess(source);
}

}  // namespace sixdof_planning
