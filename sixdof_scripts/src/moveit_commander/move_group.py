"""MoveGroupCommander: sixdof_commander.MoveGroup under moveit_commander's constructor signature."""

from __future__ import annotations

from sixdof_commander.move_group import MoveGroup


class MoveGroupCommander(MoveGroup):
    """MoveIt 1.1.16's MoveGroupCommander (every method is MoveGroup's; see its docstrings)."""

    def __init__(
        self, name: str, robot_description: str = "robot_description", ns: str = "", wait_for_servers: float = 5.0
    ) -> None:
        super().__init__(name, ns=ns, wait_for_servers=wait_for_servers, robot_description=robot_description)
