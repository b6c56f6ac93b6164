#!/usr/bin/env bash
# colcon build of every package under the repository root (merge install).
# Defaults keep a fresh build cheap: Release without debug info, no tests, no benchmarks.
#   SIXDOF_BUILD_TYPE=RelWithDebInfo scripts/build.sh   debug info (profilers, gdb)
#   SIXDOF_BUILD_TESTS=ON                                 gtests and rostest targets (scripts/test.sh sets it)
#   SIXDOF_BUILD_BENCHMARKS=ON                            benchmark executables (scripts/bench.sh sets it)
# ccache is used when it is installed (scripts/apt-packages.txt installs it).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
set +u
# shellcheck disable=SC1091
. "${SIXDOF_VENV:-$repo/.venv}/bin/activate"
set -u
cmake_args=(
  -DCMAKE_BUILD_TYPE="${SIXDOF_BUILD_TYPE:-Release}"
  -DCATKIN_ENABLE_TESTING="${SIXDOF_BUILD_TESTS:-OFF}"
  -DSIXDOF_BUILD_BENCHMARKS="${SIXDOF_BUILD_BENCHMARKS:-OFF}"
  -DCMAKE_EXPORT_COMPILE_COMMANDS=ON
)
if command -v ccache >/dev/null; then
  cmake_args+=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
# colcon keeps only the last --cmake-args: a caller's cmake arguments are appended to ours instead.
colcon_args=()
in_cmake_args=0
for arg in "$@"; do
  if [ "$arg" = --cmake-args ]; then
    in_cmake_args=1
  elif [ $in_cmake_args = 1 ] && [[ "$arg" != --* ]]; then
    cmake_args+=("$arg")
  else
    in_cmake_args=0
    colcon_args+=("$arg")
  fi
done
# The first build has no install space yet; an empty one keeps catkin's test env cache happy.
mkdir -p install/lib/python3/dist-packages
colcon build --merge-install --event-handlers console_direct- console_cohesion+ summary+ \
  "${colcon_args[@]}" --cmake-args "${cmake_args[@]}"
