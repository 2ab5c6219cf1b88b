"""screwdyn.symbolic: the seeds' two-link arm term by term against hand-written SymPy
expressions of seeds 003/004 (symbolic equality), and numeric substitution against the numeric
library (CRBA, RNEA, g) on the UR5 and the Panda at random states."""

import numpy as np
import pytest

import screwdyn
import screwdyn.symbolic as sym

sp = pytest.importorskip("sympy")


@pytest.fixture(scope="module")
def arm():
    return screwdyn.load("builtin:planar2")


def names():
    m1, m2, L1, L2, g = sp.symbols("m1 m2 L1 L2 g")
    t1, t2 = sp.symbols("theta1 theta2")
    d1, d2 = sp.symbols("thetadot1 thetadot2")
    a1, a2 = sp.symbols("thetaddot1 thetaddot2")
    return m1, m2, L1, L2, g, t1, t2, d1, d2, a1, a2


def same(a, b):
    return sp.simplify(sp.expand(a - b)) == 0


def test_mass_matrix_is_seed_003(arm):
    m1, m2, L1, L2, g, t1, t2, *_ = names()
    M = sym.mass_matrix(arm, symbols="all")
    c2 = sp.cos(t2)
    # Seed 003: M11 = m1 L1² + m2 (L1² + 2 L1 L2 c2 + L2²), M12 = m2 (L1 L2 c2 + L2²), M22 = m2 L2².
    want = sp.Matrix([[m1 * L1**2 + m2 * (L1**2 + 2 * L1 * L2 * c2 + L2**2),
                       m2 * (L1 * L2 * c2 + L2**2)],
                      [m2 * (L1 * L2 * c2 + L2**2), m2 * L2**2]])
    assert M.shape == (2, 2)
    for i in range(2):
        for j in range(2):
            assert same(M[i, j], want[i, j]), (i, j, M[i, j])
    # Symbolic, not numeric: the free symbols are exactly the seed's.
    assert M.free_symbols == {m1, m2, L1, L2, t2}


def test_velocity_gravity_and_torque_are_seed_003(arm):
    m1, m2, L1, L2, g, t1, t2, d1, d2, a1, a2 = names()
    s2, c1, c12 = sp.sin(t2), sp.cos(t1), sp.cos(t1 + t2)
    d = sym.derive(arm, "coriolis", symbols="all")
    cv = d["Cθ̇"]
    # Seed 003: the centrifugal/Coriolis terms.
    assert same(cv[0], -m2 * L1 * L2 * s2 * (2 * d1 * d2 + d2**2))
    assert same(cv[1], m2 * L1 * L2 * s2 * d1**2)
    assert (d["C"] * sp.Matrix([d1, d2]) - cv).expand() == sp.zeros(2, 1)
    G = sym.gravity_torque(arm, symbols="all")
    assert same(G[0], (m1 + m2) * g * L1 * c1 + m2 * g * L2 * c12)
    assert same(G[1], m2 * g * L2 * c12)
    tau = sym.inverse_dynamics(arm, symbols="all")
    M = sym.mass_matrix(arm, symbols="all")
    want = M * sp.Matrix([a1, a2]) + cv + G
    assert same(tau[0], want[0]) and same(tau[1], want[1])
    assert sym.torque is sym.inverse_dynamics


def test_christoffel_form_and_energy_are_seed_004(arm):
    m1, m2, L1, L2, g, t1, t2, d1, d2, a1, a2 = names()
    q, v = [t1, t2], [d1, d2]
    M = sym.mass_matrix(arm, symbols="all")
    C = sym.coriolis_matrix(arm, symbols="all", form="christoffel")
    # Seed 004: Ṁ − 2C is skew-symmetric for the Christoffel C.
    mdot = sp.Matrix(2, 2, lambda i, j: sum(sp.diff(M[i, j], q[k]) * v[k] for k in range(2)))
    n = (mdot - 2 * C).applyfunc(sp.expand)
    assert same(n[0, 0], 0) and same(n[1, 1], 0) and same(n[0, 1] + n[1, 0], 0)
    K, P = sym.energy(arm, symbols="all")
    assert same(K, (sp.Matrix(v).T * M * sp.Matrix(v))[0] / 2)
    # gravity along −y: P = (m1 + m2) g L1 s1 + m2 g L2 s12
    assert same(P, (m1 + m2) * g * L1 * sp.sin(t1) + m2 * g * L2 * sp.sin(t1 + t2))
    # Lagrange (seed 004): d/dt ∂L/∂θ̇ − ∂L/∂θ = τ, with sympy.diff on the joint symbols.
    L = K - P
    tau = sym.inverse_dynamics(arm, symbols="all")
    for i in range(2):
        dLdv = sp.diff(L, v[i])
        ddt = sum(sp.diff(dLdv, q[k]) * v[k] + sp.diff(dLdv, v[k]) * [a1, a2][k]
                  for k in range(2))
        assert same(ddt - sp.diff(L, q[i]), tau[i])


def test_fk_and_jacobian_of_the_arm(arm):
    m1, m2, L1, L2, g, t1, t2, *_ = names()
    H = sym.forward_kinematics(arm, symbols="lengths")
    # The tip of the seed's arm: (L1 c1 + L2 c12, L1 s1 + L2 s12).
    assert same(H[0, 3], L1 * sp.cos(t1) + L2 * sp.cos(t1 + t2))
    assert same(H[1, 3], L1 * sp.sin(t1) + L2 * sp.sin(t1 + t2))
    J = sym.jacobian(arm, reference="world-aligned", symbols="lengths")
    p = sp.Matrix([H[0, 3], H[1, 3]])
    for r in range(2):
        for c in range(2):
            assert same(J[3 + r, c], sp.diff(p[r], [t1, t2][c]))


def test_symbol_selection_and_names():
    ur5 = screwdyn.load("builtin:ur5")
    d = sym.derive(ur5, "gravity", symbols="a_2,d_1,m_upper_arm_link")
    assert set(d.symbols) == {"m_upper_arm_link", "d_1", "a_2"}
    assert d.values[d.symbols["a_2"]] == pytest.approx(-0.425)
    free = {s.name for s in d.matrix.free_symbols}
    assert free <= {"m_upper_arm_link", "a_2", "d_1"} | {f"theta{i}" for i in range(1, 7)}
    assert "a_2" in free and "m_upper_arm_link" in free
    q, v, a = sym.joint_symbols(ur5)
    assert [s.name for s in q][:2] == ["theta1", "theta2"] and v[0].name == "thetadot1"


def rnd(rng, n, k):
    return rng.uniform(-k, k, n)


@pytest.mark.parametrize("robot", ["builtin:ur5", "builtin:panda"])
def test_numeric_substitution_matches_the_library(robot):
    m = screwdyn.load(robot)
    rng = np.random.default_rng(4)
    # The Panda's expanded M takes SymPy ~15 s to build and lambdify: its g is checked here,
    # its M by the Rust suite (tests/symbolic.rs).
    dm = sym.derive(m, "mass-matrix") if robot.endswith("ur5") else None
    dg = sym.derive(m, "gravity")
    fm = sp.lambdify(dm.q, dm.matrix, "numpy") if dm else None
    fg = sp.lambdify(dg.q, dg.matrix, "numpy")
    for _ in range(3):
        q = rnd(rng, m.nq, 3.0)
        if fm is not None:
            np.testing.assert_allclose(np.array(fm(*q), float), m.crba(q), rtol=0,
                                       atol=1e-12 * max(1, np.abs(m.crba(q)).max()))
            np.testing.assert_allclose(dm.evaluate(q=q), m.crba(q), atol=1e-11)
        np.testing.assert_allclose(np.array(fg(*q), float).ravel(), m.gravity_torque(q),
                                   rtol=0, atol=1e-12 * max(1, np.abs(m.gravity_torque(q)).max()))


def test_torque_and_symbolic_parameters_at_their_values():
    # A 3-joint arm (the UR5's first three joints are too large expanded for a quick test:
    # the planar arm with its lengths and masses as symbols, substituted back).
    m = screwdyn.load("builtin:planar2")
    rng = np.random.default_rng(9)
    d = sym.derive(m, "torque", symbols="all")
    for _ in range(4):
        q, v, a = (rnd(rng, 2, 2.0) for _ in range(3))
        np.testing.assert_allclose(d.evaluate(q=q, v=v, a=a).ravel(), m.rnea(q, v, a),
                                   rtol=0, atol=1e-12 * max(1, np.abs(m.rnea(q, v, a)).max()))
    ur5 = screwdyn.load("builtin:ur5")
    t = sym.derive(ur5, "torque", max_terms=200_000)
    q, v, a = (rnd(rng, 6, 2.0) for _ in range(3))
    want = ur5.rnea(q, v, a)
    np.testing.assert_allclose(t.evaluate(q=q, v=v, a=a).ravel(), want, rtol=0,
                               atol=1e-12 * max(1, np.abs(want).max()))


def test_regressor_times_parameters(arm):
    d = sym.derive(arm, "regressor")
    rng = np.random.default_rng(2)
    q, v, a = (rnd(rng, 2, 2.0) for _ in range(3))
    y = d.evaluate(q=q, v=v, a=a)
    np.testing.assert_allclose(y, arm.regressor(q, v, a), atol=1e-12)
    np.testing.assert_allclose(y @ arm.inertial_parameters(), arm.rnea(q, v, a), atol=1e-12)


def test_latex_display(arm):
    d = sym.derive(arm, "mass-matrix", symbols="all")
    tex = d._repr_latex_()
    assert tex.startswith("$") and "\\cos{\\left(\\theta_{2} \\right)}" in tex and "M = " in tex
    # SymPy's own display of the matrix, and the joint-rate symbols render as dotted thetas.
    assert "\\theta_{2}" in sym.mass_matrix(arm, symbols="all")._repr_latex_()
    assert sp.latex(sym.joint_symbols(arm)[1][0]) == "\\dot{\\theta}_{1}"
    assert sp.latex(sym.joint_symbols(arm)[2][0]) == "\\ddot{\\theta}_{1}"


def test_exact_coefficients(arm):
    K, _ = sym.energy(arm, symbols="all")
    # ½ (m1 + m2) L1² θ̇1² …: the ½ is an exact Rational, not 0.5.
    assert not any(isinstance(x, sp.Float) for x in K.atoms(sp.Number))
    assert sp.Rational(1, 2) in K.atoms(sp.Rational)


def test_bad_input():
    m = screwdyn.load("builtin:planar2")
    with pytest.raises(ValueError, match="unknown quantity 'inertia'"):
        sym.derive(m, "inertia")
    with pytest.raises(ValueError, match="unknown symbol 'm7'"):
        sym.mass_matrix(m, symbols="m7")
    with pytest.raises(ValueError, match="no frame named 'hand'"):
        sym.forward_kinematics(m, frame="hand")
    with pytest.raises(ValueError, match="more than 1000 terms"):
        sym.derive(screwdyn.load("builtin:panda"), "torque", max_terms=1000)
    with pytest.raises(ValueError, match="unknown reference"):
        sym.jacobian(m, reference="sideways")
    with pytest.raises(ValueError, match="unknown Coriolis form"):
        sym.coriolis_matrix(m, form="other")


def test_prismatic_joints_are_polynomial_variables():
    # The Pinocchio fixture's random tree has prismatic joints: θ_j itself is a variable there.
    from conftest import fixture_model

    m, _ = fixture_model("tree")
    assert "prismatic" in m.joint_types
    d = sym.derive(m, "gravity")
    prismatic = {f"theta{i + 1}" for i, k in enumerate(m.joint_types) if k == "prismatic"}
    assert prismatic & {s.name for s in d.matrix.free_symbols}
    rng = np.random.default_rng(8)
    for _ in range(3):
        q = rng.uniform(-1, 1, m.nq)
        want = m.gravity_torque(q)
        np.testing.assert_allclose(d.evaluate(q=q).ravel(), want, rtol=0,
                                   atol=1e-12 * max(1, np.abs(want).max()))


def test_a_model_past_the_joint_limit_is_refused():
    # The expanded form takes at most 64 joints (angle bit masks): a 65-joint chain is refused
    # with the library's sentence naming the limit, not a hang.
    lines = ['format = "screwdyn"', 'name = "snake"']
    parent = "base"
    for i in range(65):
        lines += ["[[body]]", f'name = "l{i}"', f'parent = "{parent}"', f'joint = "j{i}"',
                  'type = "revolute"', "home = { xyz = [0.1, 0.0, 0.0] }",
                  "screw_in_child = [0, 0, 1, 0, 0, 0]", "mass = 0.1", "com = [0.05, 0, 0]",
                  "inertia = [1e-4, 0, 0, 1e-4, 0, 1e-4]"]
        parent = f"l{i}"
    m = screwdyn.load_string("\n".join(lines) + "\n", "toml")
    assert m.nq == 65
    with pytest.raises(ValueError, match="65 joints.*at most 64"):
        sym.gravity_torque(m)
