#!/usr/bin/env python3
"""scene_mirror: keeps move_group's planning scene equal to the simulator's objects.

Subscribes sixdof_sim/object_states, reads shapes once per object through sixdof_sim/get_object_state,
and applies the SceneMirror's changes through apply_planning_scene (reading get_planning_scene each cycle).
Private parameters:
  ~rate                cycles per wall-clock second (10); wall clock because the simulator may run
                       free (much faster than real time) or be paused
  ~position_threshold  MOVE an object when it moved more than this (m, 0.001)
  ~angle_threshold     ... or turned more than this (rad, 0.01)
  ~grace               seconds to leave a grasp-fix attach/detach to the script that caused it (0.5)
  ~support_clearance   static objects (the table the robot stands on) are mirrored this much lower (m, 0.002)
  ~world_file          world YAML; its objects with `collision: false` are not mirrored ('' : none)
  ~ignore              object names never mirrored ([])
"""

import math
import sys
import time
from xml.etree import ElementTree

import rospy
import yaml
from sixdof_commander import SixdofCommanderError
from sixdof_commander.mesh import load_stl
from sixdof_commander.planning_scene import default_touch_links, resolve_resource
from sixdof_commander.robot_model import parse_srdf, parse_urdf

from sixdof_bringup.mirror import (
    SceneMirror,
    SceneSnapshot,
    SimObjectState,
    non_colliding_objects,
    template_from_sim_object,
)
from sixdof_msgs.msg import ObjectStates, PlanningScene
from sixdof_msgs.srv import ApplyPlanningScene, GetObjectState, GetPlanningScene


def positive_param(name: str, default: float) -> float:
    value = rospy.get_param(name, default)
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value) or value < 0:
        raise ValueError(f"parameter {rospy.resolve_name(name)} must be a number >= 0, got {value!r}")
    return float(value)


class SceneMirrorNode:
    def __init__(self) -> None:
        self.rate = positive_param("~rate", 10.0)
        if self.rate <= 0.0:
            raise ValueError(f"parameter {rospy.resolve_name('~rate')} must be > 0")
        ignore = rospy.get_param("~ignore", [])
        if not isinstance(ignore, list):
            raise ValueError(f"parameter {rospy.resolve_name('~ignore')} must be a list of names")
        self.skip = {str(n) for n in ignore}
        world_file = rospy.get_param("~world_file", "")
        if world_file:
            with open(world_file, encoding="utf-8") as stream:
                self.skip |= non_colliding_objects(yaml.safe_load(stream))
        urdf_text = rospy.get_param("robot_description")
        urdf = parse_urdf(urdf_text)
        # Links without collision geometry can touch nothing, and the planner's collision scene does not know
        # them: touch links are the links that have geometry.
        colliding = {
            link.get("name")
            for link in ElementTree.fromstring(urdf_text).iter("link")
            if link.find("collision") is not None
        }
        srdf = parse_srdf(rospy.get_param("robot_description_semantic"))
        planning_frame = srdf.virtual_joint_parent or urdf.root_link
        self.mirror = SceneMirror(
            shapes={},
            planning_frame=planning_frame,
            touch_links=lambda link: [t for t in default_touch_links(urdf, srdf, link) if t in colliding],
            position_threshold=positive_param("~position_threshold", 0.001),
            angle_threshold=positive_param("~angle_threshold", 0.01),
            grace=positive_param("~grace", 0.5),
            support_clearance=positive_param("~support_clearance", 0.002),
        )
        for service in ("sixdof_sim/get_object_state", "get_planning_scene", "apply_planning_scene"):
            rospy.loginfo("scene_mirror: waiting for %s", rospy.resolve_name(service))
            rospy.wait_for_service(service)
        self.get_object = rospy.ServiceProxy("sixdof_sim/get_object_state", GetObjectState)
        self.get_scene = rospy.ServiceProxy("get_planning_scene", GetPlanningScene)
        self.apply = rospy.ServiceProxy("apply_planning_scene", ApplyPlanningScene)
        self.latest = None
        rospy.Subscriber("sixdof_sim/object_states", ObjectStates, self._on_states, queue_size=1)

    def _on_states(self, msg: ObjectStates) -> None:
        self.latest = msg

    def _learn_shapes(self, names: list[str]) -> None:
        for name in names:
            if name in self.mirror.shapes or name in self.skip:
                continue
            response = self.get_object(name)
            if not response.success:
                rospy.logwarn("scene_mirror: get_object_state('%s'): %s", name, response.status_message)
                continue
            self.mirror.shapes[name] = template_from_sim_object(
                response.object, lambda uri, scale: load_stl(resolve_resource(uri), scale)
            )
            if response.object.is_static:
                self.mirror.static.add(name)
            rospy.loginfo("scene_mirror: mirroring '%s'", name)

    def cycle(self) -> None:
        msg = self.latest
        if msg is None:
            return
        self._learn_shapes(list(msg.name))
        scene = self.get_scene().scene
        snapshot = SceneSnapshot(
            world={obj.id: obj.pose for obj in scene.world.collision_objects},
            attached={a.object.id: a.link_name for a in scene.robot_state.attached_collision_objects},
        )
        states = [
            SimObjectState(name=n, pose=p, attached_to=a)
            for n, p, a in zip(msg.name, msg.pose, msg.attached_to, strict=True)
        ]
        updates = self.mirror.update(states, snapshot, time.monotonic())
        if updates.empty():
            return
        diff = PlanningScene(is_diff=True)
        diff.robot_state.is_diff = True
        diff.world.collision_objects = updates.world_objects
        diff.robot_state.attached_collision_objects = updates.attached_objects
        response = self.apply(diff)
        if not response.success:
            # The next cycle re-reads the scene and retries what is still different.
            rospy.logwarn("scene_mirror: apply_planning_scene failed: %s", response.error_code.message)

    def spin(self) -> None:
        period = 1.0 / self.rate
        while not rospy.is_shutdown():
            try:
                self.cycle()
            except (rospy.ServiceException, rospy.ROSException) as err:
                if rospy.is_shutdown():
                    break
                rospy.logwarn("scene_mirror: %s", err)
            time.sleep(period)


def main() -> int:
    rospy.init_node("scene_mirror")
    try:
        node = SceneMirrorNode()
    except (ValueError, KeyError, OSError, yaml.YAMLError, SixdofCommanderError) as err:
        rospy.logfatal("scene_mirror: %s", err)
        return 1
    except rospy.ROSInterruptException:
        return 0
    node.spin()
    return 0


if __name__ == "__main__":
    sys.exit(main())
