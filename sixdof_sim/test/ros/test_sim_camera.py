#!/usr/bin/env python3
"""rostest: a world-file camera's topics, camera_info, images, organized cloud, tf frames and stamps."""

import math
import struct
import unittest

import numpy as np
import rospy
import rostest
import tf2_ros
from sensor_msgs import point_cloud2
from sensor_msgs.msg import CameraInfo, Image, PointCloud2

TIMEOUT = 60.0
WIDTH, HEIGHT, RATE = 160, 120, 10.0
FX = WIDTH / (2.0 * math.tan(math.radians(60.0) / 2.0))
FACE_DEPTH = 0.45  # the red box's front face (camera_world.yaml)
RED = (round(0.9 * 255), round(0.1 * 255), round(0.1 * 255))  # seen head-on: the object's own colour


def wait(topic: str, msg_type: type) -> object:
    return rospy.wait_for_message(topic, msg_type, timeout=TIMEOUT)


class SimCameraTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls) -> None:
        rospy.init_node("test_sim_camera")

    def check_stamp(self, msg: object) -> None:
        """Frames show the simulated time k / rate (frame k)."""
        t = msg.header.stamp.to_sec()
        self.assertGreater(t, 0.0)
        self.assertAlmostEqual(t * RATE, round(t * RATE), delta=1e-6)
        self.assertEqual(msg.header.frame_id, "cam_optical_frame")

    def test_camera_info(self) -> None:
        for topic in ("cam/color/camera_info", "cam/depth/camera_info"):
            info = wait(topic, CameraInfo)
            self.check_stamp(info)
            self.assertEqual((info.width, info.height), (WIDTH, HEIGHT))
            np.testing.assert_allclose(info.K, [FX, 0, 79.5, 0, FX, 59.5, 0, 0, 1], rtol=1e-9)
            np.testing.assert_allclose(info.P, [FX, 0, 79.5, 0, 0, FX, 59.5, 0, 0, 0, 1, 0], rtol=1e-9)

    def test_images(self) -> None:
        color = wait("cam/color/image_raw", Image)
        self.check_stamp(color)
        self.assertEqual((color.encoding, color.width, color.height, color.step), ("rgb8", WIDTH, HEIGHT, 3 * WIDTH))
        rgb = np.frombuffer(color.data, dtype=np.uint8).reshape(HEIGHT, WIDTH, 3)
        np.testing.assert_allclose(rgb[60, 80], RED, atol=1)
        self.assertEqual(rgb[0, 0].tolist(), [0, 0, 0])
        depth_msg = wait("cam/depth/image_raw", Image)
        self.check_stamp(depth_msg)
        self.assertEqual((depth_msg.encoding, depth_msg.step), ("32FC1", 4 * WIDTH))
        depth = np.frombuffer(depth_msg.data, dtype="<f4").reshape(HEIGHT, WIDTH)
        self.assertAlmostEqual(float(depth[60, 80]), FACE_DEPTH, delta=1e-3)
        self.assertTrue(math.isnan(depth[0, 0]))

    def test_cloud(self) -> None:
        cloud = wait("cam/depth/points", PointCloud2)
        self.check_stamp(cloud)
        self.assertEqual((cloud.width, cloud.height, cloud.is_dense), (WIDTH, HEIGHT, False))
        self.assertEqual([f.name for f in cloud.fields], ["x", "y", "z", "rgb"])
        points = list(point_cloud2.read_points(cloud, field_names=("x", "y", "z", "rgb"), uvs=[(80, 60), (0, 0)]))
        x, y, z, packed = points[0]
        # Pixel (80, 60) is half a pixel right of and below the optical axis.
        self.assertAlmostEqual(z, FACE_DEPTH, delta=1e-3)
        self.assertAlmostEqual(x, 0.5 / FX * z, delta=1e-4)
        self.assertAlmostEqual(y, 0.5 / FX * z, delta=1e-4)
        # PCL's packing: 0x00RRGGBB in a float's bits.
        value = struct.unpack("<I", struct.pack("<f", packed))[0]
        np.testing.assert_allclose(((value >> 16) & 0xFF, (value >> 8) & 0xFF, value & 0xFF), RED, atol=1)
        self.assertTrue(all(math.isnan(v) for v in points[1][:3]))

    def test_frames(self) -> None:
        buffer = tf2_ros.Buffer()
        tf2_ros.TransformListener(buffer)
        link = buffer.lookup_transform("world", "cam_link", rospy.Time(0), rospy.Duration(TIMEOUT)).transform
        self.assertEqual((link.translation.x, link.translation.y, link.translation.z), (0.5, 0.0, 0.1))
        optical = buffer.lookup_transform("cam_link", "cam_optical_frame", rospy.Time(0), rospy.Duration(TIMEOUT))
        q = optical.transform.rotation
        # rpy(-pi/2, 0, -pi/2) as a quaternion (x, y, z, w) = (-0.5, 0.5, -0.5, 0.5), up to sign.
        self.assertAlmostEqual(abs(q.x * -0.5 + q.y * 0.5 + q.z * -0.5 + q.w * 0.5), 1.0, delta=1e-9)


if __name__ == "__main__":
    rostest.rosrun("sixdof_sim", "test_sim_camera", SimCameraTest)
