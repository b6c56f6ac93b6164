// Planning: joint, named, pose and position goals and Cartesian paths of one group in a collision scene, through
// the core's PlanningContext (the calls move_group's planning pipeline makes). Plans run without the GIL.
#include "scene.h"
#include "sixdof_core/planning_context.h"

namespace sixdof_core::python {

namespace {

// sixdof_core.PlanningContext: the core's context over a Python CollisionScene, which it marks in use while it
// plans, and the IK solver it was given.
struct Planner {
  std::shared_ptr<Scene> scene;
  std::shared_ptr<IkSolver> ik;
  std::shared_ptr<const PlanningContext> context;
};

std::shared_ptr<Planner> makePlanner(std::shared_ptr<Scene> scene, const std::string& group,
                                     std::shared_ptr<IkSolver> ik) {
  auto planner = std::make_shared<Planner>();
  planner->context = std::make_shared<PlanningContext>(scene->model(), scene->core(), group, ik);
  planner->scene = std::move(scene);
  planner->ik = std::move(ik);
  return planner;
}

// Runs a planning call on a copy of the start state (the caller's may change meanwhile), with the scene in use
// and the GIL released.
template <class Call>
auto run(const Planner& planner, const RobotState& start, Call&& call) {
  planner.scene->checkState(start, "start");
  const RobotState start_copy = start;
  const Scene::Use in_use = planner.scene->use();
  py::gil_scoped_release release;
  return call(*planner.context, start_copy);
}

// PlanningContext::planTo<goal> (start, goal, its tolerance or pose goal options, planning options) as a method of
// Planner, run as run() does.
template <class Goal, class GoalOptions>
auto planTo(PlanningResult (PlanningContext::*plan_to)(const RobotState&, const Goal&, GoalOptions,
                                                       const PlanningOptions&) const) {
  return [plan_to](const Planner& p, const RobotState& start, const Goal& goal, GoalOptions goal_options,
                   const PlanningOptions& options) {
    return run(p, start, [&](const PlanningContext& c, const RobotState& s) {
      return (c.*plan_to)(s, goal, goal_options, options);
    });
  };
}

void bindOptions(py::module_& m) {
  py::enum_<PlanningStatus>(m, "PlanningStatus")
      .value("SUCCESS", PlanningStatus::kSuccess)
      .value("INVALID_REQUEST", PlanningStatus::kInvalidRequest, "Sizes, NaN, bounds, planner id, options.")
      .value("INVALID_START", PlanningStatus::kInvalidStart, "Out of bounds or in collision.")
      .value("INVALID_GOAL", PlanningStatus::kInvalidGoal, "Out of bounds.")
      .value("GOAL_IN_COLLISION", PlanningStatus::kGoalInCollision)
      .value("NO_IK_SOLUTION", PlanningStatus::kNoIkSolution)
      .value("TIMEOUT", PlanningStatus::kTimeout)
      .value("PLANNING_FAILED", PlanningStatus::kPlanningFailed);

  py::class_<PlanningOptions>(m, "PlanningOptions", "The planner and its budget (move_group's request fields).")
      .def(py::init([](const std::string& planner_id, double allowed_planning_time, int num_planning_attempts,
                       std::optional<std::uint32_t> seed) {
             PlanningOptions o;
             o.planner_id = planner_id;
             o.allowed_planning_time = allowed_planning_time;
             o.num_planning_attempts = num_planning_attempts;
             o.seed = seed;
             return o;
           }),
           py::arg("planner_id") = PlanningOptions().planner_id,
           py::arg("allowed_planning_time") = PlanningOptions().allowed_planning_time,
           py::arg("num_planning_attempts") = PlanningOptions().num_planning_attempts, py::arg("seed") = py::none())
      .def_readwrite("planner_id", &PlanningOptions::planner_id, "An OMPL geometric planner: available_planner_ids().")
      .def_readwrite("planner_params", &PlanningOptions::planner_params, "{OMPL parameter name: value}.")
      .def_readwrite("allowed_planning_time", &PlanningOptions::allowed_planning_time, "s, all attempts together.")
      .def_readwrite("num_planning_attempts", &PlanningOptions::num_planning_attempts)
      .def_readwrite("parallel_attempts", &PlanningOptions::parallel_attempts)
      .def_readwrite("longest_valid_segment_fraction", &PlanningOptions::longest_valid_segment_fraction,
                     "Motion check resolution as a fraction of the joint space's extent (MoveIt's).")
      .def_readwrite("longest_valid_segment_length", &PlanningOptions::longest_valid_segment_length,
                     "When > 0: the resolution as a joint-space distance instead.")
      .def_readwrite("simplify", &PlanningOptions::simplify)
      .def_readwrite("simplify_coarse_factor", &PlanningOptions::simplify_coarse_factor)
      .def_readwrite("max_joint_step", &PlanningOptions::max_joint_step, "Densify the path to this step (0: off).")
      .def_readwrite("precheck", &PlanningOptions::precheck,
                     "The sphere pre-check of motions (the same answers, fewer FCL checks); False: FCL alone.")
      .def_readwrite("seed", &PlanningOptions::seed,
                     "Reseeds OMPL's process-wide generator: repeatable plans (do not plan concurrently with it).");

  py::class_<PoseGoalOptions>(m, "PoseGoalOptions", "IK-sampled goal states of pose and position goals.")
      .def(py::init([](const IkOptions& ik, int max_states, int max_calls) {
             return PoseGoalOptions{ik, max_states, max_calls};
           }),
           py::arg("ik") = PoseGoalOptions().ik, py::arg("max_states") = PoseGoalOptions().max_states,
           py::arg("max_calls") = PoseGoalOptions().max_calls)
      .def_readwrite("ik", &PoseGoalOptions::ik, "Per IK call; its seed and random_seed are set per sample.")
      .def_readwrite("max_states", &PoseGoalOptions::max_states)
      .def_readwrite("max_calls", &PoseGoalOptions::max_calls);

  bindResult<PlanningResult>(m, "PlanningResult", "status, message (why it failed) and, on success, the path.")
      .def_property_readonly(
          "path", [](const PlanningResult& r) { return toArray(r.path); },
          "(points, joints): start first, goal last; empty unless SUCCESS.")
      .def_readonly("planning_time", &PlanningResult::planning_time, "s, the whole call.")
      .def_readonly("path_length", &PlanningResult::path_length)
      .def_readonly("simplification_time", &PlanningResult::simplification_time)
      .def_readonly("simplification_fallback", &PlanningResult::simplification_fallback)
      .def_readonly("validity_checks", &PlanningResult::validity_checks)
      .def_readonly("precheck_calls", &PlanningResult::precheck_calls)
      .def_readonly("precheck_states", &PlanningResult::precheck_states, "Motion states proven without FCL.")
      .def_readonly("solved_attempts", &PlanningResult::solved_attempts)
      .def_readonly("planner_id", &PlanningResult::planner_id);

  py::enum_<CartesianStatus>(m, "CartesianStatus")
      .value("SUCCESS", CartesianStatus::kSuccess, "The whole path (fraction 1).")
      .value("INVALID_REQUEST", CartesianStatus::kInvalidRequest)
      .value("INVALID_START", CartesianStatus::kInvalidStart)
      .value("IK_FAILED", CartesianStatus::kIkFailed)
      .value("IN_COLLISION", CartesianStatus::kInCollision)
      .value("JUMP_DETECTED", CartesianStatus::kJumpDetected);

  py::class_<JumpThreshold>(m, "JumpThreshold", "Joint-space jump detection of Cartesian paths (0 disables a test).")
      .def(py::init([](double relative, double revolute, double prismatic) {
             return JumpThreshold{relative, revolute, prismatic};
           }),
           py::arg("relative") = 0.0, py::arg("revolute") = 0.0, py::arg("prismatic") = 0.0)
      .def_readwrite("relative", &JumpThreshold::relative, "MoveIt's jump_threshold (x the mean step).")
      .def_readwrite("revolute", &JumpThreshold::revolute, "rad per step of any revolute joint.")
      .def_readwrite("prismatic", &JumpThreshold::prismatic, "m per step of any prismatic joint.");

  bindResult<CartesianPathResult>(m, "CartesianPathResult", "The path up to where it stopped, and the fraction.")
      .def_property_readonly("path", [](const CartesianPathResult& r) { return toArray(r.path); })
      .def_readonly("fraction", &CartesianPathResult::fraction, "Achieved part of the path (MoveIt's definition).");
}

}  // namespace

void bindPlanning(py::module_& m) {
  bindOptions(m);
  m.def("available_planner_ids", &availablePlannerIds, "The OMPL planner ids PlanningOptions.planner_id accepts.");

  py::class_<Planner, std::shared_ptr<Planner>>(
      m, "PlanningContext",
      "Plans one group's motions in a collision scene (move_group's pipeline without ROS: the same core calls). "
      "The joints outside the group stay where the start state has them. Failures are results with a status, "
      "never exceptions; bad construction raises ValueError.")
      .def(py::init(&makePlanner), py::arg("scene"), py::arg("group"), py::arg("ik") = nullptr,
           "ik: the group's solver (its chain must have the group's joints); without one, pose and position goals "
           "and Cartesian paths fail with INVALID_REQUEST.")
      .def_property_readonly("group", [](const Planner& p) { return p.context->group(); })
      .def_property_readonly("joint_names",
                             [](const Planner& p) {
                               std::vector<std::string> names;
                               for (const auto& joint : p.context->joints()) names.push_back(joint.name);
                               return names;
                             })
      .def_property_readonly("scene", [](const Planner& p) { return p.scene; })
      .def_property_readonly("ik", [](const Planner& p) { return p.ik; })
      .def("plan_to_joints", planTo(&PlanningContext::planToJoints), py::arg("start"), py::arg("goal"),
           py::arg("tolerance") = 0.0, py::arg("options") = PlanningOptions(),
           "To the group's joint values goal, +- tolerance per joint.")
      .def(
          "plan_to_joints",
          [](const Planner& p, const RobotState& start, const Eigen::VectorXd& goal, const Eigen::VectorXd& tolerance,
             const PlanningOptions& options) {
            return run(p, start, [&](const PlanningContext& c, const RobotState& s) {
              PlanningProblem problem = c.problem(s, options);
              problem.joint_goal = JointGoal{goal, tolerance};
              return plan(problem);
            });
          },
          py::arg("start"), py::arg("goal"), py::arg("tolerance"), py::arg("options") = PlanningOptions(),
          "The same with a tolerance per joint (move_group's joint constraints).")
      .def("plan_to_named", planTo(&PlanningContext::planToNamed), py::arg("start"), py::arg("name"),
           py::arg("tolerance") = 0.0, py::arg("options") = PlanningOptions(), "To an SRDF group_state of the group.")
      .def("plan_to_pose", planTo(&PlanningContext::planToPose), py::arg("start"), py::arg("pose"),
           py::arg("pose_goal") = PoseGoalOptions(), py::arg("options") = PlanningOptions(),
           "To a 4x4 pose of the group's tip link in its chain's base frame; goal states sampled by IK.")
      .def("plan_to_position", planTo(&PlanningContext::planToPosition), py::arg("start"), py::arg("position"),
           py::arg("pose_goal") = PoseGoalOptions(), py::arg("options") = PlanningOptions(),
           "To a position of the tip link, any orientation.")
      .def(
          "cartesian_path",
          [](const Planner& p, const RobotState& start, const std::vector<Eigen::Isometry3d>& waypoints,
             double eef_step, const JumpThreshold& jump_threshold, bool avoid_collisions, const IkOptions& ik_options) {
            return run(p, start, [&](const PlanningContext& c, const RobotState& s) {
              return c.cartesianPath(s, waypoints, eef_step, jump_threshold, avoid_collisions, ik_options);
            });
          },
          py::arg("start"), py::arg("waypoints"), py::arg("eef_step"), py::arg("jump_threshold") = JumpThreshold(),
          py::arg("avoid_collisions") = true, py::arg("ik_options") = IkOptions(),
          "A straight-line path of the tip through the 4x4 waypoints (chain base frame), at most eef_step m apart "
          "(MoveIt's computeCartesianPath).");
}

}  // namespace sixdof_core::python
