# Source this to use the workspace: the venv, then the install space (if built).
# Safe under `set -u`: the venv's activate and catkin's setup scripts read unset variables, so nounset is off
# while they run and restored afterwards.
case $- in *u*) _sixdof_nounset=1; set +u ;; *) _sixdof_nounset=0 ;; esac
_sixdof_repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck disable=SC1091
. "${SIXDOF_VENV:-$_sixdof_repo/.venv}/bin/activate"
if [ -f "$_sixdof_repo/install/setup.bash" ]; then
  # shellcheck disable=SC1091
  . "$_sixdof_repo/install/setup.bash"
fi
if [ "$_sixdof_nounset" = 1 ]; then set -u; fi
unset _sixdof_repo _sixdof_nounset
