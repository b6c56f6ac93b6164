#pragma once
// Private to planning: validation of a PlanningProblem and the goal states plan() connects to.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "ompl_setup.h"
#include "sixdof_core/planning.h"
#include "sixdof_core/result.h"

namespace sixdof_core {
namespace detail {

// "[a, b, c]".
std::string formatState(const Eigen::VectorXd& q);
// Returns an error message naming the first joint out of bounds, or "" if q is within bounds.
std::string boundsViolation(const std::vector<JointBounds>& joints, const Eigen::VectorXd& q);
// Returns "" or why a vector cannot be a joint state of this problem.
std::string shapeError(std::size_t n, const Eigen::VectorXd& q);
// Returns "" or the first invalid option.
std::string validateOptions(const PlanningOptions& o);
// Returns "" or why the joint list is not a valid problem.
std::string validateJoints(const std::vector<JointBounds>& joints);

// The distinct valid goal states of a problem (failure: why there are none).
struct GoalSet : Result<PlanningStatus> {
  std::vector<Eigen::VectorXd> states;
};

GoalSet jointGoalStates(const PlanningProblem& p, Session* session);
GoalSet explicitGoalStates(const PlanningProblem& p, Session* session);
GoalSet sampledGoalStates(const PlanningProblem& p, Session* session);

}  // namespace detail
}  // namespace sixdof_core
