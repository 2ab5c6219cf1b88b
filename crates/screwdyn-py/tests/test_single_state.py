"""The one-state calls a Python loop makes (`rnea`, `aba`, `crba`, `frame_pose`,
`frame_jacobian`): a contiguous float64 vector is read in place of conversion, anything else is
converted. Every layout and dtype must give Pinocchio's values (the fixtures of
crates/screwdyn/tests/fixtures/pinocchio) and the same bits as the contiguous float64 call."""

import threading

import numpy as np
import pytest

import screwdyn
from conftest import fixture_model

TOL = 1e-9


def close(got, want, tol=TOL):
    got, want = np.asarray(got), np.asarray(want, dtype=float)
    assert got.shape == want.shape
    scale = max(1.0, float(np.max(np.abs(want))))
    assert np.max(np.abs(got - want)) <= tol * scale, np.max(np.abs(got - want))


@pytest.fixture(scope="module", params=["ur5", "panda"])
def arm(request):
    return fixture_model(request.param)


def tool(fx):
    """The last frame the fixture gives a Jacobian of: the arm's tip."""
    return list(fx["states"][0]["jacobians_world"])[-1]


def calls(m, fx, s):
    """(function of the joint vectors, the vectors, Pinocchio's value) for the five calls."""
    f = tool(fx)
    return [
        (lambda q, v, a: m.rnea(q, v, a), (s["q"], s["v"], s["a"]), s["tau"]),
        (lambda q, v, t: m.aba(q, v, t), (s["q"], s["v"], s["tau_in"]), s["qdd"]),
        (lambda q: m.crba(q), (s["q"],), s["mass_matrix"]),
        (lambda q: m.frame_pose(q, f), (s["q"],), s["frame_poses"][f]),
        (lambda q: m.frame_jacobian(q, f, "world"), (s["q"],), s["jacobians_world"][f]),
    ]


def layouts(x):
    """The same vector as a strided view, big-endian, a list, a tuple, read-only."""
    strided = np.empty(2 * len(x))
    strided[::2] = x
    frozen = np.array(x)
    frozen.setflags(write=False)
    return [strided[::2], np.asarray(x, dtype=">f8"), list(x), tuple(x), frozen]


def test_contiguous_float64_gives_pinocchio(arm):
    m, fx = arm
    for s in fx["states"][:5]:
        for f, args, want in calls(m, fx, s):
            got = f(*(np.array(x, dtype=float) for x in args))
            assert got.dtype == np.float64 and got.flags.c_contiguous and got.flags.writeable
            close(got, want, 1e-8)


def test_every_layout_gives_the_same_bits(arm):
    m, fx = arm
    s = fx["states"][0]
    for f, args, want in calls(m, fx, s):
        contiguous = f(*(np.array(x, dtype=float) for x in args))
        close(contiguous, want, 1e-8)
        for k in range(len(args)):
            for other in layouts(args[k]):
                mixed = [np.array(x, dtype=float) for x in args]
                mixed[k] = other
                np.testing.assert_array_equal(f(*mixed), contiguous)


def test_float32_is_read_as_its_float64_values(arm):
    m, fx = arm
    s = fx["states"][1]
    for f, args, want in calls(m, fx, s):
        single = [np.asarray(x, dtype=np.float32) for x in args]
        widened = [x.astype(np.float64) for x in single]
        np.testing.assert_array_equal(f(*single), f(*widened))
        # rounding the state to float32 moves the result by about 1e-7 of its size
        close(f(*single), want, 1e-5)


def test_left_out_vectors_are_zero(arm):
    m, fx = arm
    for s in fx["states"][:3]:
        q, v = np.array(s["q"]), np.array(s["v"])
        close(m.rnea(q), s["gravity"])
        close(m.rnea(q, v), s["nonlinear_effects"])


def test_results_are_fresh_arrays(arm):
    # The model reuses one workspace; what a call returns must not change with the next call.
    m, fx = arm
    s0, s1 = fx["states"][:2]
    tau0 = m.rnea(np.array(s0["q"]), np.array(s0["v"]), np.array(s0["a"]))
    m0 = m.crba(np.array(s0["q"]))
    tau1 = m.rnea(np.array(s1["q"]), np.array(s1["v"]), np.array(s1["a"]))
    m.crba(np.array(s1["q"]))
    close(tau0, s0["tau"])
    close(m0, s0["mass_matrix"])
    close(tau1, s1["tau"])
    tau0[:] = 0.0  # writing into a result touches nothing else
    close(m.rnea(np.array(s0["q"]), np.array(s0["v"]), np.array(s0["a"])), s0["tau"])


def test_frame_by_name_or_index(arm):
    m, fx = arm
    s, f = fx["states"][2], tool(fx)
    q = np.array(s["q"])
    k = m.frame_names.index(f)
    np.testing.assert_array_equal(m.frame_pose(q, k), m.frame_pose(q, f))
    np.testing.assert_array_equal(m.frame_jacobian(q, k), m.frame_jacobian(q, f))
    close(m.frame_pose(q, np.int64(k)), s["frame_poses"][f])


def test_out_is_honoured_for_one_state(arm):
    m, fx = arm
    s, f = fx["states"][3], tool(fx)
    q, v, a = (np.array(s[k]) for k in ("q", "v", "a"))
    n = m.nq
    out = np.full(n, np.nan)
    assert m.rnea(q, v, a, out=out) is out
    close(out, s["tau"])
    out = np.full((n, n), np.nan)
    assert m.crba(q, out=out) is out
    close(out, s["mass_matrix"])
    out = np.full((6, n), np.nan)
    assert m.frame_jacobian(q, f, out=out) is out
    close(out, s["jacobians_world"][f])
    with pytest.raises(ValueError, match=rf"out has shape \({n + 1},\), expected \({n},\)"):
        m.rnea(q, v, a, out=np.zeros(n + 1))
    with pytest.raises(ValueError, match=rf"out has shape \({n}, {n}\), expected \(4, 4\)"):
        m.frame_pose(q, f, out=np.zeros((n, n)))
    with pytest.raises(TypeError, match="out has dtype float32, expected float64"):
        m.aba(q, v, a, out=np.zeros(n, np.float32))


def test_wrong_length_and_bad_values_are_refused(arm):
    m, fx = arm
    n = m.nq
    q = np.array(fx["states"][0]["q"])
    with pytest.raises(ValueError, match=f"q has {n + 1} values, the model has {n} joints"):
        m.rnea(np.zeros(n + 1))
    with pytest.raises(ValueError, match=f"v has 40 values, the model has {n} joints"):
        m.rnea(q, np.zeros(40))
    with pytest.raises(ValueError, match="threads must be a positive number"):
        m.crba(q, threads=0)
    bad = q.copy()
    bad[1] = np.nan
    with pytest.raises(ValueError, match="q"):
        m.frame_jacobian(bad, tool(fx))


def test_calls_from_several_threads(arm):
    # Each thread's results are Pinocchio's, whichever thread holds the model's workspace.
    m, fx = arm
    errors = []

    def work(states):
        try:
            for _ in range(50):
                for s in states:
                    close(m.rnea(np.array(s["q"]), np.array(s["v"]), np.array(s["a"])), s["tau"])
                    close(m.crba(np.array(s["q"])), s["mass_matrix"])
        except AssertionError as e:  # pragma: no cover - reported below
            errors.append(e)

    threads = [threading.Thread(target=work, args=(fx["states"][k::4],)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors


def planar_chain(n):
    """`n` unit links turning about z, a 1 kg point mass at the end of each, gravity along −y."""
    text = ['format = "screwdyn"', 'name = "chain"', "gravity = [0.0, -9.81, 0.0]"]
    for i in range(1, n + 1):
        text += ["[[body]]", f'name = "link{i}"', f'parent = "{"base" if i == 1 else f"link{i - 1}"}"',
                 f'joint = "joint{i}"', 'type = "revolute"', "home = { xyz = [1.0, 0.0, 0.0] }",
                 "screw_in_parent = [0, 0, 1, 0, 0, 0]", "mass = 1.0"]
    return screwdyn.load_string("\n".join(text) + "\n", "toml", name="chain")


def test_long_vectors_take_the_same_path_as_short_ones():
    # 20 joints: more than a vector kept on the stack. Analytic planar values: the end of link k
    # is p_k = Σ_{i≤k} (cos θ_i, sin θ_i) with θ_i = q_1 + … + q_i; holding the chain still takes
    # τ_i = Σ_{k≥i} m g (x_k − x_{i−1}); the tip's velocity is Σ_i q̇_i ẑ × (p_n − p_{i−1}).
    n = 20
    m = planar_chain(n)
    rng = np.random.default_rng(7)
    q, a = rng.uniform(-1, 1, n), rng.normal(size=n)
    theta = np.cumsum(q)
    p = np.vstack([[0.0, 0.0], np.cumsum(np.c_[np.cos(theta), np.sin(theta)], axis=0)])
    pose = m.frame_pose(q, f"link{n}")
    close(pose[:2, 3], p[n], 1e-12)
    close(pose[:2, :2], [[np.cos(theta[-1]), -np.sin(theta[-1])], [np.sin(theta[-1]), np.cos(theta[-1])]], 1e-12)
    g = np.array([9.81 * np.sum(p[i + 1:, 0] - p[i, 0]) for i in range(n)])
    close(m.rnea(q), g, 1e-12)
    jac = m.frame_jacobian(q, f"link{n}", "world-aligned")
    close(jac[3], -(p[n, 1] - p[:n, 1]), 1e-12)
    close(jac[4], p[n, 0] - p[:n, 0], 1e-12)
    close(jac[5], 0.0 * q, 0)
    mass = m.crba(q)
    close(mass, mass.T, 0)
    close(mass @ a, m.rnea(q, None, a) - g, 1e-10)
    close(m.aba(q, np.zeros(n), m.rnea(q, None, a)), a, 1e-8)
    # and every one of them as a list: the same bits
    np.testing.assert_array_equal(m.crba(list(q)), mass)
    np.testing.assert_array_equal(m.frame_jacobian(list(q), f"link{n}", "world-aligned"), jac)
