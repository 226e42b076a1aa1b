"""The run-time estimator over arrays and logs from Python: equal to the C++ replay of the same log
(tests/python/replay_reference.cpp) to 1e-12, the same from arrays as from a log, from currents as
from torques, and a push on a resting joint found where it was applied."""
import os
import subprocess

import numpy as np
import pytest

import tpf


def child_env():
    """The environment of a child program: without the ASan runtime the sanitized build preloads
    into Python (the sanitized tools carry their own)."""
    return {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}

RATE = 400.0  # Hz, the arm4 estimator file's sample period


@pytest.fixture(scope="module")
def files(data):
    return {"params": str(data / "arm4.params.json"), "robot": str(data / "arm4.robot.json"),
            "estimator": str(data / "arm4.estimator.json"),
            "weights": str(data / "weights/arm4.tcn.json")}


@pytest.fixture(scope="module")
def motion(files):
    """6 s of arm4: a sine on every joint, joint 2 pushed by 3 N·m from 3 to 4 s, then 2 s at
    rest; the effort is the nominal model's with seeded noise."""
    model = tpf.load_nominal_model(files["params"], files["robot"])
    t = np.arange(int(8 * RATE)) / RATE
    moving = t < 6.0
    w = 2 * np.pi * np.array([0.3, 0.4, 0.5, 0.6])
    phase = np.minimum(t, 6.0)[:, None]
    q = 0.4 * np.sin(w * phase)
    dq = np.where(moving[:, None], 0.4 * w * np.cos(w * phase), 0.0)
    ddq = np.where(moving[:, None], -0.4 * w**2 * np.sin(w * phase), 0.0)
    rigid, friction = model.predict_effort(q, dq, ddq)
    rng = np.random.default_rng(3)
    tau = rigid + friction + rng.normal(0, 0.01, q.shape)
    push = (t >= 3.0) & (t < 4.0)
    tau[push, 1] += 3.0
    return {"t": t, "q": q, "dq": dq, "tau": tau, "push": push}


def log_of(m):
    n = m["q"].shape[1]
    columns = (["t"] + [f"q{j}" for j in range(1, n + 1)] + [f"dq{j}" for j in range(1, n + 1)]
               + [f"tau{j}" for j in range(1, n + 1)])
    return tpf.Log(columns, np.column_stack([m["t"], m["q"], m["dq"], m["tau"]]),
                   {"source": "SIMULATED: test_estimate.py"})


def arrays(m):
    return {k: m[k] for k in ("t", "q", "dq", "tau")}


def test_equals_the_cpp_replay(files, motion, tmp_path):
    path = tmp_path / "motion.csv"
    log_of(motion).write(str(path))
    reference = tmp_path / "reference.csv"
    subprocess.run(env=child_env(), args=[os.environ["TPF_REPLAY_REFERENCE"], files["params"], files["robot"],
                    files["estimator"], files["weights"], str(path), str(reference)], check=True)
    ref = np.loadtxt(reference, delimiter=",")
    est = tpf.estimate(str(path), files["params"], files["robot"], estimator=files["estimator"],
                       weights=files["weights"])
    n = 4
    columns = [est["residual"], est["compensation"], est["static_estimate"],
               est["fused_estimate"], est["external"]]
    assert ref.shape == (len(motion["t"]), 3 + 5 * n)
    np.testing.assert_array_equal(est["t"], ref[:, 0])
    np.testing.assert_array_equal(est["state"], ref[:, 1])
    np.testing.assert_array_equal(est["estimator_contact"], ref[:, 2])
    for k, got in enumerate(columns):
        want = ref[:, 3 + k * n:3 + (k + 1) * n]
        np.testing.assert_array_equal(np.isnan(got), np.isnan(want))
        assert np.nanmax(np.abs(got - want)) <= 1e-12
    assert np.nanmax(np.abs(est["compensation"])) > 0  # the compensator ran


def test_arrays_equal_the_log_and_currents_equal_torques(files, motion):
    kw = {"estimator": files["estimator"], "weights": files["weights"]}
    from_arrays = tpf.estimate(arrays(motion), files["params"], files["robot"], **kw)
    from_log = tpf.estimate(log_of(motion), files["params"], files["robot"], **kw)
    robot = tpf.Robot(files["robot"])
    currents = dict(arrays(motion))
    currents["i"] = currents.pop("tau") / robot.torque_constant * 1000.0
    from_currents = tpf.estimate(currents, files["params"], files["robot"], **kw)
    for key in ("residual", "external", "fused_estimate", "compensation"):
        np.testing.assert_array_equal(from_arrays[key], from_log[key])
        np.testing.assert_allclose(from_currents[key], from_arrays[key], rtol=0, atol=1e-9)
    np.testing.assert_array_equal(from_arrays["state"], from_log["state"])
    assert from_arrays["residual"].shape == (len(motion["t"]), 4)
    assert from_arrays["state"].dtype == np.int32
    assert not from_arrays["residual"].flags.writeable


def test_push_on_a_moving_joint_is_found(files, motion):
    est = tpf.estimate(arrays(motion), files["params"], files["robot"],
                       estimator=files["estimator"])
    t, push = motion["t"], motion["push"]
    settled = push & (t >= 3.1)
    # The residual holds the 3 N·m push on joint 2 and nothing else; the estimator reports a
    # contact through it, on joint 2 only, and none before or after.
    residual = np.median(est["residual"][settled], axis=0)
    assert residual[1] == pytest.approx(3.0, abs=0.15)
    assert np.abs(residual[[0, 2, 3]]).max() < 0.1
    contact = est["estimator_contact"]
    assert contact[settled].mean() > 0.8
    assert contact[(t > 1.0) & (t < 2.95)].max() == 0
    assert contact[(t > 4.2) & (t < 5.9)].mean() < 0.05
    external = est["external"][settled]
    assert np.median(external[:, 1]) > 0.3 and np.all(external[:, [0, 2, 3]] == 0)
    assert set(np.unique(est["state"])) <= {0, 1, 2}


def test_bad_input_raises(files, motion):
    base = arrays(motion)
    with pytest.raises(ValueError, match="tau"):
        tpf.estimate({k: v for k, v in base.items() if k != "tau"}, files["params"],
                     files["robot"], estimator=files["estimator"])
    wrong = dict(base, q=base["q"][:, :3])
    with pytest.raises(ValueError, match=r"q must be \(S, 4\)"):
        tpf.estimate(wrong, files["params"], files["robot"], estimator=files["estimator"])
    with pytest.raises(tpf.Error) as e:
        tpf.estimate(base, files["params"], files["robot"])  # no estimator parameter file
    assert e.value.field == "estimator"
    with pytest.raises(tpf.Error) as e:
        tpf.estimate(base, files["params"], files["robot"], estimator=files["params"])
    assert e.value.file.endswith("arm4.params.json")
