"""Pure numpy detection of objects on known support surfaces in an organized depth cloud.

Pipeline (detect_objects): points above a known table top (the world file's tables: their top face is the
plane, so no plane fit is needed and none can tilt) and outside the masked volumes (the robot, the bins'
walls) -> connected components on the image grid (neighbouring pixels closer than a gap in 3-D) -> per
cluster a colour class from the mean colour's hue and a shape fit: sphere (least squares with the centre a
radius above the support), else box or upright cylinder told apart by the corners of the top face.

Depth noise: its vertical spread is measured on the support itself (the table points around its known height,
estimate_noise), and the fits widen their tolerances by it and take robust statistics (the top face's median
height, percentiles instead of extremes), so that noise does not raise every object or blow up its size.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from sixdof_commander.colors import color_class


@dataclass(frozen=True)
class Support:
    """A horizontal support surface: the top face of a table, an axis-aligned rectangle after yaw."""

    z: float
    centre: tuple[float, float]
    half_size: tuple[float, float]
    yaw: float = 0.0

    def contains(self, xy: np.ndarray, margin: float = 0.0) -> np.ndarray:
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        d = xy - np.asarray(self.centre)
        u = d[..., 0] * c + d[..., 1] * s
        v = -d[..., 0] * s + d[..., 1] * c
        return (np.abs(u) <= self.half_size[0] + margin) & (np.abs(v) <= self.half_size[1] + margin)


@dataclass(frozen=True)
class Box:
    """An oriented box (a volume to mask): centre, 3x3 rotation (columns = axes), half extents."""

    centre: np.ndarray
    rotation: np.ndarray
    half: np.ndarray

    def contains(self, points: np.ndarray, padding: float) -> np.ndarray:
        local = (points - self.centre) @ self.rotation
        return np.all(np.abs(local) <= self.half + padding, axis=-1)


@dataclass(frozen=True)
class Capsule:
    """A segment a-b swept by a sphere of the given radius (robot links for the self filter)."""

    a: np.ndarray
    b: np.ndarray
    radius: float

    def contains(self, points: np.ndarray, padding: float = 0.0) -> np.ndarray:
        ab = self.b - self.a
        length2 = float(ab @ ab)
        t = np.zeros(points.shape[:-1]) if length2 == 0.0 else np.clip((points - self.a) @ ab / length2, 0.0, 1.0)
        closest = self.a + t[..., None] * ab
        return np.sum((points - closest) ** 2, axis=-1) <= (self.radius + padding) ** 2


@dataclass(frozen=True)
class DetectorParams:
    min_height: float = 0.006  # m above the support: lower points are the support itself
    max_height: float = 0.25  # m above the support: higher points are not objects on it
    cluster_gap: float = 0.008  # m between neighbouring pixels of one cluster
    min_points: int = 30  # smaller clusters are noise or slivers
    top_tolerance: float = 0.004  # m below the highest point that still count as the top face
    sphere_rms: float = 0.0015  # m: a sphere fit at least this good makes a sphere
    corner_fraction: float = 0.03  # share of top-face points in the corners that makes a box
    mask_padding: float = 0.006  # m around masked boxes (bin walls)
    self_padding: float = 0.015  # m around the robot's shapes (its visuals are not exactly its boxes)

    def __post_init__(self) -> None:
        for name in (
            "min_height",
            "max_height",
            "cluster_gap",
            "top_tolerance",
            "sphere_rms",
            "mask_padding",
            "self_padding",
        ):
            value = getattr(self, name)
            if not (isinstance(value, int | float) and math.isfinite(value) and value > 0.0):
                raise ValueError(f"detector parameter {name} must be a number > 0, got {value!r}")
        if self.max_height <= self.min_height:
            raise ValueError("detector parameter max_height must be > min_height")
        if not isinstance(self.min_points, int) or self.min_points < 3:
            raise ValueError(f"detector parameter min_points must be an integer >= 3, got {self.min_points!r}")
        if not 0.0 < self.corner_fraction < 1.0:
            raise ValueError("detector parameter corner_fraction must be in (0, 1)")


@dataclass
class Detection:
    """One fitted cluster, in the frame of the points (the planning frame)."""

    color: str
    rgb: tuple[float, float, float]
    shape: str  # box, cylinder or sphere
    size: tuple[float, float, float]  # full extents along the object's axes
    position: tuple[float, float, float]
    yaw: float  # about z (boxes; 0 for cylinders and spheres)
    score: float
    point_count: int

    @property
    def label(self) -> str:
        return f"{self.color}_{self.shape}"


def foreground_mask(
    points: np.ndarray,
    supports: Sequence[Support],
    masked_boxes: Sequence[Box],
    self_filter: Sequence[Box | Capsule],
    params: DetectorParams,
) -> tuple[np.ndarray, np.ndarray]:
    """Pixels (HxW bool) of points above a support and outside masked volumes; and per pixel the height
    of the support under it (NaN where none)."""
    valid = np.all(np.isfinite(points), axis=-1)
    support_z = np.full(points.shape[:-1], np.nan)
    for support in supports:
        # The highest support under a point holds it (a box on a belt on a table): a point on or above its top.
        on = valid & (points[..., 2] - support.z > -params.min_height) & support.contains(points[..., :2])
        better = on & ~(support_z > support.z)
        support_z[better] = support.z
    held = np.isfinite(support_z)
    height = np.where(held, points[..., 2] - np.where(held, support_z, 0.0), 0.0)
    mask = held & (height > params.min_height) & (height < params.max_height)
    if not mask.any():
        return mask, support_z
    candidates = points[mask]
    keep = np.ones(len(candidates), dtype=bool)
    for box in masked_boxes:
        keep &= ~box.contains(candidates, params.mask_padding)
    for shape in self_filter:
        keep &= ~shape.contains(candidates, params.self_padding)
    mask[mask] = keep
    return mask, support_z


def estimate_noise(points: np.ndarray, supports: Sequence[Support], params: DetectorParams) -> float:
    """Vertical depth noise (m, a standard deviation): the robust spread (1.4826 * median absolute deviation)
    of the heights of the points on the supports, i.e. within min_height of a support's top. 0 when no support
    point is seen or the spread is below 0.1 mm (a noise-free camera's float rounding)."""
    valid = np.all(np.isfinite(points), axis=-1)
    residuals = []
    for support in supports:
        height = points[..., 2] - support.z
        near = valid & (np.abs(height) < params.min_height)
        near &= support.contains(points[..., :2])
        residuals.append(height[near])
    heights = np.concatenate(residuals) if residuals else np.empty(0)
    if len(heights) < params.min_points:
        return 0.0
    spread = float(1.4826 * np.median(np.abs(heights - np.median(heights))))
    return spread if spread >= 1e-4 else 0.0


def _top_height(z: np.ndarray, tolerance: float, noise: float) -> float:
    """Height of a cluster's top face: without noise its highest point; with noise the median of the points
    around the top (a band of 2.5 sigma, re-centred a few times), since the highest points are the noisiest."""
    if noise <= 0.0:
        return float(z.max())
    top = float(np.percentile(z, 99.0))
    band = max(tolerance / 2.0, 2.5 * noise)
    for _ in range(4):
        near = z[np.abs(z - top) <= band]
        if len(near) == 0:
            break
        top = float(np.median(near))
    return top


def label_components(mask: np.ndarray, points: np.ndarray, gap: float) -> np.ndarray:
    """Connected components of the mask on the 4-neighbour grid, neighbours joined when their points are
    closer than gap. Returns per pixel a component label (-1 outside the mask); labels are arbitrary ints.
    Union-find by repeated min-label hooking and pointer jumping (vectorised; a few rounds suffice)."""
    h, w = mask.shape
    index = np.arange(h * w).reshape(h, w)
    sources, targets = [], []
    for a_sl, b_sl in (
        ((slice(None), slice(0, -1)), (slice(None), slice(1, None))),
        ((slice(0, -1), slice(None)), (slice(1, None), slice(None))),
    ):
        joined = mask[a_sl] & mask[b_sl]
        joined &= np.sum((points[a_sl] - points[b_sl]) ** 2, axis=-1) < gap * gap
        sources.append(index[a_sl][joined])
        targets.append(index[b_sl][joined])
    a = np.concatenate(sources)
    b = np.concatenate(targets)
    parent = np.arange(h * w)
    while True:
        ra, rb = parent[a], parent[b]
        differ = ra != rb
        if not differ.any():
            break
        low = np.minimum(ra[differ], rb[differ])
        np.minimum.at(parent, ra[differ], low)
        np.minimum.at(parent, rb[differ], low)
        while True:
            jumped = parent[parent]
            if np.array_equal(jumped, parent):
                break
            parent = jumped
    labels = np.where(mask.ravel(), parent, -1)
    return labels.reshape(h, w)


def _min_area_yaw(xy: np.ndarray) -> float:
    """Yaw in [0, pi/2) of the smallest-area bounding rectangle of the points (1 degree steps)."""
    angles = np.radians(np.arange(0.0, 90.0, 1.0))
    c, s = np.cos(angles), np.sin(angles)
    u = xy[:, :1] * c + xy[:, 1:2] * s
    v = -xy[:, :1] * s + xy[:, 1:2] * c
    area = (u.max(axis=0) - u.min(axis=0)) * (v.max(axis=0) - v.min(axis=0))
    return float(angles[int(np.argmin(area))])


def _rotate(xy: np.ndarray, yaw: float) -> np.ndarray:
    c, s = math.cos(yaw), math.sin(yaw)
    return np.stack([xy[:, 0] * c + xy[:, 1] * s, -xy[:, 0] * s + xy[:, 1] * c], axis=1)


def _fit_sphere_on_support(points: np.ndarray, support_z: float) -> tuple[np.ndarray, float, float]:
    """Least-squares sphere whose centre lies its radius above the support: |p - c|^2 = r^2 with
    c_z = z0 + r gives x^2 + y^2 + z'^2 = 2 c_x x + 2 c_y y + 2 r z' + k (z' = z - z0, k = -c_x^2 - c_y^2),
    linear in (c_x, c_y, r, k). Returns the centre, the radius and the RMS distance error."""
    rel = points - np.array([0.0, 0.0, support_z])
    design = np.stack([2.0 * rel[:, 0], 2.0 * rel[:, 1], 2.0 * rel[:, 2], np.ones(len(rel))], axis=1)
    rhs = np.sum(rel**2, axis=1)
    (cx, cy, r, _k), *_ = np.linalg.lstsq(design, rhs, rcond=None)
    # The algebraic fit is biased by noise (it weighs errors by the radius): a few Gauss-Newton steps on
    # the geometric distances |p - c| - r, with c = (cx, cy, z0 + r).
    for _ in range(5):
        offset = rel - np.array([cx, cy, r])
        dist = np.maximum(np.linalg.norm(offset, axis=1), 1e-9)
        residual = dist - r
        jacobian = np.stack([-offset[:, 0] / dist, -offset[:, 1] / dist, -offset[:, 2] / dist - 1.0], axis=1)
        step, *_ = np.linalg.lstsq(jacobian, -residual, rcond=None)
        if not np.all(np.isfinite(step)):
            break
        cx, cy, r = cx + step[0], cy + step[1], r + step[2]
        if np.max(np.abs(step)) < 1e-7:
            break
    centre = np.array([cx, cy, support_z + r])
    errors = np.linalg.norm(points - centre, axis=1) - r
    return centre, float(r), float(np.sqrt(np.mean(errors**2)))


def fit_cluster(
    points: np.ndarray, colors: np.ndarray, support_z: float, params: DetectorParams, noise: float = 0.0
) -> Detection:
    """Colour class and shape fit of one cluster (points Nx3 in a z-up frame, colours Nx3 in [0, 1]); noise is
    the depth noise's vertical standard deviation (estimate_noise, m)."""
    mean = colors.mean(axis=0)
    rgb = (float(mean[0]), float(mean[1]), float(mean[2]))
    color = color_class(*rgb)
    height = _top_height(points[:, 2], params.top_tolerance, noise) - support_z
    centre, radius, rms = _fit_sphere_on_support(points, support_z)
    # Noise along the rays spreads a surface by about the vertical noise (the camera looks down steeply).
    sphere_rms = math.hypot(params.sphere_rms, 1.5 * noise)
    slack = 0.003 + 2.0 * noise
    if rms <= sphere_rms and radius > 0.0 and abs(2.0 * radius - height) <= 0.25 * height + 2.0 * noise:
        score = float(np.mean(np.abs(np.linalg.norm(points - centre, axis=1) - radius) < slack))
        d = 2.0 * radius
        return Detection(color, rgb, "sphere", (d, d, d), tuple(float(v) for v in centre), 0.0, score, len(points))
    top = points[points[:, 2] > support_z + height - max(params.top_tolerance, 2.5 * noise)]
    xy = points[:, :2]
    top_xy = top[:, :2] if len(top) >= 3 else xy
    yaw = _min_area_yaw(top_xy)
    # Corners of the top face (outside the inscribed ellipse of its bounding rectangle): a disc has none.
    uv = _rotate(top_xy, yaw)
    low, high = uv.min(axis=0), uv.max(axis=0)
    mid, half = (low + high) / 2.0, np.maximum((high - low) / 2.0, 1e-6)
    corners = np.all(np.abs(uv - mid) > 0.75 * half, axis=1)
    z = support_z + height / 2.0
    if np.mean(corners) >= params.corner_fraction:
        # Every visible point (top face and the sides facing the camera) lies inside the footprint.
        all_uv = _rotate(xy, yaw)
        # With noise the extremes are outliers: the footprint from percentiles instead.
        edge = 0.0 if noise <= 0.0 else 1.0
        low, high = np.percentile(all_uv, edge, axis=0), np.percentile(all_uv, 100.0 - edge, axis=0)
        mid_uv = (low + high) / 2.0
        c, s = math.cos(yaw), math.sin(yaw)
        cx, cy = mid_uv[0] * c - mid_uv[1] * s, mid_uv[0] * s + mid_uv[1] * c
        size = (float(high[0] - low[0]), float(high[1] - low[1]), height)
        inside = np.all(np.abs(all_uv - mid_uv) <= (high - low) / 2.0 + slack, axis=1)
        # Canonical yaw in [-45, 45) degrees: a box turned by 90 degrees is the same box with x and y swapped.
        if yaw >= math.pi / 4.0:
            yaw -= math.pi / 2.0
            size = (size[1], size[0], size[2])
        return Detection(color, rgb, "box", size, (float(cx), float(cy), z), yaw, float(np.mean(inside)), len(points))
    # Upright cylinder: the top disc's centroid is the axis; the radius from every point's distance to it.
    axis = top_xy.mean(axis=0)
    radial = np.linalg.norm(xy - axis, axis=1)
    radius = float(np.percentile(radial, 98 if noise <= 0.0 else 95))
    score = float(np.mean(radial <= radius + slack))
    d = 2.0 * radius
    return Detection(
        color, rgb, "cylinder", (d, d, height), (float(axis[0]), float(axis[1]), z), 0.0, score, len(points)
    )


def detect_objects(
    points: np.ndarray,
    colors: np.ndarray,
    supports: Sequence[Support],
    masked_boxes: Sequence[Box] = (),
    self_filter: Sequence[Box | Capsule] = (),
    params: DetectorParams | None = None,
) -> list[Detection]:
    """Objects in an organized cloud: points HxWx3 (planning frame, NaN where nothing was hit), colours
    HxWx3 in [0, 1]. Sorted by position (x, then y) so that the order is repeatable."""
    params = params or DetectorParams()
    if points.ndim != 3 or points.shape[-1] != 3 or colors.shape != points.shape:
        raise ValueError(f"points and colors must both be HxWx3, got {points.shape} and {colors.shape}")
    mask, support_z = foreground_mask(points, supports, masked_boxes, self_filter, params)
    noise = estimate_noise(points, supports, params)
    labels = label_components(mask, points, params.cluster_gap)
    flat = labels.ravel()
    chosen = flat >= 0
    if not chosen.any():
        return []
    ids, inverse, counts = np.unique(flat[chosen], return_inverse=True, return_counts=True)
    pts = points.reshape(-1, 3)[chosen]
    cols = colors.reshape(-1, 3)[chosen]
    zs = support_z.ravel()[chosen]
    order = np.argsort(inverse, kind="stable")
    bounds = np.concatenate([[0], np.cumsum(counts)])
    detections = []
    for k in range(len(ids)):
        if counts[k] < params.min_points:
            continue
        members = order[bounds[k] : bounds[k + 1]]
        detections.append(fit_cluster(pts[members], cols[members], float(np.nanmax(zs[members])), params, noise))
    detections.sort(key=lambda d: (round(d.position[0], 3), round(d.position[1], 3)))
    return detections
