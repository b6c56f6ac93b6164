"""Service calls with a hang guard, and clients that keep their connection to the server between calls."""

from __future__ import annotations

import math
import select
import socket
import struct
import threading
import time

import genpy
import rospy

from ._wire import WireCodec, codec

# Hang guard (wall clock) for service calls: a dead node fails at once, this only bounds a node that hangs.
SERVICE_TIMEOUT = 30.0


class PersistentService:
    """A client of a service that keeps its connection to the server between calls (rospy's persistent
    ServiceProxy), so that a call costs no master lookup and no new connection.

    A call whose kept connection turns out broken (the server restarted or died since the last call: the socket
    fails or the server closed it) is made once more on a new connection. A server's error answer (TCPROS's ok byte
    0) raises rospy.ServiceException and is never made again, so the service may have side effects. A failure on a
    new connection raises as rospy's ServiceProxy does. Calls from several threads at once are served one at a time
    on the kept connection, the others on connections of their own (as rospy's non-persistent proxies). On the kept
    connection requests and responses go through _wire's codecs (genpy's bytes and objects, made in C++).
    """

    def __init__(self, name: str, service_class: type) -> None:
        self.resolved_name = rospy.resolve_name(name)
        self._service_class = service_class
        self._codecs = (codec(service_class._request_class), codec(service_class._response_class))
        self._busy = threading.Lock()
        self._proxy: rospy.ServiceProxy | None = None

    def __call__(self, request: object) -> object:
        if not self._busy.acquire(blocking=False):
            return rospy.ServiceProxy(self.resolved_name, self._service_class)(request)
        try:
            proxy = self._kept()
            if proxy is not None:
                try:
                    return _call_kept(proxy, request, None, self._codecs)
                except (OSError, _ConnectionClosedError):
                    if self._proxy is not proxy:  # reset() while waiting: the caller gave up on this call
                        raise rospy.ServiceException(f"service [{self.resolved_name}]: connection closed") from None
                    self.reset()  # broken: made once more below, on a new connection
            proxy = rospy.ServiceProxy(self.resolved_name, self._service_class, persistent=True)
            self._proxy = proxy
            try:
                return proxy(request)
            except (rospy.ServiceException, rospy.ROSException):
                proxy.close()
                if self._proxy is proxy:
                    self._proxy = None
                raise
        finally:
            self._busy.release()

    def call(self, request: object, timeout: float) -> object:
        """self(request) given up after `timeout` wall-clock seconds (call_service). On the kept connection the call
        runs in the caller's thread, its socket bounded by the time left; opening a connection (the first call, or
        after the kept one broke) and a call while another thread holds the kept connection go through
        call_service's thread."""
        if self._busy.acquire(blocking=False):
            try:
                proxy = self._kept()
                if proxy is not None:
                    try:
                        return _call_kept(proxy, request, time.monotonic() + timeout, self._codecs)
                    except _NoAnswerError:
                        self.reset()
                        raise rospy.ROSException(
                            f"service '{self.resolved_name}' gave no answer within {timeout:g} s"
                        ) from None
                    except (OSError, _ConnectionClosedError):
                        self.reset()  # broken: made once more below, on a new connection
            finally:
                self._busy.release()
        return _call_in_thread(self, request, timeout)

    def reset(self) -> None:
        """Closes the kept connection (a call waiting on it fails); the next call opens a new one."""
        proxy, self._proxy = self._proxy, None
        if proxy is not None:
            proxy.close()

    def _kept(self) -> rospy.ServiceProxy | None:
        """The proxy of the kept connection, None while there is none."""
        proxy = self._proxy
        if proxy is not None and proxy.transport is not None and proxy.transport.socket is not None:
            return proxy
        return None


_LENGTH = struct.Struct("<I")

# The first read of an answer: most answers (a planned trajectory is ~10 KB) arrive whole in one read.
_FIRST_READ = 65536


class _NoAnswerError(Exception):
    """The deadline of a call on a kept connection passed."""


class _ConnectionClosedError(Exception):
    """The server closed the kept connection."""


def _wait(sock: socket.socket, events: int, deadline: float | None) -> None:
    """Returns once sock is ready for `events` (select.POLLIN or POLLOUT; an error or a hang-up is ready too: the
    read or write that follows reports it), _NoAnswerError once the deadline (time.monotonic(); None: none) passed."""
    poller = select.poll()
    poller.register(sock, events)
    while True:
        if deadline is None:
            timeout = None
        else:
            remaining = deadline - time.monotonic()
            if remaining <= 0.0:
                raise _NoAnswerError
            timeout = math.ceil(remaining * 1e3)
        if poller.poll(timeout):
            return


def _send_request(sock: socket.socket, data: bytes, deadline: float | None) -> None:
    """All of data written to the non-blocking sock before the deadline (_NoAnswerError after it)."""
    view = memoryview(data)
    while view:
        try:
            view = view[sock.send(view) :]
        except BlockingIOError:
            _wait(sock, select.POLLOUT, deadline)


def _receive_answer(sock: socket.socket, deadline: float | None) -> tuple[bool, bytes]:
    """A TCPROS service answer from the non-blocking sock before the deadline (time.monotonic(); None: no
    deadline): its ok byte and its bytes; _NoAnswerError after the deadline, rospy.ServiceException for bytes beyond
    the answer (the socket is closed). Each read waits for data first (poll), then takes whatever has arrived: the
    first up to _FIRST_READ bytes (most often the whole answer), the rest up to the length the answer's header
    names."""
    chunks: list[bytes] = []
    received = 0
    size = None
    while size is None or received < size:
        _wait(sock, select.POLLIN, deadline)
        try:
            chunk = sock.recv(_FIRST_READ if size is None else size - received)
        except BlockingIOError:
            continue
        if not chunk:
            raise _ConnectionClosedError
        chunks.append(chunk)
        received += len(chunk)
        if size is None and received >= 5:
            head = chunks[0] if len(chunks[0]) >= 5 else b"".join(chunks)
            size = 5 + _LENGTH.unpack_from(head, 1)[0]
    if received > size:
        sock.close()  # the stream is out of step: the next call opens a new connection
        raise rospy.ServiceException(f"a service answered {received - size} bytes more than its answer's length")
    data = chunks[0] if len(chunks) == 1 else b"".join(chunks)  # most answers arrive in one read: no copy
    return data[0] != 0, data[5:]


def _call_kept(
    proxy: rospy.ServiceProxy, request: object, deadline: float | None, codecs: tuple[WireCodec, WireCodec]
) -> object:
    """proxy(request) on its open persistent connection, read before the deadline (None: no deadline): TCPROS's
    service framing (the request's length and bytes out; an ok byte, the length and the response's bytes, or an
    error text, back), the messages written and read by `codecs` (the request's and the response's) as rospy's
    serialization would. The kept socket is non-blocking, every wait a poll bounded by the time left. A broken
    connection raises OSError or _ConnectionClosedError, the server's error answer rospy.ServiceException."""
    request = rospy.msg.args_kwds_to_message(proxy.request_class, (request,), {})
    transport = proxy.transport
    proxy.seq += 1
    if getattr(request.__class__, "_has_header", False):  # as rospy.msg.serialize_message
        request.header.seq = proxy.seq
        if request.header.frame_id is None:
            request.header.frame_id = "0"
    try:
        body = codecs[0].encode(request)
    except struct.error as err:
        raise rospy.exceptions.ROSSerializationException(err) from err
    sock = transport.socket
    if sock.gettimeout() != 0.0:
        sock.setblocking(False)
    _send_request(sock, _LENGTH.pack(len(body)) + body, deadline)
    ok, data = _receive_answer(sock, deadline)
    if not ok:
        raise rospy.ServiceException(
            f"service [{proxy.resolved_name}] responded with an error: {data.decode('utf-8', 'replace')}"
        )
    try:
        response = codecs[1].decode(data)
    except genpy.DeserializationError as err:
        raise rospy.ServiceException(f"service [{proxy.resolved_name}]: {err}") from err
    response._connection_header = transport.header
    return response


def call_service(proxy: rospy.ServiceProxy | PersistentService, request: object, timeout: float) -> object:
    """proxy(request), given up after `timeout` wall-clock seconds with rospy.ROSException naming the service (a
    PersistentService's connection is then closed: the next call opens a new one).

    rospy's service calls have no timeout: a node that accepted the connection and then stopped answering
    would block the caller forever. (A node that died answers at once: the connection is refused or closed,
    and rospy raises ServiceException.) A PersistentService bounds calls on its kept connection itself; other
    calls run in a thread of their own, waited for up to the timeout.
    """
    if isinstance(proxy, PersistentService):
        return proxy.call(request, timeout)
    return _call_in_thread(proxy, request, timeout)


def _call_in_thread(proxy: rospy.ServiceProxy | PersistentService, request: object, timeout: float) -> object:
    outcome: dict[str, object] = {}
    done = threading.Event()

    def run() -> None:
        try:
            outcome["response"] = proxy(request)
        except Exception as err:  # re-raised in the caller's thread
            outcome["error"] = err
        finally:
            done.set()

    threading.Thread(target=run, daemon=True).start()
    if not done.wait(timeout):
        if isinstance(proxy, PersistentService):
            proxy.reset()
        raise rospy.ROSException(f"service '{proxy.resolved_name}' gave no answer within {timeout:g} s")
    if "error" in outcome:
        raise outcome["error"]
    return outcome["response"]
