#!/usr/bin/env python3
"""A stand-in for the move_group and simulator nodes that accepts every request and never answers: the
commander_server_death test kills it by pid mid-request. Each request it receives sets the parameter
/stand_in/received/<name> to True, so the test knows when the request is in flight. get_robot_model is the one
it answers: relayed to the real move_group in /model_source (the commander needs the model before any request);
compute_ik answers its first request (an empty response) and hangs on the next ones."""

import threading

import actionlib
import rospy
from control_msgs.msg import GripperCommandAction
from moveit_msgs.msg import ExecuteTrajectoryAction, MoveGroupAction
from moveit_msgs.srv import (
    ApplyPlanningScene,
    GetCartesianPath,
    GetMotionPlan,
    GetPlanningScene,
    GetPositionFK,
    GetPositionIK,
    GetPositionIKResponse,
)

from sixdof_msgs.srv import GetRobotModel, RetimeTrajectory

MODEL_SOURCE = "/model_source/get_robot_model"


def hang(name: str):
    def handler(*_args):
        rospy.set_param(f"/stand_in/received/{name}", True)
        threading.Event().wait()

    return handler


def answer_once(name: str):
    answered = threading.Event()
    hung = hang(name)

    def handler(request):
        if answered.is_set():
            return hung(request)
        answered.set()
        return GetPositionIKResponse()

    return handler


def main() -> None:
    rospy.init_node("stand_in_move_group")
    servers = [
        actionlib.SimpleActionServer(name, spec, hang(name), auto_start=False)
        for name, spec in (
            ("move_group", MoveGroupAction),
            ("execute_trajectory", ExecuteTrajectoryAction),
            ("gripper_controller/gripper_cmd", GripperCommandAction),
        )
    ]
    for server in servers:
        server.start()
    services = [
        rospy.Service(name, spec, hang(name))
        for name, spec in (
            ("plan_kinematic_path", GetMotionPlan),
            ("compute_fk", GetPositionFK),
            ("compute_cartesian_path", GetCartesianPath),
            ("get_planning_scene", GetPlanningScene),
            ("apply_planning_scene", ApplyPlanningScene),
            ("retime_trajectory", RetimeTrajectory),
        )
    ]
    services.append(rospy.Service("compute_ik", GetPositionIK, answer_once("compute_ik")))
    rospy.wait_for_service(MODEL_SOURCE, timeout=60.0)
    source = rospy.ServiceProxy(MODEL_SOURCE, GetRobotModel)
    services.append(rospy.Service("get_robot_model", GetRobotModel, lambda request: source(request)))
    rospy.loginfo("stand_in_move_group: %d actions, %d services up", len(servers), len(services))
    rospy.spin()


if __name__ == "__main__":
    main()
