#!/usr/bin/env python3
"""Save the camera's colour image with the perception node's detections drawn on it (a box around each
object's projected extent and its id), as a PNG (numpy writes the pixels, imagemagick's convert draws).

    rosrun sixdof_perception draw_detections.py out.png [--camera table_cam] [--timeout 60]

Waits for a detected_objects frame and a colour image taken at or after it. Exit 0 when the PNG is written.
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
import rospy
import tf2_ros
from sensor_msgs.msg import CameraInfo, Image
from sixdof_commander.transforms import matrix_from_pose

from sixdof_msgs.msg import DetectedObjectArray
from sixdof_perception.ros_conversions import transform_matrix

COLORS = {"red": "#ff4040", "green": "#40ff40", "blue": "#4080ff", "yellow": "#ffff40"}


def corners(obj) -> np.ndarray:
    """The 8 corners (planning frame) of the detection's box-shaped extent."""
    pose = matrix_from_pose(obj.pose.pose)
    half = np.array([obj.size.x, obj.size.y, obj.size.z]) / 2.0
    signs = np.array([(sx, sy, sz) for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
    return (signs * half) @ pose[:3, :3].T + pose[:3, 3]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("output", help="PNG file to write")
    parser.add_argument("--camera", default="table_cam", help="camera name (default: table_cam)")
    parser.add_argument("--timeout", type=float, default=60.0, help="wall-clock seconds to wait for the frames")
    args = parser.parse_args(rospy.myargv(sys.argv)[1:])
    rospy.init_node("draw_detections", anonymous=True)
    buffer = tf2_ros.Buffer()
    tf2_ros.TransformListener(buffer)
    try:
        detected = rospy.wait_for_message("detected_objects", DetectedObjectArray, timeout=args.timeout)
        info = rospy.wait_for_message(f"{args.camera}/color/camera_info", CameraInfo, timeout=args.timeout)
        deadline = time.monotonic() + args.timeout
        while True:
            image = rospy.wait_for_message(f"{args.camera}/color/image_raw", Image, timeout=args.timeout)
            if image.header.stamp >= detected.header.stamp or time.monotonic() > deadline:
                break
        transform = buffer.lookup_transform(
            info.header.frame_id, detected.header.frame_id, rospy.Time(0), rospy.Duration(args.timeout)
        )
    except (rospy.ROSException, tf2_ros.TransformException) as err:
        print(f"error: {err}", file=sys.stderr)
        return 1
    if image.encoding != "rgb8":
        print(f"error: expected an rgb8 image, got {image.encoding}", file=sys.stderr)
        return 1
    to_camera = transform_matrix(transform)
    k = np.array(info.K).reshape(3, 3)
    pixels = np.frombuffer(image.data, dtype=np.uint8).reshape(image.height, image.step)[:, : 3 * image.width]
    draws = []
    for obj in detected.objects:
        pts = corners(obj) @ to_camera[:3, :3].T + to_camera[:3, 3]
        if (pts[:, 2] <= 0).any():
            continue
        uv = (pts @ k.T)[:, :2] / pts[:, 2:3]
        (u0, v0), (u1, v1) = uv.min(axis=0), uv.max(axis=0)
        color = COLORS.get(obj.color, "#ffffff")
        draws += [
            "-stroke",
            color,
            "-fill",
            "none",
            "-draw",
            f"rectangle {u0:.0f},{v0:.0f} {u1:.0f},{v1:.0f}",
            "-stroke",
            "none",
            "-fill",
            color,
            "-draw",
            f"text {u0:.0f},{max(v0 - 4, 10):.0f} '{obj.id}'",
        ]
    with tempfile.TemporaryDirectory() as tmp:
        ppm = os.path.join(tmp, "image.ppm")
        with open(ppm, "wb") as out:
            out.write(f"P6 {image.width} {image.height} 255\n".encode())
            out.write(np.ascontiguousarray(pixels).tobytes())
        result = subprocess.run(
            ["convert", ppm, "-font", "DejaVu-Sans", "-pointsize", "13", *draws, args.output],
            check=False,
            capture_output=True,
            text=True,
        )
        if result.returncode != 0:
            # Without that font (no fonts-dejavu-core): the boxes only, their colours still tell the class.
            boxes = [a for i, a in enumerate(draws) if not (i % 12 >= 6)]
            print(f"warning: labels not drawn: {result.stderr.strip().splitlines()[:1]}", file=sys.stderr)
            result = subprocess.run(["convert", ppm, *boxes, args.output], check=False)
    if result.returncode != 0:
        print(f"error: convert failed with exit code {result.returncode}", file=sys.stderr)
        return 1
    print(f"{args.output}: {len(detected.objects)} detections drawn")
    return 0


if __name__ == "__main__":
    sys.exit(main())
