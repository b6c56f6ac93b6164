#pragma once
// Forward declarations of this package's shared classes and of the moveit_msgs, sixdof_msgs and actionlib types
// named in its headers: a header can name a message or an action server without pulling in their headers (the
// .cpp includes them).

#include <memory>

// Declares a message's template Name_ and its instance Name, as the message's generated header defines them.
#define SIXDOF_PLANNING_DECLARE_MESSAGE(Name) \
  template <class ContainerAllocator>         \
  struct Name##_;                             \
  typedef Name##_<std::allocator<void>> Name;

namespace moveit_msgs {
SIXDOF_PLANNING_DECLARE_MESSAGE(ApplyPlanningSceneRequest)
SIXDOF_PLANNING_DECLARE_MESSAGE(ApplyPlanningSceneResponse)
SIXDOF_PLANNING_DECLARE_MESSAGE(Constraints)
SIXDOF_PLANNING_DECLARE_MESSAGE(ExecuteTrajectoryAction)
SIXDOF_PLANNING_DECLARE_MESSAGE(ExecuteTrajectoryGoal)
SIXDOF_PLANNING_DECLARE_MESSAGE(GetCartesianPathRequest)
SIXDOF_PLANNING_DECLARE_MESSAGE(GetCartesianPathResponse)
SIXDOF_PLANNING_DECLARE_MESSAGE(GetMotionPlanRequest)
SIXDOF_PLANNING_DECLARE_MESSAGE(GetMotionPlanResponse)
SIXDOF_PLANNING_DECLARE_MESSAGE(GetPlanningSceneRequest)
SIXDOF_PLANNING_DECLARE_MESSAGE(GetPlanningSceneResponse)
SIXDOF_PLANNING_DECLARE_MESSAGE(GetPositionFKRequest)
SIXDOF_PLANNING_DECLARE_MESSAGE(GetPositionFKResponse)
SIXDOF_PLANNING_DECLARE_MESSAGE(GetPositionIKRequest)
SIXDOF_PLANNING_DECLARE_MESSAGE(GetPositionIKResponse)
SIXDOF_PLANNING_DECLARE_MESSAGE(GetStateValidityRequest)
SIXDOF_PLANNING_DECLARE_MESSAGE(GetStateValidityResponse)
SIXDOF_PLANNING_DECLARE_MESSAGE(MotionPlanRequest)
SIXDOF_PLANNING_DECLARE_MESSAGE(MotionPlanResponse)
SIXDOF_PLANNING_DECLARE_MESSAGE(MoveGroupAction)
SIXDOF_PLANNING_DECLARE_MESSAGE(MoveGroupGoal)
SIXDOF_PLANNING_DECLARE_MESSAGE(MoveGroupResult)
SIXDOF_PLANNING_DECLARE_MESSAGE(PositionIKRequest)
SIXDOF_PLANNING_DECLARE_MESSAGE(RobotState)
}  // namespace moveit_msgs

namespace sixdof_msgs {
SIXDOF_PLANNING_DECLARE_MESSAGE(GetRobotModelRequest)
SIXDOF_PLANNING_DECLARE_MESSAGE(GetRobotModelResponse)
SIXDOF_PLANNING_DECLARE_MESSAGE(RetimeTrajectoryRequest)
SIXDOF_PLANNING_DECLARE_MESSAGE(RetimeTrajectoryResponse)
}  // namespace sixdof_msgs

#undef SIXDOF_PLANNING_DECLARE_MESSAGE

namespace actionlib {
template <class ActionSpec>
class SimpleActionServer;
}  // namespace actionlib

namespace sixdof_planning {
class MoveGroupContext;
class SceneStore;
class StageTimer;
class TrajectoryExecutor;
}  // namespace sixdof_planning
