#!/usr/bin/env python3
"""scene_mirror: keeps move_group's planning scene equal to the simulator's objects.
An object a client removed from the scene stays out until it leaves the simulator (SceneMirror).

Subscribes sixdof_sim/object_states, reads shapes once per object through sixdof_sim/get_object_state,
and applies the SceneMirror's changes through apply_planning_scene (reading get_planning_scene each cycle).
Private parameters:
  ~rate                cycles per wall-clock second (10); wall clock because the simulator may run
                       free (much faster than real time) or be paused
  ~position_threshold  MOVE an object when it moved more than this (m, 0.001)
  ~angle_threshold     ... or turned more than this (rad, 0.01)
  ~grace               seconds to leave a grasp-fix attach/detach to the script that caused it (0.5)
  ~support_clearance   static objects (the table the robot stands on) are mirrored this much lower (m, 0.002)
  ~world               the simulator's world parameter (sixdof_sim/world, waited for up to 60 s): its objects
                       declared `collision: false` are not mirrored ('': none)
  ~ignore              object names never mirrored ([])
  ~wait_for_move_group s (wall clock) to wait for move_group's services and the simulator's get_object_state
                       (60; 0: forever); the robot model comes from move_group's get_robot_model
"""

import sys
import time

import rospy
from sixdof_commander.mesh import load_stl
from sixdof_commander.planning_scene import resolve_resource
from sixdof_commander.scene_mirror import SceneMirror, SceneSnapshot, SimObjectState, template_from_sim_object
from sixdof_commander.scene_node import MOVE_GROUP_WAIT, MoveGroupScene, number_param, run
from sixdof_commander.sim_world import WORLD_PARAMETER, wait_for_world

from sixdof_msgs.msg import ObjectStates
from sixdof_msgs.srv import GetObjectState


class SceneMirrorNode:
    def __init__(self) -> None:
        self.rate = number_param("~rate", 10.0, inclusive=False)
        ignore = rospy.get_param("~ignore", [])
        if not isinstance(ignore, list):
            raise ValueError(f"parameter {rospy.resolve_name('~ignore')} must be a list of names")
        self.skip = {str(n) for n in ignore}
        world = rospy.get_param("~world", WORLD_PARAMETER)
        if world:
            self.skip |= wait_for_world(world).non_colliding()
        position_threshold = number_param("~position_threshold", 0.001)
        angle_threshold = number_param("~angle_threshold", 0.01)
        grace = number_param("~grace", 0.5)
        support_clearance = number_param("~support_clearance", 0.002)
        self.move_group = MoveGroupScene(
            "scene_mirror", number_param("~wait_for_move_group", MOVE_GROUP_WAIT), ["sixdof_sim/get_object_state"]
        )
        robot = self.move_group.robot
        self.mirror = SceneMirror(
            shapes={},
            planning_frame=robot.planning_frame,
            touch_links=robot.touch_links,
            position_threshold=position_threshold,
            angle_threshold=angle_threshold,
            grace=grace,
            support_clearance=support_clearance,
        )
        self.get_object = rospy.ServiceProxy("sixdof_sim/get_object_state", GetObjectState)
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
        scene = self.move_group.scene()
        snapshot = SceneSnapshot(
            world={obj.id: obj.pose for obj in scene.world.collision_objects},
            attached={a.object.id: a.link_name for a in scene.robot_state.attached_collision_objects},
        )
        states = [
            SimObjectState(name=n, pose=p, attached_to=a)
            for n, p, a in zip(msg.name, msg.pose, msg.attached_to, strict=True)
        ]
        self.move_group.apply(self.mirror.update(states, snapshot, time.monotonic()))


if __name__ == "__main__":
    sys.exit(run("scene_mirror", SceneMirrorNode))
