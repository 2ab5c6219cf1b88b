"""screwdyn.se3: pose helpers over NumPy arrays, against analytic cases, round trips and the
matrix definitions (``Ad_H [V] = H [V] H⁻¹``, ``ad_V X = [V] [X] − [X] [V]``)."""

import math

import numpy as np
import pytest

from screwdyn import se3

RNG = np.random.default_rng(25)


def hat3(w):
    return np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


def hat6(xi):
    m = np.zeros((4, 4))
    m[:3, :3], m[:3, 3] = hat3(xi[:3]), xi[3:]
    return m


def rot(axis, t):
    c, s = math.cos(t), math.sin(t)
    return {
        "x": np.array([[1, 0, 0], [0, c, -s], [0, s, c]]),
        "y": np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]),
        "z": np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]),
    }[axis]


def random_twist(scale=1.0):
    xi = RNG.normal(size=6) * scale
    xi[:3] *= min(1.0, 2.5 / np.linalg.norm(xi[:3]))  # |ω| < π: log's branch
    return xi


def random_pose():
    return se3.exp(random_twist(2.0))


def test_exp_of_a_rotation_about_z_and_of_a_translation():
    for t in (0.0, 0.3, -2.0, math.pi):
        H = se3.exp([0, 0, t, 0, 0, 0])
        np.testing.assert_allclose(H[:3, :3], rot("z", t), atol=1e-15)
        np.testing.assert_allclose(H[:3, 3], 0, atol=0)
    H = se3.exp([0, 0, 0, 1, 2, 3])
    np.testing.assert_array_equal(H, [[1, 0, 0, 1], [0, 1, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]])
    # Half a turn about the z axis through (1, 0, 0), S = (ẑ, −ẑ × r): the origin goes to (2, 0, 0).
    H = se3.exp(np.array([0, 0, 1, 0, -1, 0]) * math.pi)
    np.testing.assert_allclose(H[:3, 3], [2, 0, 0], atol=1e-15)


def test_log_inverts_exp_and_inverse_inverts_poses():
    for _ in range(50):
        xi = random_twist(2.0)
        np.testing.assert_allclose(se3.log(se3.exp(xi)), xi, atol=1e-12)
        H = se3.exp(xi)
        np.testing.assert_allclose(H @ se3.inverse(H), np.eye(4), atol=1e-14)
        np.testing.assert_allclose(se3.inverse(H), np.linalg.inv(H), atol=1e-13)
    np.testing.assert_array_equal(se3.log(np.eye(4)), np.zeros(6))
    # exp of the hat matrix by its power series, for a small twist.
    xi = random_twist(0.3)
    series, term = np.eye(4), np.eye(4)
    for k in range(1, 30):
        term = term @ hat6(xi) / k
        series = series + term
    np.testing.assert_allclose(se3.exp(xi), series, atol=1e-14)


def test_Ad_is_conjugation_and_ad_is_the_bracket():
    for _ in range(20):
        H, V, X = random_pose(), RNG.normal(size=6), RNG.normal(size=6)
        # Ad_H V as a matrix: H [V] H⁻¹.
        np.testing.assert_allclose(hat6(se3.Ad(H) @ V), H @ hat6(V) @ np.linalg.inv(H), atol=1e-12)
        # ad_V X = [V, X] = [V][X] − [X][V].
        np.testing.assert_allclose(hat6(se3.ad(V) @ X), hat6(V) @ hat6(X) - hat6(X) @ hat6(V),
                                   atol=1e-12)
        np.testing.assert_allclose(se3.Ad(se3.inverse(H)), np.linalg.inv(se3.Ad(H)), atol=1e-12)


def test_quaternions_of_known_rotations():
    s = math.sqrt(0.5)
    cases = [
        (np.eye(3), [1, 0, 0, 0]),
        (rot("x", math.pi), [0, 1, 0, 0]),
        (rot("y", math.pi), [0, 0, 1, 0]),
        (rot("z", math.pi / 2), [s, 0, 0, s]),
        (rot("x", -math.pi / 2), [s, -s, 0, 0]),
    ]
    for R, q in cases:
        H = np.eye(4)
        H[:3, :3] = R
        np.testing.assert_allclose(se3.to_quaternion(H), q, atol=1e-15)
        np.testing.assert_allclose(se3.to_quaternion(R), q, atol=1e-15)
        np.testing.assert_allclose(se3.from_quaternion(q)[:3, :3], R, atol=1e-15)
    # Scalar first, normalised, with a translation; q and −q are the same rotation.
    H = se3.from_quaternion([2 * s, 0, 0, 2 * s], translation=[1, 2, 3])
    np.testing.assert_allclose(H[:3, :3], rot("z", math.pi / 2), atol=1e-15)
    np.testing.assert_array_equal(H[:3, 3], [1, 2, 3])
    for _ in range(20):
        H = random_pose()
        q = se3.to_quaternion(H)
        assert q[0] >= 0 and abs(np.linalg.norm(q) - 1) < 1e-15
        np.testing.assert_allclose(se3.from_quaternion(-q)[:3, :3], H[:3, :3], atol=1e-14)


def test_rpy_is_the_urdf_convention():
    for _ in range(20):
        r, p, y = RNG.uniform(-3, 3), RNG.uniform(-1.5, 1.5), RNG.uniform(-3, 3)
        H = se3.from_rpy([r, p, y], translation=[0.1, 0.2, 0.3])
        np.testing.assert_allclose(H[:3, :3], rot("z", y) @ rot("y", p) @ rot("x", r), atol=1e-15)
        np.testing.assert_allclose(se3.to_rpy(H), [r, p, y], atol=1e-12)
        np.testing.assert_allclose(se3.to_rpy(H[:3, :3]), [r, p, y], atol=1e-12)


def bad(H, value):
    H = np.array(H, dtype=float)
    H[0, 0] = value
    return H


@pytest.mark.parametrize("call, message", [
    (lambda: se3.log(np.eye(3)), r"H has shape \(3, 3\), expected \(4, 4\)"),
    (lambda: se3.exp(np.zeros(3)), r"the twist has shape \(3,\), expected \(6,\)"),
    (lambda: se3.exp([0, 0, np.nan, 0, 0, 0]), r"the twist has a non-finite entry \(NaN\) at index 2"),
    (lambda: se3.inverse(bad(np.eye(4), np.nan)), r"H has a non-finite entry \(NaN\) at row 0, column 0"),
    (lambda: se3.Ad(bad(np.eye(4), 1.1)),
     r"the rotation part of H is not a rotation: RᵀR differs from the identity by 0\.21"),
    (lambda: se3.to_quaternion(np.diag([1.0, 1.0, -1.0])),
     r"H is a reflection \(determinant −1\), not a rotation"),
    (lambda: se3.log(np.vstack([np.eye(4)[:3], [1, 0, 0, 1]])),
     r"H is not a homogeneous transform: its bottom row is not \(0, 0, 0, 1\)"),
    (lambda: se3.from_quaternion([0, 0, 0, 0]), r"the quaternion \[0\.0, 0\.0, 0\.0, 0\.0\] is zero"),
    (lambda: se3.from_rpy([0, 0, 1], translation=[1, 2]), r"translation has shape \(2,\), expected \(3,\)"),
    (lambda: se3.to_rpy(np.zeros((2, 2))), r"H has shape \(2, 2\), expected \(4, 4\) or \(3, 3\)"),
])
def test_bad_input_is_one_sentence(call, message):
    with pytest.raises(ValueError, match=message) as e:
        call()
    assert "\n" not in str(e.value) and str(e.value).count(". ") == 0


def test_the_module_examples_run():
    import doctest

    assert doctest.testmod(se3).failed == 0
