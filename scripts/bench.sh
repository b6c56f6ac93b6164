#!/usr/bin/env bash
# Runs every benchmark executable (lib/<package>/*_bench in the install space) with its defaults, then the Python
# bindings against the C++ core (src/sixdof_core/bench/binding_bench.py), and writes the combined report to
# bench/results.md (kept in the repo; the README quotes it); then plots the scaling curves into bench/scaling_*.png
# (scripts/plot_scaling.py).
#   scripts/bench.sh                     all benchmarks
#   scripts/bench.sh ik_bench bindings   only the named ones ("bindings": the bindings' section alone); their sections
#                                        are replaced where they stand, every other section of bench/results.md stays
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
# shellcheck source=scripts/env.sh
. scripts/env.sh
SIXDOF_BUILD_BENCHMARKS=ON scripts/build.sh
# The install space as this build left it: the core's benchmarks find the sixdof arm on its ROS_PACKAGE_PATH.
# shellcheck source=scripts/env.sh
. scripts/env.sh
out=bench/results.md
mapfile -t benches < <(find install/lib -maxdepth 2 -type f -name '*_bench' -perm -u+x | sort)
bindings=1
if [ $# -gt 0 ]; then
  mapfile -t benches < <(printf '%s\n' "${benches[@]}" | grep -E "/($(IFS='|'; echo "$*"))$" || true)
  [[ " $* " == *" bindings "* ]] || bindings=0
fi
[ ${#benches[@]} -gt 0 ] || [ $bindings = 1 ] || {
  echo "no benchmark executables found under install/lib (build first)" >&2
  exit 1
}
# The benchmarks comparing the simulator with PyBullet run it in a venv of their own (the pinned version of
# scripts/requirements-bench.txt, made again when that file changes) and draw their plots into bench/.
if printf '%s\n' "${benches[@]}" | grep -qE '/sim_(vs_pybullet|scaling)_bench$'; then
  pybullet_venv=$repo/.venv-pybullet
  if ! cmp -s scripts/requirements-bench.txt "$pybullet_venv/requirements-bench.txt"; then
    rm -rf "$pybullet_venv"
    /usr/bin/python3 -m venv "$pybullet_venv"
    "$pybullet_venv/bin/pip" install --quiet --disable-pip-version-check -r scripts/requirements-bench.txt
    cp scripts/requirements-bench.txt "$pybullet_venv/requirements-bench.txt"
  fi
  export SIXDOF_PYBULLET_PYTHON=$pybullet_venv/bin/python SIXDOF_BENCH_DIR=$repo/bench
fi
if [ ${#benches[@]} -gt 0 ] && [ $# -gt 0 ]; then
  # Named benchmarks: only their sections are replaced (or added), each saying when it ran; the others stay.
  for b in "${benches[@]}"; do
    {
      echo "## $(basename "$b") ($(basename "$(dirname "$b")"))"
      echo
      echo "Run $(date -u '+%Y-%m-%d %H:%M UTC') on $(nproc) cores at commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown) (\`scripts/bench.sh $(basename "$b")\`)."
      echo
      "$b"
    } | tee "$out.section"
    python3 scripts/results_section.py "$out" "$out.section"
    rm -f "$out.section"
  done
elif [ ${#benches[@]} -gt 0 ]; then
  {
    echo "# Benchmark results"
    echo
    echo "Run $(date -u '+%Y-%m-%d %H:%M UTC') on $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'),"
    echo "commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown). Produced by \`make bench\`."
    for b in "${benches[@]}"; do
      echo
      echo "## $(basename "$b") ($(basename "$(dirname "$b")"))"
      echo
      "$b"
    done
  } | tee "$out.tmp"
  # Sections written by scripts (this one's bindings section, `make bench-build`, `make bench-pick`, ...) name the
  # script in their header, "## <name> (scripts/<script>.sh[ <arguments>])": keep them.
  if [ -f "$out" ]; then
    awk '/^## /{keep = ($0 ~ /^## .* \(scripts\/[a-z_]+\.sh( [^)]*)?\)$/)} keep' "$out" | sed '1s/^/\n/' >> "$out.tmp"
  fi
  mv "$out.tmp" "$out"
fi
if [ $bindings = 1 ]; then
  # The same IK and planning problems through the Python bindings and through the C++ core, in one run.
  python3 src/sixdof_core/bench/binding_bench.py --baseline install/lib/sixdof_core/binding_baseline \
    --report "$out.bindings"
  python3 scripts/results_section.py "$out" "$out.bindings"
  rm -f "$out.bindings"
fi
# The scaling curves (bench/scaling_*.png) and their section, from the tables just written: after a full run, or
# a named one that wrote one of their tables (scaling_bench, occupancy_bench); otherwise curves and section stay.
if [ $# -eq 0 ] || printf '%s\n' "${benches[@]}" | grep -qE '/(scaling|occupancy)_bench$'; then
  python3 scripts/plot_scaling.py "$out"
fi
echo "wrote $out"
