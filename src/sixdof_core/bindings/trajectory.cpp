// Trajectories: points, sampling (joint_trajectory_controller's interpolation) and the time parameterizations.
#include "sixdof_core/trajectory.h"

#include "common.h"
#include "sixdof_core/time_parameterization.h"

namespace sixdof_core::python {

namespace {

// One column of the trajectory's points as a (points, joints) array; empty (0, joints) when the points lack it.
template <std::vector<double> TrajectoryPoint::*Member>
py::array_t<double> column(const Trajectory& trajectory) {
  std::vector<std::vector<double>> rows;
  for (const auto& point : trajectory.points) {
    if ((point.*Member).empty()) return toArray(std::vector<std::vector<double>>(), trajectory.joint_names.size());
    rows.push_back(point.*Member);
  }
  return toArray(rows, trajectory.joint_names.size());
}

Eigen::VectorXd vectorOf(const std::vector<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

using Parameterization = TimeParameterizationResult (*)(const std::vector<std::string>&,
                                                        const std::vector<std::vector<double>>&,
                                                        const TimeParameterizationOptions&);

// A time parameterization of (points, joints) waypoints, run without the GIL.
template <Parameterization compute>
TimeParameterizationResult parameterize(const std::vector<std::string>& joint_names, const Eigen::MatrixXd& waypoints,
                                        const TimeParameterizationOptions& options) {
  std::vector<std::vector<double>> rows;
  for (const Eigen::VectorXd& row : toRows(waypoints)) rows.emplace_back(row.data(), row.data() + row.size());
  py::gil_scoped_release release;
  return compute(joint_names, rows, options);
}

void bindPoints(py::module_& m) {
  py::class_<TrajectoryPoint>(m, "TrajectoryPoint", "trajectory_msgs/JointTrajectoryPoint without effort.")
      .def(py::init([](std::vector<double> positions, std::vector<double> velocities, std::vector<double> accelerations,
                       double time_from_start) {
             return TrajectoryPoint{std::move(positions), std::move(velocities), std::move(accelerations),
                                    time_from_start};
           }),
           py::arg("positions"), py::arg("velocities") = std::vector<double>(),
           py::arg("accelerations") = std::vector<double>(), py::arg("time_from_start") = 0.0)
      .def_readwrite("positions", &TrajectoryPoint::positions)
      .def_readwrite("velocities", &TrajectoryPoint::velocities)
      .def_readwrite("accelerations", &TrajectoryPoint::accelerations)
      .def_readwrite("time_from_start", &TrajectoryPoint::time_from_start, "s");

  py::class_<TrajectorySample>(m, "TrajectorySample", "Positions, velocities and accelerations at one time.")
      .def_property_readonly(
          "position", [](const TrajectorySample& s) { return vectorOf(s.position); }, "(joints,)")
      .def_property_readonly(
          "velocity", [](const TrajectorySample& s) { return vectorOf(s.velocity); }, "(joints,)")
      .def_property_readonly(
          "acceleration", [](const TrajectorySample& s) { return vectorOf(s.acceleration); }, "(joints,)");

  py::class_<Trajectory>(m, "Trajectory", "A joint trajectory: joint names and timed points.")
      .def(py::init([](std::vector<std::string> joint_names, std::vector<TrajectoryPoint> points) {
             return Trajectory{std::move(joint_names), std::move(points)};
           }),
           py::arg("joint_names"), py::arg("points") = std::vector<TrajectoryPoint>())
      .def_readwrite("joint_names", &Trajectory::joint_names)
      .def_readwrite("points", &Trajectory::points)
      .def_property_readonly("duration", &Trajectory::duration, "s, the last point's time_from_start.")
      .def_property_readonly(
          "times",
          [](const Trajectory& t) {
            Eigen::VectorXd times(t.points.size());
            for (size_t i = 0; i < t.points.size(); ++i) times[i] = t.points[i].time_from_start;
            return times;
          },
          "(points,) times from start.")
      .def_property_readonly("positions", &column<&TrajectoryPoint::positions>, "(points, joints)")
      .def_property_readonly("velocities", &column<&TrajectoryPoint::velocities>,
                             "(points, joints); (0, joints) if none")
      .def_property_readonly("accelerations", &column<&TrajectoryPoint::accelerations>,
                             "(points, joints); (0, joints) if none")
      .def("validate", &validateTrajectory, "'' if well formed, else a message naming the problem.")
      .def(
          "sample", [](const Trajectory& t, double time) { return TrajectorySampler(t).sample(time); },
          py::arg("time"),
          "The state at time, interpolated as joint_trajectory_controller does (at rest before the first and after "
          "the last point). ValueError for a malformed trajectory or a non-finite time.");
}

}  // namespace

void bindTrajectory(py::module_& m) {
  bindPoints(m);

  py::enum_<TimeParameterizationStatus>(m, "TimeParameterizationStatus")
      .value("SUCCESS", TimeParameterizationStatus::kSuccess)
      .value("INVALID_INPUT", TimeParameterizationStatus::kInvalidInput)
      .value("NOT_CONVERGED", TimeParameterizationStatus::kNotConverged);

  py::class_<TimeParameterizationOptions>(m, "TimeParameterizationOptions",
                                          "Limits per joint (in the joint names' order) and MoveIt's scaling factors.")
      .def(
          py::init([](std::vector<double> max_velocity, std::vector<double> max_acceleration, double velocity_scaling,
                      double acceleration_scaling, double max_deviation, double sample_period, double path_resolution) {
            return TimeParameterizationOptions{std::move(max_velocity), std::move(max_acceleration),
                                               velocity_scaling,        acceleration_scaling,
                                               max_deviation,           sample_period,
                                               path_resolution};
          }),
          py::arg("max_velocity"), py::arg("max_acceleration"), py::arg("velocity_scaling") = 1.0,
          py::arg("acceleration_scaling") = 1.0, py::arg("max_deviation") = TimeParameterizationOptions().max_deviation,
          py::arg("sample_period") = TimeParameterizationOptions().sample_period,
          py::arg("path_resolution") = TimeParameterizationOptions().path_resolution)
      .def_readwrite("max_velocity", &TimeParameterizationOptions::max_velocity)
      .def_readwrite("max_acceleration", &TimeParameterizationOptions::max_acceleration)
      .def_readwrite("velocity_scaling", &TimeParameterizationOptions::velocity_scaling, "0 < f <= 1")
      .def_readwrite("acceleration_scaling", &TimeParameterizationOptions::acceleration_scaling, "0 < f <= 1")
      .def_readwrite("max_deviation", &TimeParameterizationOptions::max_deviation,
                     "How far (rad) a blend may cut an interior waypoint; 0 stops at every corner.")
      .def_readwrite("sample_period", &TimeParameterizationOptions::sample_period, "s between output points")
      .def_readwrite("path_resolution", &TimeParameterizationOptions::path_resolution);

  bindResult<TimeParameterizationResult>(m, "TimeParameterizationResult", "status, message and the timed trajectory.")
      .def_readonly("trajectory", &TimeParameterizationResult::trajectory);

  m.def("compute_time_optimal_trajectory", &parameterize<computeTimeOptimalTrajectory>, py::arg("joint_names"),
        py::arg("waypoints"), py::arg("options"),
        "Time-optimal trajectory (Kunz & Stilman, with circular blends) through the (points, joints) waypoints, "
        "e.g. a PlanningResult's path; starts and ends at rest. Bad input is a result (INVALID_INPUT).");
  m.def("compute_iterative_parabolic_trajectory", &parameterize<computeIterativeParabolicTrajectory>,
        py::arg("joint_names"), py::arg("waypoints"), py::arg("options"),
        "MoveIt's iterative parabolic parameterization (moveit_commander's retime_trajectory default): one point "
        "per (points, joints) waypoint with its time, velocities and accelerations, at rest at both ends. Bad input "
        "is a result (INVALID_INPUT); accelerations that do not settle within the limits are NOT_CONVERGED. "
        "max_deviation, sample_period and path_resolution do not apply.");
}

}  // namespace sixdof_core::python
