"""Joint trajectory plots from recorded sensor_msgs/JointState messages (matplotlib, no display needed)."""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)


@dataclass
class JointSeries:
    """Positions of named joints over time (seconds from the first sample)."""

    names: list[str]
    times: list[float]
    positions: list[list[float]]  # positions[i][j]: joint names[j] at times[i]


def series_from_messages(messages: Iterable[tuple[float, Sequence[str], Sequence[float]]]) -> JointSeries:
    """Collects (stamp seconds, names, positions) samples; joints missing from a sample keep their last value,
    and the joint set is that of the first sample (later extra joints are ignored)."""
    names: list[str] = []
    times: list[float] = []
    positions: list[list[float]] = []
    start = None
    for stamp, sample_names, sample_positions in messages:
        if len(sample_names) != len(sample_positions):
            raise ValueError(f"joint state at {stamp}: {len(sample_names)} names but {len(sample_positions)} positions")
        values = dict(zip(sample_names, sample_positions, strict=True))
        if start is None:
            start = stamp
            names = list(sample_names)
        row = [values.get(n, positions[-1][j] if positions else 0.0) for j, n in enumerate(names)]
        times.append(stamp - start)
        positions.append(row)
    if not times:
        raise ValueError("no joint states recorded")
    return JointSeries(names=names, times=times, positions=positions)


def plot_joint_series(series: JointSeries, path: str, title: str = "Joint trajectories") -> None:
    """Two panels: the revolute arm joints (rad) and the prismatic finger joints (m), against time."""
    fingers = [j for j, n in enumerate(series.names) if "finger" in n]
    arm = [j for j in range(len(series.names)) if j not in fingers]
    fig, axes = plt.subplots(2, 1, figsize=(10, 7), sharex=True, height_ratios=[3, 1])
    for ax, indices, unit in ((axes[0], arm, "position [rad]"), (axes[1], fingers, "position [m]")):
        for j in indices:
            ax.plot(series.times, [row[j] for row in series.positions], label=series.names[j], linewidth=1.2)
        ax.set_ylabel(unit)
        ax.grid(True, alpha=0.3)
        if indices:
            ax.legend(loc="upper right", fontsize=8, ncol=3)
    axes[0].set_title(title)
    axes[1].set_xlabel("simulated time [s]")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
