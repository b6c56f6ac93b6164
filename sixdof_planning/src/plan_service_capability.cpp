#include "sixdof_planning/plan_service_capability.h"

#include <sixdof_msgs/GetMotionPlan.h>

#include "sixdof_planning/move_group_context.h"

namespace sixdof_planning {

namespace {
const char* const kPlanSource = "plan_kinematic_path";
}  // namespace

MotionPlanService::MotionPlanService(MoveGroupContext* context) : context_(context), planner_(context) {
  server_ = context_->nodeHandle().advertiseService("plan_kinematic_path", &MotionPlanService::handle, this);
}

bool MotionPlanService::handle(sixdof_msgs::GetMotionPlanRequest& request,
                               sixdof_msgs::GetMotionPlanResponse& response) {
  planner_.plan(request.motion_plan_request, kPlanSource, &response.motion_plan_response);
  return true;
}

}  // namespace sixdof_planning
