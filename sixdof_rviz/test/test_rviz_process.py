"""sixdof_rviz.rviz_process with shell commands standing in for rviz and a stand-in for the X display's window list."""

from pathlib import Path

import pytest

from sixdof_rviz import rviz_process
from sixdof_rviz.rviz_process import RvizProcess

# Dies of SIGSEGV in its first `$1` starts (counted in the file `$2`), then runs until stopped.
CRASHING = (
    'n=$(cat "$2" 2>/dev/null || echo 0); echo $((n + 1)) > "$2"; [ "$n" -lt "$1" ] && kill -SEGV $$; exec sleep 60'
)


@pytest.fixture
def window_while_alive(monkeypatch):
    """The display shows a main window whenever the watched process is alive."""
    watched: list[RvizProcess] = []
    monkeypatch.setattr(rviz_process, "main_window", lambda: "0x1" if watched and watched[0].alive() else None)
    return watched


def crashing(deaths: int, tmp_path: Path) -> list[str]:
    return ["sh", "-c", CRASHING, "sh", str(deaths), str(tmp_path / "starts")]


def test_deaths_by_a_signal_are_started_again(tmp_path, window_while_alive, capsys):
    rviz = RvizProcess(crashing(2, tmp_path), tmp_path / "rviz.log", stay_up=0.5)
    window_while_alive.append(rviz)
    try:
        assert rviz.wait_up(timeout=10.0) == "0x1"
        assert len(rviz.pids) == 3 and rviz.alive()
    finally:
        rviz.stop()
    assert not rviz.alive()
    said = capsys.readouterr().out
    assert said.count("died of signal 11; started again") == 2, said
    assert "(start 3 of at most 6)" in said


def test_too_many_deaths_fail(tmp_path, window_while_alive):
    rviz = RvizProcess(crashing(5, tmp_path), tmp_path / "rviz.log", starts=3, stay_up=0.5)
    window_while_alive.append(rviz)
    with pytest.raises(RuntimeError, match=r"died of signal 11; see .*rviz\.log \(start 3 of at most 3\)"):
        rviz.wait_up(timeout=10.0)
    assert len(rviz.pids) == 3


def test_an_exit_is_not_started_again(tmp_path, window_while_alive):
    rviz = RvizProcess(["sh", "-c", "echo bad config; exit 1"], tmp_path / "rviz.log", stay_up=0.5)
    window_while_alive.append(rviz)
    with pytest.raises(RuntimeError, match=r"exited with code 1; see .*rviz\.log \(start 1 of"):
        rviz.wait_up(timeout=10.0)
    assert (tmp_path / "rviz.log").read_text() == "bad config\n"


def test_no_window_within_the_timeout_fails(tmp_path, monkeypatch):
    monkeypatch.setattr(rviz_process, "main_window", lambda: None)
    rviz = RvizProcess(["sleep", "60"], tmp_path / "rviz.log")
    try:
        with pytest.raises(RuntimeError, match=r"no rviz window on the display within 0.5 s"):
            rviz.wait_up(timeout=0.5)
    finally:
        rviz.stop()


def test_starts_must_be_positive(tmp_path):
    with pytest.raises(ValueError, match="starts must be at least 1, not 0"):
        RvizProcess(["true"], tmp_path / "rviz.log", starts=0)
