"""Joint series collection and the PNG plot."""

import pytest

from sixdof_bringup.plots import plot_joint_series, series_from_messages


def test_series_keep_the_first_joint_set_and_fill_missing_joints():
    series = series_from_messages(
        [(10.0, ["a", "b"], [0.0, 1.0]), (10.5, ["b"], [2.0]), (11.0, ["a", "b", "c"], [3, 4, 5])]
    )
    assert series.names == ["a", "b"]
    assert series.times == [0.0, 0.5, 1.0]
    assert series.positions == [[0.0, 1.0], [0.0, 2.0], [3, 4]]


def test_bad_samples_are_rejected():
    with pytest.raises(ValueError, match="no joint states"):
        series_from_messages([])
    with pytest.raises(ValueError, match="2 names but 1 positions"):
        series_from_messages([(0.0, ["a", "b"], [0.0])])


def test_plot_writes_a_png(tmp_path):
    series = series_from_messages([(t * 0.1, ["joint1", "finger1_joint"], [t * 0.01, 0.04]) for t in range(50)])
    out = tmp_path / "joints.png"
    plot_joint_series(series, str(out))
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
