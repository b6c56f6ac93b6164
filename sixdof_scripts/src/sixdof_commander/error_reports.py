"""The words of a failed move_group call: moveit_msgs' service responses carry at most a MoveItErrorCodes value, so
move_group publishes a sixdof_msgs/ErrorReport on `move_group/error_reports` for every request it refuses or fails
(docs/design.md "Standard message types on the wire"). ErrorReports collects this node's reports; a client takes
the one of its failed call by interface."""

from __future__ import annotations

import collections
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass

import rospy
from moveit_msgs.msg import MoveItErrorCodes

from sixdof_msgs.msg import ErrorReport

from ._ros import resolve
from ._service import SERVICE_TIMEOUT, PersistentService, call_service

# MoveItErrorCodes' constants by value: Python's one table of code names (C++'s: sixdof_msgs/error_code_names.h).
ERROR_NAMES = {
    value: name for name, value in vars(MoveItErrorCodes).items() if name.isupper() and isinstance(value, int)
}

# How long (wall clock) a client waits for the report of a failed call: move_group publishes it before it answers,
# so it is normally there with the answer; the wait covers a slower topic connection.
REPORT_WAIT = 1.0
# How long the constructor waits for the subscription to connect (move_group may not be up yet: then none).
CONNECT_WAIT = 1.0
# Reports kept per client: a report nobody takes (its call's caller gave up on it) is dropped eventually.
KEPT_REPORTS = 64


def error_name(value: int) -> str:
    """The MoveItErrorCodes constant's name of a value; for none of them 'unknown MoveIt error code <value>', the
    words of C++'s sixdof_msgs::errorCodeName."""
    return ERROR_NAMES.get(value, f"unknown MoveIt error code {value}")


@dataclass(frozen=True)
class CallError:
    """A call's outcome: the MoveIt error code and the words of its failure ('' on success or when none came)."""

    val: int
    message: str = ""
    source: str = ""

    @property
    def name(self) -> str:
        return error_name(self.val)

    @property
    def code(self) -> MoveItErrorCodes:
        return MoveItErrorCodes(val=self.val)

    def __str__(self) -> str:
        text = f"{self.name} ({self.val})" if self.val in ERROR_NAMES else self.name
        return f"{text}: {self.message}" if self.message else text


SUCCESS = CallError(MoveItErrorCodes.SUCCESS)


class ErrorReports:
    """This node's error reports from move_group (`<ns>/move_group/error_reports`), in arrival order.

    Subscribes at construction and waits up to CONNECT_WAIT s for the publisher. A caller that got a failed
    answer from interface X takes the oldest report of this node about X, waiting up to REPORT_WAIT s for it;
    without one, the failure is described by its code's name only.
    """

    def __init__(self, ns: str = "") -> None:
        self._reports: collections.deque[ErrorReport] = collections.deque(maxlen=KEPT_REPORTS)
        self._listeners: dict[str, Callable[[CallError], None]] = {}
        self._condition = threading.Condition()
        self._subscriber = rospy.Subscriber(
            resolve(ns, "move_group/error_reports"), ErrorReport, self._on_report, queue_size=KEPT_REPORTS
        )
        end = time.monotonic() + CONNECT_WAIT
        while self._subscriber.get_num_connections() == 0 and time.monotonic() < end and not rospy.is_shutdown():
            time.sleep(0.01)

    def _on_report(self, report: ErrorReport) -> None:
        if report.caller_id != rospy.get_name():
            return
        listener = self._listeners.get(report.interface)
        if listener is not None:
            listener(CallError(report.error_code.val, report.message, report.source))
            return
        with self._condition:
            self._reports.append(report)
            self._condition.notify_all()

    def listen(self, interface: str, callback: Callable[[CallError], None]) -> None:
        """Hands this node's reports about `interface` to callback as they come (a topic's refused messages have
        no caller waiting for them) instead of queueing them."""
        self._listeners[rospy.resolve_name(interface)] = callback

    def forget(self, interface: str) -> None:
        """Drops the reports about `interface` nobody took (call before a request, so that its failure is not
        described by an earlier one's late report)."""
        if not self._reports:  # nothing queued, the common case
            return
        resolved = rospy.resolve_name(interface)
        with self._condition:
            kept = [r for r in self._reports if r.interface != resolved]
            self._reports.clear()
            self._reports.extend(kept)

    def take(self, interface: str, timeout: float = REPORT_WAIT) -> ErrorReport | None:
        """The oldest report of this node about `interface` (a service or action name, resolved as rospy does),
        removed from the queue; None when none came within `timeout` wall-clock seconds."""
        resolved = rospy.resolve_name(interface)
        end = time.monotonic() + timeout
        with self._condition:
            while True:
                for report in self._reports:
                    if report.interface == resolved:
                        self._reports.remove(report)
                        return report
                remaining = end - time.monotonic()
                if remaining <= 0.0 or rospy.is_shutdown():
                    return None
                self._condition.wait(remaining)

    def failure(self, interface: str, val: int) -> CallError:
        """A failed answer's CallError: `val` (the answer's code; the report's where the answer has none, val 0)
        with the report's words, or the code's name alone when no report came."""
        report = self.take(interface)
        if report is None:
            return CallError(val or MoveItErrorCodes.FAILURE)
        return CallError(val or report.error_code.val, report.message, report.source)

    def call(
        self,
        proxy: rospy.ServiceProxy | PersistentService,
        request: object,
        timeout: float = SERVICE_TIMEOUT,
        code: Callable[[object], int] = lambda response: response.error_code.val,
    ) -> tuple[object | None, CallError]:
        """proxy(request) under call_service's hang guard: (response, its outcome). The outcome of a failed answer
        carries its error report's words; a call that got no answer is (None, COMMUNICATION_FAILURE naming the
        service). `code` reads the answer's MoveItErrorCodes value (0: the answer has none, the report's is used)."""
        self.forget(proxy.resolved_name)
        try:
            response = call_service(proxy, request, timeout)
        except (rospy.ServiceException, rospy.ROSException) as err:
            return None, CallError(MoveItErrorCodes.COMMUNICATION_FAILURE, f"{proxy.resolved_name}: {err}")
        val = code(response)
        if val == MoveItErrorCodes.SUCCESS:
            return response, SUCCESS
        return response, self.failure(proxy.resolved_name, val)
