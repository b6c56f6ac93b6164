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
from moveit_msgs.srv import GetPositionIKResponse
from sixdof_commander.move_group_clients import MOVE_GROUP_ACTIONS, MOVE_GROUP_SERVICES

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
    actions = {name: action for name, (action, _goal) in MOVE_GROUP_ACTIONS.items()}
    actions["gripper_controller/gripper_cmd"] = GripperCommandAction
    servers = [actionlib.SimpleActionServer(name, spec, hang(name), auto_start=False) for name, spec in actions.items()]
    for server in servers:
        server.start()
    answers = {"compute_ik": answer_once("compute_ik")}
    services = [
        rospy.Service(name, spec, answers.get(name, hang(name)))
        for name, spec in [*MOVE_GROUP_SERVICES.items(), ("retime_trajectory", RetimeTrajectory)]
    ]
    rospy.wait_for_service(MODEL_SOURCE, timeout=60.0)
    source = rospy.ServiceProxy(MODEL_SOURCE, GetRobotModel)
    services.append(rospy.Service("get_robot_model", GetRobotModel, lambda request: source(request)))
    rospy.loginfo("stand_in_move_group: %d actions, %d services up", len(servers), len(services))
    rospy.spin()


if __name__ == "__main__":
    main()
