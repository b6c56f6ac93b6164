#!/usr/bin/env python3
"""object_markers: publishes the simulator's objects as rviz markers on sixdof_sim/object_markers.

Shapes and colours come once per object from sixdof_sim/get_object_state, poses from
sixdof_sim/object_states; markers are republished at most ~rate times per wall-clock second (10).
"""

import sys
import time

import rospy
from sixdof_commander.markers import object_markers
from visualization_msgs.msg import Marker, MarkerArray

from sixdof_msgs.msg import ObjectStates
from sixdof_msgs.srv import GetObjectState


class ObjectMarkersNode:
    def __init__(self) -> None:
        rate = rospy.get_param("~rate", 10.0)
        if isinstance(rate, bool) or not isinstance(rate, int | float) or not rate > 0.0:
            raise ValueError(f"parameter {rospy.resolve_name('~rate')} must be a number > 0, got {rate!r}")
        self.period = 1.0 / float(rate)
        rospy.wait_for_service("sixdof_sim/get_object_state")
        self.get_object = rospy.ServiceProxy("sixdof_sim/get_object_state", GetObjectState)
        self.descriptions = {}
        self.known_names: set[str] = set()
        self.last_wall = 0.0
        self.publisher = rospy.Publisher("sixdof_sim/object_markers", MarkerArray, queue_size=1, latch=True)
        rospy.Subscriber("sixdof_sim/object_states", ObjectStates, self._on_states, queue_size=1)

    def _on_states(self, msg: ObjectStates) -> None:
        now = time.monotonic()
        if now - self.last_wall < self.period:
            return
        self.last_wall = now
        for name in msg.name:
            if name not in self.descriptions:
                response = self.get_object(name)
                if response.success:
                    self.descriptions[name] = response.object
        array = MarkerArray()
        gone = self.known_names - set(msg.name)
        if gone:
            # Deleted objects: clear everything, then draw what exists now.
            array.markers.append(Marker(action=Marker.DELETEALL, ns="sixdof_sim_objects"))
            for name in gone:
                self.descriptions.pop(name, None)
        self.known_names = set(msg.name)
        array.markers.extend(object_markers(self.descriptions, msg.name, msg.pose, msg.header.frame_id).markers)
        self.publisher.publish(array)


def main() -> int:
    rospy.init_node("object_markers")
    try:
        ObjectMarkersNode()
    except ValueError as err:
        rospy.logfatal("object_markers: %s", err)
        return 1
    except rospy.ROSInterruptException:
        return 0
    rospy.spin()
    return 0


if __name__ == "__main__":
    sys.exit(main())
