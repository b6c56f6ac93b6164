#!/usr/bin/env python3
"""rostest of the TCPROS side of move_group's services (sixdof_planning's TcprosServiceServer), spoken byte for byte
over sockets: the connection header exchange and its refusals, probes, persistent and one-shot connections, error
answers to requests that do not parse, and a request length out of step; after each refusal the service still
answers. Runs against move_group.test's node."""

import io
import socket
import struct
import sys
import time
import unittest

import rosgraph
import rospy
import rostest
from moveit_msgs.srv import GetPositionFK, GetPositionFKRequest, GetPositionFKResponse

PKG = "sixdof_planning"
SERVICE = "/compute_fk"


def service_address(name: str) -> tuple[str, int]:
    uri = rosgraph.Master("/test_tcpros_server").lookupService(name)
    host, port = uri[len("rosrpc://") :].rsplit(":", 1)
    return host, int(port)


def header_bytes(fields: dict) -> bytes:
    body = b"".join(struct.pack("<I", len(f)) + f for f in (f"{k}={v}".encode() for k, v in fields.items()))
    return struct.pack("<I", len(body)) + body


def read_exact(sock: socket.socket, size: int) -> bytes:
    data = b""
    while len(data) < size:
        chunk = sock.recv(size - len(data))
        if not chunk:
            raise ConnectionError(f"closed after {len(data)} of {size} bytes")
        data += chunk
    return data


def read_header(sock: socket.socket) -> dict:
    (size,) = struct.unpack("<I", read_exact(sock, 4))
    body = read_exact(sock, size)
    fields, at = {}, 0
    while at < len(body):
        (n,) = struct.unpack_from("<I", body, at)
        key, _, value = body[at + 4 : at + 4 + n].decode().partition("=")
        fields[key] = value
        at += 4 + n
    return fields


def closed(sock: socket.socket) -> bool:
    """True when the server closed the connection (recv gives end of stream within 10 s)."""
    sock.settimeout(10.0)
    try:
        return sock.recv(1) == b""
    except ConnectionResetError:
        return True


def fk_request_bytes() -> bytes:
    request = GetPositionFKRequest()
    request.header.frame_id = "world"
    request.fk_link_names = ["link6"]
    buffer = io.BytesIO()
    request.serialize(buffer)
    return buffer.getvalue()


class TcprosServerTest(unittest.TestCase):
    def setUp(self) -> None:
        rospy.wait_for_service(SERVICE, timeout=60.0)
        self.address = service_address(SERVICE)

    def connect(self, **fields: str) -> socket.socket:
        sock = socket.create_connection(self.address, timeout=10.0)
        self.addCleanup(sock.close)
        header = {"callerid": "/test_tcpros_server", "service": SERVICE, "md5sum": GetPositionFK._md5sum}
        header.update(fields)
        sock.sendall(header_bytes({k: v for k, v in header.items() if v is not None}))
        return sock

    def call(self, sock: socket.socket, request: bytes) -> tuple[int, bytes]:
        sock.sendall(struct.pack("<I", len(request)) + request)
        ok = read_exact(sock, 1)[0]
        (size,) = struct.unpack("<I", read_exact(sock, 4))
        return ok, read_exact(sock, size)

    def assert_answers(self) -> None:
        """The service answers a one-shot call (rospy's own client)."""
        response = rospy.ServiceProxy(SERVICE, GetPositionFK)(GetPositionFKRequest(fk_link_names=["link6"]))
        self.assertEqual(len(response.pose_stamped), 1)

    def test_header_names_the_service_type_and_node(self) -> None:
        header = read_header(self.connect(probe="1", md5sum="*"))
        self.assertEqual(header["md5sum"], GetPositionFK._md5sum)
        self.assertEqual(header["type"], GetPositionFK._type)
        self.assertEqual(header["request_type"], GetPositionFKRequest._type)
        self.assertEqual(header["response_type"], GetPositionFKResponse._type)
        self.assertEqual(header["callerid"], "/move_group")
        self.assertNotIn("error", header)

    def test_wrong_md5sum_is_refused_by_name(self) -> None:
        sock = self.connect(md5sum="0123456789abcdef0123456789abcdef")
        header = read_header(sock)
        self.assertEqual(list(header), ["error"])
        self.assertIn("md5sum 0123456789abcdef0123456789abcdef", header["error"])
        self.assertTrue(closed(sock))
        self.assert_answers()

    def test_other_service_name_is_refused(self) -> None:
        sock = self.connect(service="/no_such_service")
        self.assertIn("nonexistent service [/no_such_service]", read_header(sock)["error"])
        self.assertTrue(closed(sock))
        self.assert_answers()

    def test_header_without_caller_is_refused(self) -> None:
        sock = self.connect(callerid=None)
        self.assertIn("md5sum, service, callerid", read_header(sock)["error"])
        self.assertTrue(closed(sock))

    def test_header_that_does_not_parse_is_refused(self) -> None:
        sock = socket.create_connection(self.address, timeout=10.0)
        self.addCleanup(sock.close)
        sock.sendall(struct.pack("<I", 8) + struct.pack("<I", 100) + b"abcd")  # a field longer than the header
        self.assertIn("does not parse", read_header(sock)["error"])
        self.assertTrue(closed(sock))
        self.assert_answers()

    def test_persistent_connection_answers_every_request(self) -> None:
        sock = self.connect(persistent="1")
        self.assertNotIn("error", read_header(sock))
        for _ in range(3):
            ok, data = self.call(sock, fk_request_bytes())
            self.assertEqual(ok, 1)
            response = GetPositionFKResponse().deserialize(data)
            self.assertEqual(len(response.pose_stamped), 1)
            self.assertEqual(response.fk_link_names, ["link6"])

    def test_one_shot_connection_is_closed_after_its_answer(self) -> None:
        sock = self.connect()
        read_header(sock)
        ok, _ = self.call(sock, fk_request_bytes())
        self.assertEqual(ok, 1)
        self.assertTrue(closed(sock))

    def test_request_that_does_not_parse_gets_an_error_answer(self) -> None:
        sock = self.connect(persistent="1")
        read_header(sock)
        ok, text = self.call(sock, b"\x01\x02\x03")  # ends inside the header's seq
        self.assertEqual(ok, 0)
        expected = "exception: a request of 3 bytes is not a moveit_msgs/GetPositionFKRequest"
        self.assertTrue(text.decode().startswith(expected), text)
        # The connection stays in step: the next request is answered.
        ok, data = self.call(sock, fk_request_bytes())
        self.assertEqual(ok, 1)
        self.assertEqual(len(GetPositionFKResponse().deserialize(data).pose_stamped), 1)

    def test_request_length_over_a_gigabyte_closes_the_connection(self) -> None:
        sock = self.connect(persistent="1")
        read_header(sock)
        sock.sendall(struct.pack("<I", 0xFFFFFFF0))
        self.assertTrue(closed(sock))
        self.assert_answers()

    def test_client_closing_mid_request_leaves_the_service_answering(self) -> None:
        sock = self.connect(persistent="1")
        read_header(sock)
        request = fk_request_bytes()
        sock.sendall(struct.pack("<I", len(request)) + request[:5])
        sock.close()
        time.sleep(0.2)
        self.assert_answers()


if __name__ == "__main__":
    rospy.init_node("test_tcpros_server")
    rostest.rosrun(PKG, "tcpros_server", TcprosServerTest, sys.argv)
