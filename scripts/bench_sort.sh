#!/usr/bin/env bash
# Vision-based sorting benchmark on a headless stack of its own (demo.launch headless:=true perception:=true on
# sixdof_sim/worlds/sorting.yaml): seeded random layouts, detection accuracy against the simulator's ground truth
# and sorting success (bench/sort_bench.py), then the "sort" section of bench/results.md.
#   scripts/bench_sort.sh                    50 layouts, stopping after 60 minutes (make bench-sort)
#   scripts/bench_sort.sh ARGS...            ARGS go to bench/sort_bench.py (--layouts, --seed, --max-minutes, ...)
# Logs in artifacts/bench_sort_logs/.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
set +u
# shellcheck disable=SC1091
. scripts/env.sh
set -u
# shellcheck source=scripts/stack_lib.sh
. scripts/stack_lib.sh

world=$repo/sixdof_sim/worlds/sorting.yaml
stack_init "$repo/artifacts/bench_sort_logs"
report=$stack_work/report.md

echo "[bench-sort] launching the headless stack (master port $stack_port)"
stack_start launch roslaunch -p "$stack_port" sixdof_bringup demo.launch headless:=true world:="$world" perception:=true
stack_wait_ready table "${stack_pids[-1]}" || { echo "[bench-sort] the stack did not come up (see $ROS_LOG_DIR/launch.out)" >&2; exit 1; }

status=0
python3 bench/sort_bench.py --world "$world" "$@" --report "$report" || status=$?
if [ -s "$report" ]; then
  python3 scripts/results_section.py bench/results.md "$report"
  echo "[bench-sort] wrote its section of bench/results.md"
fi
exit $status
