"""RobotCommander: the robot's groups, joints, links, limits and current state (moveit_commander's API)."""

from __future__ import annotations

from geometry_msgs.msg import PoseStamped
from moveit_msgs.msg import RobotState
from sixdof_commander._ros import JointStateMonitor, load_robot_model, require_node, resolve
from sixdof_commander.exceptions import SixdofCommanderError
from sixdof_commander.kinematics import parameter_kinematics
from sixdof_commander.robot_model import Group, resolve_group
from sixdof_commander.transforms import quaternion_from_matrix

from .move_group import MoveGroupCommander


class RobotCommander:
    """The robot model (from robot_description and robot_description_semantic) and its current state (joint_states).

    Groups are MoveGroupCommanders, created on first use (they wait for move_group); everything else needs only
    the parameters and, for current values, joint_states.
    """

    class Joint:
        """One joint of the robot."""

        def __init__(self, robot: RobotCommander, name: str) -> None:
            self._robot = robot
            self._name = name
            self._joint = robot._urdf.joints[name]

        def name(self) -> str:
            """The joint's name."""
            return self._name

        def variable_count(self) -> int:
            """1 for revolute, continuous and prismatic joints, 0 for fixed ones."""
            return 0 if self._joint.type == "fixed" else 1

        def bounds(self) -> list[float]:
            """[min, max] position (radians or metres; -pi, pi for continuous joints, as MoveIt's bounds)."""
            return [self._joint.lower, self._joint.upper]

        def min_bound(self) -> float:
            return self._joint.lower

        def max_bound(self) -> float:
            return self._joint.upper

        def value(self) -> float:
            """The current position, from joint_states."""
            return self._robot._values_of([self._name])[self._name]

        def move(self, position: float, wait: bool = True) -> bool:
            """Move this joint alone to position, with the first group that contains it; False on failure."""
            group = self._robot.get_default_owner_group(self._name)
            if group is None:
                raise SixdofCommanderError(f"joint '{self._name}' belongs to no planning group: it cannot be moved")
            commander = self._robot.get_group(group)
            commander.set_joint_value_target(self._name, position)
            return commander.go(wait=wait)

        def __repr__(self) -> str:
            return f"Joint('{self._name}')"

    class Link:
        """One link of the robot."""

        def __init__(self, robot: RobotCommander, name: str) -> None:
            self._robot = robot
            self._name = name

        def name(self) -> str:
            return self._name

        def pose(self) -> PoseStamped:
            """The link's current pose in the URDF's root link (the core's forward kinematics of joint_states)."""
            robot = self._robot
            chain = robot._urdf.chain(robot._urdf.root_link, self._name)
            names = list(dict.fromkeys(j.mimic or j.name for j in chain if j.type != "fixed"))
            matrix = robot._kinematics().link_pose(self._name, robot._values_of(names))
            result = PoseStamped()
            result.header.frame_id = robot.get_planning_frame()
            p, o = result.pose.position, result.pose.orientation
            p.x, p.y, p.z = (float(v) for v in matrix[:3, 3])
            o.x, o.y, o.z, o.w = quaternion_from_matrix(matrix[:3, :3])
            return result

        def __repr__(self) -> str:
            return f"Link('{self._name}')"

    def __init__(self, robot_description: str = "robot_description", ns: str = "") -> None:
        require_node()
        self._robot_description = robot_description
        self._ns = ns
        self._urdf, self._srdf = load_robot_model(ns, robot_description)
        self._kinematics = parameter_kinematics(ns)
        self._joint_states = JointStateMonitor(resolve(ns, "joint_states"))
        self._groups: dict[str, MoveGroupCommander] = {}

    # Model -------------------------------------------------------------------------------------------
    def get_planning_frame(self) -> str:
        """The frame of plans and poses (the SRDF virtual joint's parent, else the URDF root link)."""
        return self._srdf.virtual_joint_parent or self._urdf.root_link

    def get_root_link(self) -> str:
        """The URDF's root link."""
        return self._urdf.root_link

    def _ordered_links(self) -> list[str]:
        # move_group's model order: breadth-first from the root link, siblings in URDF order (every package's).
        return list(self._urdf.link_order)

    def _group(self, name: str) -> Group:
        return resolve_group(self._urdf, self._srdf, name)

    def get_joint_names(self, group: str | None = None) -> list[str]:
        """The group's active joints; with no group, every joint of the robot (fixed and mimic ones included)."""
        if group is not None:
            return self._group(group).joint_names
        return list(self._urdf.joints)

    def get_active_joint_names(self, group: str | None = None) -> list[str]:
        """The group's active joints; with no group, every active joint of the robot (not fixed, not mimic)."""
        if group is not None:
            return self._group(group).joint_names
        return [j.name for j in self._urdf.joints.values() if j.is_active]

    def get_link_names(self, group: str | None = None) -> list[str]:
        """The group's links; with no group, every link of the robot (the model's order: root first, breadth first)."""
        if group is not None:
            return list(self._group(group).links)
        return self._ordered_links()

    def get_group_names(self) -> list[str]:
        """The SRDF's planning groups."""
        return list(self._srdf.groups)

    def has_group(self, name: str) -> bool:
        return name in self._srdf.groups

    def get_default_owner_group(self, joint_name: str) -> str | None:
        """The first group (SRDF order) whose active joints include joint_name, or None."""
        for name in self._srdf.groups:
            if joint_name in self._group(name).joint_names:
                return name
        return None

    def get_joint(self, name: str) -> RobotCommander.Joint:
        if name not in self._urdf.joints:
            raise SixdofCommanderError(f"there is no joint named '{name}'")
        return RobotCommander.Joint(self, name)

    def get_link(self, name: str) -> RobotCommander.Link:
        if name not in self._urdf.links:
            raise SixdofCommanderError(f"there is no link named '{name}'")
        return RobotCommander.Link(self, name)

    def get_group(self, name: str) -> MoveGroupCommander:
        """The MoveGroupCommander of a group (created once; unknown groups raise MoveItCommanderException)."""
        if name not in self._groups:
            if not self.has_group(name):
                self._group(name)  # raises, naming the known groups
            self._groups[name] = MoveGroupCommander(name, robot_description=self._robot_description, ns=self._ns)
        return self._groups[name]

    def get_robot_markers(self, *args: object) -> None:
        """Refused: sixdof's rviz plugins draw the robot; there is no marker export."""
        raise SixdofCommanderError("get_robot_markers() is not available on sixdof: use rviz's RobotModel display")

    # State -------------------------------------------------------------------------------------------
    def _values_of(self, names: list[str]) -> dict[str, float]:
        """Current positions of the named joints (joint_states)."""
        return self._joint_states.positions(names)

    def get_current_variable_values(self) -> dict[str, float]:
        """Current position of every joint seen on joint_states, by name."""
        state = self._joint_states.joint_state()
        return dict(zip(state.name, state.position, strict=True))

    def get_current_state(self) -> RobotState:
        """The current joint positions as a RobotState."""
        state = RobotState()
        state.joint_state = self._joint_states.joint_state()
        return state

    def __getattr__(self, name: str) -> object:
        """robot.<group>, robot.<joint>, robot.<link>, as in MoveIt."""
        if name.startswith("_"):
            raise AttributeError(name)
        if name in self._srdf.groups:
            return self.get_group(name)
        if name in self._urdf.joints:
            return self.get_joint(name)
        if name in self._urdf.links:
            return self.get_link(name)
        raise AttributeError(f"'RobotCommander' has no attribute, group, joint or link named '{name}'")
