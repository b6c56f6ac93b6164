#!/usr/bin/env bash
# Vision-based sorting benchmark on a headless stack of its own (demo.launch headless:=true perception:=true on
# sixdof_sim/worlds/sorting.yaml): seeded random layouts, detection accuracy against the simulator's ground truth
# and sorting success (bench/sort_bench.py), then the "sort" section of bench/results.md.
#   scripts/bench_sort.sh                    50 layouts, stopping after 60 minutes (make bench-sort)
#   scripts/bench_sort.sh --depth-noise S    the world's cameras get Gaussian depth noise of S m (standard
#                                            deviation; their depth_noise_stddev): the "sort with depth noise" section
#   scripts/bench_sort.sh ARGS...            ARGS go to bench/sort_bench.py (--layouts, --seed, --max-minutes, ...)
# Logs in artifacts/bench_sort_logs/.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
# shellcheck source=scripts/stack_lib.sh
. scripts/stack_lib.sh

world=$repo/sixdof_sim/worlds/sorting.yaml
noise=0
args=()
while [ $# -gt 0 ]; do
  case $1 in
    --depth-noise) [ $# -ge 2 ] || { echo "bench_sort.sh: --depth-noise needs a value (m)" >&2; exit 2; }
                   noise=$2; shift 2 ;;
    --depth-noise=*) noise=${1#*=}; shift ;;
    *) args+=("$1"); shift ;;
  esac
done
stack_init "$repo/artifacts/bench_sort_logs"
report=$stack_work/report.md

if [ "$noise" != 0 ]; then
  # The same world with noisy cameras (the simulator checks the value again and names the key).
  python3 - "$world" "$noise" "$stack_work/sorting_noisy.yaml" <<'PYEOF' || exit 2
import math
import sys

import yaml

source, noise, target = sys.argv[1:]
try:
    sigma = float(noise)
except ValueError:
    sigma = math.nan
if not (math.isfinite(sigma) and sigma >= 0.0):
    sys.exit(f"bench_sort.sh: --depth-noise must be a number >= 0 (m), got {noise!r}")
with open(source, encoding="utf-8") as stream:
    world = yaml.safe_load(stream)
for camera in world.get("cameras") or []:
    camera["depth_noise_stddev"] = sigma
with open(target, "w", encoding="utf-8") as out:
    yaml.safe_dump(world, out, sort_keys=False)
PYEOF
  world=$stack_work/sorting_noisy.yaml
fi

echo "[bench-sort] launching the headless stack (master port $stack_port)"
stack_start launch roslaunch -p "$stack_port" sixdof_bringup demo.launch headless:=true world:="$world" perception:=true
stack_wait_ready table "${stack_pids[-1]}" || { echo "[bench-sort] the stack did not come up (see $ROS_LOG_DIR/launch.out)" >&2; exit 1; }

status=0
python3 bench/sort_bench.py --depth-noise "$noise" "${args[@]}" --report "$report" || status=$?
if [ -s "$report" ]; then
  python3 scripts/results_section.py bench/results.md "$report"
  echo "[bench-sort] wrote its section of bench/results.md"
fi
exit $status
