"""The YAML the setup assistant does not write for the arm: its answers, and the controllers' PID gains."""

from __future__ import annotations

import math

import yaml

from sixdof_description.core_model import joint_space_inertia
from sixdof_description.formatting import HEADER, fmt
from sixdof_description.robot_design import ARM_JOINTS, GRIPPER_JOINTS, Robot
from sixdof_description.urdf_writer import GRASP_FIX


def _yaml(data: dict, note: str = "") -> str:
    comment = "".join(f"# {line}\n" for line in note.splitlines())
    return f"# {HEADER}\n{comment}" + yaml.safe_dump(data, sort_keys=False, default_flow_style=False, width=120)


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


def render_controllers(robot: Robot, generated: str) -> str:
    """The setup assistant's controllers.yaml (`generated`) with the design's PID gains after each controller's
    joints (for effort-controlled hardware; the simulator's position servos and move_group do not read them)."""
    c = robot.design["controllers"]
    gains = {"arm_controller": arm_gains(robot)}
    if robot.tool_joints:
        gains["gripper_controller"] = {name: dict(c["gripper_gains"]) for name in robot.tool_joints}
    data = yaml.safe_load(generated)
    for name, controller_gains in gains.items():
        items = list(data[name].items())
        after_joints = [key for key, _ in items].index("joints") + 1
        data[name] = dict([*items[:after_joints], ("gains", controller_gains), *items[after_joints:]])
    return _yaml(data, CONTROLLERS_NOTE)


def render_setup_answers(robot: Robot) -> str:
    """The setup assistant's answers for this arm: with them it writes the SRDF, kinematics, joint limits,
    controllers (gains aside), hardware.yaml and grasping.yaml of this package (generator.py runs it;
    `setup_assistant --urdf urdf/sixdof.urdf --answers` generates the same: sixdof_setup_assistant's
    test_sixdof_config.py)."""
    d = robot.design
    arm_states = {name: {j: float(fmt(v)) for j, v in zip(ARM_JOINTS, q, strict=True)}
                  for name, q in robot.states.items()}
    if robot.tool == "suction":
        return _yaml(suction_answers(robot, arm_states), ANSWERS_NOTE)
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
    return _yaml(data, ANSWERS_NOTE)


def suction_answers(robot: Robot, arm_states: dict) -> dict:
    """The answers of the suction variant: the cup link named, its payload and tolerances (the simulator's)."""
    cup = robot.design["suction_cup"]
    return {
        "density": COLLISION_DENSITY,
        "arm": {"group": "arm", "tip_link": "link6", "solver": "analytic", "controller": "arm_controller"},
        "end_effector": {"name": "hand", "parent_link": "link6"},
        "suction": {"cup_link": "cup", **{k: float(cup[k]) for k in SUCTION_KEYS if k in cup}},
        "named_states": {"arm": arm_states},
        "acceleration_limits": {name: float(robot.joint_params[name]["acceleration"]) for name in ARM_JOINTS},
    }


ANSWERS_NOTE = "Answers for `rosrun sixdof_setup_assistant setup_assistant --answers` (docs/your_own_arm.md)."
SUCTION_KEYS = ("max_payload", "tilt_tolerance", "contact_distance")


# The collision matrix of the committed SRDF is sampled at MoveIt's low density.
COLLISION_DENSITY = 1000

CONTROLLERS_NOTE = """\
ros_control layout. sixdof_sim reads type, joints, constraints, state_publish_rate and gripper_cmd; its joints
are ideal position servos, so it does not read gains (PID gains for effort-controlled joints: real hardware
or gazebo_ros_control), action_monitor_rate or stop_trajectory_duration. move_group reads controller_list."""
