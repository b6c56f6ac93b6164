"""Runs of sim_bench and of the same work in PyBullet (pybullet_world.py), for the benchmarks comparing them.

Both are installed beside this module. PyBullet runs in the benchmark venv whose Python scripts/bench.sh names
in SIXDOF_PYBULLET_PYTHON; without it a run fails naming what is missing."""

import json
import os
import statistics
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
SIM_BENCH = HERE / "sim_bench"
PYBULLET_WORLD = HERE / "pybullet_world.py"


class BenchError(RuntimeError):
    """A run that could not be made (a missing executable or venv, a failed run)."""


@dataclass
class Run:
    """One run: simulated seconds per second of wall clock and of CPU time, and its step cost."""

    rtf_wall: float
    rtf_cpu: float
    us_per_step: float
    extra: dict


def _timed(result: dict, time_step: float) -> Run:
    simulated = result["steps"] * time_step
    return Run(simulated / result["wall"], simulated / result["cpu"], result["wall"] / result["steps"] * 1e6, result)


def run_ours(objects: int, scenario: Path, seconds: float = 20.0) -> Run:
    """sim_bench with `objects` dynamic objects; it also writes the scenario PyBullet repeats."""
    if not SIM_BENCH.is_file():
        raise BenchError(f"{SIM_BENCH} not found (build with SIXDOF_BUILD_BENCHMARKS=ON)")
    cmd = [str(SIM_BENCH), "--objects", str(objects), "--seconds", str(seconds), "--scenario", str(scenario)]
    done = subprocess.run(cmd, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise BenchError(f"{' '.join(cmd)} failed: {done.stderr.strip()}")
    result = json.loads(scenario.read_text())
    return _timed(result, result["time_step"])


def pybullet_python() -> str:
    python = os.environ.get("SIXDOF_PYBULLET_PYTHON", "")
    if not python or not Path(python).is_file():
        raise BenchError(
            "SIXDOF_PYBULLET_PYTHON does not name the PyBullet venv's python: run scripts/bench.sh, "
            "which makes that venv"
        )
    return python


def run_pybullet(scenario: Path, sleep: bool) -> Run:
    """The scenario in PyBullet (objects allowed to sleep with `sleep`)."""
    cmd = [pybullet_python(), str(PYBULLET_WORLD), str(scenario)] + (["--sleep"] if sleep else [])
    done = subprocess.run(cmd, capture_output=True, text=True, check=False)
    lines = done.stdout.strip().splitlines()  # PyBullet prints its URDF import progress first
    if done.returncode != 0 or not lines:
        raise BenchError(f"{' '.join(cmd)} failed: {done.stderr.strip()[-2000:]}")
    return _timed(json.loads(lines[-1]), json.loads(scenario.read_text())["time_step"])


@dataclass
class Round:
    ours: Run
    pybullet: Run
    pybullet_sleep: Run


def alternate(objects: int, rounds: int) -> list[Round]:
    """`rounds` times: ours, then PyBullet on the scenario ours wrote, then PyBullet with sleeping objects."""
    out = []
    with tempfile.TemporaryDirectory() as tmp:
        scenario = Path(tmp) / "scenario.json"
        for _ in range(rounds):
            ours = run_ours(objects, scenario)
            out.append(Round(ours, run_pybullet(scenario, False), run_pybullet(scenario, True)))
    return out


def median(values: list[float]) -> float:
    return statistics.median(values)
