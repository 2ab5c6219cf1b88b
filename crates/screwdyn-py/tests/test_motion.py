"""Time-optimal and jerk-limited trajectories: closed forms, and every result checked with
inverse dynamics."""

import math

import numpy as np
import pytest

import screwdyn

UR5_WAYPOINTS = np.array([
    [0.0, -1.8, 1.4, -1.2, -1.6, 0.0],
    [0.8, -1.2, 1.0, -1.4, -1.6, 0.5],
    [1.6, -1.6, 1.8, -1.0, -1.2, 1.0],
])
UR5_EFFORT = np.array([150.0, 150.0, 150.0, 28.0, 28.0, 28.0])


def test_pendulum_without_gravity_is_bang_bang():
    # I = 1 kg·m²; torque limit 2 N·m less the 1e-4 margin: T = 2 √(d I / τ).
    p = screwdyn.load("builtin:pendulum")
    p.gravity = [0.0, 0.0, 0.0]
    d, tau = 0.8, 2.0 * (1 - 1e-4)
    t = screwdyn.Trajectory.time_optimal(p, [[0.0], [d]], effort=[2.0], vmax=[math.inf])
    assert t.duration == pytest.approx(2 * math.sqrt(d / tau), rel=1e-9)
    q, v, a = t.sample(np.linspace(0.0, t.duration, 201))
    torque = p.rnea(q, v, a)[:, 0]
    assert np.all(np.abs(torque) <= 2.0)
    assert q[-1, 0] == pytest.approx(d, abs=1e-12) and v[-1, 0] == pytest.approx(0.0, abs=1e-12)


def test_ur5_time_optimal_within_its_limits():
    ur5 = screwdyn.load("builtin:ur5")
    t = screwdyn.Trajectory.time_optimal(ur5, UR5_WAYPOINTS, amax=np.full(6, 10.0))
    times = np.arange(0.0, t.duration, 5e-4)
    q, v, a = t.sample(times)
    tau = ur5.rnea(q, v, a)
    assert np.all(np.abs(tau) <= UR5_EFFORT)
    assert np.all(np.abs(v) <= 3.15) and np.all(np.abs(a) <= 10.0)
    # Time-optimal: at almost every instant some limit is reached (within 3 %).
    used = np.maximum.reduce([np.max(np.abs(tau) / UR5_EFFORT, axis=1),
                              np.max(np.abs(v) / 3.15, axis=1), np.max(np.abs(a) / 10.0, axis=1)])
    assert np.mean(used > 0.97) > 0.95
    s, sd, ti = t.phase_plane()
    assert sd[0] == 0.0 and sd[-1] == 0.0 and ti[-1] == pytest.approx(t.duration)
    np.testing.assert_allclose(t.sample(ti[-1])[0], UR5_WAYPOINTS[-1], atol=1e-12)
    # Given s: the same waypoints at other parameters are another path, also feasible.
    t2 = screwdyn.Trajectory.time_optimal(ur5, UR5_WAYPOINTS, s=[0.0, 1.0, 3.0])
    assert t2.duration > 0 and repr(t2).startswith("Trajectory.time_optimal(nq=6")


def test_jerk_limited_closed_form():
    # 10 rad at 2 rad/s, 1 rad/s², 1 rad/s³: 1 + 1 + 1 s up (6 rad up and down), 2 s cruise.
    t = screwdyn.Trajectory.jerk_limited([0.0, 0.0], [10.0, -1.0], [2.0, 2.0], [1.0, 1.0], [1.0, 1.0])
    assert t.duration == pytest.approx(8.0, abs=1e-12)
    q, v, a = t.sample(np.array([4.0, 8.0]))
    np.testing.assert_allclose(q, [[5.0, -0.5], [10.0, -1.0]], atol=1e-12)
    with pytest.raises(TypeError, match="phase_plane is defined for time-optimal"):
        t.phase_plane()


def test_bad_motion_input():
    ur5 = screwdyn.load("builtin:ur5")
    T = screwdyn.Trajectory
    with pytest.raises(ValueError, match="must increase strictly"):
        T.time_optimal(ur5, UR5_WAYPOINTS, s=[0.0, 2.0, 1.0])
    with pytest.raises(ValueError, match="velocity limits must be positive"):
        T.time_optimal(ur5, UR5_WAYPOINTS, vmax=[1.0, 1.0, 0.0, 1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match=r"gravity alone needs .* at joint shoulder_lift_joint at s = .*, more than its effort limit 20 allows"):
        T.time_optimal(ur5, UR5_WAYPOINTS, effort=[150.0, 20.0, 150.0, 28.0, 28.0, 28.0])
    with pytest.raises(ValueError, match="waypoint 1: joint elbow_joint = 9"):
        T.time_optimal(ur5, [UR5_WAYPOINTS[0], [0.8, -1.2, 9.0, -1.4, -1.6, 0.5]])
    with pytest.raises(ValueError, match="non-finite"):
        T.time_optimal(ur5, [UR5_WAYPOINTS[0], [0.8, -1.2, np.nan, -1.4, -1.6, 0.5]])
    with pytest.raises(ValueError, match="jmax must be positive, but joint 0 has -1"):
        T.jerk_limited([0.0], [1.0], [1.0], [1.0], [-1.0])
