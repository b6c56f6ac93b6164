#!/usr/bin/env bash
# One idempotent set-up path: Debian packages, the venv, pinned dev tools, the colcon build.
# Each step is skipped when its inputs have not changed since it last succeeded.
#   scripts/setup.sh            everything
#   SIXDOF_SKIP_BUILD=1 ...     packages and venv only
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
cd "$repo"
venv=${SIXDOF_VENV:-$repo/.venv}
stamp_dir=$repo/.setup-stamps
mkdir -p "$stamp_dir"

log() { printf '\033[1m[setup]\033[0m %s\n' "$*"; }

sudo_cmd=()
if [ "$(id -u)" != 0 ]; then sudo_cmd=(sudo); fi

# 1. Debian packages: install only what dpkg does not already report as installed.
mapfile -t wanted < <(grep -v '^\s*#' scripts/apt-packages.txt | sed '/^\s*$/d')
missing=()
for p in "${wanted[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  log "installing ${#missing[@]} Debian packages: ${missing[*]}"
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  log "Debian packages: all ${#wanted[@]} present"
fi

# 2. The venv: Debian's interpreter (the pyenv one cannot import rospy), with system site packages.
if [ ! -x "$venv/bin/python" ] || ! "$venv/bin/python" -c 'import rospy' 2>/dev/null; then
  log "creating venv $venv from /usr/bin/python3"
  rm -rf "$venv"
  /usr/bin/python3 -m venv --system-site-packages "$venv"
fi
req=scripts/requirements-dev.txt
if ! cmp -s "$req" "$stamp_dir/requirements-dev.txt"; then
  log "pip-installing pinned dev tools"
  "$venv/bin/python" -m pip install -q --disable-pip-version-check -r "$req"
  cp "$req" "$stamp_dir/requirements-dev.txt"
else
  log "venv: dev tools up to date"
fi

# 3. Build (colcon, merge install). colcon itself skips unchanged packages.
if [ "${SIXDOF_SKIP_BUILD:-0}" != 1 ]; then
  "$repo/scripts/build.sh"
fi
