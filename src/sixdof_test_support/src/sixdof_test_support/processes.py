"""Processes a test starts: a free port for its own ROS master, and stopping a launch's process group."""

from __future__ import annotations

import os
import signal
import socket
import subprocess


def free_port() -> int:
    """A TCP port on localhost that nothing listens on now (for a test's own ROS master)."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def stop(process: subprocess.Popen, timeout: float = 60.0) -> None:
    """SIGINT to the process's group (roslaunch stops its nodes and master), SIGKILL if it is still there after
    `timeout` seconds. The process must lead its own group (started with start_new_session=True)."""
    if process.poll() is not None:
        return
    os.killpg(process.pid, signal.SIGINT)
    try:
        process.wait(timeout)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        process.wait()
