# Type stubs of sixdof_core._sixdof_core's public names (re-exported by __init__.py); test/bindings/test_stubs.py
# checks the same names, members and parameter names. Docstrings are the module's own (help(sixdof_core.RobotModel)).
from collections.abc import Callable, Mapping, Sequence
from typing import ClassVar, Final, Generic, TypeVar, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

_Array = NDArray[np.float64]  # joint values (n,), Jacobians (6, n), paths (points, joints), poses (4, 4)

class _Enum:  # the members every pybind11 enum has
    def __init__(self, value: int) -> None: ...
    def __int__(self) -> int: ...
    def __index__(self) -> int: ...
    name: Final[str]
    value: Final[int]

_Status = TypeVar("_Status", bound=_Enum)

class _Result(Generic[_Status]):  # the core's Result<Code>: a status (value 0 is success) and a message
    status: Final[_Status]
    message: Final[str]
    ok: Final[bool]
    def __bool__(self) -> bool: ...

# Bad input raises ValueError or one of these subclasses.
class RobotModelError(ValueError): ...
class SrdfError(ValueError): ...
class AnalyticIkUnsupported(ValueError): ...  # noqa: N818 (the core's name)

class SceneError(ValueError):
    status: SceneStatusCode

class ShapeType(_Enum):
    BOX: ClassVar[ShapeType]
    SPHERE: ClassVar[ShapeType]
    CYLINDER: ClassVar[ShapeType]
    MESH: ClassVar[ShapeType]

class Shape:
    @staticmethod
    def box(size: ArrayLike) -> Shape: ...
    @staticmethod
    def sphere(radius: float) -> Shape: ...
    @staticmethod
    def cylinder(radius: float, length: float) -> Shape: ...
    @staticmethod
    def mesh(path: str, scale: ArrayLike = ...) -> Shape: ...
    type: Final[ShapeType]
    box_size: Final[_Array]
    radius: Final[float]
    length: Final[float]
    mesh_resource: Final[str]
    mesh_path: Final[str]
    mesh_scale: Final[_Array]

class PlacedShape:
    def __init__(self, shape: Shape, origin: ArrayLike = ...) -> None: ...
    shape: Final[Shape]
    origin: Final[_Array]

class JointType(_Enum):
    FIXED: ClassVar[JointType]
    REVOLUTE: ClassVar[JointType]
    CONTINUOUS: ClassVar[JointType]
    PRISMATIC: ClassVar[JointType]

class JointLimits:
    bounded: Final[bool]
    lower: Final[float]
    upper: Final[float]
    velocity: Final[float]
    effort: Final[float]

class MimicInfo:
    joint: Final[str]
    multiplier: Final[float]
    offset: Final[float]

class JointModel:
    name: Final[str]
    type: Final[JointType]
    parent_link: Final[str]
    child_link: Final[str]
    origin: Final[_Array]
    axis: Final[_Array]
    limits: Final[JointLimits]
    damping: Final[float]
    friction: Final[float]
    mimic: Final[MimicInfo | None]
    variable_index: Final[int]
    is_active: Final[bool]
    is_multi_turn: Final[bool]

class LinkInertial:
    mass: Final[float]
    origin: Final[_Array]
    inertia: Final[_Array]

class LinkModel:
    name: Final[str]
    parent_joint: Final[int]
    parent_link: Final[int]
    collision_shapes: Final[list[PlacedShape]]
    inertial: Final[LinkInertial | None]

class JointGroup:
    name: Final[str]
    joints: Final[list[str]]
    active_joints: Final[list[str]]
    links: Final[list[str]]
    subgroups: Final[list[str]]
    chain_base: Final[str]
    chain_tip: Final[str]
    is_chain: Final[bool]

class GroupState:
    name: Final[str]
    group: Final[str]
    values: Final[dict[str, float]]

class EndEffector:
    name: Final[str]
    parent_link: Final[str]
    group: Final[str]
    parent_group: Final[str]

class VirtualJoint:
    name: Final[str]
    type: Final[str]
    parent_frame: Final[str]
    child_link: Final[str]

class DisabledCollisionPair:
    link1: Final[str]
    link2: Final[str]
    reason: Final[str]

class RobotModel:
    def __init__(self, urdf: str, srdf: str = "", package_dirs: Mapping[str, str] = ...,
                 search_roots: Sequence[str] | None = None) -> None: ...
    @staticmethod
    def from_files(urdf_path: str, srdf_path: str = "", package_dirs: Mapping[str, str] = ...,
                   search_roots: Sequence[str] | None = None) -> RobotModel: ...
    name: Final[str]
    root_link: Final[str]
    links: Final[list[LinkModel]]
    joints: Final[list[JointModel]]
    link_names: Final[list[str]]
    joint_names: Final[list[str]]
    variable_names: Final[list[str]]
    variable_count: Final[int]
    def link(self, name: str) -> LinkModel: ...
    def joint(self, name: str) -> JointModel: ...
    def default_positions(self) -> _Array: ...
    groups: Final[list[JointGroup]]
    group_names: Final[list[str]]
    def group(self, name: str) -> JointGroup: ...
    group_states: Final[list[GroupState]]
    end_effectors: Final[list[EndEffector]]
    virtual_joints: Final[list[VirtualJoint]]
    passive_joints: Final[list[str]]
    disabled_collision_pairs: Final[list[DisabledCollisionPair]]

def find_package(package: str, search_roots: Sequence[str] | None = None) -> str: ...

class StateSampler:
    def __init__(self, model: RobotModel, seed: int = 0) -> None: ...
    def sample(self) -> _Array: ...

class RobotState:
    def __init__(self, model: RobotModel) -> None: ...
    model: Final[RobotModel]
    positions: _Array
    def joint_position(self, name: str) -> float: ...
    def set_joint_position(self, name: str, value: float) -> None: ...
    joint_positions: Final[dict[str, float]]
    def set_joint_positions(self, values: Mapping[str, float]) -> None: ...
    def group_positions(self, group: str) -> _Array: ...
    def set_group_positions(self, group: str, values: ArrayLike) -> None: ...
    def set_to_named_state(self, group: str, name: str) -> None: ...
    def set_to_default_positions(self) -> None: ...
    def set_to_random_positions(self, sampler: StateSampler, group: str | None = None) -> None: ...
    def link_pose(self, link: str) -> _Array: ...
    def link_poses(self) -> dict[str, _Array]: ...
    def jacobian(self, group: str, link: str | None = None, reference_point: ArrayLike = ...) -> _Array: ...
    def satisfies_bounds(self, tolerance: float = 0.0) -> bool: ...
    def copy(self) -> RobotState: ...
    def __copy__(self) -> RobotState: ...
    def __deepcopy__(self, memo: dict) -> RobotState: ...

class KinematicChain:
    def __init__(self, model: RobotModel, base_link: str, tip_link: str) -> None: ...
    @staticmethod
    def for_group(model: RobotModel, group: str) -> KinematicChain: ...
    base_link: Final[str]
    tip_link: Final[str]
    dof: Final[int]
    joint_names: Final[list[str]]
    lower_limits: Final[_Array]
    upper_limits: Final[_Array]
    mid_positions: Final[_Array]
    def within_limits(self, q: ArrayLike, tolerance: float = 0.0) -> bool: ...
    def forward(self, q: ArrayLike) -> _Array: ...
    def jacobian(self, q: ArrayLike) -> _Array: ...

def rotation_from_rpy(roll: float, pitch: float, yaw: float) -> _Array: ...
def pose_from_xyz_rpy(x: float, y: float, z: float, roll: float, pitch: float, yaw: float) -> _Array: ...
def pose_error(a: ArrayLike, b: ArrayLike) -> tuple[float, float]: ...

class IkStatus(_Enum):
    SUCCESS: ClassVar[IkStatus]
    NO_SOLUTION: ClassVar[IkStatus]
    TIMEOUT: ClassVar[IkStatus]
    OUT_OF_REACH: ClassVar[IkStatus]
    JOINT_LIMITS: ClassVar[IkStatus]
    INVALID_INPUT: ClassVar[IkStatus]

class IkOptions:
    def __init__(self, timeout: float = 0.005, attempts: int = 0, epsilon: float = 1e-05, position_only: bool = False,
                 seed: ArrayLike | None = None, random_seed: int = 42) -> None: ...
    timeout: float
    attempts: int
    epsilon: float
    position_only: bool
    seed: _Array | None
    random_seed: int

class IkResult(_Result[IkStatus]):
    solution: Final[_Array]
    position_error: Final[float]
    orientation_error: Final[float]
    iterations: Final[int]
    attempts: Final[int]

class AnalyticSolutions(_Result[IkStatus]):
    solutions: Final[_Array]
    unconstrained_count: Final[int]

class IkSolver:
    name: Final[str]
    chain: Final[KinematicChain]
    @overload
    def solve(self, pose: ArrayLike, options: IkOptions = ...) -> IkResult: ...
    @overload
    def solve(self, position: ArrayLike, orientation: ArrayLike, options: IkOptions = ...) -> IkResult: ...

class AnalyticIkSolver(IkSolver):
    def __init__(self, chain: KinematicChain) -> None: ...
    def solve_all(self, pose: ArrayLike, seed: ArrayLike | None = None) -> AnalyticSolutions: ...
    wrist_center: Final[_Array]

class NumericIkSolver(IkSolver):
    def __init__(self, chain: KinematicChain) -> None: ...

class KdlIkSolver(IkSolver):
    def __init__(self, chain: KinematicChain) -> None: ...

def create_ik_solver(name: str, model: RobotModel, group: str) -> IkSolver: ...

class SceneStatusCode(_Enum):
    OK: ClassVar[SceneStatusCode]
    UNKNOWN_NAME: ClassVar[SceneStatusCode]
    DUPLICATE_NAME: ClassVar[SceneStatusCode]
    INVALID_SHAPE: ClassVar[SceneStatusCode]
    MESH_LOAD_FAILED: ClassVar[SceneStatusCode]
    INVALID_VALUE: ClassVar[SceneStatusCode]

class BodyType(_Enum):
    ROBOT_LINK: ClassVar[BodyType]
    ATTACHED_OBJECT: ClassVar[BodyType]
    WORLD_OBJECT: ClassVar[BodyType]

class CollisionScope(_Enum):
    ALL: ClassVar[CollisionScope]
    SELF: ClassVar[CollisionScope]
    WORLD: ClassVar[CollisionScope]

class BodyPair:
    body1: Final[str]
    body2: Final[str]
    type1: Final[BodyType]
    type2: Final[BodyType]

class Contact(BodyPair):
    position: Final[_Array]
    normal: Final[_Array]
    depth: Final[float]

class CollisionReport:
    colliding: Final[bool]
    contacts: Final[list[Contact]]
    def __bool__(self) -> bool: ...

class DistanceReport(BodyPair):
    found: Final[bool]
    distance: Final[float]
    point1: Final[_Array]
    point2: Final[_Array]

class CollisionScene:
    def __init__(self, model: RobotModel, padding: float = 0.0, scale: float = 1.0) -> None: ...
    model: Final[RobotModel]
    link_names: Final[list[str]]
    def copy(self) -> CollisionScene: ...
    def add_box(self, id: str, size: ArrayLike, pose: ArrayLike = ...) -> None: ...
    def add_sphere(self, id: str, radius: float, pose: ArrayLike = ...) -> None: ...
    def add_cylinder(self, id: str, radius: float, length: float, pose: ArrayLike = ...) -> None: ...
    def add_mesh(self, id: str, path: str, pose: ArrayLike = ..., scale: ArrayLike = ...) -> None: ...
    def add_object(self, id: str, shapes: Sequence[PlacedShape], pose: ArrayLike = ...) -> None: ...
    def move_object(self, id: str, pose: ArrayLike) -> None: ...
    def remove_object(self, id: str) -> None: ...
    def clear(self) -> None: ...
    world_object_ids: Final[list[str]]
    def has_world_object(self, id: str) -> bool: ...
    def attach_object(self, id: str, link: str, shapes: Sequence[PlacedShape], pose_in_link: ArrayLike = ...,
                      touch_links: Sequence[str] = ...) -> None: ...
    def attach_world_object(self, id: str, link: str, state: RobotState, touch_links: Sequence[str] = ...) -> None: ...
    def detach_object(self, id: str, state: RobotState) -> None: ...
    def remove_attached_object(self, id: str) -> None: ...
    attached_object_ids: Final[list[str]]
    def has_attached_object(self, id: str) -> bool: ...
    def set_allowed(self, a: str, b: str, allowed: bool = True) -> None: ...
    def set_default_allowed(self, name: str, allowed: bool = True) -> None: ...
    def is_allowed(self, a: str, b: str) -> bool: ...
    def set_padding(self, padding: float) -> None: ...
    def set_link_padding(self, link: str, padding: float) -> None: ...
    def link_padding(self, link: str) -> float: ...
    def set_scale(self, scale: float) -> None: ...
    def set_link_scale(self, link: str, scale: float) -> None: ...
    def link_scale(self, link: str) -> float: ...
    def is_colliding(self, state: RobotState, scope: CollisionScope = ...) -> bool: ...
    def check_collision(self, state: RobotState, scope: CollisionScope = ..., max_contacts_per_pair: int = 1,
                        max_pairs: int = 0) -> CollisionReport: ...
    def distance(self, state: RobotState, scope: CollisionScope = ...) -> DistanceReport: ...
    def set_to_random_valid_positions(self, state: RobotState, sampler: StateSampler, group: str | None = None,
                                      max_attempts: int = 1000) -> bool: ...

class PlanningStatus(_Enum):
    SUCCESS: ClassVar[PlanningStatus]
    INVALID_REQUEST: ClassVar[PlanningStatus]
    INVALID_START: ClassVar[PlanningStatus]
    INVALID_GOAL: ClassVar[PlanningStatus]
    GOAL_IN_COLLISION: ClassVar[PlanningStatus]
    NO_IK_SOLUTION: ClassVar[PlanningStatus]
    TIMEOUT: ClassVar[PlanningStatus]
    PLANNING_FAILED: ClassVar[PlanningStatus]

class PlanningOptions:
    def __init__(self, planner_id: str = "RRTConnect", allowed_planning_time: float = 5.0,
                 num_planning_attempts: int = 1, seed: int | None = None) -> None: ...
    planner_id: str
    planner_params: dict[str, str]
    allowed_planning_time: float
    num_planning_attempts: int
    parallel_attempts: bool
    longest_valid_segment_fraction: float
    longest_valid_segment_length: float
    simplify: bool
    simplify_coarse_factor: float
    max_joint_step: float
    precheck: bool
    seed: int | None

class PoseGoalOptions:
    def __init__(self, ik: IkOptions = ..., max_states: int = 8, max_calls: int = 32) -> None: ...
    ik: IkOptions
    max_states: int
    max_calls: int

class PlanningResult(_Result[PlanningStatus]):
    path: Final[_Array]
    planning_time: Final[float]
    path_length: Final[float]
    simplification_time: Final[float]
    simplification_fallback: Final[bool]
    validity_checks: Final[int]
    precheck_calls: Final[int]
    precheck_states: Final[int]
    solved_attempts: Final[int]
    planner_id: Final[str]

class CartesianStatus(_Enum):
    SUCCESS: ClassVar[CartesianStatus]
    INVALID_REQUEST: ClassVar[CartesianStatus]
    INVALID_START: ClassVar[CartesianStatus]
    IK_FAILED: ClassVar[CartesianStatus]
    IN_COLLISION: ClassVar[CartesianStatus]
    JUMP_DETECTED: ClassVar[CartesianStatus]

class JumpThreshold:
    def __init__(self, relative: float = 0.0, revolute: float = 0.0, prismatic: float = 0.0) -> None: ...
    relative: float
    revolute: float
    prismatic: float

class CartesianPathResult(_Result[CartesianStatus]):
    path: Final[_Array]
    fraction: Final[float]

def available_planner_ids() -> list[str]: ...

class PlanningContext:
    def __init__(self, scene: CollisionScene, group: str, ik: IkSolver | None = None) -> None: ...
    group: Final[str]
    joint_names: Final[list[str]]
    scene: Final[CollisionScene]
    ik: Final[IkSolver | None]
    @overload
    def plan_to_joints(self, start: RobotState, goal: ArrayLike, tolerance: float = 0.0,
                       options: PlanningOptions = ...) -> PlanningResult: ...
    @overload
    def plan_to_joints(self, start: RobotState, goal: ArrayLike, tolerance: ArrayLike,
                       options: PlanningOptions = ...) -> PlanningResult: ...
    def plan_to_named(self, start: RobotState, name: str, tolerance: float = 0.0,
                      options: PlanningOptions = ...) -> PlanningResult: ...
    def plan_to_pose(self, start: RobotState, pose: ArrayLike, pose_goal: PoseGoalOptions = ...,
                     options: PlanningOptions = ...) -> PlanningResult: ...
    def plan_to_position(self, start: RobotState, position: ArrayLike, pose_goal: PoseGoalOptions = ...,
                         options: PlanningOptions = ...) -> PlanningResult: ...
    def cartesian_path(self, start: RobotState, waypoints: Sequence[ArrayLike], eef_step: float,
                       jump_threshold: JumpThreshold = ..., avoid_collisions: bool = True,
                       ik_options: IkOptions = ...) -> CartesianPathResult: ...

class TrajectoryPoint:
    def __init__(self, positions: Sequence[float], velocities: Sequence[float] = ...,
                 accelerations: Sequence[float] = ..., time_from_start: float = 0.0) -> None: ...
    positions: list[float]
    velocities: list[float]
    accelerations: list[float]
    time_from_start: float

class TrajectorySample:
    position: Final[_Array]
    velocity: Final[_Array]
    acceleration: Final[_Array]

class Trajectory:
    def __init__(self, joint_names: Sequence[str], points: Sequence[TrajectoryPoint] = ...) -> None: ...
    joint_names: list[str]
    points: list[TrajectoryPoint]
    duration: Final[float]
    times: Final[_Array]
    positions: Final[_Array]
    velocities: Final[_Array]
    accelerations: Final[_Array]
    def validate(self) -> str: ...
    def sample(self, time: float) -> TrajectorySample: ...

class TimeParameterizationStatus(_Enum):
    SUCCESS: ClassVar[TimeParameterizationStatus]
    INVALID_INPUT: ClassVar[TimeParameterizationStatus]
    NOT_CONVERGED: ClassVar[TimeParameterizationStatus]

class TimeParameterizationOptions:
    def __init__(self, max_velocity: Sequence[float], max_acceleration: Sequence[float], velocity_scaling: float = 1.0,
                 acceleration_scaling: float = 1.0, max_deviation: float = 0.01, sample_period: float = 0.01,
                 path_resolution: float = 0.001) -> None: ...
    max_velocity: list[float]
    max_acceleration: list[float]
    velocity_scaling: float
    acceleration_scaling: float
    max_deviation: float
    sample_period: float
    path_resolution: float

class TimeParameterizationResult(_Result[TimeParameterizationStatus]):
    trajectory: Final[Trajectory]

def compute_time_optimal_trajectory(joint_names: Sequence[str], waypoints: ArrayLike,
                                    options: TimeParameterizationOptions) -> TimeParameterizationResult: ...
def compute_iterative_parabolic_trajectory(joint_names: Sequence[str], waypoints: ArrayLike,
                                           options: TimeParameterizationOptions) -> TimeParameterizationResult: ...

class DisableReason(_Enum):
    ADJACENT: ClassVar[DisableReason]
    DEFAULT: ClassVar[DisableReason]
    ALWAYS: ClassVar[DisableReason]
    NEVER: ClassVar[DisableReason]
    GRIPPER: ClassVar[DisableReason]

class CollisionMatrixOptions:
    def __init__(self, density: int = 10000, seed: int = 0, always_fraction: float = 0.95) -> None: ...
    density: int
    seed: int
    always_fraction: float

class ComputedPair:
    link1: Final[str]
    link2: Final[str]
    reason: Final[DisableReason]
    reason_name: Final[str]
    colliding_samples: Final[int]

class DisabledCollisions:
    disabled: Final[list[ComputedPair]]
    link_pairs: Final[int]
    samples: Final[int]
    pair_checks: Final[int]

def compute_disabled_collisions(model: RobotModel, options: CollisionMatrixOptions = ...,
                                progress: Callable[[int, int], None] | None = None) -> DisabledCollisions: ...
def adjacent_link_pairs(model: RobotModel) -> list[tuple[str, str]]: ...
