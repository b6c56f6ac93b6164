#!/usr/bin/env bash
# Packing benchmark on a stack of its own (make bench-pack): demo.launch rviz:=false (the simulator in real time: the
# picks are timed to the objects on ROS time) on bench/pack_world.yaml (or --world), then bench/pack_bench.py, which
# writes the "pack" section of bench/results.md ("pack, suction" with --tool suction: demo_suction.launch, the sixdof
# arm's suction variant).
#   scripts/bench_pack.sh                          0.2 m/s with 100 objects, 0.1 and 0.3 m/s with 10 each
#   scripts/bench_pack.sh --runs 0.2:20 ...        ARGS go to bench/pack_bench.py (--tool, --runs, --interval, ...)
#   scripts/bench_pack.sh --world FILE ARGS...     another world file (pack_bench.py packs from its first conveyor
#                                                  into its first bin unless --conveyor, --box)
# Logs in artifacts/bench_pack_logs/.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
world=$repo/bench/pack_world.yaml
if [ "${1:-}" = --world ]; then
  [ $# -ge 2 ] && [ -f "$2" ] || { echo "bench_pack.sh: error: --world needs a world file, got '${2:-}'" >&2; exit 2; }
  world=$(cd "$(dirname "$2")" && pwd)/$(basename "$2")
  shift 2
fi
# shellcheck source=scripts/stack_lib.sh
. scripts/stack_lib.sh

launch=$(python3 bench/pack_bench.py --launch-file "$@") || exit 2
stack_init "$repo/artifacts/bench_pack_logs"
report=$stack_work/report.md
echo "[bench-pack] launching $launch in real time (master port $stack_port)"
stack_start launch roslaunch -p "$stack_port" sixdof_bringup "$launch" rviz:=false world:="$world"
stack_wait_ready belt "${stack_pids[-1]}" || { echo "[bench-pack] the stack did not come up (see $ROS_LOG_DIR/launch.out)" >&2; exit 1; }

status=0
python3 bench/pack_bench.py "$@" --report "$report" || status=$?
if [ -s "$report" ]; then
  python3 scripts/results_section.py bench/results.md "$report"
  echo "[bench-pack] wrote its section of bench/results.md"
fi
exit $status
