"""sixdof_commander: the Python API of the sixdof stack, with moveit_commander's names and semantics.

MoveGroup      plan and move a planning group (MoveGroupCommander)
PlanningScene  collision objects of the planner's scene (PlanningSceneInterface)
Gripper        open/close/set_position of the two-finger gripper
ArmDriver      the paper's script helper: moveto_xyzrpy, moveto_named, gripper, pick, place

The package moveit_commander (same distribution) offers these classes under MoveIt 1's names and signatures.
"""

from .arm_driver import ArmDriver, rad
from .exceptions import MoveItCommanderException, SixdofCommanderError
from .gripper import Gripper
from .move_group import MoveGroup
from .planning_scene import PlanningScene
from .transforms import quaternion_from_rpy, rpy_from_quaternion

__all__ = [
    "ArmDriver",
    "Gripper",
    "MoveGroup",
    "MoveItCommanderException",
    "PlanningScene",
    "SixdofCommanderError",
    "quaternion_from_rpy",
    "rad",
    "rpy_from_quaternion",
]
