#pragma once
// Forward declarations of this package's shared classes and of the moveit_msgs, sixdof_msgs and actionlib types
// named in its headers: a header can name a message or an action server without pulling in their headers (the
// .cpp includes them).

#include <memory>

namespace moveit_msgs {
template <class ContainerAllocator>
struct ApplyPlanningSceneRequest_;
template <class ContainerAllocator>
struct ApplyPlanningSceneResponse_;
template <class ContainerAllocator>
struct Constraints_;
template <class ContainerAllocator>
struct ExecuteTrajectoryAction_;
template <class ContainerAllocator>
struct ExecuteTrajectoryGoal_;
template <class ContainerAllocator>
struct GetCartesianPathRequest_;
template <class ContainerAllocator>
struct GetCartesianPathResponse_;
template <class ContainerAllocator>
struct GetMotionPlanRequest_;
template <class ContainerAllocator>
struct GetMotionPlanResponse_;
template <class ContainerAllocator>
struct GetPlanningSceneRequest_;
template <class ContainerAllocator>
struct GetPlanningSceneResponse_;
template <class ContainerAllocator>
struct GetPositionFKRequest_;
template <class ContainerAllocator>
struct GetPositionFKResponse_;
template <class ContainerAllocator>
struct GetPositionIKRequest_;
template <class ContainerAllocator>
struct GetPositionIKResponse_;
template <class ContainerAllocator>
struct GetStateValidityRequest_;
template <class ContainerAllocator>
struct GetStateValidityResponse_;
template <class ContainerAllocator>
struct MotionPlanRequest_;
template <class ContainerAllocator>
struct MotionPlanResponse_;
template <class ContainerAllocator>
struct MoveGroupAction_;
template <class ContainerAllocator>
struct MoveGroupGoal_;
template <class ContainerAllocator>
struct MoveGroupResult_;
template <class ContainerAllocator>
struct PositionIKRequest_;
template <class ContainerAllocator>
struct RobotState_;

typedef ApplyPlanningSceneRequest_<std::allocator<void>> ApplyPlanningSceneRequest;
typedef ApplyPlanningSceneResponse_<std::allocator<void>> ApplyPlanningSceneResponse;
typedef Constraints_<std::allocator<void>> Constraints;
typedef ExecuteTrajectoryAction_<std::allocator<void>> ExecuteTrajectoryAction;
typedef ExecuteTrajectoryGoal_<std::allocator<void>> ExecuteTrajectoryGoal;
typedef GetCartesianPathRequest_<std::allocator<void>> GetCartesianPathRequest;
typedef GetCartesianPathResponse_<std::allocator<void>> GetCartesianPathResponse;
typedef GetMotionPlanRequest_<std::allocator<void>> GetMotionPlanRequest;
typedef GetMotionPlanResponse_<std::allocator<void>> GetMotionPlanResponse;
typedef GetPlanningSceneRequest_<std::allocator<void>> GetPlanningSceneRequest;
typedef GetPlanningSceneResponse_<std::allocator<void>> GetPlanningSceneResponse;
typedef GetPositionFKRequest_<std::allocator<void>> GetPositionFKRequest;
typedef GetPositionFKResponse_<std::allocator<void>> GetPositionFKResponse;
typedef GetPositionIKRequest_<std::allocator<void>> GetPositionIKRequest;
typedef GetPositionIKResponse_<std::allocator<void>> GetPositionIKResponse;
typedef GetStateValidityRequest_<std::allocator<void>> GetStateValidityRequest;
typedef GetStateValidityResponse_<std::allocator<void>> GetStateValidityResponse;
typedef MotionPlanRequest_<std::allocator<void>> MotionPlanRequest;
typedef MotionPlanResponse_<std::allocator<void>> MotionPlanResponse;
typedef MoveGroupAction_<std::allocator<void>> MoveGroupAction;
typedef MoveGroupGoal_<std::allocator<void>> MoveGroupGoal;
typedef MoveGroupResult_<std::allocator<void>> MoveGroupResult;
typedef PositionIKRequest_<std::allocator<void>> PositionIKRequest;
typedef RobotState_<std::allocator<void>> RobotState;
}  // namespace moveit_msgs

namespace sixdof_msgs {
template <class ContainerAllocator>
struct GetRobotModelRequest_;
template <class ContainerAllocator>
struct GetRobotModelResponse_;
template <class ContainerAllocator>
struct RetimeTrajectoryRequest_;
template <class ContainerAllocator>
struct RetimeTrajectoryResponse_;

typedef GetRobotModelRequest_<std::allocator<void>> GetRobotModelRequest;
typedef GetRobotModelResponse_<std::allocator<void>> GetRobotModelResponse;
typedef RetimeTrajectoryRequest_<std::allocator<void>> RetimeTrajectoryRequest;
typedef RetimeTrajectoryResponse_<std::allocator<void>> RetimeTrajectoryResponse;
}  // namespace sixdof_msgs

namespace actionlib {
template <class ActionSpec>
class SimpleActionServer;
}  // namespace actionlib

namespace sixdof_planning {
class MoveGroupContext;
class SceneStore;
class TrajectoryExecutor;
}  // namespace sixdof_planning
