"""The kept connection's reading of a TCPROS service answer (_service._receive_answer): an answer that arrives in
one read, in pieces (the 5-byte header split too), the server's error answer, a connection closed midway, and
bytes beyond the answer's length."""

from __future__ import annotations

import itertools
import socket
import struct
import threading
import time

import pytest
import rospy
from sixdof_commander import _service


def answer(ok: bool, body: bytes) -> bytes:
    return bytes([1 if ok else 0]) + struct.pack("<I", len(body)) + body


def receive(pieces: list[bytes], close: bool = False) -> tuple[bool, bytes]:
    """What _receive_answer reads from a peer that writes `pieces` one after another (then closes, if asked)."""
    client, server = socket.socketpair()
    client.setblocking(False)

    def write() -> None:
        for piece in pieces:
            server.sendall(piece)
            time.sleep(0.01)  # each piece its own read
        if close:
            server.close()

    writer = threading.Thread(target=write)
    writer.start()
    try:
        return _service._receive_answer(client, time.monotonic() + 5.0)
    finally:
        writer.join()
        client.close()
        if not close:
            server.close()


BODY = bytes(range(256)) * 50


def test_one_read():
    assert receive([answer(True, BODY)]) == (True, BODY)


@pytest.mark.parametrize("cuts", [[3], [5], [5, 100], [2, 4, 9000, 12000]])
def test_pieces(cuts):
    data = answer(True, BODY)
    bounds = [0, *cuts, len(data)]
    assert receive([data[a:b] for a, b in itertools.pairwise(bounds)]) == (True, BODY)


def test_empty_body_and_error_answer():
    assert receive([answer(True, b"")]) == (True, b"")
    assert receive([answer(False, b"no such group")]) == (False, b"no such group")


def test_closed_midway():
    with pytest.raises(_service._ConnectionClosedError):
        receive([answer(True, BODY)[:100]], close=True)


def test_bytes_beyond_the_answer():
    with pytest.raises(rospy.ServiceException, match="3 bytes more than its answer's length"):
        receive([answer(True, BODY) + b"xyz"])
