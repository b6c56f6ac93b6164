# Sourced by the scripts that bring up a whole stack of their own (demo.sh, bench_pick.sh, ...): a ROS master
# on a free port (other ROS graphs on this machine are left alone), background jobs in their own process
# groups, all stopped on exit.
#   . scripts/stack_lib.sh
#   stack_init "$log_dir"              ROS_HOME in a temp dir, ROS_LOG_DIR=$log_dir, ROS_MASTER_URI on a free port
#   stack_start <log name> <cmd...>    in the background, in a new process group; output in $ROS_LOG_DIR/<name>.out
#   stack_rviz_screenshot <png>        rviz (sixdof_bringup rviz.launch.xml) on a virtual display, a shot of its window
#   stack_wait_ready [object [pid]]    wait until move_group answers (and the object is in the planning scene);
#                                      fails at once when process group pid (the launch) has ended
#   stage <words> / fail <words>       a demo's progress line / its failure (exit 1), tagged [$stack_tag]
# The caller's EXIT trap must call stack_cleanup (stack_init installs one that does).
# Sourcing it sources scripts/env.sh (the venv and the install space) first.

# shellcheck source=scripts/env.sh
. "$(dirname "${BASH_SOURCE[0]}")/env.sh"

stack_pids=()
stack_tag=$(basename "$0" .sh | tr _ -)

stage() { printf '\n\033[1m[%s] %s\033[0m\n' "$stack_tag" "$*"; }
fail() { printf '\033[1;31m[%s] FAILED: %s\033[0m\n' "$stack_tag" "$*" >&2; exit 1; }

stack_init() {
  stack_work=$(mktemp -d)
  export ROS_HOME=$stack_work/ros
  export ROS_LOG_DIR=$1
  rm -rf "$ROS_LOG_DIR"
  mkdir -p "$ROS_HOME" "$ROS_LOG_DIR"
  stack_port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
  export ROS_MASTER_URI=http://127.0.0.1:$stack_port
  trap stack_cleanup EXIT
  trap 'exit 130' INT TERM
}

stack_cleanup() {
  local status=$?
  trap - EXIT INT TERM
  # Gently first (roslaunch stops its nodes on SIGINT), then SIGKILL whatever is left of each group.
  for pid in "${stack_pids[@]}"; do kill -INT -- "-$pid" 2>/dev/null || true; done
  for _ in $(seq 50); do
    local alive=0
    for pid in "${stack_pids[@]}"; do kill -0 -- "-$pid" 2>/dev/null && alive=1; done
    [ $alive = 0 ] && break
    sleep 0.2
  done
  for pid in "${stack_pids[@]}"; do kill -KILL -- "-$pid" 2>/dev/null || true; done
  rm -rf "$stack_work"
  exit $status
}

stack_start() {
  setsid "${@:2}" >"$ROS_LOG_DIR/$1.out" 2>&1 &
  stack_pids+=($!)
}

stack_wait_ready() {
  python3 - "${1:-}" "${2:-}" <<'PYEOF'
# Ready = move_group answers (and the scene mirror has put the object into the planning scene).
import os
import sys
import time

import rospy
from moveit_msgs.msg import PlanningSceneComponents
from moveit_msgs.srv import GetPlanningScene


def launch_alive() -> bool:
    try:
        os.killpg(int(sys.argv[2]), 0) if sys.argv[2] else None
        return True
    except ProcessLookupError:
        return False


rospy.init_node("stack_wait", anonymous=True, disable_signals=True)
deadline = time.monotonic() + 180.0
while True:
    try:
        rospy.wait_for_service("get_planning_scene", timeout=1.0)
        break
    except rospy.ROSException:
        if not launch_alive() or time.monotonic() > deadline:
            sys.exit("move_group did not come up")
scene = rospy.ServiceProxy("get_planning_scene", GetPlanningScene)
names_only = PlanningSceneComponents(components=PlanningSceneComponents.WORLD_OBJECT_NAMES)
while time.monotonic() < deadline:
    names = [o.id for o in scene(names_only).scene.world.collision_objects]
    if not sys.argv[1] or sys.argv[1] in names:
        print(f"move_group is up; planning scene objects: {', '.join(sorted(names)) or 'none'}")
        sys.exit(0)
    if not launch_alive():
        sys.exit("the launch ended")
    time.sleep(0.2)
sys.exit(f"'{sys.argv[1]}' never appeared in the planning scene")
PYEOF
}

stack_rviz_screenshot() {
  # rviz and the marker node on their own display; the screenshot waits until the rviz window is mapped and has
  # had a few seconds to draw. It is of rviz's main window, whose size the rviz config sets: the virtual screen
  # around it (no window manager) would show as a black band. rviz's output goes to $ROS_LOG_DIR/rviz.out.
  # rviz on Mesa's software renderer dies in some starts (in its first frames): it is started again
  # (rviz_respawn), and the shot is taken of a window that is still there after the wait, up to four starts.
  stack_start rviz_screenshot xvfb-run -a -s "-screen 0 1280x1024x24" bash -c '
    roslaunch sixdof_bringup rviz.launch.xml rviz_respawn:=true >"$1/rviz.out" 2>&1 &
    pid=$!
    status=1
    for _ in 1 2 3 4; do
      window=""
      for _ in $(seq 300); do
        window=$(xwininfo -root -children 2>/dev/null | awk "/ - RViz\":/ {print \$1; exit}")
        [ -n "$window" ] && break
        sleep 0.2
      done
      [ -n "$window" ] || break
      sleep 8
      xwininfo -id "$window" >/dev/null 2>&1 || continue
      import -window "$window" "$2"
      status=$?
      break
    done
    kill -INT $pid
    wait $pid
    exit $status
  ' _ "$ROS_LOG_DIR" "$1"
  wait "${stack_pids[-1]}"
}
