#!/usr/bin/env bash
# The end-to-end demo, headless: simulator in real time + move_group + scene mirroring (demo.launch rviz:=false), then
# the paper's pick-and-place (pick_place.py), verified independently (object_at.py). Saves into artifacts/:
#   demo_result.png   rviz screenshot of the final scene (rviz on a virtual X display)
#   demo_joints.png   the joint trajectories, plotted from the recorded /joint_states
#   demo.bag          the recording (/joint_states, /grasp_events, sixdof_sim/object_states)
#   demo_logs/        ROS logs
# Exits 0 only if the object ends at the place location. `make demo` runs setup first, then this.
#   scripts/demo.sh [--object red_cube] [--place X Y] [--repetitions N]   (passed to pick_place.py)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"

object=red_cube
place_x=0.40
place_y=0.20
extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --object) object=$2; shift 2 ;;
    --place) place_x=$2; place_y=$3; shift 3 ;;
    *) extra+=("$1"); shift ;;
  esac
done

artifacts=$repo/artifacts
mkdir -p "$artifacts"
# A master of our own on a free port (other ROS graphs on this machine are left alone); background jobs in their
# own process groups, stopped on exit (scripts/stack_lib.sh).
# shellcheck source=scripts/stack_lib.sh
. scripts/stack_lib.sh
stack_init "$artifacts/demo_logs"
work=$stack_work
port=$stack_port


stage "1/6 launching the simulator (real time), move_group and the scene mirror (master port $port)"
# Real time, as the end-to-end tests run: a free-running simulator (headless:=true) can outrun its consumers
# on a loaded 2-core machine (robot_state_publisher drops states, sim-time timeouts shrink to fractions of a
# wall second).
stack_start demo_launch roslaunch -p "$port" sixdof_bringup demo.launch rviz:=false
stack_wait_ready "$object" "${stack_pids[-1]}" || fail "the stack did not come up (see $ROS_LOG_DIR/demo_launch.out)"

stage "2/6 recording /joint_states, /grasp_events and object states"
stack_start rosbag rosbag record -O "$work/demo.bag" /joint_states /grasp_events /sixdof_sim/object_states
bag_pid=${stack_pids[-1]}

stage "3/6 pick and place: '$object' -> ($place_x, $place_y)"
pick_status=0
rosrun sixdof_scripts pick_place.py --object "$object" --place "$place_x" "$place_y" ${extra[@]+"${extra[@]}"} \
  || pick_status=$?
kill -INT -- "-$bag_pid" 2>/dev/null || true
for _ in $(seq 50); do kill -0 -- "-$bag_pid" 2>/dev/null || break; sleep 0.2; done

stage "4/6 checking where '$object' rests"
check_status=0
rosrun sixdof_bringup object_at.py "$object" "$place_x" "$place_y" --tolerance 0.01 || check_status=$?

stage "5/6 plotting the joint trajectories"
cp "$work/demo.bag" "$artifacts/demo.bag" 2>/dev/null || mv "$work"/demo.bag.active "$artifacts/demo.bag"
rosrun sixdof_bringup plot_joint_states.py "$artifacts/demo.bag" "$artifacts/demo_joints.png" \
  || fail "plotting the joint trajectories"

stage "6/6 rviz screenshot of the result (virtual X display)"
stack_rviz_screenshot "$artifacts/demo_result.png" || fail "rviz screenshot (see $ROS_LOG_DIR/rviz.out)"

echo
echo "[demo] artifacts:"
echo "  screenshot of the result: $artifacts/demo_result.png"
echo "  joint trajectories:       $artifacts/demo_joints.png"
echo "  recording:                $artifacts/demo.bag"
echo "  ROS logs:                 $ROS_LOG_DIR"
if [ $pick_status != 0 ] || [ $check_status != 0 ]; then
  fail "pick_place.py exit code $pick_status, placement check exit code $check_status"
fi
printf '\n\033[1;32m[demo] pick and place succeeded: %s rests at (%s, %s)\033[0m\n' "$object" "$place_x" "$place_y"
