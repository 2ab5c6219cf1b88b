"""Derivatives of the dynamics, the regressor and identification from Python: against
Pinocchio's computeRNEADerivatives / computeABADerivatives (the fixtures of
crates/screwdyn/tests/pinocchio_derivatives.rs), central finite differences of model.rnea /
model.aba, per-state calls, RNEA itself (Y π = τ) and the standard parameters by hand."""

import numpy as np
import pytest

import screwdyn
from conftest import fixture_model

TOL = 1e-9


def rel(got, want):
    got, want = np.asarray(got), np.asarray(want, dtype=float)
    assert got.shape == want.shape
    return float(np.max(np.abs(got - want) / np.maximum(1.0, np.abs(want))))


def fext_of(m, d):
    """The fixture's per-body wrenches (link frame, moving with the link) as rnea's fext."""
    return {name: w for name, w in zip(m.link_names, d["fext"]) if any(x != 0 for x in w)}


@pytest.mark.parametrize("name", ["ur5", "panda", "tree"])
def test_derivatives_match_pinocchio(name):
    m, fx = fixture_model(name)
    with_wrenches = 0
    for k, s in enumerate(fx["states"]):
        d = s["derivatives"]
        fext = fext_of(m, d)
        with_wrenches += bool(fext)
        dq, dv, mm = m.rnea_derivatives(s["q"], s["v"], s["a"], fext=fext)
        assert rel(dq, d["dtau_dq"]) < TOL, (name, k)
        assert rel(dv, d["dtau_dv"]) < TOL, (name, k)
        assert rel(mm, d["dtau_da"]) < TOL, (name, k)
        assert rel(m.rnea(s["q"], s["v"], s["a"], fext=fext), d["tau_fext"]) < TOL
        ddq, ddv, minv = m.aba_derivatives(s["q"], s["v"], s["tau_in"], fext=fext)
        assert rel(m.aba(s["q"], s["v"], s["tau_in"], fext=fext), d["qdd_fext"]) < TOL
        assert rel(ddq, d["dqdd_dq"]) < TOL, (name, k)
        assert rel(ddv, d["dqdd_dv"]) < TOL, (name, k)
        assert rel(minv, d["minv"]) < TOL, (name, k)
    assert with_wrenches == 10  # half of the 20 states carry external wrenches


def central(f, x, h=1e-6):
    """Central differences of f at x: column j is (f(x + h e_j) − f(x − h e_j)) / 2h."""
    x = np.asarray(x, dtype=float)
    cols = []
    for j in range(len(x)):
        e = np.zeros_like(x)
        e[j] = h
        cols.append((f(x + e) - f(x - e)) / (2 * h))
    return np.stack(cols, axis=1)


def close_fd(got, want, tol=1e-6):
    scale = max(1.0, float(np.max(np.abs(want))))
    assert np.max(np.abs(got - want)) <= tol * scale, np.max(np.abs(got - want))


@pytest.mark.parametrize("robot", ["builtin:ur5", "builtin:planar2", "builtin:panda"])
def test_derivatives_match_finite_differences(robot):
    m = screwdyn.load(robot)
    rng = np.random.default_rng(7)
    world = {m.link_names[-1]: [0.3, -0.2, 0.1, 2.0, -1.0, 0.5]}
    for _ in range(3):
        q, v, a, tau = (rng.uniform(-1.5, 1.5, m.nq) for _ in range(4))
        dq, dv, mm = m.rnea_derivatives(q, v, a, fext_world=world)
        close_fd(dq, central(lambda x: m.rnea(x, v, a, fext_world=world), q))
        close_fd(dv, central(lambda x: m.rnea(q, x, a, fext_world=world), v))
        close_fd(mm, central(lambda x: m.rnea(q, v, x, fext_world=world), a))
        ddq, ddv, minv = m.aba_derivatives(q, v, tau, fext_world=world)
        close_fd(ddq, central(lambda x: m.aba(x, v, tau, fext_world=world), q))
        close_fd(ddv, central(lambda x: m.aba(q, x, tau, fext_world=world), v))
        close_fd(minv, central(lambda x: m.aba(q, v, x, fext_world=world), tau))


def test_dtau_dv_is_twice_coriolis_and_da_is_crba():
    # docs/derivatives.md: without friction ∂τ/∂q̇ = 2 C(q, q̇) (the Christoffel C) and
    # ∂τ/∂q̈ = M; the forward-dynamics derivatives are −M⁻¹ times the inverse ones.
    m = screwdyn.load("builtin:ur5")
    rng = np.random.default_rng(3)
    q, v, a = (rng.uniform(-2, 2, m.nq) for _ in range(3))
    dq, dv, mm = m.rnea_derivatives(q, v, a)
    assert rel(dv, 2 * m.coriolis_matrix(q, v)) < 1e-12
    assert rel(mm, m.crba(q)) < 1e-12
    tau = m.rnea(q, v, a)
    ddq, ddv, minv = m.aba_derivatives(q, v, tau)
    assert rel(minv, np.linalg.inv(m.crba(q))) < 1e-10
    assert rel(ddq, -minv @ dq) < 1e-10
    assert rel(ddv, -minv @ dv) < 1e-10


@pytest.mark.parametrize("threads", [None, 1, 2])
def test_batches_equal_per_state(threads):
    m, fx = fixture_model("panda")
    rng = np.random.default_rng(11)
    n = 700  # more than one rayon chunk
    q, v, a, tau = (rng.uniform(-2, 2, (n, m.nq)) for _ in range(4))
    bq, bv, bm = m.rnea_derivatives(q, v, a, threads=threads)
    cq, cv, cm = m.aba_derivatives(q, v, tau, threads=threads)
    y = m.regressor(q, v, a, threads=threads)
    assert bq.shape == (n, m.nq, m.nq) and y.shape == (n, m.nq, 10 * m.nq)
    for k in (0, 1, 517, n - 1):
        sq, sv, sm = m.rnea_derivatives(q[k], v[k], a[k])
        np.testing.assert_array_equal(bq[k], sq)
        np.testing.assert_array_equal(bv[k], sv)
        np.testing.assert_array_equal(bm[k], sm)
        tq, tv, tm = m.aba_derivatives(q[k], v[k], tau[k])
        np.testing.assert_array_equal(cq[k], tq)
        np.testing.assert_array_equal(cv[k], tv)
        np.testing.assert_array_equal(cm[k], tm)
        np.testing.assert_array_equal(y[k], m.regressor(q[k], v[k], a[k]))
    # a single state broadcast against stacked ones
    dq1, _, _ = m.rnea_derivatives(q[0], v[:3], a[:3])
    np.testing.assert_array_equal(dq1[2], m.rnea_derivatives(q[0], v[2], a[2])[0])


@pytest.mark.parametrize("robot", ["builtin:ur5", "builtin:panda", "builtin:planar2"])
def test_regressor_times_parameters_is_rnea(robot):
    m = screwdyn.load(robot)
    rng = np.random.default_rng(5)
    q, v, a = (rng.uniform(-2, 2, (50, m.nq)) for _ in range(3))
    pi = m.inertial_parameters()
    assert pi.shape == (10 * m.nq,)
    tau = m.rnea(q, v, a)
    got = m.regressor(q, v, a) @ pi
    assert np.max(np.abs(got - tau)) <= 1e-12 * max(1.0, np.max(np.abs(tau)))


def test_standard_parameters_by_hand():
    # builtin:planar2 (seed 003): point masses m1 = m2 = 1 at the link ends, L1 = L2 = 1;
    # the link frames sit at the link ends, so each body's first moment and inertia about its
    # frame origin are zero and its mass is 1.
    m = screwdyn.load("builtin:planar2")
    names = m.parameter_names()
    assert names[:10] == ["m_link1", "mx_link1", "my_link1", "mz_link1", "Ixx_link1",
                          "Ixy_link1", "Iyy_link1", "Ixz_link1", "Iyz_link1", "Izz_link1"]
    pi = dict(zip(names, m.inertial_parameters()))
    assert pi["m_link1"] == 1.0 and pi["m_link2"] == 1.0
    assert all(abs(pi[k]) < 1e-15 for k in names if not k.startswith("m_"))
    fr = m.parameter_names(friction=True)
    assert fr[-2:] == ["fv_joint2", "fc_joint2"] and len(m.inertial_parameters(True)) == 24


def test_base_parameters_of_the_seed_arm():
    # docs/derivatives.md §3: the planar arm's six base parameters.
    m = screwdyn.load("builtin:planar2")
    b = m.base_parameters()
    assert b.expressions == ["Izz_link1 − m_link1 − m_link2", "Izz_link2 − m_link2",
                             "mx_link1 + m_link1 + m_link2", "my_link1", "mx_link2 + m_link2",
                             "my_link2"]
    pi = dict(zip(m.parameter_names(), m.inertial_parameters()))
    # Evaluate each expression from the standard parameters by hand.
    by_hand = [pi["Izz_link1"] - pi["m_link1"] - pi["m_link2"], pi["Izz_link2"] - pi["m_link2"],
               pi["mx_link1"] + pi["m_link1"] + pi["m_link2"], pi["my_link1"],
               pi["mx_link2"] + pi["m_link2"], pi["my_link2"]]
    np.testing.assert_allclose(b.model_values, by_hand, atol=1e-12)


@pytest.mark.parametrize("robot", ["builtin:planar2", "builtin:ur5"])
def test_identify_recovers_base_parameters_from_noise_free_data(robot):
    m = screwdyn.load(robot)
    rng = np.random.default_rng(21)
    n = 400
    q = rng.uniform(-np.pi, np.pi, (n, m.nq))
    v, a = rng.uniform(-2, 2, (n, m.nq)), rng.uniform(-2, 2, (n, m.nq))
    tau = m.rnea(q, v, a)
    est = m.identify(q, v, a, tau)
    assert est.samples == n and len(est.values) == len(est.expressions)
    # The base parameters of the model's own parameters, π_b = K π ...
    want = est.combination_matrix @ m.inertial_parameters()
    np.testing.assert_allclose(est.values, want, rtol=0, atol=1e-8 * max(1, np.abs(want).max()))
    np.testing.assert_allclose(est.model_values, want, atol=1e-12)
    # ... predict the torques exactly: the regressor's base columns times π̂_b.
    cols = [m.parameter_names().index(x) for x in est.independent]
    pred = m.regressor(q[:20], v[:20], a[:20])[:, :, cols] @ est.values
    np.testing.assert_allclose(pred, tau[:20], atol=1e-8)
    assert est.sigma < 1e-9 and est.condition_number < 1e10


def test_bad_input_is_a_value_error():
    m = screwdyn.load("builtin:ur5")
    z = np.zeros(6)
    with pytest.raises(ValueError, match="q has 3 values"):
        m.rnea_derivatives([0, 0, 0], z, z)
    with pytest.raises(ValueError, match="v"):
        m.aba_derivatives(z, [0.0, np.nan, 0, 0, 0, 0], z)
    with pytest.raises(ValueError, match="stacked arguments need the same number of rows"):
        m.regressor(np.zeros((3, 6)), np.zeros((4, 6)), z)
    with pytest.raises(ValueError, match="too few samples"):
        m.identify(np.zeros((1, 6)), np.zeros((1, 6)), np.zeros((1, 6)), np.zeros((1, 6)))
    with pytest.raises(ValueError, match="rank-deficient"):
        k = np.zeros((50, 6))
        m.identify(k, k, k, m.rnea(k, k, k))
    with pytest.raises(ValueError, match="stacked samples"):
        m.identify(np.zeros((5, 6)), z, np.zeros((5, 6)), np.zeros((5, 6)))


def test_functional_forms():
    m = screwdyn.load("builtin:planar2")
    q, v, a = [0.3, -0.4], [0.5, 0.2], [0.1, -0.3]
    for f, args in (("rnea_derivatives", (q, v, a)), ("aba_derivatives", (q, v, a))):
        for x, y in zip(getattr(screwdyn, f)(m, *args), getattr(m, f)(*args)):
            np.testing.assert_array_equal(x, y)
    np.testing.assert_array_equal(screwdyn.regressor(m, q, v, a), m.regressor(q, v, a))
