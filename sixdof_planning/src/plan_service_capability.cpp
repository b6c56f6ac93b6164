#include "sixdof_planning/plan_service_capability.h"

#include <sixdof_msgs/GetMotionPlan.h>

#include "move_group_capability_impl.h"
#include "sixdof_planning/motion_planner.h"
#include "sixdof_planning/move_group_context.h"

namespace sixdof_planning {

bool MotionPlanService::handle(sixdof_msgs::GetMotionPlanRequest& request,
                               sixdof_msgs::GetMotionPlanResponse& response) {
  MotionPlanner(context_).plan(request.motion_plan_request, service_, &response.motion_plan_response);
  return true;
}

template class ServiceCapability<MotionPlanService>;

}  // namespace sixdof_planning
