// Kinematic chains, pose helpers and every IK solver (analytic, numeric, KDL).
#include "sixdof_core/kinematics.h"

#include "common.h"
#include "sixdof_core/ik_analytic.h"
#include "sixdof_core/ik_kdl.h"
#include "sixdof_core/ik_numeric.h"
#include "sixdof_core/ik_solver.h"

namespace sixdof_core::python {

namespace {

using SolverPtr = std::shared_ptr<IkSolver>;

// The closed-form solver answers in microseconds, less than releasing and taking back the GIL costs; the iterative
// ones may spend their whole timeout and release it.
bool isClosedForm(const IkSolver& solver) { return dynamic_cast<const AnalyticIkSolver*>(&solver) != nullptr; }

template <class Solver>
std::shared_ptr<Solver> makeSolver(const KinematicChain& chain) {
  return std::make_shared<Solver>(chain);
}

void bindChain(py::module_& m) {
  py::class_<KinematicChain>(m, "KinematicChain",
                             "A serial chain from a base link to a tip link: the tip pose in the base frame as a "
                             "function of the chain's moving joints (fixed joints folded in).")
      .def(py::init([](const ModelPtr& model, const std::string& base_link, const std::string& tip_link) {
             return KinematicChain(*model, base_link, tip_link);
           }),
           py::arg("model"), py::arg("base_link"), py::arg("tip_link"),
           "Raises RobotModelError for an unknown link, a tip not below the base or a mimic joint on the way.")
      .def_static(
          "for_group",
          [](const ModelPtr& model, const std::string& group) { return KinematicChain::forGroup(*model, group); },
          py::arg("model"), py::arg("group"), "The chain of an SRDF group (its <chain>, or its joints' serial path).")
      .def_property_readonly("base_link", &KinematicChain::baseLink)
      .def_property_readonly("tip_link", &KinematicChain::tipLink)
      .def_property_readonly("dof", &KinematicChain::dof)
      .def_property_readonly("joint_names", &KinematicChain::jointNames)
      .def_property_readonly("lower_limits", &KinematicChain::lowerLimits)
      .def_property_readonly("upper_limits", &KinematicChain::upperLimits)
      .def_property_readonly("mid_positions", &KinematicChain::midPositions, "0 for continuous joints.")
      .def("within_limits", &KinematicChain::withinLimits, py::arg("q"), py::arg("tolerance") = 0.0)
      .def(
          "forward", [](const KinematicChain& c, const Eigen::VectorXd& q) { return c.forward(q); }, py::arg("q"),
          "The tip's 4x4 pose in the base frame; q has dof values.")
      .def(
          "jacobian", [](const KinematicChain& c, const Eigen::VectorXd& q) { return Eigen::MatrixXd(c.jacobian(q)); },
          py::arg("q"), "6 x dof geometric Jacobian in the base frame, reference point at the tip's origin.");

  m.def("rotation_from_rpy", &rotationFromRpy, py::arg("roll"), py::arg("pitch"), py::arg("yaw"),
        "3x3 rotation from roll, pitch, yaw about the fixed x, y, z axes (tf2's setRPY).");
  m.def(
      "pose_from_xyz_rpy",
      [](double x, double y, double z, double roll, double pitch, double yaw) {
        return poseFromXyzRpy(x, y, z, roll, pitch, yaw);
      },
      py::arg("x"), py::arg("y"), py::arg("z"), py::arg("roll"), py::arg("pitch"), py::arg("yaw"),
      "4x4 pose from a position and roll, pitch, yaw about the fixed axes.");
  m.def(
      "pose_error",
      [](const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
        const PoseError e = poseError(a, b);
        return std::make_pair(e.position, e.orientation);
      },
      py::arg("a"), py::arg("b"), "(translation distance in m, rotation angle in rad) between two poses.");
}

void bindIkTypes(py::module_& m) {
  py::enum_<IkStatus>(m, "IkStatus")
      .value("SUCCESS", IkStatus::kSuccess)
      .value("NO_SOLUTION", IkStatus::kNoSolution, "The attempt budget ran out.")
      .value("TIMEOUT", IkStatus::kTimeout, "The time budget ran out.")
      .value("OUT_OF_REACH", IkStatus::kOutOfReach, "(analytic) beyond the arm's reach.")
      .value("JOINT_LIMITS", IkStatus::kJointLimits, "(analytic) every solution violates a joint limit.")
      .value("INVALID_INPUT", IkStatus::kInvalidInput, "A non-finite or non-rigid pose, a bad seed or options.");

  py::class_<IkOptions>(m, "IkOptions", "The budget and convergence of one IK call.")
      .def(py::init([](double timeout, int attempts, double epsilon, bool position_only,
                       const std::optional<Eigen::VectorXd>& seed, std::uint64_t random_seed) {
             IkOptions o;
             o.timeout = timeout;
             o.attempts = attempts;
             o.epsilon = epsilon;
             o.position_only = position_only;
             if (seed) o.seed = *seed;
             o.random_seed = random_seed;
             return o;
           }),
           py::arg("timeout") = IkOptions().timeout, py::arg("attempts") = IkOptions().attempts,
           py::arg("epsilon") = IkOptions().epsilon, py::arg("position_only") = false, py::arg("seed") = py::none(),
           py::arg("random_seed") = IkOptions().random_seed)
      .def_readwrite("timeout", &IkOptions::timeout, "Seconds; <= 0: none (then attempts must be > 0).")
      .def_readwrite("attempts", &IkOptions::attempts, "Starts (the seed, then random ones); 0: until the timeout.")
      .def_readwrite("epsilon", &IkOptions::epsilon, "Convergence: position (m) and rotation (rad) error.")
      .def_readwrite("position_only", &IkOptions::position_only)
      .def_property(
          "seed",
          [](const IkOptions& o) -> std::optional<Eigen::VectorXd> {
            if (o.seed.size() == 0) return std::nullopt;
            return o.seed;
          },
          [](IkOptions& o, const std::optional<Eigen::VectorXd>& seed) { o.seed = seed ? *seed : Eigen::VectorXd(); },
          "Start configuration (dof values); None: the middle of the joint ranges.")
      .def_readwrite("random_seed", &IkOptions::random_seed, "Seed of the random restarts (reproducible results).");

  bindResult<IkResult>(m, "IkResult", "status, message (why it failed) and, on success, the solution.")
      .def_readonly("solution", &IkResult::solution, "The chain's joint values (set on success).")
      .def_readonly("position_error", &IkResult::position_error, "m, of the solution or the best configuration.")
      .def_readonly("orientation_error", &IkResult::orientation_error, "rad")
      .def_readonly("iterations", &IkResult::iterations)
      .def_readonly("attempts", &IkResult::attempts);

  bindResult<AnalyticSolutions>(m, "AnalyticSolutions", "Every solution of one pose; ok if any is within limits.")
      .def_property_readonly(
          "solutions", [](const AnalyticSolutions& s) { return toArray(s.solutions, 6); },
          "(k, 6): the solutions within limits (bounded multi-turn joints add 2 pi multiples).")
      .def_readonly("unconstrained_count", &AnalyticSolutions::unconstrained_count,
                    "Solutions before the joint-limit filter (up to 8).");
}

}  // namespace

void bindKinematics(py::module_& m) {
  bindChain(m);
  bindIkTypes(m);

  py::class_<IkSolver, SolverPtr>(m, "IkSolver",
                                  "Inverse kinematics of one chain; the tip pose is given in the chain's base frame. "
                                  "solve() keeps no state: one solver may serve several threads.")
      .def_property_readonly("name", &IkSolver::name)
      .def_property_readonly("chain", &IkSolver::chain)
      .def(
          "solve",
          [](const IkSolver& solver, const Eigen::Isometry3d& pose, const IkOptions& options) {
            if (isClosedForm(solver)) return solver.solve(pose, options);
            py::gil_scoped_release release;
            return solver.solve(pose, options);
          },
          py::arg("pose"), py::arg("options") = IkOptions(),
          "Solves for a 4x4 tip pose. Failures are results (IkResult.status), not exceptions. The iterative "
          "solvers run without the GIL.")
      .def(
          "solve",
          [](const IkSolver& solver, const Eigen::Vector3d& position, const Eigen::Vector4d& xyzw,
             const IkOptions& options) {
            const Eigen::Quaterniond orientation(xyzw[3], xyzw[0], xyzw[1], xyzw[2]);
            if (isClosedForm(solver)) return solver.solve(position, orientation, options);
            py::gil_scoped_release release;
            return solver.solve(position, orientation, options);
          },
          py::arg("position"), py::arg("orientation"), py::arg("options") = IkOptions(),
          "Solves for a position and a unit quaternion (x, y, z, w), as ROS and scipy order it.");

  py::class_<AnalyticIkSolver, IkSolver, std::shared_ptr<AnalyticIkSolver>>(
      m, "AnalyticIkSolver",
      "Closed-form IK of a 6R arm with a spherical wrist (every solution, refined by Newton steps).")
      .def(py::init(&makeSolver<AnalyticIkSolver>), py::arg("chain"),
           "Raises AnalyticIkUnsupported naming the condition the chain violates.")
      .def(
          "solve_all",
          [](const AnalyticIkSolver& solver, const Eigen::Isometry3d& pose,
             const std::optional<Eigen::VectorXd>& seed) {
            return solver.solveAll(pose, seed ? *seed : Eigen::VectorXd());
          },
          py::arg("pose"), py::arg("seed") = py::none(),
          "All solutions within limits; the seed only places continuous joints and free joints at singularities.")
      .def_property_readonly("wrist_center", &AnalyticIkSolver::wristCenter);
  py::class_<NumericIkSolver, IkSolver, std::shared_ptr<NumericIkSolver>>(
      m, "NumericIkSolver", "Levenberg-Marquardt IK for any chain, restarted from random configurations.")
      .def(py::init(&makeSolver<NumericIkSolver>), py::arg("chain"));
  py::class_<KdlIkSolver, IkSolver, std::shared_ptr<KdlIkSolver>>(
      m, "KdlIkSolver", "KDL's Newton-Raphson IK with joint limits (MoveIt's default), with random restarts.")
      .def(py::init(&makeSolver<KdlIkSolver>), py::arg("chain"));

  m.def(
      "create_ik_solver",
      [](const std::string& name, const ModelPtr& model, const std::string& group) -> SolverPtr {
        return createIkSolver(name, *model, group);
      },
      py::arg("name"), py::arg("model"), py::arg("group"),
      "The solver kinematics.yaml names ('analytic', 'numeric' or 'kdl') for a group's chain.");
}

}  // namespace sixdof_core::python
