"""The committed generated files are exactly what the generator produces; bad design input is named."""

import os
import shutil
import subprocess
import sys

import pytest
import yaml

from sixdof_description import cad
from sixdof_description.generator import GENERATED_FILES, generate_files, load_design


@pytest.fixture(scope="module")
def generated(pkg):
    previous = (pkg / "config" / "sixdof.srdf").read_text(encoding="utf-8")
    return generate_files(pkg / "config" / "design.yaml", previous)


def test_generator_makes_every_file(generated):
    assert sorted(generated) == sorted(GENERATED_FILES)


@pytest.mark.parametrize("rel", GENERATED_FILES)
def test_committed_file_is_up_to_date(pkg, generated, rel):
    committed = (pkg / rel).read_bytes()
    assert committed == generated[rel], f"{rel} is stale: run `make -C sixdof_description`"


def test_generator_is_deterministic(pkg, generated):
    again = generate_files(pkg / "config" / "design.yaml", generated["config/sixdof.srdf"].decode())
    assert again == generated


def test_cli_check_reports_a_stale_file(pkg, tmp_path):
    for sub in ("config", "urdf", "meshes"):
        shutil.copytree(pkg / sub, tmp_path / sub)
    stale = tmp_path / "meshes" / "collision" / "link3.stl"
    stale.write_bytes(stale.read_bytes()[:-50])
    # The source tree's generator first; sixdof_core from the workspace.
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(pkg / "src"), os.environ.get("PYTHONPATH", "")]))
    run = subprocess.run(
        [sys.executable, str(pkg / "scripts" / "generate_description.py"), "--package-dir", str(pkg),
         "--output-dir", str(tmp_path), "--check"],
        capture_output=True, text=True, check=False, env=env)
    assert run.returncode == 1, run.stdout + run.stderr
    assert "link3.stl" in run.stderr and "urdf" not in run.stderr


def test_missing_design_parameter_is_named(pkg, tmp_path):
    with open(pkg / "config" / "design.yaml", encoding="utf-8") as f:
        design = yaml.safe_load(f)
    del design["density"]
    bad = tmp_path / "design.yaml"
    bad.write_text(yaml.safe_dump(design), encoding="utf-8")
    with pytest.raises(cad.DesignError, match="density"):
        load_design(bad)


def test_unreachable_named_state_is_an_error(pkg, tmp_path):
    with open(pkg / "config" / "design.yaml", encoding="utf-8") as f:
        design = yaml.safe_load(f)
    design["named_states"]["pick pose"]["xyz"] = [1.5, 0.0, 0.3]
    bad = tmp_path / "design.yaml"
    bad.write_text(yaml.safe_dump(design), encoding="utf-8")
    with pytest.raises(cad.DesignError, match="pick pose.*unreachable"):
        generate_files(bad, None)


def test_missing_nested_parameter_is_named(pkg, tmp_path):
    with open(pkg / "config" / "design.yaml", encoding="utf-8") as f:
        design = yaml.safe_load(f)
    del design["links"]["link2"]["elbow_r"]
    bad = tmp_path / "design.yaml"
    bad.write_text(yaml.safe_dump(design), encoding="utf-8")
    with pytest.raises(cad.DesignError, match="elbow_r"):
        generate_files(bad, None)
