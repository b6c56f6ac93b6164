"""ArmDriver: the paper's script helper (moveto_xyzrpy, moveto_named, gripper, pick and place)."""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import rospy
from control_msgs.msg import GripperCommandResult
from geometry_msgs.msg import Pose
from moveit_msgs.srv import GetPositionIK, GetPositionIKRequest, GetStateValidity, GetStateValidityRequest
from shape_msgs.msg import SolidPrimitive

from sixdof_msgs.srv import GetObjectState

from ._ros import ServerWaiter, query_robot_model, resolve
from ._service import SERVICE_TIMEOUT, PersistentService, call_service
from .exceptions import SixdofCommanderError
from .goals import check_number, check_scaling_factor
from .grasping import (
    GraspSpec,
    ObjectGeometry,
    grasp_spec,
    grasp_tcp_pose,
    object_geometry,
    place_tcp_pose,
    raised,
    tip_pose,
)
from .gripper import Gripper
from .move_group import MoveGroup
from .package_defaults import arm_group, find_gripper, home_state, link_in_link
from .planning_scene import PlanningScene, default_touch_links
from .straight_moves import GRIPPER, UNREACHABLE, AllowedContacts, StraightMoves
from .suction import SuctionGripper, suction_tcp_pose
from .transforms import matrix_from_pose

# gripper_close: a finger joint this close (a fraction of its open-to-closed travel) to the closed state holds nothing.
CLOSED_ON_NOTHING = 0.025
# A held object's contacts at most this far (m) above its bottom are with the surface it is put on or lifted from.
SURFACE_CONTACT = 0.005


def rad(degrees: Sequence[float]) -> list[float]:
    """Degrees to radians, as a plain list (so that `xyz + rad(rpy)` concatenates)."""
    if isinstance(degrees, str) or not isinstance(degrees, Sequence | np.ndarray):
        raise SixdofCommanderError(f"rad() needs a list of angles in degrees, got {type(degrees).__name__}")
    return [math.radians(check_number(v, f"angle {i}")) for i, v in enumerate(degrees)]


@dataclass
class _Held:
    name: str
    height: float
    round: bool  # a sphere: no side to stand on, put down as it is held


class ArmDriver(StraightMoves):
    """Moves the arm and the gripper the way the paper's script does, and picks and places objects.

    Motions return True on success and False on planning/execution failure; `last_failure` then says
    what failed and `last_failure_kind` how: UNREACHABLE when there is no top-down grasp or place at that spot
    (the object does not fit the gripper, or the arm cannot reach the poses above and at it, or cannot descend
    straight to it without collision), GRIPPER when the gripper did not open or close, FAILED otherwise.
    The straight moves onto and off objects are collision-checked against everything but the contacts they are
    meant to make, which MoveIt's pick and place allow too: the gripper's links (the end-effector link's touch
    links) with the object it takes (grasp), and the held object with the surface below it (place). Lift and retreat
    go back up the checked descent, out of the contacts it ended in, unchecked.
    Misuse raises SixdofCommanderError.

    Everything robot-specific comes from the config package through move_group's get_robot_model: the gripper's
    TCP, open and closed states and widths (its grasping.yaml), the arm group (the one the gripper is the end
    effector of; `group_name` overrides it) and the home state (`home`: the arm group's first SRDF state).

    The gripper is optional: when move_group serves no grasping information (for `gripper_group`, or at all when
    it is None), `gripper` is None, the arm motions work and the gripper methods (gripper_open/close, grasp,
    pick, place, grasp_spec) raise SixdofCommanderError saying why.
    """

    def __init__(
        self,
        group_name: str | None = None,
        gripper_group: str | None = None,
        ns: str = "",
        wait_for_servers: float = 5.0,
        velocity_scaling: float = 0.5,
        acceleration_scaling: float = 0.5,
        approach_distance: float = 0.08,
        grasp_fix_timeout: float = 2.0,
        node_name: str = "arm_driver",
    ) -> None:
        # Arguments first: misuse fails before any waiting for servers.
        velocity = check_scaling_factor(velocity_scaling, "velocity_scaling")
        acceleration = check_scaling_factor(acceleration_scaling, "acceleration_scaling")
        self.approach_distance = check_number(approach_distance, "approach_distance")
        if self.approach_distance <= 0.0:
            raise SixdofCommanderError(f"approach_distance must be > 0, got {self.approach_distance}")
        self.grasp_fix_timeout = check_number(grasp_fix_timeout, "grasp_fix_timeout")
        if self.grasp_fix_timeout < 0.0:
            raise SixdofCommanderError(f"grasp_fix_timeout must be >= 0, got {self.grasp_fix_timeout}")
        if not rospy.core.is_initialized():
            rospy.init_node(node_name, anonymous=True)
        self._ns = ns
        self._wait = wait_for_servers
        waiter = ServerWaiter(wait_for_servers)
        waiter.service(resolve(ns, "get_robot_model"))
        waiter.check("ArmDriver")
        urdf, srdf = query_robot_model(ns, timeout=wait_for_servers)
        self.gripper_model, self._no_gripper = find_gripper(srdf, gripper_group)
        self.arm = MoveGroup(
            group_name or arm_group(srdf, self.gripper_model), ns=ns, wait_for_servers=wait_for_servers
        )
        self.arm.set_max_velocity_scaling_factor(velocity)
        self.arm.set_max_acceleration_scaling_factor(acceleration)
        self.home = home_state(srdf, self.arm.get_name())
        self.home_joints = dict(srdf.group_states[self.arm.get_name()][self.home])
        self.gripper: Gripper | SuctionGripper | None = None
        self._spec: GraspSpec | None = None
        if self.gripper_model is not None and self.gripper_model.suction_cup:
            g = self.gripper_model
            self.gripper = SuctionGripper(ns=ns, action_name=f"{g.vacuum_controller}/gripper_cmd",
                                          wait_for_servers=wait_for_servers)
            self._spec = grasp_spec(g, link_in_link(urdf, self.arm.get_end_effector_link(), g.parent_link))
        elif self.gripper_model is not None:
            g = self.gripper_model
            self.gripper = Gripper(
                ns=ns,
                group_name=g.group,
                wait_for_servers=wait_for_servers,
                open_state=g.open_state,
                close_state=g.closed_state,
            )
            self._spec = grasp_spec(g, link_in_link(urdf, self.arm.get_end_effector_link(), g.parent_link))
        self.scene = PlanningScene(ns=ns, wait_for_servers=wait_for_servers)
        # The links an object held at the end-effector link may touch (the scene's attached objects' touch links):
        # also those that may touch an object while the gripper takes or releases it.
        self._gripper_links = frozenset(default_touch_links(urdf, srdf, self.arm.get_end_effector_link()))
        self._validity = PersistentService(resolve(ns, "check_state_validity"), GetStateValidity)
        self._validity_request = GetStateValidityRequest(group_name=self.arm.get_name())
        self._validity_request.robot_state.is_diff = True
        self._ik = PersistentService(resolve(ns, "compute_ik"), GetPositionIK)
        self._ik_request = GetPositionIKRequest()
        ik = self._ik_request.ik_request
        ik.group_name, ik.ik_link_name = self.arm.get_name(), self.arm.get_end_effector_link()
        ik.robot_state.is_diff = True
        ik.pose_stamped.header.frame_id = self.arm.get_planning_frame()
        self.cartesian_step = 0.005
        self.last_failure = ""
        self.last_failure_kind = ""
        self._object_state = None
        self._held: _Held | None = None
        self._object_in_tcp: np.ndarray | None = None

    rad = staticmethod(rad)

    @property
    def ns(self) -> str:
        """The namespace of the planner and simulator nodes."""
        return self._ns

    @property
    def suction(self) -> bool:
        """Whether the tool is a suction cup (its vacuum is `gripper`, a SuctionGripper)."""
        return isinstance(self.gripper, SuctionGripper)

    @property
    def grasp_spec(self) -> GraspSpec:
        """The gripper's grasp geometry (tcp in the tip link, closing axis, opening, finger reach, palm depth) from
        the package's grasping information, for callers that grasp objects located by other means than the
        simulator (e.g. a camera)."""
        return self._require_gripper("grasp_spec")[1]

    def _require_gripper(self, what: str) -> tuple[Gripper | SuctionGripper, GraspSpec]:
        """The gripper and its grasp geometry; SixdofCommanderError saying why there is none."""
        if self.gripper is None or self._spec is None:
            raise SixdofCommanderError(f"ArmDriver.{what}: {self._no_gripper}")
        return self.gripper, self._spec

    # The paper's interface ---------------------------------------------------------------------------
    def moveto_xyzrpy(self, xyzrpy: Sequence[float]) -> bool:
        """Plan and move the arm's tip link (the sixdof arm's link6) to [x, y, z, roll, pitch, yaw] (metres,
        radians, fixed axes) in the planning frame."""
        if isinstance(xyzrpy, str) or not isinstance(xyzrpy, Sequence | np.ndarray) or len(xyzrpy) != 6:
            raise SixdofCommanderError(f"moveto_xyzrpy needs [x, y, z, roll, pitch, yaw] (6 numbers), got {xyzrpy!r}")
        values = list(xyzrpy)
        self.arm.set_pose_target(values)
        if not self.arm.go(wait=True):
            return self._fail(f"moving to xyzrpy {[round(v, 4) for v in values]} failed", self.arm.last_error)
        return True

    def moveto_pose(self, pose: Pose) -> bool:
        """Plan and move the tip link to a Pose in the planning frame."""
        self.arm.set_pose_target(pose)
        if not self.arm.go(wait=True):
            return self._fail("moving to pose failed", self.arm.last_error)
        return True

    def moveto_named(self, name: str) -> bool:
        """Plan and move to a named state of the arm group (the SRDF's group states)."""
        self.arm.set_named_target(name)
        if not self.arm.go(wait=True):
            return self._fail(f"moving to named pose '{name}' failed", self.arm.last_error)
        return True

    def gripper_open(self) -> bool:
        """Open the gripper (a suction tool: vacuum off); True when the fingers reached the 'open' position (the
        vacuum is off)."""
        return self._opened(self._require_gripper("gripper_open")[0].open())

    def _opened(self, result: GripperCommandResult) -> bool:
        """True when an open command's result reached the open state; a GRIPPER failure otherwise."""
        if result.reached_goal:
            return True
        said = f": {self.gripper.last_status_text}" if self.gripper.last_status_text else ""
        return self._fail(
            f"gripper did not open (position {result.position:.4f}, stalled {result.stalled}){said}", kind=GRIPPER
        )

    def _open_to_release(self, name: str) -> bool:
        """gripper_open() on the object just put down. The grasp fix lets go of it only once the fingers have moved
        its release tolerance away; until then the object, fixed to the palm, drags on the fingers, and where that
        lasts longer than the gripper controller's stall window the open ends stalled short of the open state while
        the fingers, still commanded, go on opening. Such an open is commanded again once the grasp fix has let go
        (within grasp_fix_timeout)."""
        gripper = self._require_gripper("release_at")[0]
        result = gripper.open()
        if not (result.reached_goal or self.suction) and result.stalled and self.get_object_state(name).attached_to:
            rospy.logwarn(
                f"the gripper stalled opening at {result.position:.4f} while the grasp fix held '{name}': "
                "opening again once it lets go"
            )
            if self._wait_for_grasp_fix(name, attached=False):
                result = gripper.open()
        return self._opened(result)

    def gripper_close(self) -> bool:
        """Close the gripper; True when it stopped on something (did not close on empty air: its finger joint
        ended within 2.5 % of its open-to-closed travel of the closed state, whichever way that runs). A suction
        tool: vacuum on; True when the cup holds an object (sealed on nothing otherwise, the vacuum left on)."""
        gripper = self._require_gripper("gripper_close")[0]
        result = gripper.close()
        if isinstance(gripper, SuctionGripper):
            return result.stalled or self._fail("the suction cup sealed on nothing (vacuum on, nothing held)")
        if not (result.reached_goal or result.stalled):
            said = f": {gripper.last_status_text}" if gripper.last_status_text else ""
            return self._fail(f"gripper did not close (position {result.position:.4f}){said}", kind=GRIPPER)
        travel = abs(gripper.open_position - gripper.close_position)
        if abs(result.position - gripper.close_position) <= CLOSED_ON_NOTHING * travel:
            return self._fail(f"gripper closed on nothing (position {result.position:.4f})")
        return True

    def gripper_opening(self, position: float) -> float:
        """The distance between the pads (m) at finger joint position `position`: the package's closed and open
        widths, interpolated linearly between the two states (exact for prismatic fingers, an estimate for a
        revolute linkage)."""
        gripper = self._require_gripper("gripper_opening")[0]
        if isinstance(gripper, SuctionGripper):
            raise SixdofCommanderError("ArmDriver.gripper_opening: a suction tool has no opening")
        g = self.gripper_model
        assert g is not None
        fraction = (position - gripper.close_position) / (gripper.open_position - gripper.close_position)
        return g.closed_width + fraction * (g.max_opening - g.closed_width)

    def gripper_closing_time(self, width: float) -> float:
        """The time (s) the fingers take from the open state to `width` between the pads (gripper_opening's linear
        map, clipped to the gripper's range) at the finger joint's URDF velocity limit; 0 without a limit."""
        gripper = self._require_gripper("gripper_closing_time")[0]
        if isinstance(gripper, SuctionGripper):
            raise SixdofCommanderError("ArmDriver.gripper_closing_time: a suction tool has no fingers")
        g = self.gripper_model
        assert g is not None
        fraction = min(max((width - g.closed_width) / (g.max_opening - g.closed_width), 0.0), 1.0)
        return (1.0 - fraction) * abs(gripper.open_position - gripper.close_position) / gripper.velocity

    # Simulator objects -------------------------------------------------------------------------------
    def get_object_state(self, name: str) -> GetObjectState._response_class:
        """The simulator's state of an object (sixdof_sim/get_object_state); unknown objects raise."""
        if self._object_state is None:
            service = resolve(self._ns, "sixdof_sim/get_object_state")
            waiter = ServerWaiter(self._wait)
            waiter.service(service)
            waiter.check("ArmDriver")
            self._object_state = rospy.ServiceProxy(service, GetObjectState)
        try:
            response = call_service(self._object_state, name, SERVICE_TIMEOUT)
        except (rospy.ServiceException, rospy.ROSException) as err:
            raise SixdofCommanderError(f"sixdof_sim/get_object_state failed: {err}") from err
        if not response.success:
            raise SixdofCommanderError(f"simulator object '{name}': {response.status_message}")
        return response

    def _wait_for_grasp_fix(self, name: str, attached: bool) -> bool:
        """Wait (wall clock, up to grasp_fix_timeout s) until the simulator's grasp fix has attached
        (released) the object, so that lifting (retreating) does not outrun it. A simulator without the
        grasp fix never attaches: that is reported as a warning, the grasp may still hold by friction."""
        end = time.monotonic() + self.grasp_fix_timeout
        while True:
            holder = self.get_object_state(name).attached_to
            if bool(holder) == attached:
                return True
            if time.monotonic() >= end or rospy.is_shutdown():
                state = "attached" if attached else "released"
                rospy.logwarn(f"'{name}' not {state} by the grasp fix within {self.grasp_fix_timeout:g} s")
                return False
            time.sleep(0.02)

    def _scene_attach(self, name: str, attach: bool) -> bool:
        """Attach (detach) the object in the planning scene, as the grasp fix did in the simulator. scene_mirror
        does the same on its own once its grace period is over, so under load it can come first: the change then
        being refused while the object already is attached (detached) is success."""
        if attach:
            done = self.scene.attach_object(name, self.arm.get_end_effector_link())
        else:
            done = self.scene.detach_object(name)
        if done or (name in self.scene.get_attached_object_names()) == attach:
            return True
        return self._fail(
            f"{'attaching' if attach else 'detaching'} '{name}' in the planning scene failed", self.scene.last_error
        )

    # Pick and place, in the paper's stages ------------------------------------------------------------
    def grasp(self, object_name: str) -> bool:
        """'pick pose': open, move above the object, descend straight and close the gripper on it."""
        self._require_gripper("grasp")
        if self._held is not None:
            raise SixdofCommanderError(f"already holding '{self._held.name}': place it first")
        state = self.get_object_state(object_name)
        pose = matrix_from_pose(state.object.pose)
        try:
            geometry = object_geometry(pose, state.object.shape)
            grasp_tip = self.grasp_tip(geometry)
        except SixdofCommanderError as err:
            return self._fail(f"no top-down grasp of '{object_name}': {err}", kind=UNREACHABLE)
        where = f"'{object_name}' at ({pose[0, 3]:.3f}, {pose[1, 3]:.3f})"
        allowed = AllowedContacts(self._gripper_links, frozenset([object_name]))
        if not (
            self.gripper_open() and self._descend_to(grasp_tip, "approach", where, allowed) and self.gripper_close()
        ):
            return False
        self._wait_for_grasp_fix(object_name, attached=True)
        if object_name in self.scene.get_known_object_names() and not self._scene_attach(object_name, True):
            return False
        round_ = state.object.shape.type == SolidPrimitive.SPHERE
        self._held = _Held(name=object_name, height=geometry.height, round=round_)
        return True

    def grasp_tip(self, geometry: ObjectGeometry) -> np.ndarray:
        """The tip link's pose (4x4) that grasps the object from the top: the suction cup's face on the centre of
        its top (suction.suction_tcp_pose), or the fingers around it (grasping.grasp_tcp_pose);
        SixdofCommanderError when the object has no such grasp."""
        spec = self._require_gripper("grasp_tip")[1]
        return tip_pose(suction_tcp_pose(geometry) if self.suction else grasp_tcp_pose(geometry, spec)[0], spec)

    def lift(self) -> bool:
        """'after pick pose': lift the grasped object straight up by the approach distance."""
        _, spec = self._require_gripper("lift")
        held = self._require_held("lift")
        # Back up the grasp's checked descent, out of the contacts it ends in (the object on its support surface).
        if not self.move_straight(raised(self._current_tip(), self.approach_distance), "lift", avoid_collisions=False):
            return False
        self._note_in_hand(held, spec)
        return True

    def _note_in_hand(self, held: _Held, spec: GraspSpec) -> None:
        """Where and how the object really sits in the hand (it may have shifted or leaned while closing and
        lifting); a sphere's lean does not matter (place stands the others upright)."""
        obj = matrix_from_pose(self.get_object_state(held.name).object.pose)
        tcp = self._current_tip() @ spec.tcp_in_tip
        self._object_in_tcp = np.linalg.inv(tcp) @ (obj[:, 3] if held.round else obj)

    def pick(self, object_name: str) -> bool:
        """Grasp the simulator object from the top and lift it."""
        return self.grasp(object_name) and self.lift()

    def release_at(self, position: Sequence[float]) -> bool:
        """'place pose': carry the held object above position [x, y, z] (its centre), upright (a box or cylinder that
        leans in the hand), descend and open."""
        held = self._require_held("place")
        place_tip = self.place_tip(position)
        where = f"({place_tip[0, 3]:.3f}, {place_tip[1, 3]:.3f})"
        bottom = self._check_position(position, held)[2] - held.height / 2.0
        allowed = AllowedContacts(frozenset([held.name]), below=bottom + SURFACE_CONTACT)
        if not (self._descend_to(place_tip, "place descent", where, allowed) and self._open_to_release(held.name)):
            return False
        self._wait_for_grasp_fix(held.name, attached=False)
        if held.name in self.scene.get_attached_object_names() and not self._scene_attach(held.name, False):
            return False
        self.forget_held()
        return True

    def place_tip(self, position: Sequence[float]) -> np.ndarray:
        """The tip link's pose (4x4) that puts the held object down upright with its centre at [x, y, z] ([x, y]: on
        the table at z = 0)."""
        _, spec = self._require_gripper("place")
        held = self._require_held("place")
        target = self._check_position(position, held)
        if self._object_in_tcp is None:
            raise SixdofCommanderError("place: lift() the object first (its position in the hand is unknown)")
        return tip_pose(place_tcp_pose(target, self._object_in_tcp, spec.clearance), spec)

    def retreat(self) -> bool:
        """'after place pose': move the open gripper straight up by the approach distance."""
        # Back up the place's checked descent, out of the contacts it ends in (the fingers with the object let go of
        # and, in a box or bin, with its walls or neighbours).
        return self.move_straight(
            raised(self._current_tip(), self.approach_distance), "retreat", avoid_collisions=False
        )

    def place(self, position: Sequence[float]) -> bool:
        """Put the held object down with its centre at [x, y, z] ([x, y]: resting on the table at z = 0)
        and retreat."""
        return self.release_at(position) and self.retreat()

    def hold(self, object_name: str, height: float, round_: bool = False) -> bool:
        """Take over an object the gripper holds and has lifted by other means than grasp() and lift() (e.g.
        moving_pick.pick_moving; round_: a sphere): attach it in the planning scene and note where it sits in the
        hand, so that place() can put it down."""
        spec = self._require_gripper("hold")[1]
        state = self.get_object_state(object_name).object
        if object_name in self.scene.get_known_object_names():
            # Where the simulator has it now: the scene's pose of an object picked off a belt lags behind.
            if state.mesh_resource:
                if not self._scene_attach(object_name, True):
                    return False
            elif not self.scene.attach_primitive(
                object_name, self.arm.get_end_effector_link(), state.pose, state.shape
            ):
                return self._fail(f"attaching '{object_name}' in the planning scene failed", self.scene.last_error)
        self._held = _Held(name=object_name, height=height, round=round_)
        self._note_in_hand(self._held, spec)
        return True

    def forget_held(self) -> None:
        """Forget the held object without placing it (it was deleted or lost): the next grasp starts afresh."""
        self._held = None
        self._object_in_tcp = None

    def _require_held(self, what: str) -> _Held:
        if self._held is None:
            raise SixdofCommanderError(f"{what}: no object is held (pick one first)")
        return self._held

    @staticmethod
    def _check_position(position: Sequence[float], held: _Held) -> np.ndarray:
        if isinstance(position, str) or not isinstance(position, Sequence | np.ndarray) or len(position) not in (2, 3):
            raise SixdofCommanderError(f"place position must be [x, y] or [x, y, z], got {position!r}")
        values = [check_number(v, f"place position element {i}") for i, v in enumerate(position)]
        if len(values) == 2:
            values.append(held.height / 2.0)
        return np.array(values)
