"""The YAML files of the designed arm: kinematics, joint limits, controllers and the setup assistant's answers."""

from __future__ import annotations

import math

import yaml

from sixdof_description.core_model import joint_space_inertia
from sixdof_description.formatting import HEADER, fmt
from sixdof_description.robot_design import ARM_JOINTS, GRIPPER_JOINTS, Robot
from sixdof_description.urdf_writer import GRASP_FIX
from sixdof_setup_assistant.real_robot import hardware_yaml


def _yaml(data: dict, note: str = "") -> str:
    comment = "".join(f"# {line}\n" for line in note.splitlines())
    return f"# {HEADER}\n{comment}" + yaml.safe_dump(data, sort_keys=False, default_flow_style=False, width=120)


def render_kinematics(robot: Robot) -> str:
    return _yaml({"arm": {
        "kinematics_solver": "analytic",
        "kinematics_solver_search_resolution": 0.005,
        "kinematics_solver_timeout": 0.005,
        "kinematics_solver_attempts": 3,
        "position_only_ik": False,
    }})


def render_joint_limits(robot: Robot) -> str:
    limits = {}
    for name in (*ARM_JOINTS, *GRIPPER_JOINTS):
        p = robot.joint_params[name]
        limits[name] = {
            "has_velocity_limits": True,
            "max_velocity": float(p["velocity"]),
            "has_acceleration_limits": True,
            "max_acceleration": float(p["acceleration"]),
        }
    return _yaml({"joint_limits": limits})


def arm_gains(robot: Robot) -> dict:
    """PD(+I) gains from the joint-space inertia at 'home pose' (critically damped at the design frequency)."""
    c = robot.design["controllers"]
    mass = joint_space_inertia(robot, robot.states["home pose"])
    w = 2.0 * math.pi * float(c["natural_frequency_hz"])
    gains = {}
    for k, name in enumerate(ARM_JOINTS):
        inertia = max(float(mass[k, k]), float(c["min_inertia"]))
        p = inertia * w * w
        gains[name] = {"p": round(p, 1), "d": round(2.0 * float(c["damping_ratio"]) * inertia * w, 2),
                       "i": round(float(c["integral_ratio"]) * p, 1)}
    return gains


def render_controllers(robot: Robot) -> str:
    c = robot.design["controllers"]
    arm_constraints = {"goal_time": float(c["goal_time"]),
                       "stopped_velocity_tolerance": float(c["stopped_velocity_tolerance"])}
    for name in ARM_JOINTS:
        arm_constraints[name] = {"trajectory": float(c["trajectory_tolerance"]), "goal": float(c["goal_tolerance"])}
    gripper_constraints = {"goal_time": float(c["goal_time"]),
                           "stopped_velocity_tolerance": float(c["stopped_velocity_tolerance"])}
    for name in GRIPPER_JOINTS:
        gripper_constraints[name] = {"trajectory": 0.0, "goal": float(c["gripper_goal_tolerance"])}
    gripper_gains = {name: dict(c["gripper_gains"]) for name in GRIPPER_JOINTS}
    data = {
        "joint_state_controller": {"type": "joint_state_controller/JointStateController", "publish_rate": 100},
        "arm_controller": {
            "type": "position_controllers/JointTrajectoryController",
            "joints": list(ARM_JOINTS),
            "gains": arm_gains(robot),
            "constraints": arm_constraints,
            "state_publish_rate": 50,
            "action_monitor_rate": 20,
            "stop_trajectory_duration": 0.5,
        },
        "gripper_controller": {
            "type": "position_controllers/JointTrajectoryController",
            "joints": list(GRIPPER_JOINTS),
            "gains": gripper_gains,
            "constraints": gripper_constraints,
            "state_publish_rate": 50,
            "action_monitor_rate": 20,
            "stop_trajectory_duration": 0.2,
        },
        "controller_list": [
            {"name": "arm_controller", "action_ns": "follow_joint_trajectory", "type": "FollowJointTrajectory",
             "default": True, "joints": list(ARM_JOINTS)},
            {"name": "gripper_controller", "action_ns": "follow_joint_trajectory", "type": "FollowJointTrajectory",
             "default": True, "joints": list(GRIPPER_JOINTS)},
        ],
    }
    return _yaml(data, CONTROLLERS_NOTE)


def render_hardware(robot: Robot) -> str:
    """sixdof_control's hardware.yaml: the setup assistant's, for the joints the controllers command (the arm and
    the first finger; the second finger mimics it)."""
    actuated = (*ARM_JOINTS, GRIPPER_JOINTS[0])
    joints = [{"name": j.name, "type": j.joint_type, "bounded": True, "lower": j.lower, "upper": j.upper}
              for j in robot.joints if j.name in actuated]
    return hardware_yaml(joints, f"# {HEADER}")


def render_setup_answers(robot: Robot) -> str:
    """The setup assistant's answers for this arm: with them, `setup_assistant --urdf urdf/sixdof.urdf` generates
    the SRDF, kinematics, joint limits, controllers and grasping.yaml of this package (sixdof_setup_assistant's
    test_sixdof_config.py; generator.py writes grasping.yaml with the setup assistant's own code)."""
    d = robot.design
    arm_states = {name: {j: float(fmt(v)) for j, v in zip(ARM_JOINTS, q, strict=True)}
                  for name, q in robot.states.items()}
    gripper_states = {name: {GRIPPER_JOINTS[0]: float(fmt(value))} for name, value in d["gripper_states"].items()}
    data = {
        "density": COLLISION_DENSITY,
        "arm": {"group": "arm", "tip_link": "link6", "solver": "analytic", "controller": "arm_controller"},
        "gripper": {"group": "gripper", "joints": list(GRIPPER_JOINTS), "controller": "gripper_controller"},
        "end_effector": {"name": "hand", "parent_link": "link6"},
        "named_states": {"arm": arm_states, "gripper": gripper_states},
        "acceleration_limits": {name: float(robot.joint_params[name]["acceleration"])
                                for name in (*ARM_JOINTS, *GRIPPER_JOINTS)},
        # The grasp fix the URDF's gazebo_grasp_fix block has, for config/grasping.yaml (the TCP is the link tcp).
        "grasping": {"grasp_fix": dict(GRASP_FIX)},
    }
    return _yaml(data, "Answers for `rosrun sixdof_setup_assistant setup_assistant --answers` (docs/your_own_arm.md).")


# The collision matrix of the committed SRDF is sampled at MoveIt's low density.
COLLISION_DENSITY = 1000

CONTROLLERS_NOTE = """\
ros_control layout. sixdof_sim reads type, joints, constraints, state_publish_rate and gripper_cmd; its joints
are ideal position servos, so it does not read gains (PID gains for effort-controlled joints: real hardware
or gazebo_ros_control), action_monitor_rate or stop_trajectory_duration. move_group reads controller_list."""
