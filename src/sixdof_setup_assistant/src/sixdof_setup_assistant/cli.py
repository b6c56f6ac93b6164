"""`rosrun sixdof_setup_assistant setup_assistant`: the command line (run it with --help)."""

from __future__ import annotations

import argparse
import os
import shlex
import sys
import tempfile

from .answers import AnswersError
from .generator import GenerationError, Options, core_environment, generate, run_core
from .infer import InferenceError
from .xacro_loader import DescriptionError, load_description, parse_xacro_args

USAGE = """\
setup_assistant --urdf FILE --package-out DIR [--name NAME] [--answers FILE] [--density N] [--seed S]
                [--xacro-args "name:=value ..."]
setup_assistant --urdf FILE --srdf-out FILE [--srdf-in FILE] [--density N] [--seed S] [--groups-skeleton]
                [--xacro-args "name:=value ..."]"""

DESCRIPTION = """\
Generates a ready sixdof config package for a robot (URDF or xacro): SRDF (groups, end effector, named states,
self-collision matrix), kinematics.yaml, joint_limits.yaml, controllers.yaml, a world with a table, launch files
(demo.launch, move_group.launch), an rviz config and a README, in DIR/NAME (default NAME: <robot>_sixdof_config).
Then `ROS_PACKAGE_PATH=DIR:$ROS_PACKAGE_PATH roslaunch NAME demo.launch`. Choices are inferred (arm = the longest
serial chain of actuated joints from the root, gripper = the moving joints after the arm's tip, home = zeros
clamped into the limits, gripper open/close = the ends of the finger joints' ranges where the pads are furthest
apart / closest, the grasp frame (TCP) between the pads, analytic IK where the closed form fits; moving links
without a usable inertia get one computed from their geometry, and each such repair is a warning);
--answers FILE overrides any of them (format: docs/your_own_arm.md). Re-running keeps files edited by hand and
the SRDF's hand-written parts, and lists what it regenerates. With --srdf-out: only the SRDF (its collision
matrix; the hand-written parts of --srdf-in are kept). Bad input: one line naming the problem, exit code 2,
nothing written."""


class UsageError(Exception):
    pass


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> None:  # one line instead of argparse's usage block
        raise UsageError(message)


def _positive(text: str) -> int:
    if not text.isdigit() or int(text) == 0:
        raise argparse.ArgumentTypeError(f"must be a whole number > 0, got '{text}'")
    return int(text)


def _whole(text: str) -> int:
    if not text.isdigit():
        raise argparse.ArgumentTypeError(f"must be a whole number >= 0, got '{text}'")
    return int(text)


def parser() -> argparse.ArgumentParser:
    p = _Parser(prog="setup_assistant", usage=USAGE, description=DESCRIPTION,
                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--urdf", required=True, help="robot description: .urdf, or .xacro (expanded with --xacro-args; "
                   "$(find pkg) resolves through ROS_PACKAGE_PATH)")
    p.add_argument("--xacro-args", default="", help='xacro arguments, e.g. "prefix:=left_ hand:=true"')
    p.add_argument("--package-out", help="folder the config package is written into (as DIR/NAME)")
    p.add_argument("--name", default="", help="package name (default: answers' name, else <robot>_sixdof_config)")
    p.add_argument("--answers", default="", help="YAML overriding inferred choices (docs/your_own_arm.md)")
    p.add_argument("--density", type=_positive, help="self-collision samples (1000 low .. 100000 high; "
                   "default 10000)")
    p.add_argument("--seed", type=_whole, help="sampling seed (default 0); the same inputs give the same files")
    p.add_argument("--srdf-out", help="SRDF-only mode: where to write the SRDF")
    p.add_argument("--srdf-in", help="SRDF-only mode: an SRDF whose hand-written parts are kept")
    p.add_argument("--groups-skeleton", action="store_true",
                   help="SRDF-only mode: write arm/gripper groups when --srdf-in has none")
    return p


def _srdf_only(args: argparse.Namespace, mappings: dict[str, str]) -> None:
    urdf_text = load_description(args.urdf, mappings)
    with tempfile.TemporaryDirectory(prefix="setup_assistant.") as work:
        urdf = os.path.join(work, os.path.basename(args.urdf).removesuffix(".xacro"))
        with open(urdf, "w", encoding="utf-8") as file:
            file.write(urdf_text)
        core_args = ["--urdf", urdf, "--srdf-out", args.srdf_out]
        if args.srdf_in:
            core_args += ["--srdf-in", args.srdf_in]
        if args.density:
            core_args += ["--density", str(args.density)]
        if args.seed is not None:
            core_args += ["--seed", str(args.seed)]
        if args.groups_skeleton:
            core_args.append("--groups-skeleton")
        run_core(core_args, env=core_environment(args.urdf))


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    try:
        args = parser().parse_args(argv)
        if bool(args.package_out) == bool(args.srdf_out):
            raise UsageError("give exactly one of --package-out and --srdf-out")
        if args.package_out and (args.srdf_in or args.groups_skeleton):
            raise UsageError("--srdf-in and --groups-skeleton belong to the --srdf-out mode")
        if args.srdf_out and (args.name or args.answers):
            raise UsageError("--name and --answers belong to the --package-out mode")
        mappings = parse_xacro_args(args.xacro_args)
        if args.srdf_out:
            _srdf_only(args, mappings)
            return 0
        command = "rosrun sixdof_setup_assistant setup_assistant " + " ".join(shlex.quote(a) for a in argv)
        result = generate(Options(urdf=args.urdf, package_out=args.package_out, name=args.name, answers=args.answers,
                                  density=args.density, seed=args.seed, xacro_args=mappings, command=command))
    except (UsageError, DescriptionError, AnswersError, InferenceError, GenerationError) as error:
        print(f"setup_assistant: {' '.join(str(error).split())}", file=sys.stderr)
        return 2
    except OSError as error:  # e.g. an output folder without write permission
        print(f"setup_assistant: {error.filename or ''}: {error.strerror or error}", file=sys.stderr)
        return 2
    for warning in result.warnings:
        print(f"setup_assistant: warning: {warning}", file=sys.stderr)
    for label, files in (("created", result.created), ("regenerated", result.regenerated),
                         ("kept (edited by hand; delete to regenerate)", result.kept),
                         ("removed (no longer generated)", result.removed)):
        if files:
            print(f"{label}: {', '.join(files)}")
    if result.srdf_hand_edits_kept:
        print("SRDF edited by hand: its groups, states, end effectors and virtual joints kept, collision pairs "
              "recomputed")
    for group in result.report["groups"]:
        if group["chain"]:
            print(f"group {group['name']}: IK {group['solver']} ({group['solver_reason']})")
    print(f"wrote {result.path}")
    return 0
