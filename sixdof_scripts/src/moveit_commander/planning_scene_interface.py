"""PlanningSceneInterface: sixdof_commander.PlanningScene under moveit_commander's signatures."""

from __future__ import annotations

from moveit_msgs.msg import AttachedCollisionObject
from sixdof_commander.planning_scene import PlanningScene


class PlanningSceneInterface(PlanningScene):
    """MoveIt 1.1.16's PlanningSceneInterface. synchronous=True (our default; upstream's is False): each call returns
    once move_group applied it (apply_planning_scene), so a script that then waits for the scene to update finds it
    updated at once; synchronous=False: changes are published on move_group's planning_scene topic, in order, and
    the calls return at once."""

    def __init__(self, ns: str = "", synchronous: bool = True, service_timeout: float = 5.0) -> None:
        super().__init__(ns=ns, wait_for_servers=service_timeout, synchronous=synchronous)

    def attach_object(self, attached_collision_object: AttachedCollisionObject) -> bool:  # upstream's signature
        """Apply an AttachedCollisionObject (with shapes: a new object; without: the world object of its id)."""
        return self.attach_collision_object(attached_collision_object)
