"""Batches equal per-state calls (exactly, or to round-off for the functions the library runs
eight states side by side), whatever the thread count or the split; shapes and broadcasting."""

import numpy as np
import pytest

import screwdyn

rng = np.random.default_rng(7)


@pytest.fixture(scope="module")
def ur5():
    return screwdyn.load("builtin:ur5")


def states(n, nq=6):
    return rng.uniform(-2, 2, (n, nq)), rng.normal(size=(n, nq)), rng.normal(size=(n, nq))


CALLS = {
    "rnea": lambda m, q, v, a, **k: m.rnea(q, v, a, **k),
    "crba": lambda m, q, v, a, **k: m.crba(q, **k),
    "mass_matrix_inverse": lambda m, q, v, a, **k: m.mass_matrix_inverse(q, **k),
    "coriolis_matrix": lambda m, q, v, a, **k: m.coriolis_matrix(q, v, **k),
    "gravity_torque": lambda m, q, v, a, **k: m.gravity_torque(q, **k),
    "nonlinear_effects": lambda m, q, v, a, **k: m.nonlinear_effects(q, v, **k),
    "aba": lambda m, q, v, a, **k: m.aba(q, v, a, **k),
    "walker-orin": lambda m, q, v, a, **k: m.forward_dynamics(q, v, a, method="walker-orin", **k),
    "kinetic_energy": lambda m, q, v, a, **k: m.kinetic_energy(q, v, **k),
    "potential_energy": lambda m, q, v, a, **k: m.potential_energy(q, **k),
    "total_energy": lambda m, q, v, a, **k: m.total_energy(q, v, **k),
    "power": lambda m, q, v, a, **k: m.power(a, v, **k),
    "center_of_mass": lambda m, q, v, a, **k: m.center_of_mass(q, **k),
    "frame_pose": lambda m, q, v, a, **k: m.frame_pose(q, "tool0", **k),
    "frame_jacobian": lambda m, q, v, a, **k: m.frame_jacobian(q, "tool0", "local", **k),
    "link_jacobian": lambda m, q, v, a, **k: m.link_jacobian(q, 3, **k),
    "frame_twist": lambda m, q, v, a, **k: m.frame_twist(q, v, "tool0", "world-aligned", **k),
    "frame_acceleration": lambda m, q, v, a, **k: m.frame_acceleration(q, v, a, "tool0", **k),
    "frame_jdot_qdot": lambda m, q, v, a, **k: m.frame_jdot_qdot(q, v, "tool0", **k),
    "rnea_fext": lambda m, q, v, a, **k: m.rnea(q, v, a, fext={"wrist_3_link": [1, 2, 3, 4, 5, 6]}, **k),
}


# Stacked states of these go through the library's batch kernels (screwdyn::batch: the same
# recursions on eight states side by side, with a branch-free sine and cosine), single states
# through the per-call functions: the two agree to round-off, not to the bit.
LANES = {"rnea", "crba", "gravity_torque", "nonlinear_effects", "aba"}


@pytest.mark.parametrize("name", list(CALLS))
def test_batch_equals_per_state_calls(ur5, name):
    f = CALLS[name]
    n = 1500  # more than one rayon chunk, so the batch really runs in parallel
    q, v, a = states(n)
    batch = f(ur5, q, v, a)
    single = np.array([f(ur5, q[k], v[k], a[k]) for k in range(n)])
    assert batch.shape == single.shape
    assert batch.dtype == np.float64
    if name in LANES:
        # Per state, relative to its largest entry (ABA of random torques reaches q̈ ~ 10⁴ through
        # an ill-conditioned M, hence the looser bound there).
        rows = (n, -1)
        err = np.abs(batch - single).reshape(rows).max(axis=1)
        scale = np.maximum(1.0, np.abs(single).reshape(rows).max(axis=1))
        assert (err / scale).max() < (1e-11 if name == "aba" else 1e-13)
    else:
        np.testing.assert_array_equal(batch, single)
    np.testing.assert_array_equal(f(ur5, q, v, a, threads=1), batch)
    np.testing.assert_array_equal(f(ur5, q, v, a, threads=2), batch)


@pytest.mark.parametrize("name", sorted(LANES))
def test_a_state_gets_the_same_bits_however_the_batch_is_split(ur5, name):
    f = CALLS[name]
    q, v, a = states(37)
    whole = f(ur5, q, v, a)
    # Pieces of every length put each state into another lane, group of eight or the tail.
    for cut in (1, 5, 8, 13, 29):
        parts = np.concatenate([f(ur5, q[:cut], v[:cut], a[:cut]), f(ur5, q[cut:], v[cut:], a[cut:])])
        np.testing.assert_array_equal(parts, whole)


def test_shapes_lists_and_broadcasting(ur5):
    q, v, a = states(4)
    assert ur5.rnea(q[0], v[0], a[0]).shape == (6,)
    assert ur5.rnea(q, v, a).shape == (4, 6)
    assert ur5.crba(q).shape == (4, 6, 6)
    assert ur5.frame_jacobian(q, "tool0").shape == (4, 6, 6)
    assert ur5.frame_pose(q, "tool0").shape == (4, 4, 4)
    assert isinstance(ur5.kinetic_energy(q[0], v[0]), float)
    assert ur5.kinetic_energy(q, v).shape == (4,)
    # lists, tuples and integer arrays are accepted
    np.testing.assert_array_equal(ur5.rnea(q[0].tolist(), tuple(v[0]), a[0]), ur5.rnea(q[0], v[0], a[0]))
    np.testing.assert_array_equal(ur5.gravity_torque(np.zeros(6, dtype=int)), ur5.gravity_torque(np.zeros(6)))
    # a single v is broadcast against stacked q
    np.testing.assert_array_equal(ur5.rnea(q, v[0], a[0]), ur5.rnea(q, np.tile(v[0], (4, 1)), np.tile(a[0], (4, 1))))
    np.testing.assert_allclose(ur5.rnea(q, v[0], a[0]), np.array([ur5.rnea(qk, v[0], a[0]) for qk in q]), rtol=1e-12, atol=1e-12)
    # non-contiguous input (a column slice) is read correctly
    big = np.hstack([q, q])
    np.testing.assert_array_equal(ur5.crba(big[:, :6]), ur5.crba(q))
    # Fortran-ordered and transposed inputs are read in logical (row) order
    np.testing.assert_array_equal(ur5.rnea(np.asfortranarray(q), v, a), ur5.rnea(q, v, a))
    np.testing.assert_array_equal(ur5.crba(np.ascontiguousarray(q.T).T), ur5.crba(q))
    # zero states
    assert ur5.rnea(np.zeros((0, 6)), np.zeros((0, 6)), np.zeros((0, 6))).shape == (0, 6)
    # frame_poses batches every frame
    poses = ur5.frame_poses(q)
    np.testing.assert_array_equal(poses["tool0"], ur5.frame_pose(q, "tool0"))


def test_rnea_defaults_to_zero_velocity_and_acceleration(ur5):
    q = states(1)[0][0]
    np.testing.assert_array_equal(ur5.rnea(q), ur5.gravity_torque(q))


@pytest.mark.parametrize("name", list(CALLS))
def test_out_receives_exactly_the_fresh_result(ur5, name):
    # out= starts as NaN, so an entry the call did not write would show; the call returns out
    # itself, single state and stacked, on one thread and on all.
    f = CALLS[name]
    q, v, a = states(1500)
    fresh = f(ur5, q, v, a)
    for threads in (None, 1):
        out = np.full(fresh.shape, np.nan)
        assert f(ur5, q, v, a, threads=threads, out=out) is out
        np.testing.assert_array_equal(out, fresh)
    one = np.asarray(f(ur5, q[0], v[0], a[0]))
    out = np.full(one.shape, np.nan)  # a 0-d array for the scalar results (energies, power)
    assert f(ur5, q[0], v[0], a[0], out=out) is out
    np.testing.assert_array_equal(out, one)


def test_out_on_a_branched_tree_gets_the_zeros_of_uncoupled_bodies():
    tree = screwdyn.load("builtin:branched")
    q = rng.uniform(-2, 2, (100, tree.nq))
    fresh = tree.crba(q)
    assert (fresh == 0).any()  # bodies on different branches do not couple
    out = np.full(fresh.shape, np.nan)
    np.testing.assert_array_equal(tree.crba(q, out=out), fresh)


def test_out_as_a_block_of_rows_of_a_bigger_array(ur5):
    # A long log processed chunk after chunk into one preallocated result.
    q, v, a = states(3000)
    tau = np.empty((3000, 6))
    for k in range(0, 3000, 1000):
        ur5.rnea(q[k:k + 1000], v[k:k + 1000], a[k:k + 1000], out=tau[k:k + 1000])
    np.testing.assert_array_equal(tau, ur5.rnea(q, v, a))


def test_bad_out_is_refused_with_a_sentence(ur5):
    q, v, a = states(10)
    cases = [
        ([[0.0] * 6] * 6, TypeError, r"out must be a NumPy float64 array of shape \(10, 6, 6\), got list"),
        (np.zeros((10, 6, 6), np.float32), TypeError, "out has dtype float32, expected float64"),
        (np.zeros((9, 6, 6)), ValueError, r"out has shape \(9, 6, 6\), expected \(10, 6, 6\)"),
        (np.zeros((10, 6, 6)).transpose(0, 2, 1), ValueError, "out must be C-contiguous"),
    ]
    frozen = np.zeros((10, 6, 6))
    frozen.setflags(write=False)
    cases.append((frozen, ValueError, "out is read-only"))
    for out, error, message in cases:
        with pytest.raises(error, match=message):
            ur5.crba(q, out=out)
    # out may not share memory with an input (the result would overwrite what is being read)
    with pytest.raises(ValueError, match="out shares memory with an input argument"):
        ur5.rnea(q, v, a, out=q)
    with pytest.raises(ValueError, match="out shares memory with an input argument"):
        ur5.rnea(q, v, a, out=a[:, :])
    # a scalar result of one state wants a 0-d array
    with pytest.raises(ValueError, match=r"out has shape \(1,\), expected \(\)"):
        ur5.kinetic_energy(q[0], v[0], out=np.zeros(1))


def test_one_state_in_any_layout_or_dtype(ur5):
    # A float64 vector is copied at once, anything else converted: the same numbers either way.
    q, v, a = (x[0] for x in states(1))
    expected = ur5.rnea(q, v, a)
    strided = np.empty(12)
    strided[::2] = q
    for qq in (strided[::2], q.astype(">f8"), q.tolist(), np.asfortranarray(q)):
        np.testing.assert_array_equal(ur5.rnea(qq, v, a), expected)
    np.testing.assert_array_equal(ur5.rnea(q.astype(np.float32), v, a),
                                  ur5.rnea(q.astype(np.float32).astype(float), v, a))
    # a one-state out= may even be an input: the inputs are read before anything is written
    qc = q.copy()
    np.testing.assert_array_equal(ur5.rnea(qc, v, a, out=qc), expected)


def test_unaligned_float64_buffers(ur5):
    # NumPy allows float64 data at an odd address (a view into a byte buffer; Dask hands such
    # arrays to its workers after unpickling): the values are read, not the address trusted.
    q, v, a = states(5)
    expected = ur5.rnea(q, v, a)

    def unaligned(x):
        buf = np.zeros(x.nbytes + 1, dtype=np.uint8)
        y = np.ndarray(x.shape, dtype=np.float64, buffer=buf, offset=1)
        y[...] = x
        assert not y.flags.aligned
        return y

    np.testing.assert_array_equal(ur5.rnea(unaligned(q), unaligned(v), unaligned(a)), expected)
    np.testing.assert_array_equal(ur5.rnea(unaligned(q[0]), v[0], a[0]), ur5.rnea(q[0], v[0], a[0]))
    np.testing.assert_array_equal(ur5.rnea(unaligned(q)[::2], v[::2], a[::2]), expected[::2])
