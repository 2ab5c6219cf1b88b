"""The seeds' two-link arm (seeds 003/004) in closed form: masses m1, m2 at the link ends,
lengths L1, L2, gravity g along −y. builtin:planar2 is m1 = m2 = 1 kg, L1 = L2 = 1 m; a
second arm with other values is loaded from a DH table through load_string."""

import math

import numpy as np
import pytest

import screwdyn

G = 9.81


def arm(m1=1.0, m2=1.0, l1=1.0, l2=1.0):
    if (m1, m2, l1, l2) == (1.0, 1.0, 1.0, 1.0):
        return screwdyn.load("builtin:planar2")
    # Standard DH, point masses at the link ends (com = 0 in frame i, which sits at the end).
    text = f"""
format = "dh"
gravity = [0, -{G}, 0]
[[row]]
type = "R"
a = {l1}
mass = {m1}
[[row]]
type = "R"
a = {l2}
mass = {m2}
"""
    return screwdyn.load_string(text, "toml", name="arm")


def closed(m1, m2, l1, l2, q, v, a):
    c1, c2, s2, c12 = math.cos(q[0]), math.cos(q[1]), math.sin(q[1]), math.cos(q[0] + q[1])
    M = np.array([[m1 * l1**2 + m2 * (l1**2 + 2 * l1 * l2 * c2 + l2**2), m2 * (l1 * l2 * c2 + l2**2)],
                  [m2 * (l1 * l2 * c2 + l2**2), m2 * l2**2]])
    h = m2 * l1 * l2 * s2
    cv = np.array([-h * v[1] ** 2 - 2 * h * v[0] * v[1], h * v[0] ** 2])
    g = np.array([(m1 + m2) * G * l1 * c1 + m2 * G * l2 * c12, m2 * G * l2 * c12])
    return M, cv, g, h


PARAMS = [(1.0, 1.0, 1.0, 1.0), (2.0, 0.7, 0.8, 0.5)]
STATES = [([0.3, 0.5], [1.0, -1.0], [0.5, 0.2]), ([-1.2, 2.0], [0.4, 2.5], [-1.0, 0.3]),
          ([0.0, 0.0], [0.0, 0.0], [0.0, 0.0])]


@pytest.mark.parametrize("p", PARAMS)
def test_closed_forms_of_seeds_003_004(p):
    m1, m2, l1, l2 = p
    model = arm(*p)
    for q, v, a in STATES:
        M, cv, g, _ = closed(m1, m2, l1, l2, q, v, a)
        np.testing.assert_allclose(model.crba(q), M, atol=1e-12)
        np.testing.assert_allclose(model.coriolis_matrix(q, v) @ v, cv, atol=1e-12)
        np.testing.assert_allclose(model.gravity_torque(q), g, atol=1e-12)
        np.testing.assert_allclose(model.nonlinear_effects(q, v), cv + g, atol=1e-12)
        np.testing.assert_allclose(model.rnea(q, v, a), M @ a + cv + g, atol=1e-12)
        tau = M @ a + cv + g
        for method in ("aba", "crba", "walker-orin"):
            np.testing.assert_allclose(model.forward_dynamics(q, v, tau, method=method), a, atol=1e-10)
        # the seeds' closed form M = Sᵀ Lᵀ 𝔍 L S, C, g as arrays
        cf = model.closed_form(q, v)
        np.testing.assert_allclose(cf.M, M, atol=1e-12)
        np.testing.assert_allclose(cf.C @ v, cv, atol=1e-12)
        np.testing.assert_allclose(cf.g, g, atol=1e-12)
        np.testing.assert_allclose(cf.S.T @ cf.L.T @ cf.inertia @ cf.L @ cf.S, M, atol=1e-12)
        np.testing.assert_allclose(cf.L @ (np.eye(12) - cf.A), np.eye(12), atol=1e-12)
        np.testing.assert_allclose(cf.J, cf.L @ cf.S, atol=1e-12)
        # energies: ½ vᵀ M v and m g y of the two point masses
        y = m1 * l1 * math.sin(q[0]) + m2 * (l1 * math.sin(q[0]) + l2 * math.sin(q[0] + q[1]))
        np.testing.assert_allclose(model.kinetic_energy(q, v), 0.5 * np.dot(v, M @ v), atol=1e-12)
        np.testing.assert_allclose(model.potential_energy(q), G * y, atol=1e-12)
        np.testing.assert_allclose(model.total_energy(q, v), 0.5 * np.dot(v, M @ v) + G * y, atol=1e-12)
        np.testing.assert_allclose(model.power(tau, v), np.dot(tau, v), atol=1e-12)
        com = (m1 * np.array([l1 * math.cos(q[0]), l1 * math.sin(q[0]), 0])
               + m2 * np.array([l1 * math.cos(q[0]) + l2 * math.cos(q[0] + q[1]),
                                l1 * math.sin(q[0]) + l2 * math.sin(q[0] + q[1]), 0])) / (m1 + m2)
        np.testing.assert_allclose(model.center_of_mass(q), com, atol=1e-12)


@pytest.mark.parametrize("p", PARAMS)
def test_lagrange_coefficients_and_effective_inertias_of_seed_004(p):
    m1, m2, l1, l2 = p
    model = arm(*p)
    q = [0.4, 1.1]
    M, _, g, h = closed(m1, m2, l1, l2, q, [0, 0], [0, 0])
    lc = model.lagrange_coefficients(q)
    np.testing.assert_allclose(lc.D_ij, M, atol=1e-12)
    np.testing.assert_allclose(lc.D_i, g, atol=1e-12)
    # D_111 = 0, D_112 = D_121 = −h, D_122 = −h, D_211 = h, D_212 = D_221 = D_222 = 0
    want = np.array([[[0, -h], [-h, -h]], [[h, 0], [0, 0]]])
    np.testing.assert_allclose(lc.D_ijk, want, atol=1e-9)
    assert "D_{ij}" in lc._repr_markdown_()
    # dM/dq2: ∂M11/∂q2 = −2 m2 L1 L2 s2, ∂M12/∂q2 = −m2 L1 L2 s2
    dm = model.mass_matrix_derivatives(q)
    np.testing.assert_allclose(dm[0], 0, atol=1e-9)
    np.testing.assert_allclose(dm[1], [[-2 * h, -h], [-h, 0]], atol=1e-9)
    # effective inertias: locked = D_ii; joint 1 with joint 2 free: D11 − D12²/D22
    assert model.effective_inertia(q, 0) == pytest.approx(M[0, 0], abs=1e-12)
    assert model.effective_inertia(q, "joint2") == pytest.approx(M[1, 1], abs=1e-12)
    assert model.effective_inertia(q, 0, free="all") == pytest.approx(M[0, 0] - M[0, 1] ** 2 / M[1, 1], abs=1e-12)
    assert model.effective_inertia(q, 1, free=["joint1"]) == pytest.approx(M[1, 1] - M[0, 1] ** 2 / M[0, 0], abs=1e-12)


def test_rnea_trace_reads_like_the_lecture():
    model = arm()
    q, v, a = [0.3, 0.5], [1.0, -1.0], [0.5, 0.2]
    tr = model.rnea_trace(q, v, a)
    M, cv, g, _ = closed(1, 1, 1, 1, q, v, a)
    np.testing.assert_allclose(tr.tau, M @ np.array(a) + cv + g, atol=1e-12)
    # planar arm: ω_z of link i is the sum of the joint rates; |v| of the link-2 frame origin
    # (the tip) is the classic planar tip speed.
    np.testing.assert_allclose(tr.twist[:, 2], [v[0], v[0] + v[1]], atol=1e-14)
    x_dot = -math.sin(q[0]) * v[0] - math.sin(q[0] + q[1]) * (v[0] + v[1])
    y_dot = math.cos(q[0]) * v[0] + math.cos(q[0] + q[1]) * (v[0] + v[1])
    assert np.linalg.norm(tr.twist[1, 3:]) == pytest.approx(math.hypot(x_dot, y_dot), abs=1e-12)
    # τ_i = S_iᵀ W_i, and V̇_0 = (0, −g) = (0, 0, 0 | 0, 9.81, 0)
    np.testing.assert_allclose(np.einsum("ij,ij->i", tr.screw, tr.wrench), tr.tau, atol=1e-12)
    np.testing.assert_allclose(tr.base_acceleration, [0, 0, 0, 0, G, 0])
    md = tr._repr_markdown_()
    assert "Forward iterations" in md and "Backward iterations" in md
    assert r"\tau_2" in md and r"\mathrm{Ad}_{H_1^2}" in md
    assert "τ_1 = S_1ᵀ W_1" in str(tr)


def test_external_and_tip_wrenches():
    model = arm()
    model.gravity = [0, 0, 0]
    q = [0.0, 0.0]
    # Seed 000 statics: a tip pushing 1 N along its local y needs τ = J_eᵀ W = (L1 + L2, L2).
    tau = model.rnea(q, tip_wrenches={"link2": [0, 0, 0, 0, 1, 0]})
    np.testing.assert_allclose(tau, [2.0, 1.0], atol=1e-12)
    # The environment pushing on link 2 with the same force: τ = −(2, 1).
    np.testing.assert_allclose(model.rnea(q, fext={"link2": [0, 0, 0, 0, 1, 0]}), [-2.0, -1.0], atol=1e-12)
    # In the world frame at q = 0: f = ŷ at the tip (2, 0, 0): moment about the origin 2 ẑ.
    np.testing.assert_allclose(model.rnea(q, fext_world={"link2": [0, 0, 2, 0, 1, 0]}), [-2.0, -1.0], atol=1e-12)
    # Forward dynamics with the same wrench balances the torque: a = 0.
    np.testing.assert_allclose(model.forward_dynamics(q, [0, 0], [2.0, 1.0],
                               tip_wrenches={"link2": [0, 0, 0, 0, 1, 0]}), [0, 0], atol=1e-12)


def test_closed_form_to_sympy():
    sympy = pytest.importorskip("sympy")
    cf = arm().closed_form([0.3, 0.5], [1.0, -1.0])
    s = cf.to_sympy()
    assert isinstance(s["M"], sympy.Matrix) and s["M"].shape == (2, 2)
    assert float(s["M"][0, 1]) == cf.M[0, 1]
    assert "\\mathfrak{J}" in cf._repr_markdown_()
