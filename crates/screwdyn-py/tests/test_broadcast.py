"""One rule for per-joint parameters: a single number stands for the same value at every joint
(trajectory limits and end points, controller gains and targets, damping and friction)."""

import numpy as np
import pytest

import screwdyn


def test_trapezoid_takes_scalar_limits():
    # Rest to rest over 1 rad at vmax = 1 rad/s, amax = 2 rad/s²: accelerate for v/a = 0.5 s
    # (0.25 rad), cruise 0.5 rad for 0.5 s, brake 0.5 s: 1.5 s in all.
    t = screwdyn.Trapezoid(np.zeros(3), np.ones(3), vmax=1.0, amax=2.0)
    assert t.nq == 3 and t.duration == pytest.approx(1.5, abs=1e-12)
    np.testing.assert_allclose(t.cruise_speeds(), [1.0, 1.0, 1.0], atol=1e-12)
    q, v, a = t.sample(0.75)  # the middle of the cruise: halfway, at full speed
    np.testing.assert_allclose(q, [0.5] * 3, atol=1e-12)
    np.testing.assert_allclose(v, [1.0] * 3, atol=1e-12)
    # NumPy scalars and 0-d arrays too, for end points as well as limits.
    t2 = screwdyn.Trapezoid(0.0, [1.0, 1.0, 1.0], vmax=np.float64(1.0), amax=np.array(2.0))
    assert t2.nq == 3 and t2.duration == pytest.approx(1.5, abs=1e-12)


def test_quintic_takes_scalar_boundary_values():
    t = screwdyn.Quintic([0.0, 0.0], [1.0, 2.0], 2.0, v0=0.5, vf=-0.25)
    _, v0, a0 = t.sample(0.0)
    qf, vf, _ = t.sample(2.0)
    np.testing.assert_allclose(v0, [0.5, 0.5], atol=1e-12)
    np.testing.assert_allclose(a0, [0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(vf, [-0.25, -0.25], atol=1e-12)
    np.testing.assert_allclose(qf, [1.0, 2.0], atol=1e-12)


def test_controller_gains_and_friction_take_scalars():
    ur5 = screwdyn.load("builtin:ur5")
    q0 = np.array([0.1, -0.8, 0.9, 0.0, 0.3, 0.0])
    target = 0.2
    # At t = 0 (q̇ = 0): τ = Kp (q* − q) − Kd q̇ + g(q) with Kp = 100 at every joint.
    run = ur5.simulate(q0, duration=0.002, dt=0.001, effects=False,
                       controller=screwdyn.PD(target, kp=100.0, kd=20.0))
    np.testing.assert_allclose(run.tau[0], 100.0 * (target - q0) + ur5.gravity_torque(q0), atol=1e-9)
    run = ur5.simulate(q0, duration=0.002, dt=0.001, effects=False,
                       controller=screwdyn.ConstantTorque(1.5))
    np.testing.assert_allclose(run.tau[0], np.full(6, 1.5))
    m = ur5.with_joint_friction(0.5, 0.1)
    np.testing.assert_array_equal(m.damping, np.full(6, 0.5))
    np.testing.assert_array_equal(m.friction, np.full(6, 0.1))


def test_a_vector_must_still_have_one_value_per_joint():
    ur5 = screwdyn.load("builtin:ur5")
    with pytest.raises(ValueError, match="damping has 2 values, the model has 6 joints"):
        ur5.with_joint_friction([0.5, 0.5], 0.1)
    with pytest.raises(ValueError, match="kp has 3 values, the model has 6 joints"):
        ur5.simulate(np.zeros(6), duration=0.01, controller=screwdyn.PD(0.0, kp=[1, 2, 3]))
    with pytest.raises(ValueError, match="vmax must be a 1-D array"):
        screwdyn.Trapezoid(np.zeros(2), np.ones(2), vmax=np.ones((2, 2)), amax=1.0)
    with pytest.raises(ValueError):
        screwdyn.Trapezoid(np.zeros(2), np.ones(3), vmax=1.0, amax=1.0)
