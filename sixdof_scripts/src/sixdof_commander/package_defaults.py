"""What scripts take from the robot's config package instead of robot-specific flags: the gripper (its grasping
information, move_group's get_robot_model), the arm group it is the end effector of, the arm's home state, and
where the gripper's TCP sits in the arm's tip link."""

from __future__ import annotations

import numpy as np

from .exceptions import SixdofCommanderError
from .robot_model import GripperModel, RobotDescription, SemanticDescription


def find_gripper(srdf: SemanticDescription, group: str | None) -> tuple[GripperModel | None, str]:
    """(the gripper whose grasping information move_group serves, ""): the one of planning group `group`, or the
    first when `group` is None; (None, why not) when there is none."""
    for gripper in srdf.grippers:
        if group is None or gripper.group == group:
            return gripper, ""
    source = "move_group has no grasping information (robot_description_grasping: a config package's grasping.yaml)"
    if group is None:
        return None, f"the robot has no gripper: {source}"
    if group not in srdf.groups:
        return None, f"the robot has no gripper: its SRDF has no group '{group}' (groups: {sorted(srdf.groups)})"
    known = [g.group for g in srdf.grippers]
    return None, f"group '{group}' is no gripper: {source} for it" + (f" (only for {known})" if known else "")


def arm_group(srdf: SemanticDescription, gripper: GripperModel | None) -> str:
    """The group the gripper is the end effector of (its SRDF end effector's parent group, else the chain group
    whose tip is the end effector's parent link); without a gripper, or none of these, the SRDF's first chain
    group. SixdofCommanderError when there is no chain group at all."""
    chains = [g for g in srdf.groups.values() if g.chains]
    if gripper is not None:
        eef = next((e for e in srdf.end_effectors if e.name == gripper.end_effector), None)
        if eef is not None and eef.parent_group in srdf.groups:
            return eef.parent_group
        parent = eef.parent_link if eef is not None else gripper.parent_link
        for group in chains:
            if group.chains[-1][1] == parent:
                return group.name
    if not chains:
        raise SixdofCommanderError(f"the SRDF has no chain group to move the arm with (groups: {sorted(srdf.groups)})")
    return chains[0].name


def home_state(srdf: SemanticDescription, group: str) -> str:
    """The arm's home: the first named state of `group` in the SRDF (the setup assistant's `home`, the sixdof
    arm's `home pose`). SixdofCommanderError when the group has none."""
    states = srdf.group_states.get(group, {})
    if not states:
        raise SixdofCommanderError(f"the SRDF has no named state of group '{group}' to use as the home state")
    return next(iter(states))


def link_in_link(urdf: RobotDescription, frame: str, link: str) -> np.ndarray:
    """4x4 pose of `link` in `frame`, for two links joined by fixed joints only (either below the other)."""
    if frame == link:
        return np.eye(4)
    if frame in urdf.descendant_links(link):
        return np.linalg.inv(urdf.fixed_transform(link, frame))
    if link in urdf.descendant_links(frame):
        return urdf.fixed_transform(frame, link)
    raise SixdofCommanderError(f"links '{frame}' and '{link}' are not joined by fixed joints")
