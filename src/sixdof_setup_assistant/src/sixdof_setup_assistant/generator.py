"""Config-package generation: `setup_assistant --urdf FILE --package-out DIR` (see cli.py for the options).

The package is built in a staging folder beside the target and renamed into place: on any error nothing is
written. A re-run keeps every file edited by hand since it was generated (the hashes of what was generated are
in `.setup_assistant.yaml`), keeps the hand-written parts of the SRDF and lists what it regenerates.
"""

from __future__ import annotations

import hashlib
import os
import re
import shlex
import shutil
import subprocess
import tempfile
from dataclasses import dataclass, field
from typing import Any

import yaml

from . import grasping, packing_world, real_robot, suction, templates
from .answers import load_answers
from .infer import Plan, complete_gripper_states, infer
from .xacro_loader import load_description

MANIFEST = ".setup_assistant.yaml"
PACKAGE_NAME = re.compile(r"^[a-z][a-z0-9_]*$")


class GenerationError(Exception):
    """Bad input or an output that cannot be written; the message names the problem."""


def find_core() -> str:
    """sixdof_core's setup_assistant_core executable: $SIXDOF_SETUP_ASSISTANT_CORE, else lib/sixdof_core of the first
    prefix on CMAKE_PREFIX_PATH (a sourced workspace) that has it."""
    candidates = [os.environ.get("SIXDOF_SETUP_ASSISTANT_CORE", "")]
    for prefix in os.environ.get("CMAKE_PREFIX_PATH", "").split(os.pathsep):
        if prefix:
            candidates.append(os.path.join(prefix, "lib", "sixdof_core", "setup_assistant_core"))
    for candidate in candidates:
        if candidate and os.access(candidate, os.X_OK) and os.path.isfile(candidate):
            return candidate
    raise GenerationError("setup_assistant_core not found (build sixdof_core and source the workspace)")


def core_environment(source: str) -> dict[str, str]:
    """The core finds package:// meshes in the folders above the URDF it reads, then on ROS_PACKAGE_PATH: it
    reads an expanded copy, so the three folders above the source file go first on its ROS_PACKAGE_PATH."""
    roots = []
    folder = os.path.dirname(os.path.abspath(source))
    while len(roots) < 3 and folder != os.path.dirname(folder):
        roots.append(folder)
        folder = os.path.dirname(folder)
    env = dict(os.environ)
    rest = [p for p in env.get("ROS_PACKAGE_PATH", "").split(os.pathsep) if p]
    env["ROS_PACKAGE_PATH"] = os.pathsep.join(roots + rest)
    return env


def run_core(args: list[str], echo: bool = True, env: dict[str, str] | None = None) -> str:
    """Runs setup_assistant_core, echoing its progress lines; raises GenerationError with its error line."""
    process = subprocess.Popen([find_core(), *args], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               env=env)
    output = []
    assert process.stdout is not None
    for line in process.stdout:
        output.append(line)
        if echo and not line.startswith("wrote "):  # the core's files are staging files
            print(line, end="", flush=True)
    error = process.stderr.read() if process.stderr else ""
    if process.wait() != 0:
        lines = [line for line in error.splitlines() if line.strip()]
        message = lines[0] if lines else f"setup_assistant_core exited with {process.returncode}"
        raise GenerationError(message.removeprefix("setup_assistant: "))
    return "".join(output)


def _sha(text: str) -> str:
    return hashlib.sha256(text.encode()).hexdigest()


@dataclass
class Options:
    urdf: str
    package_out: str
    name: str = ""
    answers: str = ""
    density: int | None = None
    seed: int | None = None
    xacro_args: dict[str, str] = field(default_factory=dict)
    command: str = ""


@dataclass
class Analysis:
    model: dict[str, Any]  # the core's description of the input
    plan: Plan
    repairs: dict[str, Any]  # the core's repairs report
    urdf: str  # path of the repaired URDF


@dataclass
class Result:
    path: str
    created: list[str] = field(default_factory=list)
    regenerated: list[str] = field(default_factory=list)
    kept: list[str] = field(default_factory=list)  # edited by hand since generated: left as they are
    removed: list[str] = field(default_factory=list)  # generated before, not any more, not edited
    srdf_hand_edits_kept: bool = False
    report: dict[str, Any] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)  # what the setup assistant repaired or could not infer


def _read(path: str) -> str:
    with open(path, encoding="utf-8") as file:
        return file.read()


def _write(path: str, text: str) -> None:
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as file:
        file.write(text)


def _existing_ancestor(path: str) -> str:
    path = os.path.abspath(path)
    while not os.path.exists(path):
        path = os.path.dirname(path)
    return path


def generate(options: Options) -> Result:
    """Generates (or updates) the package. Raises GenerationError / DescriptionError / AnswersError /
    InferenceError naming the problem; nothing is written then."""
    answers = load_answers(options.answers)
    out_dir = os.path.abspath(options.package_out)
    if os.path.exists(out_dir) and not os.path.isdir(out_dir):
        raise GenerationError(f"--package-out {options.package_out}: is a file, not a folder")
    ancestor = _existing_ancestor(out_dir)
    if not os.path.isdir(ancestor):
        raise GenerationError(f"--package-out {options.package_out}: '{ancestor}' is a file, not a folder")
    urdf_text = load_description(options.urdf, options.xacro_args)

    staging_root = tempfile.mkdtemp(prefix=".setup_assistant.", dir=ancestor)
    try:
        return _generate(options, answers, urdf_text, out_dir, staging_root)
    finally:
        shutil.rmtree(staging_root, ignore_errors=True)


def _analyze(urdf_text: str, answers: dict[str, Any], env: dict[str, str], work: str) -> Analysis:
    """The core's description of the model, the choices for it and its repairs (inertias, the gripper's grasp
    geometry and TCP frame), with the repaired URDF written into work."""
    urdf_in = os.path.join(work, "input.urdf")
    _write(urdf_in, urdf_text)
    model_path = os.path.join(work, "model.yaml")
    run_core(["--urdf", urdf_in, "--describe", model_path], echo=False, env=env)
    model = yaml.safe_load(_read(model_path))
    plan = infer(model, answers)
    suction.attach(plan, model, answers)
    repaired_urdf = os.path.join(work, "repaired.urdf")
    repairs_path = os.path.join(work, "repairs.yaml")
    run_core(["--urdf", urdf_in, "--urdf-out", repaired_urdf, "--repairs", repairs_path,
              *grasping.core_arguments(plan, answers)], echo=False, env=env)
    repairs = yaml.safe_load(_read(repairs_path))
    if repairs.get("grasp"):
        complete_gripper_states(plan, repairs["grasp"])
    if plan.suction:
        _write(repaired_urdf, suction.with_tcp_link(_read(repaired_urdf), plan.suction))
    return Analysis(model=model, plan=plan, repairs=repairs, urdf=repaired_urdf)


def config_files(urdf: str, answers: str = "", previous_srdf: str | None = None) -> dict[str, str]:
    """The config files `generate` writes for this description and answers file ({package-relative path: text}:
    config/<robot>.srdf, kinematics.yaml, joint_limits.yaml, controllers.yaml, hardware.yaml and, with a gripper,
    grasping.yaml), without a package around them: for a description package that keeps its own config
    (sixdof_description). previous_srdf: an earlier SRDF of the robot, whose hand-written group states and
    disabled pairs are kept (templates.srdf_skeleton). Raises what `generate` raises on bad input."""
    loaded = load_answers(answers)
    urdf_text = load_description(urdf, {})
    env = core_environment(urdf)
    with tempfile.TemporaryDirectory(prefix="setup_assistant.") as tmp:
        # The core looks for packages in the three folders above the URDF it reads before ROS_PACKAGE_PATH: nested
        # three deep, those hold this run's files only (not another checkout of the package beside the temp folder).
        work = os.path.join(tmp, "run", "work")
        os.makedirs(work)
        analysis = _analyze(urdf_text, loaded, env, work)
        srdf_in = os.path.join(work, "skeleton.srdf")
        _write(srdf_in, templates.srdf_skeleton(analysis.plan, previous_srdf))
        srdf, report, _density, _seed = _collision_matrix(analysis, srdf_in, loaded, work, env, echo=False)
    return _config(analysis, report, srdf, loaded)


def _collision_matrix(analysis: Analysis, srdf_in: str, answers: dict[str, Any], work: str, env: dict[str, str],
                      density: int | None = None, seed: int | None = None,
                      echo: bool = True) -> tuple[str, dict[str, Any], int, int]:
    """The core's SRDF (srdf_in with the disabled collision pairs) and its report of the model with it; the
    density and seed it sampled with (the options', else the answers', else the defaults)."""
    density = density or answers.get("density") or 10000
    seed = seed if seed is not None else answers.get("seed", 0)
    srdf_out = os.path.join(work, "out.srdf")
    report_path = os.path.join(work, "report.yaml")
    run_core(["--urdf", analysis.urdf, "--srdf-in", srdf_in, "--srdf-out", srdf_out, "--describe", report_path,
              "--density", str(density), "--seed", str(seed)], echo=echo, env=env)
    report = yaml.safe_load(_read(report_path))
    plan = analysis.plan
    arm_report = next((g for g in report["groups"] if g["name"] == plan.arm.name), None)
    if plan.arm.solver and arm_report and plan.arm.solver == "analytic" and arm_report["solver"] != "analytic":
        raise GenerationError(f"answers arm.solver: analytic does not fit group '{plan.arm.name}': "
                              f"{arm_report['solver_reason']}")
    return _read(srdf_out), report, density, seed


def _config(analysis: Analysis, report: dict[str, Any], srdf: str, answers: dict[str, Any]) -> dict[str, str]:
    """The config/ files of a package: the core's SRDF and the YAML rendered from the plan and the core's report."""
    plan = analysis.plan
    files = {
        f"config/{plan.robot}.srdf": srdf,
        "config/kinematics.yaml": templates.kinematics_yaml(plan, report),
        "config/joint_limits.yaml": templates.joint_limits_yaml(report, answers),
        "config/controllers.yaml": templates.controllers_yaml(plan),
        "config/hardware.yaml": real_robot.hardware_yaml(
            real_robot.hardware_joints([j for g in (plan.arm, plan.gripper) if g for j in g.joints], report["joints"]),
            f"# {templates.HEADER}."),
    }
    if plan.suction:
        files["config/grasping.yaml"] = suction.grasping_yaml(plan)
    elif templates.has_grasping(plan):
        files["config/grasping.yaml"] = grasping.grasping_yaml(plan, analysis.repairs, answers)
    return files


def _generate(options: Options, answers: dict[str, Any], urdf_text: str, out_dir: str, staging_root: str) -> Result:
    work = os.path.join(staging_root, "work")
    os.makedirs(work)
    env = core_environment(options.urdf)
    analysis = _analyze(urdf_text, answers, env, work)
    model, plan, repairs = analysis.model, analysis.plan, analysis.repairs
    urdf_text = _read(analysis.urdf)
    name = options.name or answers.get("name") or f"{model['robot'].lower()}_sixdof_config"
    if not PACKAGE_NAME.match(name):
        raise GenerationError(f"package name '{name}' is not a valid ROS package name (^[a-z][a-z0-9_]*$)")
    target = os.path.join(out_dir, name)
    if os.path.exists(target) and not os.path.isdir(target):
        raise GenerationError(f"{target}: is a file, not a folder")
    manifest: dict[str, Any] = {}
    if os.path.isdir(target):
        if not os.path.isfile(os.path.join(target, MANIFEST)):
            raise GenerationError(f"{target}: exists and was not generated by setup_assistant (no {MANIFEST})")
        manifest = yaml.safe_load(_read(os.path.join(target, MANIFEST))) or {}
    hashes: dict[str, str] = manifest.get("files", {})

    def edited(rel: str) -> bool:
        path = os.path.join(target, rel)
        return os.path.isfile(path) and rel in hashes and _sha(_read(path)) != hashes[rel]

    urdf_rel = f"urdf/{plan.robot}.urdf"
    srdf_rel = f"config/{plan.robot}.srdf"
    if edited(urdf_rel):
        raise GenerationError(f"{os.path.join(target, urdf_rel)}: edited by hand; edit the source "
                              f"({options.urdf}) instead, or delete this file")
    result = Result(path=target)
    srdf_in = os.path.join(work, "skeleton.srdf")
    if edited(srdf_rel):
        shutil.copyfile(os.path.join(target, srdf_rel), srdf_in)
        result.srdf_hand_edits_kept = True
    else:
        _write(srdf_in, templates.srdf_skeleton(plan))
    srdf, report, density, seed = _collision_matrix(analysis, srdf_in, answers, work, env, options.density,
                                                    options.seed)
    result.report = report
    result.warnings = grasping.warnings(model, repairs)
    if result.srdf_hand_edits_kept:
        _sync_plan_with_srdf(plan, report)

    command = options.command or "setup_assistant --urdf " + shlex.quote(options.urdf)
    world_pack = packing_world.packing_world(plan, report, urdf_text, srdf,
                                             env["ROS_PACKAGE_PATH"].split(os.pathsep))
    if world_pack is None:
        result.warnings.append("no config/world_pack.yaml: no belt in front of the arm and box beside it that the "
                               "tool reaches pointing down")
    files = {
        "package.xml": templates.package_xml(name, plan),
        "CMakeLists.txt": templates.cmakelists(name),
        urdf_rel: urdf_text,
        **_config(analysis, report, srdf, answers),
        "config/world.yaml": templates.world_yaml(plan, report),
        **({"config/world_pack.yaml": world_pack} if world_pack else {}),
        "config/motion_planning.rviz": templates.rviz_config(plan, report),
        "launch/demo.launch": templates.demo_launch(name, plan),
        "launch/move_group.launch": templates.move_group_launch(name, plan),
        "launch/real.launch": real_robot.real_launch(name, plan.robot, templates.launch_files(name, plan),
                                                     templates.HEADER),
        "README.md": templates.readme(name, plan, report, command)
        + grasping.readme_sections(plan, model, repairs, answers) + packing_world.readme_section(name, world_pack),
    }
    staged = os.path.join(staging_root, name)
    os.makedirs(staged)
    # Whatever the user added to the package is carried over untouched; a file generated before that is no
    # longer generated (e.g. another robot name) goes unless it was edited.
    new_hashes: dict[str, str] = {}
    if os.path.isdir(target):
        for dirpath, _dirnames, filenames in os.walk(target):
            for filename in filenames:
                rel = os.path.relpath(os.path.join(dirpath, filename), target)
                if rel == MANIFEST or rel in files:
                    continue
                if rel in hashes and not edited(rel):
                    result.removed.append(rel)
                    continue
                if rel in hashes:
                    new_hashes[rel] = hashes[rel]
                    result.kept.append(rel)
                os.makedirs(os.path.join(staged, os.path.dirname(rel)), exist_ok=True)
                shutil.copy2(os.path.join(target, rel), os.path.join(staged, rel))
    for rel, text in files.items():
        existing = os.path.join(target, rel)
        if rel != srdf_rel and edited(rel):
            os.makedirs(os.path.dirname(os.path.join(staged, rel)), exist_ok=True)
            shutil.copy2(existing, os.path.join(staged, rel))
            new_hashes[rel] = hashes[rel]  # still "edited" next time
            result.kept.append(rel)
            continue
        if os.path.isfile(existing) and rel not in hashes and _read(existing) != text:
            # In the package but never generated by us (e.g. written by hand before the first run): keep it.
            result.kept.append(rel)
            new_hashes[rel] = _sha(text)
            continue
        _write(os.path.join(staged, rel), text)
        new_hashes[rel] = _sha(text)
        (result.regenerated if os.path.isfile(existing) else result.created).append(rel)
    manifest_data = {"generator": "sixdof_setup_assistant", "command": command,
                     "inputs": {"urdf": os.path.abspath(options.urdf), "xacro_args": options.xacro_args,
                                "answers": os.path.abspath(options.answers) if options.answers else None,
                                "density": density, "seed": seed},
                     "files": new_hashes}
    _write(os.path.join(staged, MANIFEST),
           "# Written by setup_assistant: what it generated (sha256), to tell hand edits apart. Do not edit.\n"
           + yaml.safe_dump(manifest_data, sort_keys=False))
    os.makedirs(out_dir, exist_ok=True)
    if os.path.isdir(target):
        old = os.path.join(staging_root, "previous")
        os.rename(target, old)
        try:
            os.rename(staged, target)
        except OSError:
            os.rename(old, target)
            raise
    else:
        os.rename(staged, target)
    return result


def _sync_plan_with_srdf(plan: Any, report: dict[str, Any]) -> None:
    """With a hand-edited SRDF, the config files follow its groups (as the core read them)."""
    groups = {g["name"]: g for g in report["groups"]}
    for group in (plan.arm, plan.gripper):
        if group is None:
            continue
        if group.name in groups:
            group.joints = [j for j in groups[group.name]["joints"]
                            if any(k["name"] == j and k["type"] != "fixed" for k in report["joints"])]
    if plan.gripper and plan.gripper.name not in groups:
        plan.gripper = None
    if plan.arm.name not in groups:
        raise GenerationError(f"the hand-edited SRDF has no group '{plan.arm.name}' (the arm group)")
