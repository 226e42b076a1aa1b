"""Friction files and parameter files from Python: the Stribeck curve against its formula, LuGre
settling on it, the nominal model's prediction against its parts, and a parameter file's round
trip."""
import json

import numpy as np
import pytest

import tpf


@pytest.fixture(scope="module")
def arm(data):
    return tpf.Robot(str(data / "arm4.robot.json"))


def stribeck_formula(p, dq, abs_g):
    """The documented curve: g·sgn(q̇) + (b + α_v|G|)·q̇, g = τ_c + α_c|G| + (τ_s−τ_c)e^−|q̇/q̇_s|^δ."""
    level = p.coulomb + p.load_coulomb * abs_g + (p.static_friction - p.coulomb) * np.exp(
        -np.abs(dq / p.stribeck_velocity)**p.stribeck_exponent)
    return level * np.sign(dq) + (p.viscous + p.load_viscous * abs_g) * dq


def test_friction_file_and_stribeck_curve(data):
    path = data / "arm4.friction.json"
    p = tpf.load_stribeck_parameters(str(path))
    declared = json.loads(path.read_text())
    assert p.joint_count == 4
    np.testing.assert_array_equal(p.coulomb, declared["coulomb"])
    np.testing.assert_array_equal(p.static_friction, declared["static"])
    np.testing.assert_array_equal(p.load_viscous, declared["load_viscous"])
    rng = np.random.default_rng(1)
    dq, abs_g = rng.uniform(-1, 1, (50, 4)), rng.uniform(0, 20, (50, 4))
    dq[0] = 0.0
    tau = p.friction(dq, abs_g)
    assert np.abs(tau - stribeck_formula(p, dq, abs_g)).max() < 1e-12
    np.testing.assert_array_equal(tau[0], 0.0)  # sgn(0) = 0
    assert np.abs(p.friction(dq) - stribeck_formula(p, dq, 0.0)).max() < 1e-12


def test_lugre_settles_on_the_stribeck_curve(data):
    lugre = tpf.load_lugre_parameters(str(data / "arm4.friction.json"))
    assert lugre.bristle_stiffness[0] == 1.2e4
    dq = np.tile([0.3, -0.2, 0.5, -0.05], (400, 1))
    tau, z = lugre.simulate(dq, 1e-3)
    assert tau.shape == (400, 4) and z.shape == (4,)
    steady = lugre.stribeck.friction(dq[-1])
    assert np.abs(tau[-1] - steady).max() < 1e-9
    assert np.abs(tau[0] - steady).max() > 0.1  # from rest it starts elsewhere
    # Continuing from the returned deflection is the same as one longer run.
    first, z_mid = lugre.simulate(dq[:200], 1e-3)
    second, _ = lugre.simulate(dq[200:], 1e-3, z0=z_mid)
    np.testing.assert_array_equal(np.vstack([first, second]), tau)


def test_nominal_model_predicts_its_parts(data, arm):
    model = tpf.load_nominal_model(str(data / "arm4.params.json"), str(data / "arm4.robot.json"))
    assert model.joint_count == 4 and model.base_count == len(model.base_values) > 0
    assert model.base_names[0] == "Izz1"
    rng = np.random.default_rng(2)
    q, dq, ddq = (rng.uniform(-a, a, (20, 4)) for a in (2.5, 1.0, 3.0))
    rigid, friction = model.predict_effort(q, dq, ddq)
    Y = arm.compute_regressor(q, dq, ddq)
    by_regressor = Y[:, :, model.base_columns] @ model.base_values
    assert np.abs(rigid - by_regressor).max() < 1e-12 * (1 + np.abs(rigid).max())
    # The declared model's base parameters are those of the robot file: rigid = RNEA.
    assert np.abs(rigid - arm.rnea(q, dq, ddq)).max() < 1e-8 * np.abs(rigid).max()
    abs_g = np.abs(arm.compute_gravity(q))
    assert np.abs(friction - model.friction.friction(dq, abs_g)).max() < 1e-12


def test_parameter_file_round_trip(data, tmp_path):
    robot = str(data / "arm4.robot.json")
    model = tpf.load_nominal_model(str(data / "arm4.params.json"), robot)
    path = tmp_path / "copy.params.json"
    model.save(str(path), source="python round trip")
    assert json.loads(path.read_text())["source"] == "python round trip"
    back = tpf.load_nominal_model(str(path), robot)
    assert back.base_names == model.base_names
    np.testing.assert_array_equal(back.base_values, model.base_values)
    np.testing.assert_array_equal(back.friction.viscous, model.friction.viscous)
    q, dq, ddq = np.full(4, 0.3), np.array([0.2, -0.1, 0.0, 0.5]), np.full(4, -1.0)
    for a, b in zip(back.predict_effort(q, dq, ddq), model.predict_effort(q, dq, ddq)):
        np.testing.assert_array_equal(a, b)
