#!/usr/bin/env bash
# Runs every test: builds with tests enabled (the same package selection), static checks (ruff,
# catkin_lint, generated files), then colcon test (gtest, rostest, pytest) of all packages. Results are
# aggregated from the JUnit files, because `colcon test` exits 0 when tests fail. Exits non-zero on any
# failure or on zero tests.
#   scripts/test.sh [colcon test args, e.g. --packages-select sixdof_core]
set -uo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
# shellcheck source=scripts/env.sh
. scripts/env.sh
status=0

# The build gets the package selection (--packages-*) of the arguments, not test-only ones (--ctest-args ...).
build_args=()
selecting=0
for arg in "$@"; do
  case "$arg" in
    --packages-*) selecting=1; build_args+=("$arg") ;;
    --*) selecting=0 ;;
    *) [ $selecting = 1 ] && build_args+=("$arg") ;;
  esac
done
echo "== build (tests enabled)"
SIXDOF_BUILD_TESTS=ON scripts/build.sh "${build_args[@]}" || exit 1
# The install space as this build left it (a fresh clone has none before): tests find packages they cannot depend
# on (sixdof_core's and sixdof_setup_assistant's tests: the sixdof arm of sixdof_description) on its ROS_PACKAGE_PATH.
# shellcheck source=scripts/env.sh
. scripts/env.sh

echo "== ruff"
ruff check . || status=1

echo "== catkin_lint"
catkin_lint -W1 --strict --ignore missing_directory --ignore unknown_package . || status=1

rm -rf build/*/test_results
# Each rostest starts its own master on a random port; one package at a time keeps the 2 cores sane.
# colcon keeps only the last --ctest-args: --output-on-failure joins the caller's (e.g. --ctest-args -R name).
test_args=("$@")
if printf '%s\n' "$@" | grep -qx -- --ctest-args; then
  test_args+=(--output-on-failure)
else
  test_args+=(--ctest-args --output-on-failure)
fi
colcon test --merge-install --event-handlers console_direct- console_cohesion+ summary+ \
  --executor sequential "${test_args[@]}" || status=1

echo "== results"
python3 scripts/junit_summary.py build || status=1
exit $status
