"""neutral() and random_configuration(): within the limits, deterministic for a seed, covering
each joint's range (statistical bounds)."""

import math

import numpy as np
import pytest

import screwdyn

# Limits away from zero, none, one-sided, and a prismatic joint without limits.
BODY = """[[body]]
name = "l{k}"
parent = "{parent}"
type = "{kind}"
home = {{ xyz = [0.1, 0, 0] }}
screw_in_child = [{screw}]
limits = {{ lower = {lower}, upper = {upper} }}
mass = 1.0
com = [0.05, 0, 0]
"""
SPECS = [  # what, kind, lower, upper, expected range, expected neutral
    ("limited", "revolute", "0.5", "2.0", (0.5, 2.0), 0.5),
    ("free", "revolute", "-inf", "inf", (-math.pi, math.pi), 0.0),
    ("slide", "prismatic", "-inf", "inf", (-1.0, 1.0), 0.0),
    ("from_five", "revolute", "5.0", "inf", (5.0, 5.0 + 2 * math.pi), 5.0),
    ("below", "revolute", "-inf", "-0.3", (-math.pi, -0.3), -0.3),
]


@pytest.fixture(scope="module")
def chain():
    text = 'format = "screwdyn"\nname = "ranges"\n'
    for k, (_, kind, lo, hi, _, _) in enumerate(SPECS):
        screw = "0, 0, 0, 0, 0, 1" if kind == "prismatic" else "0, 0, 1, 0, 0, 0"
        text += BODY.format(k=k, parent="base" if k == 0 else f"l{k - 1}", kind=kind, screw=screw,
                            lower=lo, upper=hi)
    return screwdyn.load_string(text, "toml")


def test_neutral_is_zero_or_the_nearest_point_of_the_range(chain):
    np.testing.assert_array_equal(chain.neutral(), [s[5] for s in SPECS])
    assert chain.neutral().shape == (chain.nq,)
    np.testing.assert_array_equal(screwdyn.load("builtin:ur5").neutral(), np.zeros(6))


def test_ranges_are_the_limits_or_the_documented_defaults(chain):
    np.testing.assert_allclose(chain.configuration_ranges, [s[4] for s in SPECS], rtol=0, atol=0)


@pytest.mark.parametrize("rng", [7, np.random.default_rng(7)], ids=["seed", "generator"])
def test_random_configurations_stay_within_the_limits_and_cover_them(chain, rng):
    n = 4000
    q = chain.random_configuration(rng, n=n)
    assert q.shape == (n, chain.nq)
    lo, hi = chain.configuration_ranges.T
    assert np.all(q >= lo) and np.all(q <= hi)
    assert np.all(q >= chain.lower_limits) and np.all(q <= chain.upper_limits)
    w = hi - lo
    # Uniform on [lo, hi]: the mean within 5 σ/√n of the middle (σ = w/√12); the extremes within
    # 0.5 % of the width of each end (a miss has probability (1 − 0.005)^4000 ≈ 2·10⁻⁹).
    assert np.all(np.abs(q.mean(axis=0) - (lo + hi) / 2) < 5 * w / math.sqrt(12 * n))
    assert np.all(q.min(axis=0) - lo < 0.005 * w) and np.all(hi - q.max(axis=0) < 0.005 * w)
    # A quarter of the draws in the first quarter of each range, within 5 binomial σ.
    quarter = (q < lo + w / 4).sum(axis=0)
    assert np.all(np.abs(quarter - n / 4) < 5 * math.sqrt(n * 0.25 * 0.75))


def test_random_configurations_are_the_same_for_a_seed(chain):
    a = chain.random_configuration(3, n=5)
    np.testing.assert_array_equal(a, chain.random_configuration(3, n=5))
    np.testing.assert_array_equal(a[0], chain.random_configuration(np.int64(3)))
    assert not np.array_equal(a, chain.random_configuration(4, n=5))
    g1, g2 = np.random.default_rng(11), np.random.default_rng(11)
    np.testing.assert_array_equal(chain.random_configuration(g1), chain.random_configuration(g2))
    # A generator maps its uniform numbers onto the ranges: q = lo + u (hi − lo).
    u = np.random.default_rng(5).random((1, chain.nq))[0]
    lo, hi = chain.configuration_ranges.T
    np.testing.assert_allclose(chain.random_configuration(np.random.default_rng(5)), lo + u * (hi - lo))
    q = chain.random_configuration()
    assert q.shape == (chain.nq,) and np.all((q >= lo) & (q <= hi))
    assert chain.random_configuration(1, n=0).shape == (0, chain.nq)


def test_random_configuration_arguments(chain):
    with pytest.raises(TypeError, match="rng is a numpy.random.Generator, an int seed or None"):
        chain.random_configuration("seven")
    with pytest.raises(ValueError, match=r"rng as a seed is an integer in \[0, 2\*\*64\), got -1"):
        chain.random_configuration(-1)
    with pytest.raises(ValueError, match="n is the number of configurations, at least 0, got -2"):
        chain.random_configuration(1, n=-2)
    with pytest.raises(TypeError, match="n is the number of configurations"):
        chain.random_configuration(1, n=2.5)
