#include "sixdof_planning/plan_service_capability.h"

#include <moveit_msgs/GetMotionPlan.h>

#include "move_group_capability_impl.h"
#include "sixdof_planning/motion_planner.h"
#include "sixdof_planning/move_group_context.h"

namespace sixdof_planning {

ErrorCode MotionPlanService::handle(const moveit_msgs::GetMotionPlanRequest& request,
                               moveit_msgs::GetMotionPlanResponse& response) {
  return MotionPlanner(context_).plan(request.motion_plan_request, service_, &response.motion_plan_response);
}

template class ServiceCapability<MotionPlanService>;

}  // namespace sixdof_planning
