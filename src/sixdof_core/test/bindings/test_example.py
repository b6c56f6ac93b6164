"""The example script and the README's code run as documented: no ROS master, only the sixdof_description folder
on ROS_PACKAGE_PATH."""

from __future__ import annotations

import os
import re
import subprocess
import sys

from conftest import BUILD_PYTHONPATH, CORE, DESCRIPTION


def environment() -> dict[str, str]:
    env = dict(os.environ)
    env["ROS_PACKAGE_PATH"] = str(DESCRIPTION)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (BUILD_PYTHONPATH, env.get("PYTHONPATH", "")) if p)
    env.pop("ROS_MASTER_URI", None)
    return env


def test_example_script_plans_for_the_sixdof_arm():
    run = subprocess.run([sys.executable, str(CORE / "examples" / "ik_collision_plan.py")], env=environment(),
                         capture_output=True, text=True, timeout=120, check=False)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "IK (numeric): SUCCESS" in run.stdout
    assert "collision check: free" in run.stdout
    assert "plan: SUCCESS" in run.stdout and "trajectory: SUCCESS" in run.stdout


def test_example_script_names_bad_input():
    run = subprocess.run([sys.executable, str(CORE / "examples" / "ik_collision_plan.py"), "--urdf", "/nope.urdf"],
                         env=environment(), capture_output=True, text=True, timeout=120, check=False)
    assert run.returncode == 2 and "/nope.urdf" in run.stderr


def test_example_script_finds_the_arm_below_a_search_root():
    env = environment()
    env["ROS_PACKAGE_PATH"] = ""
    root = ["--search-root", str(DESCRIPTION.parent)]
    run = subprocess.run([sys.executable, str(CORE / "examples" / "ik_collision_plan.py"), *root], env=env,
                         capture_output=True, text=True, timeout=120, check=False)
    assert run.returncode == 0, run.stdout + run.stderr
    missing = subprocess.run([sys.executable, str(CORE / "examples" / "ik_collision_plan.py")], env=env,
                             capture_output=True, text=True, timeout=120, check=False)
    assert missing.returncode == 2 and "sixdof_description" in missing.stderr


def test_readme_code_runs():
    readme = (CORE / "README.md").read_text(encoding="utf-8")
    section = readme[readme.index("## Python bindings"):]
    code = re.search(r"```python\n(.*?)```", section, re.DOTALL).group(1)
    run = subprocess.run([sys.executable, "-c", code], env=environment(), capture_output=True, text=True,
                         timeout=120, check=False)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "PlanningStatus.SUCCESS" in run.stdout
