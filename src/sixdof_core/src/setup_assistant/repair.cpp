// repairModel(): the inertias and the TCP frame the setup assistant writes into a package's URDF, and the mimic
// joints whose limits it warns about.
#include <algorithm>
#include <sstream>

#include "sixdof_core/kinematics.h"
#include "sixdof_core/setup_assistant.h"
#include "sixdof_core/urdf_edit.h"
#include "yaml_text.h"

namespace sixdof_core {

namespace {

std::string inertiaNote(const InertiaRepair& repair) {
  std::ostringstream note;
  note << "computed by sixdof setup_assistant (" << repair.problem << "): ";
  if (repair.source == "default") {
    note << "no geometry, a default " << kDefaultLinkMass << " kg";
  } else {
    note << "from the " << repair.source << " geometry at " << repair.density << " kg/m^3";
  }
  return note.str();
}

std::string yamlMap(const std::map<std::string, double>& values) {
  std::string out = "{";
  for (const auto& [name, value] : values) {
    out += (out.size() > 1 ? ", " : "") + yamlString(name) + ": " + yamlNumber(value);
  }
  return out + "}";
}

}  // namespace

std::vector<MimicLimitConflict> mimicLimitConflicts(const RobotModel& model) {
  std::vector<MimicLimitConflict> conflicts;
  for (const JointModel& joint : model.joints()) {
    if (!joint.mimic || !joint.limits.bounded) continue;
    const JointModel& master = model.joints()[joint.mimic->joint_index];
    const double a = joint.mimic->multiplier * master.limits.lower + joint.mimic->offset;
    const double b = joint.mimic->multiplier * master.limits.upper + joint.mimic->offset;
    const double from = std::min(a, b);
    const double to = std::max(a, b);
    const double slack = 1e-9 * std::max(1.0, std::abs(from) + std::abs(to));
    if (from < joint.limits.lower - slack || to > joint.limits.upper + slack) {
      conflicts.push_back({joint.name, master.name, from, to, joint.limits.lower, joint.limits.upper});
    }
  }
  return conflicts;
}

RepairResult repairModel(const std::string& urdf_xml, const RepairOptions& options, const PackageResolver& resolver) {
  const auto model = std::make_shared<const RobotModel>(urdf_xml, "", resolver);
  RepairResult result;
  result.inertias = inertiaRepairs(*model, options.density);
  UrdfEdits edits;
  for (const InertiaRepair& repair : result.inertias) {
    edits.inertials[repair.link] = UrdfInertial{repair.inertial, inertiaNote(repair)};
  }
  if (options.gripper) {
    result.grasp = analyzeGripper(model, *options.gripper);
    const std::string& frame = options.gripper->tcp_link;
    if (model->linkIndex(frame) < 0) {
      std::string joint = options.tcp_joint;
      for (int n = 2; model->jointIndex(joint) >= 0; ++n) joint = options.tcp_joint + "_" + std::to_string(n);
      edits.frames.push_back(UrdfFrame{frame, joint, options.gripper->parent_link, result.grasp->tcp});
      result.tcp_frame_added = frame;
    }
  }
  result.urdf = edits.inertials.empty() && edits.frames.empty() ? urdf_xml : editUrdf(urdf_xml, edits);
  // What is written must load, with every repaired inertia usable.
  const RobotModel check(result.urdf, "", resolver);
  for (const InertiaRepair& repair : result.inertias) {
    const std::string problem = inertialProblem(check.link(repair.link).inertial);
    if (!problem.empty()) {
      throw RobotModelError("the inertia computed for link '" + repair.link + "' is not usable: " + problem);
    }
  }
  return result;
}

std::string describeRepairs(const RepairResult& result) {
  std::ostringstream out;
  out << "inertias:" << (result.inertias.empty() ? " []" : "") << "\n";
  for (const InertiaRepair& r : result.inertias) {
    const Eigen::Matrix3d& i = r.inertial.inertia;
    out << "- {link: " << yamlString(r.link) << ", problem: " << yamlString(r.problem)
        << ", source: " << r.source << ", density: " << yamlNumber(r.density)
        << ", mass: " << yamlNumber(r.inertial.mass) << ", com: " << yamlVector(r.inertial.origin.translation())
        << ", inertia: [" << yamlNumber(i(0, 0)) << ", " << yamlNumber(i(0, 1)) << ", " << yamlNumber(i(0, 2))
        << ", " << yamlNumber(i(1, 1)) << ", " << yamlNumber(i(1, 2)) << ", " << yamlNumber(i(2, 2)) << "]}\n";
  }
  out << "tcp_frame_added: " << yamlString(result.tcp_frame_added) << "\n";
  if (!result.grasp) return out.str();
  const GraspGeometry& g = *result.grasp;
  out << "grasp:\n";
  out << "  parent_link: " << yamlString(g.parent_link) << "\n";
  out << "  tcp: {xyz: " << yamlVector(g.tcp.translation()) << ", rpy: " << yamlVector(rpyFromRotation(g.tcp.linear()))
      << ", source: " << yamlString(g.tcp_source) << "}\n";
  out << "  pad_links: " << yamlNames(g.pad_links) << "\n";
  out << "  finger_links: " << yamlNames(g.finger_links) << "\n";
  out << "  closing_direction: " << yamlVector(g.closing_direction) << "\n";
  out << "  approach_direction: " << yamlVector(g.approach_direction) << "\n";
  out << "  finger_joints:\n";
  for (const FingerJoint& f : g.finger_joints) {
    out << "  - {joint: " << yamlString(f.joint) << ", width_at_lower: " << yamlNumber(f.width_at_lower)
        << ", width_at_upper: " << yamlNumber(f.width_at_upper) << ", open: " << yamlNumber(f.open)
        << ", closed: " << yamlNumber(f.closed) << "}\n";
  }
  out << "  open: " << yamlMap(g.open) << "\n";
  out << "  closed: " << yamlMap(g.closed) << "\n";
  out << "  open_width: " << yamlNumber(g.open_width) << "\n";
  out << "  closed_width: " << yamlNumber(g.closed_width) << "\n";
  out << "  reach: " << yamlNumber(g.reach) << "\n";
  out << "  palm_depth: " << yamlNumber(g.palm_depth) << "\n";
  out << "  warnings: " << yamlNames(g.warnings) << "\n";
  return out.str();
}

}  // namespace sixdof_core
