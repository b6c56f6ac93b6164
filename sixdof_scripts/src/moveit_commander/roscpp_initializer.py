"""roscpp_initialize / roscpp_shutdown: MoveIt's commander wraps C++ and starts roscpp; sixdof's is pure Python.

Nothing needs starting: the commander runs on the script's rospy node (rospy.init_node reads the same remapping
arguments from sys.argv). The functions check their argument and remember the state, so scripts that call them,
as MoveIt's tutorials do, run unchanged.
"""

from __future__ import annotations

from collections.abc import Sequence

from sixdof_commander.exceptions import SixdofCommanderError

_state = {"initialized": False}


def roscpp_initialize(args: Sequence[str]) -> None:
    """Accepts the script's argv (a list of strings, e.g. sys.argv); rospy.init_node applies its remappings."""
    if isinstance(args, str) or not isinstance(args, Sequence) or not all(isinstance(a, str) for a in args):
        raise SixdofCommanderError(f"roscpp_initialize needs a list of strings (e.g. sys.argv), got {args!r}")
    _state["initialized"] = True


def roscpp_shutdown() -> None:
    """Counterpart of roscpp_initialize; the rospy node keeps running (as with MoveIt, whose roscpp is separate)."""
    _state["initialized"] = False
