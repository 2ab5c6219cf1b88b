"""Models pickle (so they travel to worker processes) and come back equal, computing the same
bits."""

import pathlib
import pickle

import numpy as np
import pytest

import screwdyn
from conftest import ROOT, fixture_model

rng = np.random.default_rng(3)


def same(a, b):
    assert a == b
    assert a.joint_names == b.joint_names and a.frame_names == b.frame_names
    q, v, t = (rng.normal(size=a.nq) for _ in range(3))
    np.testing.assert_array_equal(a.rnea(q, v, t), b.rnea(q, v, t))
    np.testing.assert_array_equal(a.aba(q, v, t), b.aba(q, v, t))
    np.testing.assert_array_equal(a.gravity, b.gravity)


@pytest.mark.parametrize("source", ["builtin:ur5", "builtin:planar2", "builtin:branched",
                                    str(ROOT / "models" / "ur5.urdf"), ROOT / "models" / "panda.toml"])
def test_round_trip(source):
    m = screwdyn.load(source)
    same(m, pickle.loads(pickle.dumps(m)))


def test_round_trip_of_string_models_and_changes():
    m, _ = fixture_model("tree")
    same(m, pickle.loads(pickle.dumps(m)))
    m.gravity = [0.5, 0.0, -3.0]
    back = pickle.loads(pickle.dumps(m, protocol=pickle.HIGHEST_PROTOCOL))
    same(m, back)
    np.testing.assert_array_equal(back.gravity, [0.5, 0.0, -3.0])
    f = m.with_joint_friction(np.full(m.nq, 0.1), np.full(m.nq, 0.2))
    back = pickle.loads(pickle.dumps(f))
    same(f, back)
    np.testing.assert_array_equal(back.damping, np.full(m.nq, 0.1))
    assert f != m


def test_gravity_changes_the_dynamics():
    # g(q) scales with gravity (physical invariant), and the model's repr shows it.
    m = screwdyn.load("builtin:ur5")
    q = rng.normal(size=6)
    g0 = m.gravity_torque(q)
    m.gravity = m.gravity * 2
    np.testing.assert_allclose(m.gravity_torque(q), 2 * g0, rtol=1e-12, atol=1e-12)
    assert "gravity=[0, 0, -19.62]" in repr(m)
