#!/usr/bin/env bash
# colcon build of every package under the repository root (merge install, Release with debug info).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
set +u
# shellcheck disable=SC1091
. "${SIXDOF_VENV:-$repo/.venv}/bin/activate"
set -u
# The first build has no install space yet; an empty one keeps catkin's test env cache happy.
mkdir -p install/lib/python3/dist-packages
colcon build --merge-install --event-handlers console_direct- console_cohesion+ summary+ \
  --cmake-args -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_EXPORT_COMPILE_COMMANDS=ON "$@"
