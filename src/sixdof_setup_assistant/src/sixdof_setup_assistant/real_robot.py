"""A config package's files for the real robot: launch/real.launch (sixdof_bringup's real.launch with the package's
files) and config/hardware.yaml (sixdof_control's control loop settings and a commented block per hardware plugin).
sixdof_description's generator writes the sixdof arm's hardware.yaml with the same function."""

from __future__ import annotations

from typing import Any

from .templates import include_args

HARDWARE_HEADER = """\
# sixdof_control's hardware.yaml (docs/real_robot.md): the control loop's settings, then one block of parameters per
# hardware plugin. `real.launch driver:=<plugin>` runs the controllers of controllers.yaml on that plugin, which gets
# the block named like it and the joints the controllers command (actuated joints only: mimic joints follow their
# master): {joints}.
# Control loop
rate: 100                 # Hz of read -> update -> write
start_tolerance: 0.01     # rad or m: a goal whose first point is at time 0 must start this close to the joints
read_timeout: 0.1         # s: a hardware read that fails or takes longer is a fault (goals abort, the joints hold)
velocity_tolerance: 0.05  # fraction by which a command may exceed max_velocity (splines overshoot between points)
realtime_priority: 0      # 1..99: the loop's thread runs SCHED_FIFO (root or an rtprio limit); 0: normal scheduling
publish_rate: 100         # Hz of joint_states, action feedback and the controllers' state topics
"""


def hardware_joints(controller_joints: list[str], joints: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """The model's joints (the core's description, model order) that the controllers command: actuated ones."""
    wanted = set(controller_joints)
    return [j for j in joints if j["name"] in wanted and j["type"] != "fixed" and not j.get("mimic")]


def _rest(joint: dict[str, Any]) -> float:
    """Where the mock's joint starts: 0 when within the limits, else the middle of the range."""
    if not joint.get("bounded", True) or joint["lower"] <= 0.0 <= joint["upper"]:
        return 0.0
    return round((joint["lower"] + joint["upper"]) / 2.0, 6)


def hardware_yaml(joints: list[dict[str, Any]], header: str) -> str:
    """hardware.yaml for these joints (hardware_joints), below the `# ...` header line(s)."""
    names = ", ".join(j["name"] for j in joints)
    initial = ", ".join(f"{j['name']}: {_rest(j)!r}" for j in joints)
    servos = []
    for servo_id, joint in enumerate(joints, start=1):
        ratio = "20.0" if joint["type"] == "prismatic" else "1.0"
        note = "  # servo rad per m: a 5 cm pinion; set yours" if joint["type"] == "prismatic" else ""
        entry = f"{{id: {servo_id}, zero_offset: 0.0, direction: 1, gear_ratio: {ratio}}}"
        servos.append(f"    {joint['name']}: {entry}{note}")
    return f"""{header}
{HARDWARE_HEADER.format(joints=names)}
# driver:=mock: joints that follow their commands with a first-order lag; no hardware (trying the stack, tests).
mock:
  time_constant: 0.05     # s
  initial_positions: {{{initial}}}
  # position_noise: 0.0   # standard deviation of each reading (rad or m)
  # seed: 0
  # Fault injection (tests): unresponsive_joint: <joint> with unresponsive_after: <s>, or lost_after: <s>, counted
  # from the first read, or from the first motion with fault_clock: first_motion.

# driver:=dynamixel port:=/dev/ttyUSB0: Dynamixel X series servos (position control mode) on one Protocol 2.0 bus.
# Set each joint's servo id and calibrate zero_offset, direction and gear_ratio (docs/real_robot.md "Calibration")
# before the first motion.
dynamixel:
  port: /dev/ttyUSB0      # or the port:= argument of real.launch
  baud: 57600             # the servos' baud rate: 9600, 57600, 115200, 1000000, 2000000, 3000000, 4000000
  timeout: 0.02           # s a status packet is awaited
  joints:
{chr(10).join(servos)}
"""


def real_launch(name: str, robot: str, files: dict[str, str], header: str) -> str:
    """launch/real.launch of package `name`: sixdof_bringup's real.launch with the package's files."""
    passed = include_args({**files, "rviz_config": f"$(find {name})/config/motion_planning.rviz"},
                          ("hardware_file", "driver", "port", "rviz"))
    return f"""<?xml version="1.0"?>
<!-- {header}.
     The real {robot}: sixdof_bringup's real.launch with this package's files (robot_state_publisher, move_group,
     rviz on the wall clock) and the controllers of config/controllers.yaml served by a driver:
       roslaunch {name} real.launch driver:=mock                           sixdof_control, simulated joints
       roslaunch {name} real.launch driver:=dynamixel port:=/dev/ttyUSB0   sixdof_control, Dynamixel servos
       roslaunch {name} real.launch                                        your robot's own driver serves
                                                                           controller_list (driver:=none)
     config/hardware.yaml holds the control loop's settings and each plugin's parameters (docs/real_robot.md). -->
<launch>
  <arg name="driver" default="none"
       doc="none: start no driver, one started elsewhere serves the controllers (control_msgs/FollowJointTrajectory
            on controller_list's actions, joint_states); mock, dynamixel or &lt;package&gt;/&lt;class&gt;:
            sixdof_control with that hardware plugin and its block of hardware_file"/>
  <arg name="port" default=""
       doc="the hardware plugin's port (the dynamixel plugin's serial port, e.g. /dev/ttyUSB0); empty:
            hardware_file's"/>
  <arg name="rviz" default="true" doc="start rviz"/>
  <arg name="hardware_file" default="$(find {name})/config/hardware.yaml"
       doc="sixdof_control's hardware.yaml (control loop settings, a block per plugin); unused with driver:=none"/>

  <include file="$(find sixdof_bringup)/launch/real.launch">
{passed}
  </include>
</launch>
"""
