"""How far a gripper reaches beyond its tool centre point along the tool axis, from the collision geometry of
move_group's robot model (get_robot_model with collision geometry): a top-down grasp must keep the fingertips
above the surface the object stands on."""

from __future__ import annotations

import numpy as np

from .robot_model import RobotDescription


def gripper_reach(description: RobotDescription, tip_link: str, tcp_in_tip: np.ndarray) -> float:
    """How far the links below tip_link (fingers at zero) reach beyond the tcp along the tool z axis (m, >= 0).

    `description` must carry the collision geometry (query_robot_model(..., collision_geometry=True)); the bound
    is the convex hull of each link's shapes (RobotDescription.collision_points)."""
    tip_in_tcp = np.linalg.inv(tcp_in_tip)
    reach = 0.0
    for link in description.descendant_links(tip_link):
        points = description.collision_points(link)
        if not len(points):
            continue
        link_in_tcp = tip_in_tcp @ description.chain_transform(tip_link, link)
        z = points @ link_in_tcp[2, :3] + link_in_tcp[2, 3]
        reach = max(reach, float(z.max()))
    return reach
