"""The one exception type of the sixdof_commander API."""


class SixdofCommanderError(Exception):
    """Raised on misuse of the API: bad arguments, unknown names, unavailable servers.

    Planning and execution failures are not exceptions: they come back as results and error codes,
    as in moveit_commander.
    """
