"""moveit_commander.exception: the exception type, defined once in sixdof_commander.exceptions."""

from sixdof_commander.exceptions import MoveItCommanderException

__all__ = ["MoveItCommanderException"]
