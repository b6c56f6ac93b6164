"""Stable ids for detections across frames: each detection takes the nearest track of the same label
within a gate; unmatched detections start new tracks (<label>_<n>); tracks unseen for several frames are
dropped, except while the robot hides them (inside its self-filter volume) or holds them (attached in the
planning scene)."""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

from .detection import Detection


@dataclass
class Track:
    id: str
    detection: Detection
    position: tuple[float, float, float]
    missed: int = 0  # consecutive frames without a matching detection


@dataclass
class Tracker:
    gate: float = 0.04  # m: a detection further than this from every track of its label is a new object
    forget_after: int = 5  # frames: a track missed this many frames in a row is dropped
    tracks: dict[str, Track] = field(default_factory=dict)
    _counters: dict[str, int] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if not (isinstance(self.gate, int | float) and math.isfinite(self.gate) and self.gate > 0.0):
            raise ValueError(f"tracker gate must be a number > 0, got {self.gate!r}")
        if not isinstance(self.forget_after, int) or self.forget_after < 1:
            raise ValueError(f"tracker forget_after must be an integer >= 1, got {self.forget_after!r}")

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
    ) -> list[tuple[str, Detection]]:
        """Ids of this frame's detections, in their order. held: ids the planning scene has attached to the
        robot (value None) or has back in its world at a pose the robot put it (value: that position; the
        track moves there so that the object is recognised where it was placed). hidden(position): True
        where the robot hides a track's last position (it is kept, not aged). touching(detection): True when
        the detected object touches the robot; such a detection that matches no track is left out (an object
        the robot is handling, or a part of it, becomes a new object only once the robot has left it)."""
        held = held or {}
        for track_id, position in held.items():
            if track_id in self.tracks and position is not None:
                self.tracks[track_id].position = position
        candidates = []
        for i, det in enumerate(detections):
            for track in self.tracks.values():
                if track.detection.label != det.label or held.get(track.id, ()) is None:
                    continue
                distance = math.dist(det.position, track.position)
                if distance <= self.gate:
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
