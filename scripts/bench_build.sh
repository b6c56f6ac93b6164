#!/usr/bin/env bash
# Build cost of a fresh clone (`make bench-build`): CPU and wall time of a cold `scripts/build.sh` with the
# defaults, against the previous defaults (RelWithDebInfo, tests and benchmarks built) in the same run, plus
# the other steps between `git clone` and a finished `make demo`: the venv with the pinned tools, the demo
# itself and, with --apt, the Debian packages installed into a fresh debootstrap chroot (needs root and
# debootstrap; downloads ~1.3 GB). ccache is disabled so every build is cold. Writes the "build" section of
# bench/results.md (scripts/bench.sh keeps it).
#   scripts/bench_build.sh [--apt] [--no-baseline] [--no-demo]
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
apt=0 baseline=1 demo=1
for arg in "$@"; do
  case "$arg" in
    --apt) apt=1 ;;
    --no-baseline) baseline=0 ;;
    --no-demo) demo=0 ;;
    *) echo "bench_build.sh: unknown argument '$arg' (use --apt, --no-baseline, --no-demo)" >&2; exit 2 ;;
  esac
done
work=$(mktemp -d /tmp/sixdof-bench-build.XXXXXX)
cleanup() {
  mountpoint -q "$work/chroot/proc" 2>/dev/null && umount "$work/chroot/proc"
  rm -rf "$work"
}
trap cleanup EXIT
report=$work/report.md

# Seconds of wall time and CPU (user + sys) of a command, appended as a table row: name, wall, cpu.
measure() {
  local name=$1
  shift
  /usr/bin/time -f "%e %U %S" -o "$work/time" "$@" > "$work/$name.log" 2>&1 || {
    echo "bench_build.sh: '$name' failed, see its log:" >&2
    tail -20 "$work/$name.log" >&2
    exit 1
  }
  read -r wall user sys < "$work/time"
  python3 -c "import sys; w, c = float(sys.argv[2]), float(sys.argv[3]) + float(sys.argv[4]);
print(f'| {sys.argv[1]} | {w / 60:.2f} | {c / 60:.2f} |')" "$name" "$wall" "$user" "$sys" >> "$report.rows"
}

git clone -q "$repo" "$work/clone"
cd "$work/clone"
measure "venv + pinned tools (pip, no cache)" bash -c \
  "/usr/bin/python3 -m venv --system-site-packages .venv && .venv/bin/python -m pip install -q --no-cache-dir \
   --disable-pip-version-check -r scripts/requirements-dev.txt"
export CCACHE_DISABLE=1
measure "build, defaults (Release, no tests, no benchmarks)" scripts/build.sh
packages=$(grep -E '^Finished <<<' "$work/build, defaults (Release, no tests, no benchmarks).log" |
  sed -E 's/Finished <<< ([a-z_]+) \[(.*)\]/\1 \2/' | paste -sd, | sed 's/,/, /g')
if [ $demo = 1 ]; then
  measure "make demo (after the build)" scripts/demo.sh
fi
if [ $baseline = 1 ]; then
  rm -rf build install log
  measure "build, previous defaults (RelWithDebInfo, tests, benchmarks)" env SIXDOF_BUILD_TYPE=RelWithDebInfo \
    SIXDOF_BUILD_TESTS=ON SIXDOF_BUILD_BENCHMARKS=ON scripts/build.sh
fi
if [ $apt = 1 ]; then
  chroot_dir=$work/chroot
  measure "debootstrap (minbase, not part of a real machine)" debootstrap --variant=minbase bookworm "$chroot_dir" \
    http://deb.debian.org/debian
  grep -v '^\s*#' scripts/apt-packages.txt | sed '/^\s*$/d' > "$chroot_dir/root/packages.txt"
  cp /etc/resolv.conf "$chroot_dir/etc/resolv.conf"
  mount -t proc proc "$chroot_dir/proc"
  measure "Debian packages (apt-get update + install, fresh minbase chroot)" chroot "$chroot_dir" bash -c \
    'export DEBIAN_FRONTEND=noninteractive; apt-get update -qq && apt-get install -y -qq --no-install-recommends $(cat /root/packages.txt)'
fi

{
  echo "## build (scripts/bench_build.sh)"
  echo
  echo "Fresh clone of $(git rev-parse --short HEAD), ccache disabled, $(nproc) cores. Minutes."
  echo
  echo "| step | wall | CPU (user + sys) |"
  echo "|---|---:|---:|"
  cat "$report.rows"
  echo
  echo "Per package (wall, 2 packages at a time), defaults: $packages"
} > "$report"
cat "$report"

# Replace (or add) the build section of bench/results.md, keeping every other section.
results=$repo/bench/results.md
python3 "$repo/scripts/results_section.py" "$results" "$report"
echo "wrote the build section of $results"
