#!/usr/bin/env python3
"""Regenerates sixdof_description's meshes, URDF, SRDF and config YAML from config/design.yaml.

  generate_description.py                      write into the package (source tree when run from it)
  generate_description.py --check              exit 1 if a committed file differs from the generator's
  generate_description.py --output-dir DIR     write elsewhere (the previous SRDF is read from DIR)
  generate_description.py --tool suction       the arm with the suction cup (default: the design's `tool`):
                                               urdf/sixdof_suction.urdf, config/suction/, meshes/*/cup.stl
"""

import argparse
import sys
from pathlib import Path

import rospkg

from sixdof_description.cad import DesignError
from sixdof_description.generator import generate_files, generated_files, write_files
from sixdof_description.robot_design import TOOLS, load_design


def package_dir() -> Path:
    """The source tree this script lives in, else the package found by rospack."""
    here = Path(__file__).resolve().parent.parent
    if (here / "package.xml").is_file() and (here / "config" / "design.yaml").is_file():
        return here
    return Path(rospkg.RosPack().get_path("sixdof_description"))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--package-dir", type=Path, help="package whose config/design.yaml is read")
    parser.add_argument("--output-dir", type=Path, help="where to write (default: the package dir)")
    parser.add_argument("--check", action="store_true", help="compare instead of writing; exit 1 on a difference")
    parser.add_argument("--tool", choices=TOOLS, help="the arm's tool (default: the design's `tool`)")
    args = parser.parse_args()
    pkg = args.package_dir or package_dir()
    out = args.output_dir or pkg
    try:
        design = pkg / "config" / "design.yaml"
        tool = args.tool or load_design(design).get("tool", TOOLS[0])
        srdf = out / generated_files(tool)[1]
        previous = srdf.read_text(encoding="utf-8") if srdf.is_file() else None
        files = generate_files(design, previous, tool)
    except DesignError as error:
        print(f"generate_description.py: {error}", file=sys.stderr)
        return 2
    if args.check:
        stale = [rel for rel, data in files.items() if not (out / rel).is_file() or (out / rel).read_bytes() != data]
        for rel in stale:
            print(f"out of date: {out / rel}", file=sys.stderr)
        return 1 if stale else 0
    write_files(files, out)
    print(f"wrote {len(files)} files under {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
