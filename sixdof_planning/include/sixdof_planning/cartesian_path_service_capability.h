#pragma once
// compute_cartesian_path (MoveIt's cartesian_path_service_capability): straight tip lines through waypoints.

#include <memory>

#include <ros/service_server.h>

#include "sixdof_planning/fwd.h"

namespace sixdof_planning {

class CartesianPathService {  // compute_cartesian_path
 public:
  explicit CartesianPathService(MoveGroupContext* context);
  bool handle(sixdof_msgs::GetCartesianPathRequest& request, sixdof_msgs::GetCartesianPathResponse& response);

 private:
  sixdof_msgs::MoveItErrorCodes compute(const sixdof_msgs::GetCartesianPathRequest& request,
                                        sixdof_msgs::GetCartesianPathResponse* response) const;

  MoveGroupContext* context_;
  ros::ServiceServer server_;
};

}  // namespace sixdof_planning
