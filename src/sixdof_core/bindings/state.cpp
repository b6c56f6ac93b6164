// RobotState (joint values and the link transforms of forward kinematics) and the random state sampler.
#include <map>

#include "common.h"
#include "sixdof_core/setup_assistant.h"

namespace sixdof_core::python {

namespace {

std::string knownStates(const RobotModel& model, const std::string& group) {
  std::string known;
  for (const auto& state : model.groupStates()) {
    if (state.group == group) known += (known.empty() ? "'" : ", '") + state.name + "'";
  }
  return known.empty() ? "none" : known;
}

void setToNamedState(RobotState& state, const std::string& group, const std::string& name) {
  if (!state.model().findGroup(group)) throw std::invalid_argument("unknown group '" + group + "'");
  if (!state.setToNamedState(group, name)) {
    throw std::invalid_argument("group '" + group + "' has no named state '" + name +
                                "' (known: " + knownStates(state.model(), group) + ")");
  }
}

// Every value is checked before any is set, so bad input changes nothing.
void setJointPositions(RobotState& state, const std::map<std::string, double>& values) {
  Eigen::VectorXd positions = state.positions();
  for (const auto& [name, value] : values) {
    const int index = state.model().jointIndex(name);
    if (index < 0) throw std::invalid_argument("unknown joint '" + name + "'");
    const JointModel& joint = state.model().joints()[index];
    if (!joint.isActive()) throw std::invalid_argument("joint '" + name + "' is fixed or a mimic joint");
    positions[joint.variable_index] = value;
  }
  state.setPositions(positions);
}

// In variable order.
py::dict jointPositions(const RobotState& state) {
  py::dict out;
  const auto& names = state.model().variableNames();
  for (size_t i = 0; i < names.size(); ++i) out[py::str(names[i])] = state.positions()[i];
  return out;
}

// The group's chain tip, else its last link: MoveIt's default link of getJacobian.
std::string defaultJacobianLink(const RobotModel& model, const std::string& group) {
  const JointGroup* g = model.findGroup(group);
  if (!g) throw std::invalid_argument("unknown group '" + group + "'");
  if (g->isChain()) return g->chain_tip;
  if (g->links.empty()) throw std::invalid_argument("group '" + group + "' has no links");
  return g->links.back();
}

void setToRandomPositions(RobotState& state, StateSampler& sampler, const std::optional<std::string>& group) {
  const Eigen::VectorXd sample = sampler.sample();
  if (sample.size() != state.positions().size()) {
    throw std::invalid_argument("the sampler was made for a model with " + std::to_string(sample.size()) +
                                " variables, the state has " + std::to_string(state.positions().size()));
  }
  if (!group) {
    state.setPositions(sample);
    return;
  }
  const JointGroup* g = state.model().findGroup(*group);
  if (!g) throw std::invalid_argument("unknown group '" + *group + "'");
  Eigen::VectorXd values(g->active_joints.size());
  for (size_t i = 0; i < g->active_joints.size(); ++i) {
    values[i] = sample[state.model().joint(g->active_joints[i]).variable_index];
  }
  state.setGroupPositions(*group, values);
}

}  // namespace

void bindState(py::module_& m) {
  py::class_<StateSampler>(m, "StateSampler",
                           "Random joint positions, uniform within each active joint's limits (continuous joints in "
                           "[-pi, pi]); the same seed gives the same sequence on every platform.")
      .def(py::init([](const ModelPtr& model, std::uint64_t seed) { return StateSampler(*model, seed); }),
           py::arg("model"), py::arg("seed") = 0)
      .def("sample", &StateSampler::sample, "Positions of every variable, in the model's variable order.");

  py::class_<RobotState>(m, "RobotState",
                         "Joint positions of every variable plus the transform of every link in the root link's "
                         "frame, kept consistent: each setter applies mimic joints and recomputes forward kinematics.")
      .def(py::init([](const ModelPtr& model) { return RobotState(model); }), py::arg("model"),
           "At the model's default positions.")
      .def_property_readonly("model",
                             [](const RobotState& s) { return std::const_pointer_cast<RobotModel>(s.modelPtr()); })
      .def_property(
          "positions", [](const RobotState& s) { return Eigen::VectorXd(s.positions()); }, &RobotState::setPositions,
          "Every variable, in RobotModel.variable_names order (a copy; assign to set).")
      .def("joint_position", &RobotState::jointPosition, py::arg("name"), "Any joint, mimic joints included.")
      .def("set_joint_position", &RobotState::setJointPosition, py::arg("name"), py::arg("value"))
      .def_property_readonly("joint_positions", &jointPositions, "{variable name: position}.")
      .def("set_joint_positions", &setJointPositions, py::arg("values"),
           "Sets active joints by name ({name: position}); nothing changes when one is bad.")
      .def("group_positions", &RobotState::groupPositions, py::arg("group"), "In JointGroup.active_joints order.")
      .def("set_group_positions", &RobotState::setGroupPositions, py::arg("group"), py::arg("values"))
      .def("set_to_named_state", &setToNamedState, py::arg("group"), py::arg("name"),
           "Applies an SRDF group_state; raises ValueError naming the known ones.")
      .def("set_to_default_positions", [](RobotState& s) { s.setPositions(s.model().defaultPositions()); })
      .def("set_to_random_positions", &setToRandomPositions, py::arg("sampler"), py::arg("group") = py::none(),
           "Draws every variable (or only the group's) from the sampler.")
      .def(
          "link_pose", [](const RobotState& s, const std::string& link) { return s.linkTransform(link); },
          py::arg("link"), "Forward kinematics: the link's 4x4 pose in the root link's frame.")
      .def(
          "link_poses",
          [](const RobotState& s) {
            py::dict poses;
            for (size_t i = 0; i < s.model().links().size(); ++i) {
              poses[py::str(s.model().links()[i].name)] = s.linkTransform(static_cast<int>(i));
            }
            return poses;
          },
          "{link name: 4x4 pose} of every link, in model order.")
      .def(
          "jacobian",
          [](const RobotState& s, const std::string& group, const std::optional<std::string>& link,
             const Eigen::Vector3d& reference_point) {
            return Eigen::MatrixXd(
                s.jacobian(group, link ? *link : defaultJacobianLink(s.model(), group), reference_point));
          },
          py::arg("group"), py::arg("link") = py::none(), py::arg("reference_point") = Eigen::Vector3d::Zero(),
          "6 x n geometric Jacobian (rows: linear, then angular velocity; columns: the group's active joints) of "
          "reference_point, fixed in `link` (default: the group's chain tip), in the root link's frame.")
      .def("satisfies_bounds", &RobotState::satisfiesBounds, py::arg("tolerance") = 0.0,
           "Every bounded variable within its limits (+- tolerance).")
      .def("copy", [](const RobotState& s) { return RobotState(s); })
      .def("__copy__", [](const RobotState& s) { return RobotState(s); })
      .def(
          "__deepcopy__", [](const RobotState& s, const py::dict&) { return RobotState(s); }, py::arg("memo"))
      .def("__repr__", [](const RobotState& s) {
        std::string text = "<RobotState of '" + s.model().name() + "':";
        const auto& names = s.model().variableNames();
        for (size_t i = 0; i < names.size(); ++i) text += " " + names[i] + "=" + std::to_string(s.positions()[i]);
        return text + ">";
      });
}

}  // namespace sixdof_core::python
