#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sixdof_core/time_parameterization.h"

namespace sixdof_core {

// The check both parameterizations start with: the INVALID_INPUT result naming what is wrong with the joint names,
// the waypoints (rows of joint values) or the options; nullopt when nothing is.
std::optional<TimeParameterizationResult> rejectInvalidInput(const std::vector<std::string>& names,
                                                             const std::vector<std::vector<double>>& waypoints,
                                                             const TimeParameterizationOptions& options);

}  // namespace sixdof_core
