"""identify and validate from Python against the CLI on the same MEASURED Kinova Gen3 logs
(data/real/kinova-gen3, MIT licence): the Python results equal the JSON `tpf identify --out` and
`tpf validate --json` write, field by field; the parameter file round-trips; bad input raises."""
import json
import math
import os
import pathlib
import subprocess

import numpy as np
import pytest

import tpf


def child_env():
    """The environment of a child program: without the ASan runtime the sanitized build preloads
    into Python (the sanitized tools carry their own)."""
    return {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}

GEN3 = "real/kinova-gen3"
FIT = ["RunTrajectory1.csv.gz", "Trajectory1.csv.gz"]
HELD_OUT = ["opti_traj_testing2.csv.gz"]


def same(a, b, path="", rel=1e-12):
    """Asserts that two JSON values are equal, numbers to `rel`, naming the first field that
    differs."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and sorted(a) == sorted(b), f"{path}: keys {sorted(a)}"
        for k in a:
            same(a[k], b[k], f"{path}.{k}", rel)
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), f"{path}: length"
        for k, (x, y) in enumerate(zip(a, b)):
            same(x, y, f"{path}[{k}]", rel)
    elif isinstance(a, float) or isinstance(b, float):
        assert math.isclose(a, b, rel_tol=rel, abs_tol=1e-300), f"{path}: {a} != {b}"
    else:
        assert a == b, f"{path}: {a!r} != {b!r}"


@pytest.fixture(scope="module")
def paths(data):
    logs = data / GEN3 / "logs"
    return {"robot": str(data / GEN3 / "gen3.robot.json"),
            "fit": [str(logs / f) for f in FIT], "held_out": [str(logs / f) for f in HELD_OUT]}


def cli(*args):
    subprocess.run(env=child_env(), args=[os.environ["TPF_CLI"], *args], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)


@pytest.fixture(scope="module")
def identified(paths, tmp_path_factory):
    out = tmp_path_factory.mktemp("identify")
    params = out / "cli.params.json"
    cli("identify", *sum((["--log", p] for p in paths["fit"]), []), "--robot", paths["robot"],
        "--out", str(params), "--quiet")
    result = tpf.identify(paths["fit"], paths["robot"])
    return result, params, out


def test_identify_equals_the_cli(identified, paths):
    result, params, out = identified
    written = json.loads(params.read_text())
    same(result.fit, written["fit"])
    assert result.source == written["source"]
    # Refitted on every row exactly where the CLI held rows out (two files of one motion are one
    # group: nothing is left to hold out, and the fit says so).
    assert result.refitted == ("heldout_note" not in written["fit"])
    # The model itself: the parameter file Python writes is the CLI's, field by field.
    result.save(str(out / "py.params.json"))
    same(json.loads((out / "py.params.json").read_text()), written)
    cli_model = tpf.load_nominal_model(str(params), paths["robot"])
    np.testing.assert_array_equal(result.nominal.base_values, cli_model.base_values)
    assert result.nominal.base_names == cli_model.base_names
    # Held out: the last file; the held-out RMSE per joint is that of the residual's held-out rows.
    assert len(result.fit["heldout_rmse"]) == 7
    assert result.residual.shape[1] == 7 and not result.residual.flags.writeable


def test_parameter_file_round_trip(identified, paths, tmp_path):
    result, _, _ = identified
    path = tmp_path / "round.params.json"
    result.save(str(path))
    back = tpf.load_nominal_model(str(path), paths["robot"])
    np.testing.assert_array_equal(back.base_values, result.nominal.base_values)
    np.testing.assert_array_equal(back.friction.coulomb, result.nominal.friction.coulomb)
    np.testing.assert_array_equal(back.friction.viscous, result.nominal.friction.viscous)
    q = np.linspace(-1, 1, 7 * 5).reshape(5, 7)
    for a, b in zip(back.predict_effort(q, 0.5 * q, q), result.nominal.predict_effort(q, 0.5 * q, q)):
        np.testing.assert_array_equal(a, b)


def test_validate_equals_the_cli(identified, paths):
    result, params, out = identified
    report = out / "validate.json"
    cli("validate", "--params", str(params), "--robot", paths["robot"],
        *sum((["--log", p] for p in paths["held_out"]), []), "--json", str(report))
    written = json.loads(report.read_text())
    same(tpf.validate(str(params), paths["held_out"], robot=paths["robot"]), written)
    # The same from the model object, and from the log read beforehand.
    same(tpf.validate(result.nominal, paths["held_out"]), written)
    assert written["estimates"] and written["files"] == paths["held_out"]


def test_identify_options_change_the_fit(paths):
    plain = tpf.identify(paths["fit"][:1], paths["robot"], load_friction=False,
                         inertia_prior=False, hold_out=False)
    assert not plain.refitted
    assert "inertia_prior" not in plain.fit
    np.testing.assert_array_equal(plain.nominal.friction.load_coulomb, 0)
    assert plain.fit["heldout_rmse"][0]["all"] is None  # nothing held out: JSON null
    # A tpf.Log read beforehand gives the same fit as its path.
    from_log = tpf.identify(tpf.read_log(paths["fit"][0]), paths["robot"], load_friction=False,
                            inertia_prior=False, hold_out=False)
    same(from_log.fit, plain.fit)
    np.testing.assert_array_equal(from_log.nominal.base_values, plain.nominal.base_values)


def test_bad_input_raises(paths, data):
    with pytest.raises(tpf.Error) as e:
        tpf.identify(paths["fit"][:1], str(data / "arm4.robot.json"))
    assert e.value.file == paths["fit"][0]
    with pytest.raises(tpf.Error) as e:
        tpf.identify(str(data / "no-such-log.csv"), paths["robot"])
    assert e.value.file.endswith("no-such-log.csv")
    with pytest.raises(ValueError, match="robot"):
        tpf.validate(str(data / "arm4.params.json"), paths["held_out"])
    with pytest.raises(tpf.Error) as e:
        tpf.validate(str(data / "arm4.params.json"), paths["held_out"],
                     robot=str(data / "arm4.robot.json"))
    assert "4" in str(e.value) and "7" in str(e.value)
    with pytest.raises(TypeError):
        tpf.identify(paths["fit"], paths["robot"], 1e-4)  # options are keyword-only


def test_diagnose_equals_the_cli(paths, tmp_path):
    report, params = tmp_path / "cli.diagnosis.json", tmp_path / "cli.params.json"
    cli("diagnose", "--log", paths["fit"][0], "--robot", paths["robot"], "--json", str(report),
        "--params", str(params), "--quiet")
    result = tpf.diagnose(paths["fit"][0], paths["robot"])
    same(result.report, json.loads(report.read_text()))
    result.save(str(tmp_path / "py.params.json"))
    same(json.loads((tmp_path / "py.params.json").read_text()), json.loads(params.read_text()))
    with pytest.raises(ValueError, match="min_improvement"):
        tpf.diagnose(paths["fit"][0], paths["robot"], min_improvement=1.5)


def test_train_equals_the_cli(identified, paths, tmp_path):
    _, params, _ = identified
    short = ["--per-joint", "--max-epochs", "2", "--epoch-windows", "16", "--verbose"]
    cli_out = tmp_path / "cli.tcn.json"
    run = subprocess.run(env=child_env(), args=[os.environ["TPF_CLI"], "train", *sum((["--log", p] for p in paths["fit"]), []),
                          "--params", str(params), "--robot", paths["robot"], "--out", str(cli_out),
                          *short], check=True, capture_output=True, text=True)
    result = tpf.train(paths["fit"], str(params), paths["robot"], str(tmp_path / "py.tcn.json"),
                       per_joint=True, max_epochs=2, epoch_windows=16)
    assert len(result["files"]) == 7 and len(result["networks"]) == 7
    for j, (path, weights) in enumerate(zip(result["files"], result["weights"])):
        assert path.endswith(f"py.tcn.joint{j + 1}.json")
        same(weights, json.loads((tmp_path / f"cli.tcn.joint{j + 1}.json").read_text()))
        assert weights == json.loads(pathlib.Path(path).read_text())
    # The held-out verdict the CLI prints, line by line.
    printed = [line[len("train:   "):] for line in run.stdout.splitlines()
               if line.startswith("train:   joint")]
    assert result["held_out_lines"] == printed
    moving = result["held_out"]["moving"]
    assert moving["nominal_rmse"].shape == (7,) and np.all(moving["rows"] > 0)
    np.testing.assert_allclose(moving["gain"], 1 - moving["compensated_rmse"] / moving["nominal_rmse"],
                               rtol=1e-12)
    assert all(n["epochs"] <= 2 for n in result["networks"])
    with pytest.raises(tpf.Error) as e:
        tpf.train(paths["fit"], str(params), paths["robot"], str(tmp_path / "x.json"),
                  without_input=["torque"])
    assert e.value.field == "input"
    with pytest.raises(ValueError, match="joint_hidden"):
        tpf.train(paths["fit"], str(params), paths["robot"], str(tmp_path / "x.json"),
                  joint_hidden=8)
