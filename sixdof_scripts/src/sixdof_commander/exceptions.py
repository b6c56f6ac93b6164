"""The exception types of the sixdof_commander API (moveit_commander's names live here too: one hierarchy)."""


class MoveItCommanderException(Exception):  # noqa: N818 (upstream's name)
    """moveit_commander's exception type (also importable as moveit_commander.MoveItCommanderException)."""


class SixdofCommanderError(MoveItCommanderException):
    """Raised on misuse of the API: bad arguments, unknown names, unavailable servers.

    Planning and execution failures are not exceptions: they come back as results and error codes,
    as in moveit_commander.
    """


class UnknownGroupError(SixdofCommanderError, RuntimeError):
    """The SRDF has no such planning group. A RuntimeError too, as moveit_commander's C++ wrapper raises one."""
