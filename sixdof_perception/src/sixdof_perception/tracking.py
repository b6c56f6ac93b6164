"""Stable ids for detections across frames: each detection takes the nearest track of the same label
within a gate around the track's predicted position; unmatched detections start new tracks (<label>_<n>); tracks
unseen for several frames are dropped, except while the robot hides them (inside its self-filter volume) or holds
them (attached in the planning scene).

Velocity: with stamped frames, each track fits a constant velocity (least squares of position over time) to its
detections of the last `velocity_window` seconds, once it has `min_samples` of them spanning at least half the
window; until then its velocity is None. A track's predicted position is its last position moved by that velocity
(by nothing while it has none); a track without a velocity yet also accepts a detection up to `max_speed` times the
elapsed time beyond the gate (an object on a belt moves several centimetres between frames)."""

from __future__ import annotations

import math
from collections import deque
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from .detection import Detection


@dataclass
class Track:
    id: str
    detection: Detection
    position: tuple[float, float, float]
    missed: int = 0  # consecutive frames without a matching detection
    history: deque = field(default_factory=deque)  # (stamp, position) of the detections within the window
    velocity: tuple[float, float, float] | None = None  # m/s, None until the fit has enough samples

    def predicted(self, stamp: float | None) -> tuple[float, float, float]:
        """Where the track should be at `stamp` (its last position without a stamp or a velocity)."""
        if stamp is None or self.velocity is None or not self.history:
            return self.position
        dt = stamp - self.history[-1][0]
        return tuple(p + v * dt for p, v in zip(self.position, self.velocity, strict=True))

    def observe(self, stamp: float, position: tuple[float, float, float], window: float, min_samples: int) -> None:
        """Add a stamped detection and refit the velocity over the window."""
        if self.history and stamp <= self.history[-1][0]:
            self.history.clear()  # time went back (a simulator reset): start afresh
        self.history.append((stamp, position))
        while stamp - self.history[0][0] > window:
            self.history.popleft()
        times = np.array([t for t, _ in self.history])
        if len(times) < min_samples or times[-1] - times[0] < window / 2.0:
            self.velocity = None
            return
        positions = np.array([p for _, p in self.history])
        centred = times - times.mean()
        slope = centred @ (positions - positions.mean(axis=0)) / (centred @ centred)
        self.velocity = (float(slope[0]), float(slope[1]), float(slope[2]))


@dataclass
class Tracker:
    gate: float = 0.04  # m: a detection further than this from every track of its label is a new object
    forget_after: int = 5  # frames: a track missed this many frames in a row is dropped
    velocity_window: float = 1.0  # s of stamped detections the velocity is fitted to
    min_samples: int = 3  # detections within the window before a track has a velocity
    max_speed: float = 0.0  # m/s: how fast an object without a velocity yet may have moved since its last frame
    tracks: dict[str, Track] = field(default_factory=dict)
    _counters: dict[str, int] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if not (isinstance(self.gate, int | float) and math.isfinite(self.gate) and self.gate > 0.0):
            raise ValueError(f"tracker gate must be a number > 0, got {self.gate!r}")
        if not isinstance(self.forget_after, int) or self.forget_after < 1:
            raise ValueError(f"tracker forget_after must be an integer >= 1, got {self.forget_after!r}")
        for name in ("velocity_window", "max_speed"):
            value = getattr(self, name)
            if not (isinstance(value, int | float) and math.isfinite(value) and value >= 0.0):
                raise ValueError(f"tracker {name} must be a number >= 0, got {value!r}")
        if self.velocity_window <= 0.0:
            raise ValueError(f"tracker velocity_window must be > 0, got {self.velocity_window!r}")
        if not isinstance(self.min_samples, int) or self.min_samples < 2:
            raise ValueError(f"tracker min_samples must be an integer >= 2, got {self.min_samples!r}")

    def _new_id(self, label: str) -> str:
        n = self._counters.get(label, 0) + 1
        self._counters[label] = n
        return f"{label}_{n}"

    def update(
        self,
        detections: Sequence[Detection],
        held: Mapping[str, tuple[float, float, float] | None] | None = None,
        hidden: Callable[[tuple[float, float, float]], bool] = lambda _p: False,
        touching: Callable[[Detection], bool] = lambda _d: False,
        stamp: float | None = None,
    ) -> list[tuple[str, Detection]]:
        """Ids of this frame's detections, in their order. held: ids the planning scene has attached to the
        robot (value None) or has back in its world at a pose the robot put it (value: that position; the
        track moves there so that the object is recognised where it was placed). hidden(position): True
        where the robot hides a track's last position (it is kept, not aged). touching(detection): True when
        the detected object touches the robot; such a detection that matches no track is left out (an object
        the robot is handling, or a part of it, becomes a new object only once the robot has left it). stamp: the
        frame's time in seconds; without it no velocities are estimated."""
        held = held or {}
        for track_id, position in held.items():
            if track_id in self.tracks and position is not None:
                track = self.tracks[track_id]
                track.position, track.velocity = position, None
                track.history.clear()
        candidates = []
        for i, det in enumerate(detections):
            for track in self.tracks.values():
                if track.detection.label != det.label or held.get(track.id, ()) is None:
                    continue
                distance = math.dist(det.position, track.predicted(stamp))
                if distance <= self._gate(track, stamp):
                    candidates.append((distance, i, track.id))
        candidates.sort()
        assigned: dict[int, str] = {}
        used: set[str] = set()
        for _distance, i, track_id in candidates:
            if i in assigned or track_id in used:
                continue
            assigned[i] = track_id
            used.add(track_id)
        out = []
        for i, det in enumerate(detections):
            track_id = assigned.get(i)
            if track_id is None and touching(det):
                continue
            if track_id is None:
                track_id = self._new_id(det.label)
                self.tracks[track_id] = Track(track_id, det, det.position)
            track = self.tracks[track_id]
            track.detection, track.position, track.missed = det, det.position, 0
            if stamp is not None:
                track.observe(stamp, det.position, self.velocity_window, self.min_samples)
            out.append((track_id, det))
        for track in list(self.tracks.values()):
            if track.id in used or any(track.id == t for t, _ in out):
                continue
            if track.id in held or hidden(track.position):
                continue
            track.missed += 1
            if track.missed >= self.forget_after:
                del self.tracks[track.id]
        return out

    def _gate(self, track: Track, stamp: float | None) -> float:
        """The largest distance from the track's predicted position a detection of it may have."""
        if track.velocity is not None or stamp is None or not track.history:
            return self.gate
        return self.gate + self.max_speed * max(stamp - track.history[-1][0], 0.0)
