"""Two hosts in two network namespaces joined by a veth pair with addresses of their own (ROS_IP and ROS_MASTER_URI
use only those):
- the robot host (ROS master, simulator, move_group: sixdof_bringup robot_host.launch) and the operator host (a
  moveit_commander script, multihost_client.py). In the middle of a motion the link goes down for 5 s: go() must
  fail cleanly (False with COMMUNICATION_FAILURE, not hang) and, once the link is back, the next motion must work.
- a real robot's two machines: the driver (sixdof_control on the mock plugin, driver.launch) on the robot host,
  move_group (real.launch driver:=none, with the ROS master) and the commander script on the other: the script's
  motions execute through the driver across the link.
The namespaces, the veth pair and every process are created and removed here; root is needed (ip netns).

    sudo -E python -m pytest test/ros/multihost.py
"""

from __future__ import annotations

import json
import os
import queue
import shutil
import signal
import subprocess
import tempfile
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest
from moveit_msgs.msg import MoveItErrorCodes

from sixdof_test_support.processes import stop

HERE = Path(__file__).resolve().parent
DROP_SECONDS = 5.0
STARTUP_TIMEOUT = 240.0
# Bounds are outcomes (the call returned, it did not hang), not speed claims.
RETURN_BOUND = 15.0  # go() returns within this after the link went down
MOTION_BOUND = 120.0  # a motion with the link up returns within this


def run(*args: str) -> None:
    subprocess.run(args, check=True, capture_output=True, text=True, timeout=30)


@dataclass
class Hosts:
    robot_ns: str
    operator_ns: str
    robot_if: str
    robot_ip: str
    operator_ip: str
    log_dir: Path

    def env(self, ip: str) -> dict[str, str]:
        env = dict(os.environ)
        env.update(
            ROS_IP=ip,
            ROS_MASTER_URI=f"http://{self.robot_ip}:11311",
            ROS_LOG_DIR=str(self.log_dir),
            ROS_HOME=str(self.log_dir / "ros_home"),
        )
        env.pop("ROS_HOSTNAME", None)
        return env

    def link(self, up: bool) -> None:
        run("ip", "-n", self.robot_ns, "link", "set", self.robot_if, "up" if up else "down")


@pytest.fixture(scope="module")
def hosts(request: pytest.FixtureRequest) -> Iterator[Hosts]:
    """Two network namespaces joined by a veth pair; removed afterwards (with the processes left in them)."""
    if os.geteuid() != 0:
        pytest.fail("the multi-host test needs root to create network namespaces (ip netns)")
    tag = f"{os.getpid() % 100000}"
    subnet = 10 + os.getpid() % 200
    h = Hosts(
        robot_ns=f"sxr{tag}",
        operator_ns=f"sxo{tag}",
        robot_if=f"sxr{tag}v",
        robot_ip=f"10.231.{subnet}.1",
        operator_ip=f"10.231.{subnet}.2",
        log_dir=Path(tempfile.mkdtemp(prefix="multihost_")),
    )
    operator_if = f"sxo{tag}v"
    try:
        run("ip", "netns", "add", h.robot_ns)
        run("ip", "netns", "add", h.operator_ns)
        run("ip", "link", "add", h.robot_if, "type", "veth", "peer", "name", operator_if)
        for ns, interface, ip in ((h.robot_ns, h.robot_if, h.robot_ip), (h.operator_ns, operator_if, h.operator_ip)):
            run("ip", "link", "set", interface, "netns", ns)
            run("ip", "-n", ns, "addr", "add", f"{ip}/24", "dev", interface)
            run("ip", "-n", ns, "link", "set", interface, "up")
            run("ip", "-n", ns, "link", "set", "lo", "up")
        yield h
    finally:
        for ns in (h.robot_ns, h.operator_ns):
            pids = subprocess.run(["ip", "netns", "pids", ns], capture_output=True, text=True).stdout.split()
            for pid in pids:
                try:
                    os.kill(int(pid), signal.SIGKILL)
                except ProcessLookupError:
                    pass
            subprocess.run(["ip", "netns", "del", ns], capture_output=True)
        if request.session.testsfailed:
            print(f"multihost: logs kept in {h.log_dir}")
        else:
            shutil.rmtree(h.log_dir, ignore_errors=True)


@pytest.fixture
def robot_host(hosts: Hosts) -> Iterator[subprocess.Popen]:
    """The robot host's part of the demo (master, simulator in real time, move_group, scene mirror), no rviz."""
    with open(hosts.log_dir / "robot_host.out", "w") as log:
        process = subprocess.Popen(
            ["ip", "netns", "exec", hosts.robot_ns, "roslaunch", "-p", "11311", "sixdof_bringup", "robot_host.launch"],
            env=hosts.env(hosts.robot_ip),
            stdout=log,
            stderr=subprocess.STDOUT,
            start_new_session=True,
        )
    yield process
    stop(process, 30.0)


def read_lines(stream, lines: queue.Queue) -> None:
    for line in stream:
        lines.put(line.rstrip("\n"))
    lines.put(None)


def next_line(lines: queue.Queue, timeout: float, what: str, log: Path) -> str:
    deadline = time.monotonic() + timeout
    while True:
        try:
            line = lines.get(timeout=max(0.0, deadline - time.monotonic()))
        except queue.Empty:
            pytest.fail(f"no {what} from the operator host within {timeout:g} s (see {log})")
        if line is None:
            pytest.fail(f"the operator host's script ended before its {what} (see {log})")
        if line == "MOVING" or line.startswith("{"):
            return line


def commander_script(hosts: Hosts, env: dict[str, str], log: Path) -> tuple[subprocess.Popen, queue.Queue]:
    """multihost_client.py on the operator host: the process and a queue of its output lines."""
    with open(log, "w") as err:
        client = subprocess.Popen(
            ["ip", "netns", "exec", hosts.operator_ns, "python3", str(HERE / "multihost_client.py")],
            env=env,
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=err,
            text=True,
            start_new_session=True,
        )
    lines: queue.Queue = queue.Queue()
    threading.Thread(target=read_lines, args=(client.stdout, lines), daemon=True).start()
    return client, lines


def test_link_drop_mid_motion_fails_cleanly_and_the_next_motion_works(hosts: Hosts, robot_host: subprocess.Popen):
    log = hosts.log_dir / "operator_host.err"
    client, lines = commander_script(hosts, hosts.env(hosts.operator_ip), log)
    try:
        assert next_line(lines, STARTUP_TIMEOUT, "MOVING", log) == "MOVING"
        assert robot_host.poll() is None, "the robot host's launch ended"
        time.sleep(1.5)  # into the motion
        hosts.link(False)
        dropped = time.monotonic()
        try:
            first = json.loads(next_line(lines, RETURN_BOUND, "result of the interrupted motion", log))
            returned = time.monotonic() - dropped
        finally:
            time.sleep(max(0.0, DROP_SECONDS - (time.monotonic() - dropped)))
            hosts.link(True)
        assert not first["ok"], f"the motion succeeded although the link was down: {first}"
        assert first["code"] == MoveItErrorCodes.COMMUNICATION_FAILURE, first
        assert returned <= RETURN_BOUND, first
        client.stdin.write("link up\n")
        client.stdin.flush()
        second = json.loads(next_line(lines, MOTION_BOUND, "result of the motion after the link returned", log))
        print(f"multihost: link down -> go() returned after {returned:.2f} s: {first}; after the link: {second}")
        assert second["ok"], f"the motion after the link returned failed: {second}"
    finally:
        stop(client, 30.0)


def test_driver_on_the_robot_host_move_group_on_the_other(hosts: Hosts):
    operator = hosts.env(hosts.operator_ip)
    operator["ROS_MASTER_URI"] = f"http://{hosts.operator_ip}:11311"
    robot = dict(operator, ROS_IP=hosts.robot_ip)
    processes = []
    try:
        with open(hosts.log_dir / "planning_host.out", "w") as log:
            processes.append(subprocess.Popen(
                ["ip", "netns", "exec", hosts.operator_ns, "roslaunch", "-p", "11311", "sixdof_bringup", "real.launch",
                 "rviz:=false"],
                env=operator, stdout=log, stderr=subprocess.STDOUT, start_new_session=True,
            ))
        # The driver reads the robot description the planning host's launch puts on the parameter server.
        deadline = time.monotonic() + STARTUP_TIMEOUT
        while subprocess.run(["ip", "netns", "exec", hosts.robot_ns, "rosparam", "get", "/robot_description"],
                             env=robot, capture_output=True, timeout=30).returncode != 0:
            assert time.monotonic() < deadline, "the planning host's launch did not load the robot description"
            time.sleep(1.0)
        share = Path(subprocess.run(["rospack", "find", "sixdof_description"], capture_output=True, text=True,
                                    check=True).stdout.strip())
        with open(hosts.log_dir / "driver_host.out", "w") as log:
            processes.append(subprocess.Popen(
                ["ip", "netns", "exec", hosts.robot_ns, "roslaunch", "sixdof_control", "driver.launch", "plugin:=mock",
                 f"hardware_file:={share / 'config' / 'hardware.yaml'}",
                 f"controllers_file:={share / 'config' / 'controllers.yaml'}"],
                env=robot, stdout=log, stderr=subprocess.STDOUT, start_new_session=True,
            ))
        log = hosts.log_dir / "operator_script.err"
        client, lines = commander_script(hosts, operator, log)
        processes.append(client)
        assert next_line(lines, STARTUP_TIMEOUT, "MOVING", log) == "MOVING"
        first = json.loads(next_line(lines, MOTION_BOUND, "result of the first motion", log))
        client.stdin.write("again\n")
        client.stdin.flush()
        second = json.loads(next_line(lines, MOTION_BOUND, "result of the second motion", log))
        print(f"multihost: motions through the driver on the other host: {first}, {second}")
        assert first["ok"] and second["ok"], (first, second)
    finally:
        for process in reversed(processes):
            stop(process, 30.0)
