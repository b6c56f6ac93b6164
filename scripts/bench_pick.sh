#!/usr/bin/env bash
# Randomized pick-and-place benchmark and soak on a headless stack of its own, then the "pick" (or "soak") section
# of bench/results.md. The sixdof arm by default (sixdof_bringup's demo.launch headless:=true on an empty table,
# sixdof_sim/worlds/table_only.yaml); with --config, any config package the setup assistant generated (its
# demo.launch headless:=true and its own world, a table under the robot), in a section "pick, <package>".
#   scripts/bench_pick.sh                    100 seeded trials (make bench-pick)
#   scripts/bench_pick.sh --soak             500 trials with every node's RSS sampled (make soak); fails on any
#                                            failed trial or a node growing by more than 5 MB
#   scripts/bench_pick.sh --config PKG       the robot of config package PKG: a package name on ROS_PACKAGE_PATH,
#                                            or its folder (make bench-pick CONFIG=PKG, make soak CONFIG=PKG)
#   scripts/bench_pick.sh [--soak] [--config PKG] ARGS...   ARGS go to bench/pick_bench.py (--trials, --seed, ...)
#   scripts/bench_pick.sh --only 35 220      replay trials 35 and 220 of the seeded sequence (results.md untouched)
# Logs in artifacts/bench_pick_logs/.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
# shellcheck source=scripts/stack_lib.sh
. scripts/stack_lib.sh

args=()  # pick_bench.py: 100 trials
config=""
while [ $# -gt 0 ]; do
  case "$1" in
    --soak) args+=(--trials 500 --rss); shift ;;
    --config) [ $# -ge 2 ] && [ -n "$2" ] || { echo "bench_pick.sh: --config needs a package" >&2; exit 2; }
              config=$2; shift 2 ;;
    *) break ;;
  esac
done
if [ -n "$config" ] && [ -d "$config" ]; then
  # A package folder: its parent goes on ROS_PACKAGE_PATH.
  config=$(cd "$config" && pwd)
  export ROS_PACKAGE_PATH=$(dirname "$config")${ROS_PACKAGE_PATH:+:$ROS_PACKAGE_PATH}
  config=$(basename "$config")
fi
stack_init "$repo/artifacts/bench_pick_logs"
report=$stack_work/report.md

echo "[bench-pick] launching the headless stack (master port $stack_port)${config:+ of $config}"
if [ -n "$config" ]; then
  rospack find "$config" >/dev/null || { echo "bench_pick.sh: no package '$config' on ROS_PACKAGE_PATH" >&2; exit 2; }
  args+=(--label "$config")
  stack_start launch roslaunch -p "$stack_port" "$config" demo.launch headless:=true
else
  stack_start launch roslaunch -p "$stack_port" sixdof_bringup demo.launch headless:=true \
    world:="$repo/sixdof_sim/worlds/table_only.yaml"
fi
stack_wait_ready "" "${stack_pids[-1]}" || { echo "[bench-pick] the stack did not come up (see $ROS_LOG_DIR/launch.out)" >&2; exit 1; }

status=0
python3 bench/pick_bench.py "${args[@]}" "$@" --report "$report" || status=$?
if [[ " $* " == *" --only "* ]]; then
  echo "[bench-pick] a replay of some trials (--only): bench/results.md left as it is"
elif [ -s "$report" ]; then
  python3 scripts/results_section.py bench/results.md "$report"
  echo "[bench-pick] wrote its section of bench/results.md"
fi
exit $status
