#!/usr/bin/env bash
# Packing from a running belt, without a screen (make demo-pack): demo.launch rviz:=false (the simulator in real time:
# the picks are timed to the objects on ROS time) on sixdof_sim/worlds/packing.yaml, whose source puts objects onto a
# belt running at 0.2 m/s, then pack_objects.py fills the box 2x2. Saves into artifacts/:
#   pack_box.png      the box_cam camera's rendering of the filled box
#   pack_picks.png    picks over time with the belt speed (matplotlib)
#   pack_result.json  every arriving object's outcome (pack_objects.py --json)
#   demo_pack_logs/   ROS logs
# Exits with pack_objects.py's code: 0 only if every slot holds its object upright.
#   scripts/demo_pack.sh [--tool fingers|suction] [pack_objects.py args]   (e.g. --pattern 2x2)
# --tool suction: demo_suction.launch, the sixdof arm's suction variant (default: fingers, demo.launch).
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
launch=demo.launch
if [ "${1:-}" = --tool ]; then
  case "${2:-}" in
    fingers) ;;
    suction) launch=demo_suction.launch ;;
    *) echo "demo_pack.sh: error: --tool must be fingers or suction, got '${2:-}'" >&2; exit 2 ;;
  esac
  shift 2
fi
# shellcheck source=scripts/stack_lib.sh
. scripts/stack_lib.sh

artifacts=$repo/artifacts
mkdir -p "$artifacts"
stack_init "$artifacts/demo_pack_logs"


stage "1/3 launching the simulator and move_group with $launch (master port $stack_port)"
stack_start launch roslaunch -p "$stack_port" sixdof_bringup "$launch" rviz:=false \
  world:="$repo/sixdof_sim/worlds/packing.yaml"
stack_wait_ready belt "${stack_pids[-1]}" || fail "the stack did not come up (see $ROS_LOG_DIR/launch.out)"

stage "2/3 packing what the belt brings"
pack_status=0
rosrun sixdof_scripts pack_objects.py --box box --pattern 2x2 --json "$artifacts/pack_result.json" "$@" \
  || pack_status=$?

stage "3/3 the camera's picture of the box and the plot of picks over time"
python3 scripts/pack_pictures.py camera box_cam "$artifacts/pack_box.png" || fail "camera picture"
python3 scripts/pack_pictures.py plot "$artifacts/pack_result.json" "$artifacts/pack_picks.png" || fail "plot"

echo
echo "[demo-pack] artifacts:"
echo "  the filled box:        $artifacts/pack_box.png"
echo "  picks over time:       $artifacts/pack_picks.png"
echo "  outcomes:              $artifacts/pack_result.json"
echo "  ROS logs:              $ROS_LOG_DIR"
[ $pack_status = 0 ] || fail "pack_objects.py exit code $pack_status"
printf '\n\033[1;32m[demo-pack] every slot holds its object upright\033[0m\n'
