"""Detection on synthetic organized clouds: a small numpy ray caster renders known boxes, cylinders and
spheres on a table the way the simulator's camera sees them (pinhole, looking down at an angle)."""

import math

import numpy as np
import pytest

from sixdof_perception.detection import (
    Box,
    Capsule,
    DetectorParams,
    Support,
    color_class,
    detect_objects,
    estimate_noise,
    label_components,
)
from sixdof_perception.tracking import Tracker

TABLE = Support(0.0, (0.2, 0.0), (0.5, 0.6))


CAMERA_POSITION, CAMERA_TARGET = (0.95, 0.0, 0.8), (0.38, 0.0, 0.0)


def camera_rays(width=320, height=240, fov_deg=60.0, position=CAMERA_POSITION, target=CAMERA_TARGET):
    """Ray origins and unit directions (HxWx3) of a pinhole camera at position looking at target."""
    forward = np.subtract(target, position)
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    down = np.cross(forward, right)
    f = (width / 2.0) / math.tan(math.radians(fov_deg) / 2.0)
    u, v = np.meshgrid(np.arange(width) - (width - 1) / 2.0, np.arange(height) - (height - 1) / 2.0)
    dirs = forward * f + u[..., None] * right + v[..., None] * down
    dirs /= np.linalg.norm(dirs, axis=-1, keepdims=True)
    return np.broadcast_to(np.asarray(position, float), dirs.shape), dirs


def hit_box(o, d, centre, yaw, size):
    c, s = math.cos(yaw), math.sin(yaw)
    rot = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    lo, ld = (o - centre) @ rot, d @ rot
    half = np.asarray(size) / 2.0
    with np.errstate(divide="ignore", invalid="ignore"):
        t1, t2 = (-half - lo) / ld, (half - lo) / ld
    tmin = np.nanmax(np.minimum(t1, t2), axis=-1)
    tmax = np.nanmin(np.maximum(t1, t2), axis=-1)
    return np.where((tmax >= tmin) & (tmin > 0), tmin, np.inf)


def hit_sphere(o, d, centre, r):
    oc = o - centre
    b = np.sum(oc * d, axis=-1)
    disc = b * b - (np.sum(oc * oc, axis=-1) - r * r)
    t = -b - np.sqrt(np.maximum(disc, 0.0))
    return np.where((disc >= 0) & (t > 0), t, np.inf)


def hit_cylinder(o, d, centre, r, length):
    ox, oy = o[..., 0] - centre[0], o[..., 1] - centre[1]
    a = d[..., 0] ** 2 + d[..., 1] ** 2
    b = ox * d[..., 0] + oy * d[..., 1]
    cc = ox**2 + oy**2 - r * r
    disc = b * b - a * cc
    t_side = (-b - np.sqrt(np.maximum(disc, 0.0))) / a
    z = o[..., 2] + t_side * d[..., 2]
    side = np.where((disc >= 0) & (np.abs(z - centre[2]) <= length / 2), t_side, np.inf)
    t_cap = (centre[2] + length / 2 - o[..., 2]) / d[..., 2]
    px, py = ox + t_cap * d[..., 0], oy + t_cap * d[..., 1]
    cap = np.where((t_cap > 0) & (px**2 + py**2 <= r * r), t_cap, np.inf)
    return np.minimum(side, cap)


def render(objects, depth_noise=0.0, seed=0, **camera):
    """objects: (kind, centre, params, rgb). Returns points, colours (table brown) like the simulator's cloud;
    depth_noise (m) is Gaussian noise on the depth (along the optical axis), as the simulator's camera adds it."""
    o, d = camera_rays(**camera)
    t_best = np.where(d[..., 2] < 0, -o[..., 2] / d[..., 2], np.inf)
    colors = np.broadcast_to(np.array([0.55, 0.4, 0.25]), d.shape).copy()
    for kind, centre, params, rgb in objects:
        centre = np.asarray(centre, float)
        if kind == "box":
            t = hit_box(o, d, centre, params["yaw"], params["size"])
        elif kind == "sphere":
            t = hit_sphere(o, d, centre, params["radius"])
        else:
            t = hit_cylinder(o, d, centre, params["radius"], params["length"])
        closer = t < t_best
        t_best = np.where(closer, t, t_best)
        # Lambert-like darkening keeps the hue.
        colors[closer] = np.asarray(rgb) * 0.8
    if depth_noise > 0.0:
        forward = np.subtract(camera.get("target", CAMERA_TARGET), camera.get("position", CAMERA_POSITION))
        cosine = d @ (forward / np.linalg.norm(forward))
        t_best = t_best + np.random.default_rng(seed).normal(0.0, depth_noise, t_best.shape) / cosine
    points = o + d * t_best[..., None]
    points[~np.isfinite(t_best)] = np.nan
    return points, colors


LAYOUT = [
    ("box", (0.34, -0.12, 0.02), {"yaw": 0.3, "size": (0.04, 0.04, 0.04)}, (0.9, 0.1, 0.1)),
    ("sphere", (0.48, 0.06, 0.022), {"radius": 0.022}, (0.9, 0.1, 0.1)),
    ("cylinder", (0.45, -0.16, 0.025), {"radius": 0.02, "length": 0.05}, (0.15, 0.75, 0.2)),
    ("box", (0.30, 0.08, 0.0175), {"yaw": -0.5, "size": (0.035, 0.035, 0.035)}, (0.15, 0.75, 0.2)),
    ("cylinder", (0.38, -0.02, 0.03), {"radius": 0.018, "length": 0.06}, (0.1, 0.2, 0.9)),
    ("sphere", (0.52, -0.06, 0.025), {"radius": 0.025}, (0.1, 0.2, 0.9)),
]


def test_color_classes():
    assert color_class(0.9, 0.1, 0.1) == "red"
    assert color_class(0.15, 0.75, 0.2) == "green"
    assert color_class(0.1, 0.2, 0.9) == "blue"
    assert color_class(0.95, 0.85, 0.1) == "yellow"
    assert color_class(0.5, 0.5, 0.5) == "unknown"
    assert color_class(0.0, 0.0, 0.0) == "unknown"
    with pytest.raises(ValueError, match="colour components"):
        color_class(2.0, 0.0, 0.0)


def test_components_split_on_depth_gaps():
    mask = np.ones((4, 6), dtype=bool)
    mask[:, 2] = False
    points = np.zeros((4, 6, 3))
    points[..., 0] = np.arange(6) * 0.001
    points[:2, 3:, 2] = 0.5  # a depth jump inside the right block
    labels = label_components(mask, points, 0.01)
    assert (labels[:, 2] == -1).all()
    assert len({labels[0, 0], labels[0, 3], labels[3, 3]}) == 3
    assert len(np.unique(labels[:, :2])) == 1


def test_layout_found_with_right_shapes_colours_and_positions():
    points, colors = render(LAYOUT, width=640, height=480)
    found = detect_objects(points, colors, [TABLE])
    assert len(found) == len(LAYOUT), [(d.label, d.position) for d in found]
    for kind, centre, params, rgb in LAYOUT:
        nearest = min(found, key=lambda d: math.dist(d.position, centre))
        error = math.dist(nearest.position, centre)
        assert error < 0.004, (kind, centre, nearest)
        assert nearest.shape == kind, (kind, centre, nearest)
        assert nearest.color == color_class(*rgb)
        if kind == "sphere":
            assert nearest.size[0] == pytest.approx(2 * params["radius"], abs=0.004)
        elif kind == "cylinder":
            assert nearest.size[0] == pytest.approx(2 * params["radius"], abs=0.005)
            assert nearest.size[2] == pytest.approx(params["length"], abs=0.003)
        else:
            assert nearest.size[2] == pytest.approx(params["size"][2], abs=0.003)
            assert sorted(nearest.size[:2]) == pytest.approx(sorted(params["size"][:2]), abs=0.006)
            turn = (nearest.yaw - params["yaw"]) % (math.pi / 2)
            assert min(turn, math.pi / 2 - turn) < math.radians(5)


@pytest.mark.parametrize("sigma", [0.001, 0.002])
def test_depth_noise_measured_on_the_table_and_tolerated(sigma):
    """Realistic depth noise (1-2 mm at about 1 m): every object found with its shape and colour, its centre
    within 3 mm (the highest points of a noisy cluster are not its top, the extremes not its footprint)."""
    points, colors = render(LAYOUT, depth_noise=sigma, seed=7, width=640, height=480)
    # The vertical part of noise along rays that look down at 35-70 degrees.
    assert 0.5 * sigma < estimate_noise(points, [TABLE], DetectorParams()) < sigma
    found = detect_objects(points, colors, [TABLE])
    assert len(found) == len(LAYOUT), [(d.label, d.position) for d in found]
    for kind, centre, _params, rgb in LAYOUT:
        nearest = min(found, key=lambda d: math.dist(d.position, centre))
        assert math.dist(nearest.position, centre) < 0.003, (kind, centre, nearest)
        assert (nearest.shape, nearest.color) == (kind, color_class(*rgb)), (kind, centre, nearest)
    assert estimate_noise(*render(LAYOUT, width=320, height=240)[:1], [TABLE], DetectorParams()) == 0.0


def test_masks_and_self_filter_remove_points():
    points, colors = render(LAYOUT[:1], width=320, height=240)
    wall = Box(np.array([0.34, -0.12, 0.02]), np.eye(3), np.array([0.03, 0.03, 0.03]))
    assert detect_objects(points, colors, [TABLE], masked_boxes=[wall]) == []
    arm = Capsule(np.array([0.34, -0.12, 0.3]), np.array([0.34, -0.12, 0.0]), 0.05)
    assert detect_objects(points, colors, [TABLE], self_filter=[arm]) == []
    assert len(detect_objects(points, colors, [TABLE])) == 1


def test_empty_table_and_bad_input():
    points, colors = render([], width=160, height=120)
    assert detect_objects(points, colors, [TABLE]) == []
    with pytest.raises(ValueError, match="HxWx3"):
        detect_objects(points[..., :2], colors, [TABLE])
    with pytest.raises(ValueError, match="min_points"):
        DetectorParams(min_points=1)


def test_tracker_keeps_ids_and_forgets_missing_objects():
    points, colors = render(LAYOUT[:2], width=320, height=240)
    detections = detect_objects(points, colors, [TABLE])
    tracker = Tracker(gate=0.04, forget_after=2)
    first = dict(tracker.update(detections))
    assert sorted(first) == ["red_box_1", "red_sphere_1"]
    moved = [LAYOUT[0], ("sphere", (0.50, 0.07, 0.022), {"radius": 0.022}, (0.9, 0.1, 0.1))]
    second = dict(tracker.update(detect_objects(*render(moved, width=320, height=240), [TABLE])))
    assert sorted(second) == ["red_box_1", "red_sphere_1"]
    assert second["red_sphere_1"].position[0] == pytest.approx(0.50, abs=0.005)
    only_box = detect_objects(*render(LAYOUT[:1], width=320, height=240), [TABLE])
    tracker.update(only_box)
    assert "red_sphere_1" in tracker.tracks
    tracker.update(only_box)
    assert "red_sphere_1" not in tracker.tracks
    # Held (attached in the scene) tracks are never aged, whatever the camera sees.
    tracker.update(only_box, held={"red_box_1": None})
    tracker.update([], held={"red_box_1": None})
    tracker.update([], held={"red_box_1": None})
    assert "red_box_1" in tracker.tracks
    # A new object gets a new id.
    again = dict(tracker.update(detect_objects(*render(LAYOUT[1:2], width=320, height=240), [TABLE])))
    assert list(again) == ["red_sphere_2"]


def test_tracker_estimates_the_velocity_of_a_moving_box():
    """A box rendered 10 frames a second moving at 0.2 m/s along y: its id stays, and after a second of frames the
    fitted velocity is within 5 % of the true one (the rostest moving_pick does the same on the simulator's belt)."""
    tracker = Tracker(gate=0.01, forget_after=2, max_speed=0.5)
    speed, rate = 0.2, 10.0
    ids, velocity = set(), None
    for k in range(15):
        t = k / rate
        box = ("box", (0.40, -0.15 + speed * t, 0.02), {"yaw": 0.0, "size": (0.04, 0.04, 0.04)}, (0.9, 0.1, 0.1))
        identified = tracker.update(detect_objects(*render([box], width=320, height=240), [TABLE]), stamp=t)
        assert len(identified) == 1
        ids.add(identified[0][0])
        velocity = tracker.tracks[identified[0][0]].velocity
        if k < 5:
            assert velocity is None  # under half the window of frames
    assert ids == {"red_box_1"}
    assert velocity is not None
    assert velocity[1] == pytest.approx(speed, rel=0.05)
    assert math.hypot(velocity[0], velocity[2]) < 0.05 * speed
    # Without max_speed the 2 cm jump of the second frame is beyond the 1 cm gate: a new track.
    still = Tracker(gate=0.01)
    first = ("box", (0.40, -0.15, 0.02), {"yaw": 0.0, "size": (0.04, 0.04, 0.04)}, (0.9, 0.1, 0.1))
    moved = ("box", (0.40, -0.13, 0.02), {"yaw": 0.0, "size": (0.04, 0.04, 0.04)}, (0.9, 0.1, 0.1))
    still.update(detect_objects(*render([first], width=320, height=240), [TABLE]), stamp=0.0)
    second = still.update(detect_objects(*render([moved], width=320, height=240), [TABLE]), stamp=0.1)
    assert [i for i, _ in second] == ["red_box_2"]
    with pytest.raises(ValueError, match="min_samples"):
        Tracker(min_samples=1)
    with pytest.raises(ValueError, match="velocity_window"):
        Tracker(velocity_window=0.0)


def test_an_object_on_a_belt_stands_on_the_belt():
    """A cube on a 3 cm belt standing on the table: the belt's top is its support (its height is the cube's), the
    belt itself is masked like other scenery and is no object."""
    belt = ("box", (0.45, 0.0, 0.015), {"yaw": math.pi / 2, "size": (1.0, 0.16, 0.03)}, (0.15, 0.15, 0.17))
    cube = ("box", (0.45, -0.2, 0.05), {"yaw": 0.0, "size": (0.04, 0.04, 0.04)}, (0.9, 0.1, 0.1))
    points, colors = render([belt, cube], width=320, height=240)
    top = Support(0.03, (0.45, 0.0), (0.5, 0.08), math.pi / 2)
    mask = Box(
        np.array([0.45, 0.0, 0.015]),
        np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]),
        np.array([0.5, 0.08, 0.015]),
    )
    detections = detect_objects(points, colors, [TABLE, top], [mask])
    assert [d.label for d in detections] == ["red_box"]
    assert detections[0].position == pytest.approx((0.45, -0.2, 0.05), abs=0.003)
    assert detections[0].size[2] == pytest.approx(0.04, abs=0.003)
