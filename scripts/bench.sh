#!/usr/bin/env bash
# Runs every benchmark executable (lib/<package>/*_bench in the install space) with its defaults and
# writes the combined report to bench/results.md (kept in the repo; the README quotes it).
#   scripts/bench.sh            all benchmarks
#   scripts/bench.sh ik_bench   only the named ones
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
# shellcheck source=scripts/env.sh
. scripts/env.sh
SIXDOF_BUILD_BENCHMARKS=ON scripts/build.sh
out=bench/results.md
mapfile -t benches < <(find install/lib -maxdepth 2 -type f -name '*_bench' -perm -u+x | sort)
if [ $# -gt 0 ]; then
  mapfile -t benches < <(printf '%s\n' "${benches[@]}" | grep -E "/($(IFS='|'; echo "$*"))$")
fi
[ ${#benches[@]} -gt 0 ] || { echo "no benchmark executables found under install/lib (build first)" >&2; exit 1; }
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
# Sections written by other scripts (`make bench-build`, `make bench-pick`, ...) name the script in their
# header, "## <name> (scripts/<script>.sh)": keep them.
if [ -f "$out" ]; then
  awk '/^## /{keep = ($0 ~ /^## .* \(scripts\/[a-z_]+\.sh\)$/)} keep' "$out" | sed '1s/^/\n/' >> "$out.tmp"
fi
mv "$out.tmp" "$out"
echo "wrote $out"
