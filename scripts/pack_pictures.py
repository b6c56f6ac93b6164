#!/usr/bin/env python3
"""The packing demo's pictures (scripts/demo_pack.sh):

    scripts/pack_pictures.py camera CAMERA OUT.png    the simulator camera's next colour image (needs the stack)
    scripts/pack_pictures.py plot RESULT.json OUT.png  picks over time with the belt speed, from pack_objects.py --json

Exit 0 when the PNG is written, 1 when the camera sent no image or the result file is unreadable.
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path


def save_camera_image(camera: str, output: str, timeout: float) -> int:
    import numpy as np
    import rospy
    from sensor_msgs.msg import Image

    rospy.init_node("pack_pictures", anonymous=True)
    try:
        image = rospy.wait_for_message(f"{camera}/color/image_raw", Image, timeout=timeout)
    except rospy.ROSException as err:
        print(f"error: no image from camera '{camera}': {err}", file=sys.stderr)
        return 1
    if image.encoding != "rgb8":
        print(f"error: expected an rgb8 image, got {image.encoding}", file=sys.stderr)
        return 1
    pixels = np.frombuffer(image.data, dtype=np.uint8).reshape(image.height, image.step)[:, : 3 * image.width]
    with tempfile.TemporaryDirectory() as tmp:
        ppm = Path(tmp) / "image.ppm"
        ppm.write_bytes(f"P6 {image.width} {image.height} 255\n".encode() + np.ascontiguousarray(pixels).tobytes())
        if subprocess.run(["convert", str(ppm), output], check=False).returncode != 0:
            print("error: convert failed", file=sys.stderr)
            return 1
    print(f"{output}: camera '{camera}', {image.width}x{image.height}")
    return 0


def plot(result_file: str, output: str) -> int:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    try:
        result = json.loads(Path(result_file).read_text())
        outcomes, speeds = result["outcomes"], result["belt_speed"]
    except (OSError, ValueError, KeyError) as err:
        print(f"error: {result_file}: {err}", file=sys.stderr)
        return 1
    placed = sorted(o["time"] for o in outcomes if o["outcome"] in ("packed", "misplaced"))
    failed = [o for o in outcomes if o["outcome"] not in ("packed", "misplaced")]
    fig, ax = plt.subplots(figsize=(9, 4.5))
    ax.step([0.0, *placed], range(len(placed) + 1), where="post", color="tab:blue", label="objects placed")
    for o in failed:
        ax.axvline(o["time"], color="tab:red", alpha=0.5, linewidth=1)
    if failed:
        ax.plot([], [], color="tab:red", alpha=0.5, label=f"not placed ({len(failed)})")
    ax.set_xlabel("simulated time (s)")
    ax.set_ylabel("objects placed")
    rate = result.get("picks_per_minute", math.nan)
    ax.set_title(f"pack_objects.py: {len(placed)} placed, {rate:.1f} picks per minute (simulated time)")
    belt = ax.twinx()
    belt.plot([t for t, _ in speeds], [v for _, v in speeds], color="tab:green", label="belt speed")
    belt.set_ylabel("belt speed (m/s)")
    belt.set_ylim(0.0, max([v for _, v in speeds if math.isfinite(v)] + [0.1]) * 1.5)
    lines = ax.get_legend_handles_labels()
    more = belt.get_legend_handles_labels()
    ax.legend(lines[0] + more[0], lines[1] + more[1], loc="upper left")
    fig.tight_layout()
    fig.savefig(output, dpi=100)
    print(f"{output}: {len(placed)} placements, {len(failed)} other outcomes")
    return 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="what", required=True)
    camera = sub.add_parser("camera", help="save the camera's next colour image")
    camera.add_argument("camera")
    camera.add_argument("output")
    camera.add_argument("--timeout", type=float, default=30.0, help="wall-clock seconds to wait (30)")
    plotting = sub.add_parser("plot", help="plot picks over time with the belt speed")
    plotting.add_argument("result")
    plotting.add_argument("output")
    args = parser.parse_args()
    if args.what == "camera":
        return save_camera_image(args.camera, args.output, args.timeout)
    return plot(args.result, args.output)


if __name__ == "__main__":
    sys.exit(main())
