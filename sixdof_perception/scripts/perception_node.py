#!/usr/bin/env python3
"""perception_node: objects on the table from the camera's organized depth cloud, published as
detected_objects (sixdof_msgs/DetectedObjectArray, with each track's velocity) and rviz markers, and kept in
move_group's planning scene.

It never reads the simulator's object states: what it knows besides the cloud comes from the world the
simulator loaded, its ~world parameter (the tables' top faces are the supports, the static scenery and the bins'
walls go into the planning scene and are masked out of the cloud) and from tf (the robot's links are filtered out
of the cloud).
The planning scene follows what the camera sees through sixdof_commander's SceneMirror: objects are added,
moved and removed (a track missed ~forget_after frames in a row), ids stay stable across frames. An object
the planning scene has attached to the robot is left alone (it stays attached until its user detaches it)
and an object hidden by the robot keeps its last pose.

Private parameters:
  ~world               name of the simulator's world parameter (sixdof_sim/world): supports, scenery, cameras;
                       waited for up to 60 s (wall clock)
  ~camera              camera name ('': the world's first camera); subscribes <camera>/depth/points
  ~rate                frames processed per wall-clock second at most (5)
  ~hand_padding        m added around the box of each end effector's links (a held object is inside) (0.02)
  ~forget_after        frames a track may be missed before it is removed (5)
  ~gate                m: the largest distance from a track's predicted position that keeps an object's id (0.04)
  ~velocity_window     s of a track's detections its velocity is fitted to (1.0; detected_objects' velocity)
  ~max_speed           m/s an object whose track has no velocity yet may move between frames (0.5 in a world
                       with conveyors, else 0)
  ~update_scene        keep move_group's planning scene equal to what is seen (true)
  ~position_threshold  m: MOVE a scene object when its detection moved more than this (0.003)
  ~angle_threshold     rad: ... or turned more than this (0.05)
  ~wait_for_move_group s (wall clock) to wait for move_group's services (60; 0: forever); the robot model (planning
                       frame, end effectors, the links' collision shapes) comes from move_group's get_robot_model
"""

import sys
import threading
import time

import numpy as np
import rospy
import tf2_ros
from sensor_msgs.msg import PointCloud2
from sixdof_commander.markers import object_marker
from sixdof_commander.scene_mirror import SceneMirror, SceneSnapshot, SimObjectState, template_from_sim_object
from sixdof_commander.scene_node import MOVE_GROUP_WAIT, MoveGroupScene, number_param, run
from sixdof_commander.sim_world import WORLD_PARAMETER, wait_for_world
from std_msgs.msg import Header
from visualization_msgs.msg import Marker, MarkerArray

from sixdof_msgs.msg import DetectedObjectArray
from sixdof_perception import world as scenery
from sixdof_perception.detection import Box, Detection, DetectorParams, detect_objects
from sixdof_perception.ros_conversions import (
    cloud_arrays,
    detected_object,
    sim_object,
    static_sim_object,
    transform_matrix,
    transform_points,
)
from sixdof_perception.self_filter import hand_box, link_boxes, posed_boxes
from sixdof_perception.tracking import Tracker


class PerceptionNode:
    def __init__(self) -> None:
        world = wait_for_world(rospy.get_param("~world", WORLD_PARAMETER))
        self.supports = scenery.supports(world)
        if not self.supports:
            raise ValueError(f"the simulator's world '{world.name}' has no tables: nothing to detect objects on")
        self.scenery = scenery.static_boxes(world)
        # Points on the scenery other than the tables (bin walls, fixtures) are masked out of the cloud.
        self.masks = [box.as_mask() for box in self.scenery if not box.table]
        camera = rospy.get_param("~camera", "")
        if not camera:
            if not world.cameras:
                raise ValueError(f"the simulator's world '{world.name}' has no cameras and ~camera is not set")
            camera = world.cameras[0]
        self.rate = number_param("~rate", 5.0, inclusive=False)
        forget_after = rospy.get_param("~forget_after", 5)
        self.tracker = Tracker(
            gate=number_param("~gate", 0.04, inclusive=False),
            forget_after=forget_after,
            velocity_window=number_param("~velocity_window", 1.0, inclusive=False),
            max_speed=number_param("~max_speed", 0.5 if world.conveyors else 0.0),
        )
        self.update_scene = bool(rospy.get_param("~update_scene", True))
        self.params = DetectorParams()
        # Checked before waiting for move_group: a bad value fails at once.
        hand_padding = number_param("~hand_padding", 0.02, inclusive=False)
        position_threshold = number_param("~position_threshold", 0.003, inclusive=False)
        angle_threshold = number_param("~angle_threshold", 0.05, inclusive=False)
        self.move_group = MoveGroupScene(
            "perception", number_param("~wait_for_move_group", MOVE_GROUP_WAIT), collision_geometry=True
        )
        robot = self.move_group.robot
        self.planning_frame = robot.planning_frame
        # Self filter: every link's collision-geometry box, and one box around each hand (a held object is inside
        # it), both from move_group's model.
        self.link_boxes = link_boxes(robot.urdf.collision.values())
        self.hands = [(eef.parent_link, robot.touch_links(eef.parent_link)) for eef in robot.srdf.end_effectors]
        self.hand_padding = hand_padding
        self.mirror = SceneMirror(
            shapes={},
            planning_frame=self.planning_frame,
            touch_links=lambda _link: [],
            position_threshold=position_threshold,
            angle_threshold=angle_threshold,
            grace=0.0,
        )
        self.static_states = []
        for box in self.scenery:
            description = static_sim_object(box)
            self.mirror.shapes[box.name] = template_from_sim_object(description, lambda *_: None)
            self.mirror.static.add(box.name)
            self.static_states.append(SimObjectState(box.name, description.pose, ""))
        self.was_attached: set[str] = set()
        self.tf_buffer = tf2_ros.Buffer(cache_time=rospy.Duration(30.0))
        self.tf_listener = tf2_ros.TransformListener(self.tf_buffer)
        self.detected_pub = rospy.Publisher("detected_objects", DetectedObjectArray, queue_size=1, latch=True)
        self.marker_pub = rospy.Publisher("detected_objects/markers", MarkerArray, queue_size=1, latch=True)
        self.lock = threading.Lock()
        self.latest: PointCloud2 | None = None
        topic = f"{camera}/depth/points"
        rospy.loginfo("perception: camera '%s', planning frame '%s'", camera, self.planning_frame)
        rospy.Subscriber(topic, PointCloud2, self._on_cloud, queue_size=1, buff_size=2**24)

    def _on_cloud(self, msg: PointCloud2) -> None:
        with self.lock:
            self.latest = msg

    def _lookup(self, target: str, source: str, stamp: rospy.Time) -> np.ndarray:
        try:
            transform = self.tf_buffer.lookup_transform(target, source, stamp, rospy.Duration(0.2))
        except (tf2_ros.ExtrapolationException, tf2_ros.LookupException, tf2_ros.ConnectivityException):
            transform = self.tf_buffer.lookup_transform(target, source, rospy.Time(0), rospy.Duration(0.2))
        return transform_matrix(transform)

    def _self_filter(self, stamp: rospy.Time) -> list[Box]:
        poses = {link: self._lookup(self.planning_frame, link, stamp) for link in self.link_boxes}
        shapes = posed_boxes(self.link_boxes, poses)
        for parent, links in self.hands:
            for link in links:
                if link not in poses:
                    poses[link] = self._lookup(self.planning_frame, link, stamp)
            box = hand_box(self.link_boxes, poses, parent, links)
            if box is not None:
                shapes.append(Box(box.centre, box.rotation, box.half + self.hand_padding))
        return shapes

    def cycle(self) -> None:
        with self.lock:
            cloud, self.latest = self.latest, None
        if cloud is None:
            return
        points, colors = cloud_arrays(cloud)
        to_planning = self._lookup(self.planning_frame, cloud.header.frame_id, cloud.header.stamp)
        points = transform_points(points, to_planning)
        robot = self._self_filter(cloud.header.stamp)
        detections = detect_objects(points, colors, self.supports, self.masks, robot, self.params)

        attached: dict[str, str] = {}
        world_poses = {}
        if self.update_scene:
            scene = self.move_group.scene()
            attached = {a.object.id: a.link_name for a in scene.robot_state.attached_collision_objects}
            world_poses = {o.id: o.pose for o in scene.world.collision_objects}
        held: dict[str, tuple[float, float, float] | None] = {}
        for track_id in self.tracker.tracks:
            if track_id in attached:
                held[track_id] = None
                self.was_attached.add(track_id)
            elif track_id in self.was_attached and track_id in world_poses:
                p = world_poses[track_id].position
                held[track_id] = (p.x, p.y, p.z)
                self.was_attached.discard(track_id)

        def hidden(position: tuple[float, float, float]) -> bool:
            p = np.asarray(position)[None, :]
            return any(bool(shape.contains(p, self.params.self_padding + 0.01)[0]) for shape in robot)

        def touching(det: Detection) -> bool:
            p = np.asarray(det.position)[None, :]
            margin = self.params.self_padding + max(det.size) / 2.0 + 0.01
            return any(bool(shape.contains(p, margin)[0]) for shape in robot)

        identified = self.tracker.update(detections, held, hidden, touching, cloud.header.stamp.to_sec())
        header = Header(stamp=cloud.header.stamp, frame_id=self.planning_frame)
        array = DetectedObjectArray(header=header)
        markers = MarkerArray(markers=[Marker(action=Marker.DELETEALL, ns="detected_objects")])
        for i, (object_id, det) in enumerate(identified):
            velocity = self.tracker.tracks[object_id].velocity
            array.objects.append(detected_object(object_id, det, header, velocity))
            description = sim_object(object_id, det)
            marker = object_marker(description, description.pose, self.planning_frame, 2 * i)
            marker.ns = "detected_objects"
            marker.header.stamp = cloud.header.stamp
            text = Marker(
                header=marker.header,
                ns="detected_objects",
                id=2 * i + 1,
                type=Marker.TEXT_VIEW_FACING,
                action=Marker.ADD,
                text=object_id,
            )
            text.pose.position.x, text.pose.position.y = det.position[0], det.position[1]
            text.pose.position.z = det.position[2] + det.size[2] / 2.0 + 0.03
            text.pose.orientation.w = 1.0
            text.scale.z = 0.025
            text.color.r = text.color.g = text.color.b = text.color.a = 1.0
            markers.markers += [marker, text]
        self.detected_pub.publish(array)
        self.marker_pub.publish(markers)
        if self.update_scene:
            self._sync_scene(attached, world_poses, scene)

    def _sync_scene(self, attached: dict, world_poses: dict, scene) -> None:
        states = list(self.static_states)
        for track in self.tracker.tracks.values():
            description = sim_object(track.id, track.detection)
            if track.id in attached:
                # Held by the robot: the mirror sees it as held where the scene holds it and leaves it alone.
                states.append(SimObjectState(track.id, description.pose, attached[track.id]))
                continue
            self.mirror.shapes[track.id] = template_from_sim_object(description, lambda *_: None)
            states.append(SimObjectState(track.id, description.pose, ""))
        snapshot = SceneSnapshot(world=world_poses, attached=attached)
        updates = self.mirror.update(states, snapshot, time.monotonic())
        # An object attached in the scene that the tracker forgot is still held: never detach it here.
        updates.attached_objects = [a for a in updates.attached_objects if a.object.id not in attached]
        self.move_group.apply(updates)


if __name__ == "__main__":
    sys.exit(run("perception", PerceptionNode, (tf2_ros.TransformException, ValueError)))
