# Source this to use the workspace: the venv, then the install space (if built).
_sixdof_repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck disable=SC1091
. "${SIXDOF_VENV:-$_sixdof_repo/.venv}/bin/activate"
if [ -f "$_sixdof_repo/install/setup.bash" ]; then
  # shellcheck disable=SC1091
  . "$_sixdof_repo/install/setup.bash"
fi
unset _sixdof_repo
