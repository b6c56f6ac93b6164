#!/usr/bin/env bash
# Vision-based sorting, headless: demo.launch perception:=true on sixdof_sim/worlds/sorting.yaml (the planning scene
# is what the camera sees, no ground-truth mirror), then sort_objects.py. Saves into artifacts/:
#   sort_detections.png   the camera's image with the perception node's detections drawn (before sorting)
#   sort_result.png       rviz screenshot of the final scene (rviz on a virtual X display)
#   sort_result.json      each object's outcome and the simulator's final check
#   demo_sort_logs/       ROS logs
# Exits with sort_objects.py's code: 0 only if every object rests in the bin of its colour.
#   scripts/demo_sort.sh [--real-time]   (default: the simulator runs as fast as possible)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
# shellcheck source=scripts/stack_lib.sh
. scripts/stack_lib.sh

launch_args=(headless:=true)
if [ "${1:-}" = --real-time ]; then
  launch_args=(rviz:=false)
fi
world=$repo/sixdof_sim/worlds/sorting.yaml
artifacts=$repo/artifacts
mkdir -p "$artifacts"
stack_init "$artifacts/demo_sort_logs"


stage "1/4 launching the simulator, move_group and the perception node (master port $stack_port)"
stack_start launch roslaunch -p "$stack_port" sixdof_bringup demo.launch "${launch_args[@]}" world:="$world" \
  perception:=true
stack_wait_ready table "${stack_pids[-1]}" || fail "the stack did not come up (see $ROS_LOG_DIR/launch.out)"

stage "2/4 the camera image with the detections drawn"
rosrun sixdof_perception draw_detections.py "$artifacts/sort_detections.png" --camera table_cam \
  || fail "drawing the detections (see $ROS_LOG_DIR/launch.out)"

stage "3/4 sorting what the camera sees"
sort_status=0
rosrun sixdof_scripts sort_objects.py --json "$artifacts/sort_result.json" || sort_status=$?

stage "4/4 rviz screenshot of the result (virtual X display)"
stack_rviz_screenshot "$artifacts/sort_result.png" || fail "rviz screenshot (see $ROS_LOG_DIR/rviz.out)"

echo
echo "[demo-sort] artifacts:"
echo "  detections:         $artifacts/sort_detections.png"
echo "  rviz screenshot:    $artifacts/sort_result.png"
echo "  outcomes and check: $artifacts/sort_result.json"
echo "  ROS logs:           $ROS_LOG_DIR"
[ $sort_status = 0 ] || fail "sort_objects.py exit code $sort_status"
printf '\n\033[1;32m[demo-sort] every object rests in the bin of its colour\033[0m\n'
