"""rviz as a child process on this process's X display, for tests and scripts that look at it.

rviz on Mesa's software renderer (llvmpipe) under Xvfb dies now and then in its first frames, inside Mesa's buffer
swap (SIGSEGV, SIGBUS, or glibc's abort on a corrupted heap), stock rviz with only stock displays too, and on a
loaded host in runs of a few starts in a row. RvizProcess starts it again when it dies of a signal before it has
stayed up `stay_up` seconds with its main window mapped, up to `starts` starts, and says so on stdout; any other
exit, or one more death, is an error naming the log.

    rviz = RvizProcess(["rviz", "-d", config], log)
    window = rviz.wait_up(timeout=120.0)  # the main window's id
    ...
    assert rviz.alive(), rviz.exited()
    rviz.stop()
"""

from __future__ import annotations

import re
import subprocess
import time
from pathlib import Path

from sixdof_test_support import processes

# rviz processes at most: the first and up to five restarts.
STARTS = 6
# Seconds (wall clock) rviz must stay up with its main window mapped; Mesa's deaths come within ~3 s of a start.
STAY_UP = 5.0

_MAIN_WINDOW = re.compile(r'^\s*(0x[0-9a-f]+) "[^"]* - RViz"', re.MULTILINE)


def main_window() -> str | None:
    """The id of an rviz main window mapped on the display ('... - RViz'), None while there is none."""
    tree = subprocess.run(["xwininfo", "-root", "-children"], capture_output=True, text=True).stdout
    match = _MAIN_WINDOW.search(tree)
    return match.group(1) if match else None


class RvizProcess:
    """rviz started with `command` (output appended to `log`), restarted when Mesa kills it in its first seconds."""

    def __init__(self, command: list[str], log: Path, starts: int = STARTS, stay_up: float = STAY_UP) -> None:
        if starts < 1:
            raise ValueError(f"starts must be at least 1, not {starts}")
        self.command, self.log = list(command), Path(log)
        self.starts, self.stay_up = starts, stay_up
        self.pids: list[int] = []
        self.log.write_text("")
        self._start()

    def _start(self) -> None:
        with open(self.log, "a") as out:
            self.process = subprocess.Popen(self.command, stdout=out, stderr=subprocess.STDOUT, start_new_session=True)
        self.pids.append(self.process.pid)

    def alive(self) -> bool:
        return self.process.poll() is None

    def exited(self) -> str:
        """What became of the current rviz, for an assertion message."""
        code = self.process.poll()
        if code is None:
            return f"rviz (pid {self.process.pid}) is running; see {self.log}"
        how = f"died of signal {-code}" if code < 0 else f"exited with code {code}"
        return f"rviz {how}; see {self.log}"

    def wait_up(self, timeout: float) -> str:
        """The id of rviz's main window once rviz has stayed up `stay_up` seconds with it mapped. RuntimeError naming
        the log when rviz exits other than by a signal, dies in more than `starts` starts, or has shown no main
        window within `timeout` seconds of a start."""
        deadline = time.monotonic() + timeout
        up_since = None
        while True:
            if not self.alive():
                died_of_signal = self.process.returncode < 0
                if not died_of_signal or len(self.pids) >= self.starts:
                    raise RuntimeError(f"{self.exited()} (start {len(self.pids)} of at most {self.starts})")
                print(
                    f"rviz (pid {self.process.pid}) died of signal {-self.process.returncode}; started again"
                    f" (start {len(self.pids) + 1} of at most {self.starts})",
                    flush=True,
                )
                self._start()
                deadline = time.monotonic() + timeout
                up_since = None
                continue
            window = main_window()
            if window is None:
                up_since = None
            elif up_since is None:
                up_since = time.monotonic()
            elif time.monotonic() - up_since >= self.stay_up:
                return window
            if window is None and time.monotonic() > deadline:
                raise RuntimeError(f"no rviz window on the display within {timeout:g} s; see {self.log}")
            time.sleep(0.25)

    def stop(self, timeout: float = 20.0) -> None:
        """Ends rviz (SIGINT, then SIGKILL after `timeout` seconds) and waits for it."""
        processes.stop(self.process, timeout)
