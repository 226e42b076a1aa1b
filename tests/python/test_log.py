"""tpf logs as numpy arrays: a measured log's columns, views into its values, and the round trip
through a file (plain and gzip)."""
import math

import numpy as np
import pytest

import tpf

GEN3 = "real/kinova-gen3"


def test_measured_log_as_arrays(data):
    log = tpf.read_log(str(data / GEN3 / "logs/joint_1_trapez.csv.gz"))
    robot = tpf.Robot(str(data / GEN3 / "gen3.robot.json"))
    S = len(log)
    assert log.joint_count == 7 and S > 1000
    assert log.rate_hz == 1000
    assert ("rate_hz", "1000") in log.meta
    assert log.t.shape == (S,) and np.all(np.diff(log.t) > 0)
    assert log.q.shape == (S, 7) and log.dq.shape == (S, 7)
    assert log.ddq is None and log.tau is None
    assert log.effort_prefix == "i"
    # Adjacent columns are views of the values, not copies.
    assert np.shares_memory(log.q, log.values)
    np.testing.assert_array_equal(log.q[:, 2], log.column("q3"))
    np.testing.assert_array_equal(log.torque(robot),
                                  log.i * (robot.torque_constant / 1000.0))
    with pytest.raises(ValueError):
        log.q[0, 0] = 1.0  # joint arrays are read-only


def test_kept_columns(data):
    log = tpf.read_log(str(data / GEN3 / "logs/joint_1_trapez.csv.gz"), columns=["q1", "dq1"])
    assert log.columns == ["t", "q1", "dq1"]


@pytest.mark.parametrize("name", ["round.csv", "round.csv.gz"])
def test_log_round_trip(tmp_path, name):
    rng = np.random.default_rng(3)
    S = 200
    t = np.arange(S) / 400.0
    q, dq, tau = rng.normal(size=(S, 2)), rng.normal(size=(S, 2)), rng.normal(size=(S, 2)) * 1e3
    values = np.column_stack([t, q, dq, tau, rng.normal(size=S) * 1e-300])
    values[5, 3] = math.nan
    columns = ["t", "q1", "q2", "dq1", "dq2", "tau1", "tau2", "extra"]
    log = tpf.Log(columns, values, {"robot": "arm2", "rate_hz": "400"})
    path = tmp_path / name
    log.write(str(path))
    back = tpf.read_log(str(path))
    assert back.columns == columns
    assert back.meta[0] == ("tpf-log", "1")
    assert ("robot", "arm2") in back.meta
    np.testing.assert_array_equal(back.values, values)  # NaN in place, every bit kept
    assert back.joint_count == 2 and back.effort_prefix == "tau"
    np.testing.assert_array_equal(back.tau, tau)


def test_values_are_a_writable_view(tmp_path):
    log = tpf.Log(["t", "x"], np.array([[0.0, 1.0], [1.0, 2.0]]))
    log.column("x")[:] = [5.0, 6.0]
    np.testing.assert_array_equal(log.values[:, 1], [5.0, 6.0])
    with pytest.raises(ValueError, match="column names"):
        tpf.Log(["t"], np.zeros((2, 2)))
