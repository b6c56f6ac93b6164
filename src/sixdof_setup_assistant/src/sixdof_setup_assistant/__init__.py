"""The setup assistant's front end: xacro expansion and config-package generation (see `setup_assistant --help`).

The robot model itself (URDF/SRDF reading, limits, groups, IK solver fit, self-collision sampling) is the C++
core's: this package only talks to it through the `setup_assistant_core` executable.
"""
