"""The robot model of the unit tests that run without a move_group: the get_robot_model response move_group would
send, built from the core's RobotModel (sixdof_core's bindings, the project's only URDF/SRDF reader) as move_group
fills it (describeRobotModel, query_robot_model_service_capability.cpp), read by the commander's
model_from_response. So these tests see move_group's model: its joint, link and group order and expansion."""

from __future__ import annotations

from sixdof_commander.robot_model import RobotDescription, SemanticDescription, model_from_response
from sixdof_commander.transforms import pose_from_matrix

import sixdof_core
from sixdof_msgs.msg import RobotModelEndEffector, RobotModelGroup, RobotModelGroupState, RobotModelJoint
from sixdof_msgs.srv import GetRobotModelResponse


def _joint(joint: sixdof_core.JointModel) -> RobotModelJoint:
    msg = RobotModelJoint(
        name=joint.name,
        type=joint.type.name.lower(),
        parent_link=joint.parent_link,
        child_link=joint.child_link,
        origin=pose_from_matrix(joint.origin),
        continuous=joint.type == sixdof_core.JointType.CONTINUOUS,
        has_position_limits=joint.type != sixdof_core.JointType.FIXED and joint.limits.bounded,
        min_position=joint.limits.lower,
        max_position=joint.limits.upper,
        max_velocity=joint.limits.velocity,
        max_effort=joint.limits.effort,
        variable_index=joint.variable_index,
    )
    msg.axis.x, msg.axis.y, msg.axis.z = (float(v) for v in joint.axis)
    if joint.mimic is not None:
        msg.mimic_joint = joint.mimic.joint
        msg.mimic_multiplier, msg.mimic_offset = joint.mimic.multiplier, joint.mimic.offset
    return msg


def load_model(urdf: str, srdf: str = "") -> tuple[RobotDescription, SemanticDescription]:
    """The commander's model of a URDF and SRDF (documents, not paths); the core's exception names bad input."""
    model = sixdof_core.RobotModel(urdf, srdf)
    response = GetRobotModelResponse(
        robot_name=model.name,
        root_link=model.root_link,
        planning_frame=model.virtual_joints[0].parent_frame if model.virtual_joints else model.root_link,
        link_names=list(model.link_names),
        joints=[_joint(joint) for joint in model.joints],
        variable_names=list(model.variable_names),
        groups=[
            RobotModelGroup(
                name=g.name,
                active_joints=g.active_joints,
                joints=g.joints,
                links=g.links,
                subgroups=g.subgroups,
                chain_base_link=g.chain_base,
                chain_tip_link=g.chain_tip,
            )
            for g in model.groups
        ],
        group_states=[
            RobotModelGroupState(
                group=s.group, name=s.name, joint_names=list(s.values), positions=list(s.values.values())
            )
            for s in model.group_states
        ],
        end_effectors=[
            RobotModelEndEffector(name=e.name, parent_link=e.parent_link, group=e.group, parent_group=e.parent_group)
            for e in model.end_effectors
        ],
    )
    return model_from_response(response)
