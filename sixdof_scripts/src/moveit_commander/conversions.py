"""moveit_commander.conversions: lists <-> geometry_msgs, as MoveIt's (quaternions (x, y, z, w); 6-lists are
x, y, z, roll, pitch, yaw about fixed axes)."""

from __future__ import annotations

from collections.abc import Sequence
from io import BytesIO

from geometry_msgs.msg import Pose, PoseStamped, Transform
from sixdof_commander.exceptions import SixdofCommanderError
from sixdof_commander.goals import check_number
from sixdof_commander.transforms import quaternion_from_rpy


def msg_to_string(msg: object) -> bytes:
    """The message serialized (rospy's wire format)."""
    buffer = BytesIO()
    msg.serialize(buffer)
    return buffer.getvalue()


def msg_from_string(msg: object, data: bytes) -> None:
    """Fill msg from its serialized form."""
    msg.deserialize(data)


def _numbers(values: Sequence[float], lengths: tuple[int, ...], what: str) -> list[float]:
    if isinstance(values, str) or not hasattr(values, "__len__") or len(values) not in lengths:
        expected = " or ".join(str(n) for n in lengths)
        raise SixdofCommanderError(
            f"{what}: expected a list of {expected} elements (x, y, z, roll, pitch, yaw) or "
            f"(x, y, z, qx, qy, qz, qw), got {values!r}"
        )
    return [check_number(v, f"{what} element {i}") for i, v in enumerate(values)]


def _quaternion(values: list[float]) -> tuple[float, float, float, float]:
    return quaternion_from_rpy(*values[3:]) if len(values) == 6 else tuple(values[3:])


# Pose (position, orientation) and Transform (translation, rotation) hold the same two parts under other names: the
# converters read and write a message's two fields in their order.
def pose_to_list(pose_msg: Pose | Transform) -> list[float]:
    """[x, y, z, qx, qy, qz, qw] of a Pose (or of a Transform: transform_to_list is this function)."""
    vector, quaternion = (getattr(pose_msg, field) for field in pose_msg.__slots__)
    return [vector.x, vector.y, vector.z, quaternion.x, quaternion.y, quaternion.z, quaternion.w]


transform_to_list = pose_to_list


def _from_list(values: Sequence[float], message_type: type, what: str) -> Pose | Transform:
    numbers = _numbers(values, (6, 7), what)
    message = message_type()
    vector, quaternion = (getattr(message, field) for field in message.__slots__)
    vector.x, vector.y, vector.z = numbers[:3]
    quaternion.x, quaternion.y, quaternion.z, quaternion.w = _quaternion(numbers)
    return message


def list_to_pose(pose_list: Sequence[float]) -> Pose:
    """Pose from [x, y, z, roll, pitch, yaw] or [x, y, z, qx, qy, qz, qw]."""
    return _from_list(pose_list, Pose, "list_to_pose")


def list_to_pose_stamped(pose_list: Sequence[float], target_frame: str) -> PoseStamped:
    """PoseStamped in target_frame from a 6- or 7-list."""
    stamped = PoseStamped()
    stamped.header.frame_id = target_frame
    stamped.pose = list_to_pose(pose_list)
    return stamped


def list_to_transform(trf_list: Sequence[float]) -> Transform:
    """Transform from [x, y, z, roll, pitch, yaw] or [x, y, z, qx, qy, qz, qw]."""
    return _from_list(trf_list, Transform, "list_to_transform")
