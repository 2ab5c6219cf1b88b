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


UR5_Q0 = np.array([0.3, -1.2, 1.5, -1.9, -1.57, 0.2])


def test_linear_move_stays_on_the_line_within_the_tool_speed():
    ur5 = screwdyn.load("builtin:ur5")
    start = ur5.frame_pose(UR5_Q0, "tool0")
    target = start.copy()
    target[:3, 3] += [0.0, 0.2, 0.0]
    line = screwdyn.Trajectory.linear(ur5, "tool0", UR5_Q0, target, speed=0.25)
    t = np.arange(0.0, line.duration, 1e-3)
    q, _, _ = line.sample(t)
    poses = ur5.frame_pose(q, "tool0")
    d = poses[:, :3, 3] - start[:3, 3]
    # On the segment (forward kinematics of every sample), orientation held.
    assert np.max(np.abs(d[:, [0, 2]])) < 2e-6
    assert np.max(np.abs(poses[:, :3, :3] - start[:3, :3])) < 2e-6
    # The tool speed by differences of the forward kinematics: at most 0.25 m/s.
    speed = np.linalg.norm(np.diff(poses[:, :3, 3], axis=0), axis=1) / 1e-3
    assert speed.max() <= 0.25 * (1 + 1e-6)
    assert line.duration > 0.2 / 0.25


def test_circular_move_and_a_move_out_of_reach():
    ur5 = screwdyn.load("builtin:ur5")
    start = ur5.frame_pose(UR5_Q0, "tool0")
    center = start[:3, 3] - [0.1, 0.0, 0.0]
    target = start.copy()
    target[:3, 3] = center - [0.1, 0.0, 0.0]
    arc = screwdyn.Trajectory.circular(ur5, "tool0", UR5_Q0, center + [0.0, 0.1, 0.0], target)
    q, _, _ = arc.sample(np.linspace(0.0, arc.duration, 200))
    p = ur5.frame_pose(q, "tool0")[:, :3, 3]
    assert np.max(np.abs(np.linalg.norm(p - center, axis=1) - 0.1)) < 2e-6
    far = start.copy()
    far[:3, 3] -= [1.0, 0.0, 0.0]
    with pytest.raises(ValueError, match=r"stops at .* % of the path \(.* m of 1.0000 m\)"):
        screwdyn.Trajectory.linear(ur5, "tool0", UR5_Q0, far)
