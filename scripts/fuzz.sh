#!/usr/bin/env bash
# The fuzz rostest (test/ros/faults_headless.test) with more requests than `make test` sends:
#   scripts/fuzz.sh [requests per service, default 500] [seed, default 13]
set -uo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
# shellcheck source=scripts/env.sh
. scripts/env.sh
# The tests package runs from its source folder (as colcon test runs it).
export ROS_PACKAGE_PATH="$repo/test:${ROS_PACKAGE_PATH:-}"
rostest --text test/ros/faults_headless.test fuzz_requests:="${1:-500}" fuzz_seed:="${2:-13}"
