"""ArmDriver's straight-line moves of the tip link: move_straight, and the descents onto an object or a surface,
collision-checked against everything but the contacts they are meant to make (as MoveIt's pick and place allow
the gripper to touch the object and the held object the surface it is put on)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import rospy
from moveit_msgs.msg import ContactInformation, MoveItErrorCodes, RobotState, RobotTrajectory
from moveit_msgs.srv import GetStateValidityResponse
from sensor_msgs.msg import JointState

from ._service import SERVICE_TIMEOUT, call_service
from .error_reports import CallError
from .exceptions import SixdofCommanderError
from .grasping import raised
from .move_group import MoveGroup
from .transforms import matrix_from_pose, pose_from_matrix

# ArmDriver.last_failure_kind of a failure: no top-down grasp or place at that spot; a gripper that did not open, or
# did not close (nor stall on an object); anything else.
UNREACHABLE = "unreachable"
GRIPPER = "gripper"
FAILED = "failed"
# Other IK solutions of the pose above an object tried when the straight descent from the first one collides: seeded
# with the home state, then with this many random states.
RANDOM_SEEDS = 8


@dataclass(frozen=True)
class AllowedContacts:
    """The contacts a straight move is meant to make: between one of `bodies` (robot links or a held object) and
    one of `others` (world objects; None: any world object), and with `below` only at contact points at most that
    high in the planning frame (the surface an object is put on). Every other contact is a collision."""

    bodies: frozenset[str] = frozenset()
    others: frozenset[str] | None = None
    below: float = math.inf

    def allows(self, contact: ContactInformation) -> bool:
        """Whether this contact (check_state_validity's) is one of the allowed ones."""
        if contact.position.z > self.below:
            return False
        ends = (
            (contact.contact_body_1, contact.contact_body_2, contact.body_type_2),
            (contact.contact_body_2, contact.contact_body_1, contact.body_type_1),
        )
        for body, other, other_type in ends:
            if body not in self.bodies or other_type != ContactInformation.WORLD_OBJECT:
                continue
            if self.others is None or other in self.others:
                return True
        return False


def describe(contact: ContactInformation) -> str:
    """'A with B at z = ... m' of a contact."""
    return f"'{contact.contact_body_1}' with '{contact.contact_body_2}' at z = {contact.position.z:.3f} m"


class StraightMoves:
    """ArmDriver's Cartesian part: straight-line moves of the tip link, the descents onto an object or a surface,
    and the IK and state validity queries they use (move_group's compute_ik, check_state_validity)."""

    # Set by ArmDriver.
    arm: MoveGroup
    cartesian_step: float
    approach_distance: float
    home_joints: dict[str, float]  # the home state's values of the arm's joints
    last_failure: str
    last_failure_kind: str

    def move_straight(
        self,
        tip_target: np.ndarray,
        what: str,
        avoid_collisions: bool,
        infeasible_kind: str = FAILED,
        allowed: AllowedContacts | None = None,
    ) -> bool:
        """Straight-line move of the tip link to a 4x4 pose; the whole path must be feasible (a path that is not
        fails as `infeasible_kind`). avoid_collisions: every state of the path collision-free (move_group's check);
        with `allowed`, the path is checked here instead, every state through check_state_validity, and the allowed
        contacts are no collision (avoid_collisions must then be True)."""
        if allowed is not None and not avoid_collisions:
            raise SixdofCommanderError(f"move_straight ({what}): allowed contacts need avoid_collisions=True")
        trajectory, failure = self._straight_path(None, tip_target, avoid_collisions, allowed)
        if failure:
            return self._fail(f"{what}: {failure}", kind=infeasible_kind)
        return self._execute(trajectory, what)

    def _execute(self, trajectory: RobotTrajectory, what: str) -> bool:
        if not self.arm.execute(trajectory, wait=True):
            return self._fail(f"{what}: execution failed", self.arm.last_error)
        return True

    def _straight_path(
        self,
        start: Sequence[float] | None,
        tip_target: np.ndarray,
        avoid_collisions: bool,
        allowed: AllowedContacts | None,
    ) -> tuple[RobotTrajectory, str]:
        """The straight path of the tip link from the arm's joint values `start` (None: the current state) to
        `tip_target`, and why it cannot be taken ('' when it can)."""
        if start is None:
            self.arm.set_start_state_to_current_state()
        else:
            state = RobotState(is_diff=True)
            state.joint_state = JointState(name=self.arm.get_active_joints(), position=[float(v) for v in start])
            self.arm.set_start_state(state)
        try:
            trajectory, fraction = self.arm.compute_cartesian_path(
                [pose_from_matrix(tip_target)], self.cartesian_step, 0.0, avoid_collisions and allowed is None
            )
        finally:
            self.arm.set_start_state_to_current_state()
        if fraction < 1.0 - 1e-6:
            return trajectory, f"Cartesian path only {max(fraction, 0.0) * 100:.0f}% feasible: {self.arm.last_error}"
        if allowed is not None:
            names = trajectory.joint_trajectory.joint_names
            for point in trajectory.joint_trajectory.points:
                collisions = [c for c in self.contacts(names, point.positions) if not allowed.allows(c)]
                if collisions:
                    return trajectory, "the path would collide: " + "; ".join(describe(c) for c in collisions[:3])
        return trajectory, ""

    def contacts(self, joints: Sequence[str], positions: Sequence[float]) -> list[ContactInformation]:
        """The contacts move_group's check_state_validity finds with these joints at these positions (on the current
        scene, held objects included); SixdofCommanderError when the call fails."""
        return list(self._validity_check(joints, positions).contacts)

    def state_valid(self, joints: Sequence[str], positions: Sequence[float]) -> bool:
        """move_group's check_state_validity of the arm group with these joints at these positions (on the current
        scene, held objects included); SixdofCommanderError when the call fails."""
        return bool(self._validity_check(joints, positions).valid)

    def _validity_check(self, joints: Sequence[str], positions: Sequence[float]) -> GetStateValidityResponse:
        request = self._validity_request
        request.robot_state.joint_state = JointState(name=list(joints), position=[float(v) for v in positions])
        try:
            return call_service(self._validity, request, SERVICE_TIMEOUT)
        except (rospy.ServiceException, rospy.ROSException) as err:
            raise SixdofCommanderError(f"check_state_validity failed: {err}") from err

    def tip_ik(self, tip: np.ndarray, seed: Sequence[float], avoid_collisions: bool = True) -> np.ndarray | None:
        """move_group's compute_ik of the arm's tip link at `tip` (4x4, planning frame), seeded with `seed` (the arm's
        active joints, in order): the solution in that order, None when there is none; SixdofCommanderError when the
        call fails."""
        request, names = self._ik_request, self.arm.get_active_joints()
        request.ik_request.robot_state.joint_state = JointState(name=names, position=[float(v) for v in seed])
        request.ik_request.pose_stamped.pose = pose_from_matrix(tip)
        request.ik_request.avoid_collisions = avoid_collisions
        try:
            response = call_service(self._ik, request, SERVICE_TIMEOUT)
        except (rospy.ServiceException, rospy.ROSException) as err:
            raise SixdofCommanderError(f"compute_ik failed: {err}") from err
        if response.error_code.val != MoveItErrorCodes.SUCCESS:
            return None
        solution = dict(zip(response.solution.joint_state.name, response.solution.joint_state.position, strict=True))
        return np.array([solution[name] for name in names])

    def _current_tip(self) -> np.ndarray:
        return matrix_from_pose(self.arm.get_current_pose().pose)

    def _descend_to(self, tip: np.ndarray, what: str, where: str, allowed: AllowedContacts) -> bool:
        """Move the tip link the approach distance above `tip`, then straight down to it, every state of the descent
        collision-free but for the `allowed` contacts (the fingers straddling the object at a grasp, the held object
        meeting the surface at a place). When the descent from the pose the arm reached above `where` would collide
        (e.g. another arm configuration with the same tip pose, its elbow below the tip), the other IK solutions of
        that pose are tried and the arm moves to the first whose descent is free. No pose above `where` the arm can
        reach (no IK solution, or in collision), or none from which it can go straight down without collision,
        fails as UNREACHABLE."""
        above = raised(tip, self.approach_distance)
        if not self.moveto_pose(pose_from_matrix(above)):
            if self.arm.last_error.val in (MoveItErrorCodes.NO_IK_SOLUTION, MoveItErrorCodes.GOAL_IN_COLLISION):
                return self._fail(
                    f"{what}: no top-down pose above {where} the arm can reach", self.arm.last_error, UNREACHABLE
                )
            return False
        descent = f"{what}: straight down to {where}"
        trajectory, failure = self._straight_path(None, tip, True, allowed)
        if failure:
            rospy.logwarn(f"{descent}: {failure}; trying the other arm configurations above it")
            start = self._free_descent_start(above, tip, allowed)
            if start is None:
                return self._fail(f"{descent}: {failure} (and from every other IK solution above it)", kind=UNREACHABLE)
            self.arm.set_joint_value_target([float(v) for v in start])
            if not self.arm.go(wait=True):
                return self._fail(
                    f"{descent}: moving to another arm configuration above it failed", self.arm.last_error
                )
            trajectory, failure = self._straight_path(None, tip, True, allowed)
            if failure:
                return self._fail(f"{descent}: {failure}", kind=UNREACHABLE)
        return self._execute(trajectory, descent)

    def _free_descent_start(self, above: np.ndarray, tip: np.ndarray, allowed: AllowedContacts) -> np.ndarray | None:
        """An IK solution of the tip link at `above` (collision-free) from which the straight path down to `tip` is
        free but for the allowed contacts, seeded with the home state and then random states; None if none is."""
        names, current = self.arm.get_active_joints(), self.arm.get_current_joint_values()
        home = [self.home_joints.get(name, value) for name, value in zip(names, current, strict=True)]
        seeds = [home, *(self.arm.get_random_joint_values() for _ in range(RANDOM_SEEDS))]
        tried: list[np.ndarray] = [np.array(current)]
        for seed in seeds:
            solution = self.tip_ik(above, seed)
            if solution is None or any(np.allclose(solution, other, atol=1e-3) for other in tried):
                continue
            tried.append(solution)
            if not self._straight_path(solution, tip, True, allowed)[1]:
                return solution
        return None

    def _fail(self, what: str, error: CallError | None = None, kind: str = FAILED) -> bool:
        self.last_failure = f"{what}: {error}" if error is not None else what
        self.last_failure_kind = kind
        rospy.logerr(self.last_failure)
        return False
