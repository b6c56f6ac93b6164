#include "time_parameterization_inputs.h"

#include <cmath>
#include <set>
#include <sstream>

namespace sixdof_core {
namespace {

// The parts written one after the other into a string (a stream is made only for a message: valid input needs none).
template <class... Parts>
std::string message(const Parts&... parts) {
  std::ostringstream msg;
  (msg << ... << parts);
  return msg.str();
}

std::string checkInputs(const std::vector<std::string>& names, const std::vector<std::vector<double>>& waypoints,
                        const TimeParameterizationOptions& o) {
  const std::size_t n = names.size();
  if (n == 0) return "no joint names";
  if (std::set<std::string>(names.begin(), names.end()).size() != n) return "duplicate joint names";
  if (waypoints.empty()) return "no waypoints";
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    if (waypoints[i].size() != n) {
      return message("waypoint ", i, " has ", waypoints[i].size(), " values for ", n, " joints");
    }
    for (double v : waypoints[i]) {
      if (!std::isfinite(v)) {
        return message("waypoint ", i, " is not finite");
      }
    }
  }
  if (o.max_velocity.size() != n || o.max_acceleration.size() != n) {
    return message("max_velocity and max_acceleration need ", n, " values (got ", o.max_velocity.size(), " and ",
                   o.max_acceleration.size(), ")");
  }
  for (std::size_t j = 0; j < n; ++j) {
    if (!std::isfinite(o.max_velocity[j]) || o.max_velocity[j] <= 0.0) {
      return message("max_velocity of ", names[j], " must be > 0 and finite, got ", o.max_velocity[j]);
    }
    if (!std::isfinite(o.max_acceleration[j]) || o.max_acceleration[j] <= 0.0) {
      return message("max_acceleration of ", names[j], " must be > 0 and finite, got ", o.max_acceleration[j]);
    }
  }
  if (!(o.velocity_scaling > 0.0 && o.velocity_scaling <= 1.0)) {
    return message("velocity scaling factor must be in (0, 1], got ", o.velocity_scaling);
  }
  if (!(o.acceleration_scaling > 0.0 && o.acceleration_scaling <= 1.0)) {
    return message("acceleration scaling factor must be in (0, 1], got ", o.acceleration_scaling);
  }
  if (!std::isfinite(o.max_deviation) || o.max_deviation < 0.0) {
    return message("max_deviation must be >= 0 and finite, got ", o.max_deviation);
  }
  if (!std::isfinite(o.sample_period) || o.sample_period <= 0.0) {
    return message("sample_period must be > 0 and finite, got ", o.sample_period);
  }
  if (!std::isfinite(o.path_resolution) || o.path_resolution <= 0.0) {
    return message("path_resolution must be > 0 and finite, got ", o.path_resolution);
  }
  return "";
}

}  // namespace

std::optional<TimeParameterizationResult> rejectInvalidInput(const std::vector<std::string>& names,
                                                             const std::vector<std::vector<double>>& waypoints,
                                                             const TimeParameterizationOptions& options) {
  const std::string invalid = checkInputs(names, waypoints, options);
  if (invalid.empty()) return std::nullopt;
  TimeParameterizationResult result;
  result.fail(TimeParameterizationStatus::kInvalidInput, "time parameterization: " + invalid);
  return result;
}

}  // namespace sixdof_core
