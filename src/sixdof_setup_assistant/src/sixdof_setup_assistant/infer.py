"""The choices the setup assistant makes without answers, on the core's description of the model.

The description is what `setup_assistant_core --describe` writes (the core is the only URDF/SRDF reader):
links and joints in model order with types, limits and mimic relations. The rules:
- arm: from the root link, follow the tree while exactly one branch holds moving joints; the actuated (not
  fixed, not mimic) joints met are the arm, less trailing prismatic ones (a one-finger gripper). Where the root
  branches at once (e.g. two arms), the root-to-link path with the most actuated joints. Chain: root -> the
  child link of the arm's last joint.
- gripper: every moving joint below the arm's tip (mimic joints included, as MoveIt lists them); none if there
  are none. End effector `hand` on the arm's tip.
- named states: arm `home` = zeros clamped into the limits; gripper `open` / `close` = the end of each finger
  joint's range where its pads are furthest apart / closest (the core's grasp geometry, filled in by
  `complete_gripper_states`). States list only the actuated joints: mimic joints follow their master.
- planning frame `world`: a fixed virtual joint world -> root link, unless the root link is `world` itself.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from .answers import AnswersError


class InferenceError(Exception):
    """The model does not allow a choice (or an answer names what the model lacks); the message says which."""


@dataclass
class GroupPlan:
    name: str
    joints: list[str]  # every moving joint of the group (mimic ones included), in model order
    base_link: str = ""  # set for a chain group
    tip_link: str = ""
    controller: str = ""
    controller_type: str = "position_controllers/JointTrajectoryController"
    solver: str = ""  # arm only: empty = whatever fits (the core's verdict)


# A gripper state whose values come from the grasp geometry (complete_gripper_states).
GRIPPER_STATES = ("open", "close")


@dataclass
class Plan:
    robot: str
    root_link: str
    arm: GroupPlan
    gripper: GroupPlan | None
    end_effector: dict[str, str] | None
    # (name, group, values); the gripper's open/close have values None until complete_gripper_states
    states: list[tuple[str, str, dict[str, float] | None]] = field(default_factory=list)
    planning_frame: str = "world"
    suction: Any = None  # a suction tool (suction.SuctionTool) instead of a gripper; set by suction.attach

    @property
    def virtual_joint(self) -> bool:
        return self.planning_frame != self.root_link


def _moving(joint: dict[str, Any]) -> bool:
    return joint["type"] != "fixed"


def _actuated(joint: dict[str, Any]) -> bool:
    return bool(joint["active"])


class ModelView:
    """Tree queries on a model description."""

    def __init__(self, model: dict[str, Any]) -> None:
        self.model = model
        self.joints = {j["name"]: j for j in model["joints"]}
        self.order = [j["name"] for j in model["joints"]]
        self.links = [link["name"] for link in model["links"]]
        self.children: dict[str, list[dict[str, Any]]] = {name: [] for name in self.links}
        self.parent_joint: dict[str, dict[str, Any]] = {}
        for joint in model["joints"]:
            self.children[joint["parent"]].append(joint)
            self.parent_joint[joint["child"]] = joint

    def subtree_joints(self, link: str) -> list[dict[str, Any]]:
        found: list[dict[str, Any]] = []
        stack = [link]
        while stack:
            for joint in self.children[stack.pop()]:
                found.append(joint)
                stack.append(joint["child"])
        return sorted(found, key=lambda j: self.order.index(j["name"]))

    def path(self, base: str, tip: str) -> list[dict[str, Any]]:
        """Joints from base down to tip; raises InferenceError if tip is not below base."""
        joints: list[dict[str, Any]] = []
        link = tip
        while link != base:
            if link not in self.parent_joint:
                raise InferenceError(f"no chain from '{base}' to '{tip}': '{tip}' is not below '{base}'")
            joints.append(self.parent_joint[link])
            link = self.parent_joint[link]["parent"]
        return list(reversed(joints))

    def check_link(self, link: str, where: str) -> None:
        if link not in self.children:
            raise InferenceError(f"{where}: no link '{link}' in robot '{self.model['robot']}'")

    def check_joint(self, joint: str, where: str) -> None:
        if joint not in self.joints:
            raise InferenceError(f"{where}: no joint '{joint}' in robot '{self.model['robot']}'")


def _infer_arm_joints(view: ModelView) -> list[dict[str, Any]]:
    walk: list[dict[str, Any]] = []
    link = view.model["root_link"]
    while True:
        branches = [j for j in view.children[link] if _moving(j) or any(map(_moving, view.subtree_joints(j["child"])))]
        if len(branches) != 1:
            break
        joint = branches[0]
        if _actuated(joint):
            walk.append(joint)
        link = joint["child"]
    if not walk:
        # The root branches at once: the path to any link with the most actuated joints.
        best: list[dict[str, Any]] = []
        for name in view.links:
            path = [j for j in view.path(view.model["root_link"], name) if _actuated(j)]
            if len(path) > len(best):
                best = path
        walk = best
    rotary = [j for j in walk if j["type"] in ("revolute", "continuous")]
    while rotary and walk and walk[-1]["type"] == "prismatic":
        walk.pop()
    if not walk:
        raise InferenceError(f"robot '{view.model['robot']}' has no actuated joint for an arm")
    return walk


def _clamp(value: float, joint: dict[str, Any]) -> float:
    if not joint.get("bounded", True):
        return value
    return min(max(value, joint["lower"]), joint["upper"])


def _in_group_order(group_joints: list[str], values: dict[str, float]) -> dict[str, float]:
    return {name: float(values[name]) for name in group_joints if name in values}


def infer(model: dict[str, Any], answers: dict[str, Any]) -> Plan:
    """The plan for a model, answers overriding every inferred choice. Raises InferenceError naming the problem."""
    view = ModelView(model)
    root = model["root_link"]
    arm_answers = answers.get("arm", {})
    if "joints" in arm_answers:
        for name in arm_answers["joints"]:
            view.check_joint(name, "answers arm.joints")
        arm = GroupPlan(name=arm_answers.get("group", "arm"),
                        joints=[n for n in view.order if n in arm_answers["joints"]])
        tip = view.joints[arm.joints[-1]]["child"]
    else:
        if "tip_link" in arm_answers or "base_link" in arm_answers:
            base = arm_answers.get("base_link", root)
            view.check_link(base, "answers arm.base_link")
            if "tip_link" in arm_answers:
                tip = arm_answers["tip_link"]
                view.check_link(tip, "answers arm.tip_link")
            else:
                tip = _infer_arm_joints(view)[-1]["child"]
            chain = [j for j in view.path(base, tip) if _moving(j)]
            if not any(_actuated(j) for j in chain):
                raise InferenceError(f"answers arm: the chain '{base}' -> '{tip}' has no actuated joint")
        else:
            base = root
            walk = _infer_arm_joints(view)
            tip = walk[-1]["child"]
            chain = [j for j in view.path(base, tip) if _moving(j)]
        arm = GroupPlan(name=arm_answers.get("group", "arm"), joints=[j["name"] for j in chain], base_link=base,
                        tip_link=tip)
    arm.controller = arm_answers.get("controller", f"{arm.name}_controller")
    arm.controller_type = arm_answers.get("controller_type", arm.controller_type)
    arm.solver = arm_answers.get("solver", "")

    gripper: GroupPlan | None = None
    gripper_answers = answers.get("gripper", {})
    if gripper_answers != "none":
        if "joints" in gripper_answers:
            for name in gripper_answers["joints"]:
                view.check_joint(name, "answers gripper.joints")
                if name in arm.joints:
                    raise InferenceError(f"answers gripper.joints: '{name}' is already in the arm group")
            joints = [n for n in view.order if n in gripper_answers["joints"]]
        else:
            joints = [j["name"] for j in view.subtree_joints(tip) if _moving(j) and j["name"] not in arm.joints]
        if joints:
            name = gripper_answers.get("group", "gripper")
            if name == arm.name:
                raise InferenceError(f"answers gripper.group: '{name}' is the arm group's name too")
            gripper = GroupPlan(name=name, joints=joints,
                                controller=gripper_answers.get("controller", f"{name}_controller"),
                                controller_type=gripper_answers.get("controller_type", GroupPlan.controller_type))
        elif gripper_answers and "suction" not in answers:
            raise InferenceError(f"answers gripper: no moving joint below the arm's tip '{tip}'")
    if gripper and "suction" in answers:
        raise InferenceError(f"answers suction: the arm's tip '{tip}' has moving joints below it "
                             f"({', '.join(gripper.joints)}): a suction tool has none (answer gripper: none to "
                             "leave them out)")
    if gripper and gripper.controller == arm.controller:
        raise InferenceError(f"answers: arm and gripper both use controller '{arm.controller}'")

    end_effector = None
    ee_answers = answers.get("end_effector", {})
    if ee_answers and not gripper and "suction" not in answers:
        raise InferenceError("answers end_effector: there is no gripper group (nor a suction tool) for it")
    if gripper:
        end_effector = {"name": ee_answers.get("name", "hand"), "parent_link": ee_answers.get("parent_link", tip),
                        "group": gripper.name}
        view.check_link(end_effector["parent_link"], "answers end_effector.parent_link")

    states: list[tuple[str, str, dict[str, float]]] = []
    arm_active = [n for n in arm.joints if _actuated(view.joints[n])]
    states.append(("home", arm.name, {n: _clamp(0.0, view.joints[n]) for n in arm_active}))
    if gripper:
        states += [(state, gripper.name, None) for state in GRIPPER_STATES]
    groups = {arm.name: arm, **({gripper.name: gripper} if gripper else {})}
    for group, named in answers.get("named_states", {}).items():
        if group not in groups:
            raise InferenceError(f"answers named_states: no group '{group}' (groups: {', '.join(groups)})")
        # Given states replace the inferred ones of the group; the gripper's open/close stay unless given.
        kept = GRIPPER_STATES if gripper and group == gripper.name else ()
        states = [s for s in states if s[1] != group or (s[0] in kept and s[0] not in named)]
        for state, values in named.items():
            where = f"answers named_states.{group}.{state}"
            for joint in values:
                view.check_joint(joint, where)
                if joint not in groups[group].joints:
                    raise InferenceError(f"{where}: joint '{joint}' is not in the group")
                mimic = view.joints[joint].get("mimic")
                if mimic:
                    raise InferenceError(f"{where}: joint '{joint}' mimics '{mimic['joint']}': give '{mimic['joint']}' "
                                         "only (mimic joints follow their master)")
            states.append((state, group, _in_group_order(groups[group].joints, dict(values))))

    for joint in answers.get("acceleration_limits", {}):
        view.check_joint(joint, "answers acceleration_limits")
        if not _moving(view.joints[joint]):
            raise AnswersError(f"answers acceleration_limits: joint '{joint}' is fixed")
    return Plan(robot=model["robot"], root_link=root, arm=arm, gripper=gripper, end_effector=end_effector,
                states=states, planning_frame=answers.get("planning_frame", "world"))


def given_gripper_positions(plan: Plan) -> dict[str, dict[str, float]]:
    """The gripper's open/close states the answers give (state -> joint -> value), for the grasp geometry."""
    if not plan.gripper:
        return {}
    return {name: values for name, group, values in plan.states
            if group == plan.gripper.name and name in GRIPPER_STATES and values is not None}


def complete_gripper_states(plan: Plan, grasp: dict[str, Any]) -> None:
    """Fills the gripper's inferred open/close states from the core's grasp geometry (its `open` / `closed`)."""
    for i, (name, group, values) in enumerate(plan.states):
        if values is None:
            found = grasp["open" if name == "open" else "closed"]
            plan.states[i] = (name, group, _in_group_order(plan.gripper.joints if plan.gripper else [], found))
