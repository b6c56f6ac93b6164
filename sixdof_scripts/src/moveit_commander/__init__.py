"""moveit_commander on sixdof: MoveIt 1.1.16's Python API (names, signatures, defaults, return types).

The same implementation as sixdof_commander: MoveGroupCommander is sixdof_commander.MoveGroup under upstream's
constructor signature, PlanningSceneInterface is its PlanningScene, and sixdof_commander.SixdofCommanderError is
a MoveItCommanderException. What sixdof cannot honour raises MoveItCommanderException naming the method.
"""

from . import conversions
from .exception import MoveItCommanderException
from .move_group import MoveGroupCommander
from .planning_scene_interface import PlanningSceneInterface
from .robot import RobotCommander
from .roscpp_initializer import roscpp_initialize, roscpp_shutdown

__all__ = [
    "MoveGroupCommander",
    "MoveItCommanderException",
    "PlanningSceneInterface",
    "RobotCommander",
    "conversions",
    "roscpp_initialize",
    "roscpp_shutdown",
]
