"""Model.inverse_kinematics: every answer checked by forward kinematics (frame_pose) and
against the joint limits; batches against single solves; closed-form solutions; bad input."""

import numpy as np
import pytest

import screwdyn


def _limits(model):
    return model.lower_limits, model.upper_limits


def _random_q(model, count, seed=3):
    rng = np.random.default_rng(seed)
    lo, hi = (np.clip(x, -3.0, 3.0) for x in _limits(model))
    return lo + (hi - lo) * rng.random((count, model.nq))


def _pose_errors(a, b):
    dp = np.linalg.norm(a[:3, 3] - b[:3, 3])
    c = (np.trace(a[:3, :3].T @ b[:3, :3]) - 1.0) / 2.0
    return dp, float(np.arccos(np.clip(c, -1.0, 1.0)))


def _within(model, q):
    lo, hi = _limits(model)
    return np.all(q >= lo) and np.all(q <= hi)


@pytest.mark.parametrize("name,frame", [("ur5", "tool0"), ("panda", "panda_link8")])
def test_round_trip_confirmed_by_frame_pose(name, frame):
    m = screwdyn.load(f"builtin:{name}")
    for q_true in _random_q(m, 5):
        target = m.frame_pose(q_true, frame)
        r = m.inverse_kinematics(frame, target)
        assert r.success and r.failure is None
        assert isinstance(r.iterations, int)
        dp, dr = _pose_errors(m.frame_pose(r.q, frame), target)
        assert dp <= 1e-6 and dr <= 1e-6
        assert _within(m, r.q)
        assert r.position_error <= 1e-6 and r.orientation_error <= 1e-6


def test_batch_matches_fk_and_thread_count():
    m = screwdyn.load("builtin:ur5")
    qs = _random_q(m, 24, seed=5)
    targets = m.frame_pose(qs, "tool0")  # (24, 4, 4)
    r1 = m.inverse_kinematics("tool0", targets, threads=1)
    r2 = m.inverse_kinematics("tool0", targets, threads=2)
    assert r1.q.shape == (24, 6) and r1.success.shape == (24,)
    assert r1.success.all()
    np.testing.assert_array_equal(r1.q, r2.q)
    reached = m.frame_pose(r1.q, "tool0")
    for k in range(24):
        dp, dr = _pose_errors(reached[k], targets[k])
        assert dp <= 1e-6 and dr <= 1e-6
        assert _within(m, r1.q[k])


def test_position_only_planar2_closed_form():
    m = screwdyn.load("builtin:planar2")
    target = np.eye(4)
    target[:3, 3] = [1.0, 1.0, 0.0]
    r = m.inverse_kinematics("link2", target, [0.1, 1.0], position_only=True)
    assert r.success
    # Law of cosines: |p|² = 2 + 2 cos q2 = 2, so q2 = ±π/2.
    assert abs(abs(r.q[1]) - np.pi / 2) < 1e-6
    q1, q2 = r.q
    np.testing.assert_allclose([np.cos(q1) + np.cos(q1 + q2), np.sin(q1) + np.sin(q1 + q2)],
                               [1.0, 1.0], atol=1e-6)


def test_unreachable_is_not_an_error():
    m = screwdyn.load("builtin:planar2")
    target = np.eye(4)
    target[:3, 3] = [3.0, 0.0, 0.0]
    r = m.inverse_kinematics("link2", target, [0.2, 0.3], position_only=True)
    assert not r.success and r.failure is not None
    assert abs(r.position_error - 1.0) < 1e-6  # reach 2 m, the nearest point is 1 m away


def test_all_closed_form_solutions_of_ur5():
    m = screwdyn.load("builtin:ur5")
    target = m.frame_pose([0.3, -1.2, 1.5, -0.4, 1.1, 0.7], "tool0")
    sols = m.inverse_kinematics_all("tool0", target)
    assert sols.shape == (8, 6)
    for q in sols:
        dp, dr = _pose_errors(m.frame_pose(q, "tool0"), target)
        assert dp <= 1e-6 and dr <= 1e-6
        assert _within(m, q)
    assert len({tuple(np.round(q, 4)) for q in sols}) == 8


def test_bad_input():
    m = screwdyn.load("builtin:ur5")
    good = m.frame_pose(np.zeros(6), "tool0")
    with pytest.raises(ValueError, match="no frame named"):
        m.inverse_kinematics("nope", good)
    bad = good.copy()
    bad[:3, :3] *= 1.01
    with pytest.raises(ValueError, match="orthonormal"):
        m.inverse_kinematics("tool0", bad)
    nan = good.copy()
    nan[0, 3] = np.nan
    with pytest.raises(ValueError, match="non-finite"):
        m.inverse_kinematics("tool0", nan)
    with pytest.raises(ValueError, match="outside its limits"):
        m.inverse_kinematics("tool0", good, [0, 0, 0, 0, 0, 7.0])
    with pytest.raises(ValueError, match="shape"):
        m.inverse_kinematics("tool0", good[:3])
    with pytest.raises(ValueError, match="bottom row"):
        row = good.copy()
        row[3, 0] = 1.0
        m.inverse_kinematics("tool0", row)


def test_dask_batches_match_one_call():
    da = pytest.importorskip("dask.array")
    import screwdyn.dask as sdask

    m = screwdyn.load("builtin:ur5")
    targets = m.frame_pose(_random_q(m, 10, seed=9), "tool0")
    q, success, dp, dr = sdask.map_inverse_kinematics(
        m, "tool0", da.from_array(targets, chunks=(3, 4, 4)), threads=1)
    q, success, dp = q.compute(scheduler="sync"), success.compute(scheduler="sync"), dp.compute()
    assert q.shape == (10, 6) and success.all() and (dp <= 1e-6).all()
    for k in range(10):
        dp_k, dr_k = _pose_errors(m.frame_pose(q[k], "tool0"), targets[k])
        assert dp_k <= 1e-6 and dr_k <= 1e-6


def test_calls_that_change_frame_or_options_between_them():
    # The model keeps the last solver for the next call: alternating frames, tasks and
    # tolerances, every answer is still confirmed by forward kinematics of its own frame.
    m = screwdyn.load("builtin:ur5")
    for k, q_true in enumerate(_random_q(m, 6, seed=11)):
        frame = ["tool0", "wrist_2_link"][k % 2]
        target = m.frame_pose(q_true, frame)
        if k % 3 == 2:
            r = m.inverse_kinematics(frame, target, position_only=True, position_tolerance=1e-9)
            assert r.success
            assert np.linalg.norm(m.frame_pose(r.q, frame)[:3, 3] - target[:3, 3]) <= 1e-9
        else:
            r = m.inverse_kinematics(frame, target, seed=k)
            assert r.success and _within(m, r.q)
            dp, dr = _pose_errors(m.frame_pose(r.q, frame), target)
            assert dp <= 1e-6 and dr <= 1e-6
        # The same call again gives the same answer (a cached solver starts afresh).
        again = m.inverse_kinematics(
            frame, target, position_only=(k % 3 == 2), seed=0 if k % 3 == 2 else k,
            position_tolerance=1e-9 if k % 3 == 2 else None,
        )
        np.testing.assert_array_equal(again.q, r.q)
        for q in m.inverse_kinematics_all("tool0", m.frame_pose(q_true, "tool0")):
            dp, dr = _pose_errors(m.frame_pose(q, "tool0"), m.frame_pose(q_true, "tool0"))
            assert dp <= 1e-6 and dr <= 1e-6
