"""Simulation, controllers (built-in and Python callables), disturbances, trajectories and
torque profiles, checked against physical invariants and closed forms."""

import math

import numpy as np
import pytest

import screwdyn


@pytest.fixture(scope="module")
def arm():
    return screwdyn.load("builtin:planar2")


def test_passive_run_conserves_energy(arm):
    run = arm.simulate([0.5, -0.3], [0.0, 0.0], duration=1.0, dt=1e-3, effects=False)
    assert len(run) == 1001 and run.q.shape == (1001, 2) and run.t[-1] == pytest.approx(1.0)
    e = run.total_energy
    assert np.max(np.abs(e - e[0])) < 1e-6 * max(1.0, abs(e[0]))
    np.testing.assert_allclose(run.total_energy, run.kinetic_energy + run.potential_energy)
    # recorded accelerations are the forward dynamics of the recorded states
    np.testing.assert_allclose(run.a, arm.aba(run.q, run.v, run.tau), atol=1e-12)


def test_pendulum_period():
    # small oscillation: period 2π √(l/g); released at rest, q returns to q0 after one period
    p = screwdyn.load("builtin:pendulum")
    period = 2 * math.pi * math.sqrt(1.0 / 9.81)
    run = p.simulate([0.01], duration=period, dt=1e-4, effects=False, integrator="dopri5", record_every=1)
    assert run.q[-1, 0] == pytest.approx(0.01, abs=2e-6)


def test_python_controller_gravity_compensation_holds_the_arm(arm):
    calls = []

    def hold(t, q, v):
        calls.append(t)
        return arm.gravity_torque(q)

    run = arm.simulate([0.4, 0.2], duration=0.5, dt=1e-3, controller=hold, effects=False)
    assert len(calls) > 0
    np.testing.assert_allclose(run.q, np.tile([0.4, 0.2], (len(run), 1)), atol=1e-9)


def test_python_controller_exception_propagates(arm):
    class Boom(Exception):
        pass

    def bad(t, q, v):
        if t > 0.01:
            raise Boom("stop here")
        return [0.0, 0.0]

    with pytest.raises(Boom, match="stop here"):
        arm.simulate([0, 0], duration=0.1, controller=bad)
    with pytest.raises(ValueError, match=r"the controller's torque has shape \(3,\)"):
        arm.simulate([0, 0], duration=0.1, controller=lambda t, q, v: [0, 0, 0])


def test_builtin_controllers(arm):
    pd = screwdyn.PD([0.5, -0.3], [100, 100], [40, 40])
    run = arm.simulate([0, 0], duration=5.0, dt=1e-3, controller=pd, record_every=100)
    np.testing.assert_allclose(run.q[-1], [0.5, -0.3], atol=1e-3)
    # the library's default gains (Kp = ω² M_ii(q*), Kd = 2ω M_ii(q*)) also settle at the target
    run = arm.simulate([0, 0], duration=5.0, dt=1e-3, controller=screwdyn.PD([0.5, -0.3]),
                       record_every=100, effects=False)
    np.testing.assert_allclose(run.q[-1], [0.5, -0.3], atol=1e-3)
    # computed torque with default gains tracks a quintic it starts on
    ref0 = screwdyn.Quintic([0, 0], [0.4, 0.2], 1.0)
    run = arm.simulate([0, 0], duration=1.0, controller=screwdyn.ComputedTorque(ref0), effects=False)
    np.testing.assert_allclose(run.q, ref0.sample(run.t)[0], atol=1e-8)
    # computed torque tracks a quintic exactly (no model error): q(t) = q_d(t)
    ref = screwdyn.Quintic([0, 0], [1.0, -0.5], 1.0)
    run = arm.simulate([0, 0], duration=1.0, controller=screwdyn.ComputedTorque(ref, [100, 100], [20, 20]),
                       effects=False)
    qd, _, _ = ref.sample(run.t)
    np.testing.assert_allclose(run.q, qd, atol=1e-8)
    # constant torque = gravity at q0 holds the arm at q0 (statics)
    g = arm.gravity_torque([0.3, 0.1])
    run = arm.simulate([0.3, 0.1], duration=0.2, controller=g, effects=False)
    np.testing.assert_allclose(run.q[-1], [0.3, 0.1], atol=1e-9)
    # a torque series equal to that constant does the same
    series = screwdyn.TorqueSeries([0.0, 1.0], [g, g])
    run2 = arm.simulate([0.3, 0.1], duration=0.2, controller=series, effects=False)
    np.testing.assert_allclose(run2.q, run.q, atol=1e-12)


def test_disturbance_enters_like_an_external_wrench(arm):
    # a disturbance holding link 2 against gravity from t = 0: with gravity compensation of
    # link 1 only, the result equals an undisturbed run without gravity on link 2 … simpler
    # invariant: the initial acceleration equals aba with the same external wrench.
    w = [0, 0, 0.3, 0, 2.0, 0]
    run = arm.simulate([0.2, 0.4], duration=0.01, dt=1e-3, effects=False,
                       disturbances=[screwdyn.Disturbance("link2", w, 0.0, 1.0)])
    a0 = arm.aba([0.2, 0.4], [0, 0], [0, 0], fext={"link2": w})
    np.testing.assert_allclose(run.a[0], a0, atol=1e-12)
    run = arm.simulate([0.2, 0.4], duration=0.01, dt=1e-3, effects=False,
                       disturbances=[screwdyn.Disturbance("link2", w, 0.0, 1.0, frame="world")])
    np.testing.assert_allclose(run.a[0], arm.aba([0.2, 0.4], [0, 0], [0, 0], fext_world={"link2": w}), atol=1e-12)


def test_joint_effects_damping_dissipates():
    p = screwdyn.load("builtin:pendulum").with_joint_friction([0.5], [0.0])
    run = p.simulate([1.0], duration=2.0, effects={"damping": True, "friction": False,
                                                   "saturate": False, "position_limits": False})
    # power balance: dE/dt = −d q̇² ≤ 0
    assert np.all(np.diff(run.total_energy) <= 1e-12)
    assert run.total_energy[-1] < run.total_energy[0] - 0.1
    with pytest.raises(ValueError, match="unknown joint effect 'magic'"):
        p.simulate([1.0], effects={"magic": True})


def test_trapezoid_and_torque_profile():
    ur5 = screwdyn.load("builtin:ur5")
    qf = [1.5, -1.2, 1.4, -0.8, 1.0, 2.0]
    tr = screwdyn.Trapezoid(np.zeros(6), qf, np.full(6, 3.15), np.full(6, 50.0))
    q, v, a = tr.sample(0.0)
    np.testing.assert_array_equal(q, np.zeros(6))
    q, v, a = tr.sample(tr.duration)
    np.testing.assert_allclose(q, qf, atol=1e-12)
    np.testing.assert_allclose(v, 0, atol=1e-12)
    # mid-way every joint cruises at its cruise speed (synchronised)
    _, v, a = tr.sample(tr.duration / 2)
    np.testing.assert_allclose(np.abs(v), tr.cruise_speeds(), atol=1e-12)
    np.testing.assert_array_equal(np.sign(v), np.sign(qf))
    prof = ur5.torque_profile(tr, dt=0.01)
    s = prof.samples
    np.testing.assert_allclose(s.tau, ur5.rnea(s.q, s.v, s.a), atol=1e-12)
    np.testing.assert_allclose(prof.peak, np.max(np.abs(s.tau), axis=0))
    np.testing.assert_allclose(prof.rms, np.sqrt(np.mean(s.tau ** 2, axis=0)))
    np.testing.assert_array_equal(prof.effort_limit, ur5.effort_limits)
    over = np.abs(s.tau) > ur5.effort_limits
    assert len(prof.violations) == int(over.sum())
    assert "| joint | peak |" in prof._repr_markdown_()
    for j, name in enumerate(ur5.joint_names):
        k = int(np.argmax(np.abs(s.tau[:, j])))
        assert prof.peak_time[j] == pytest.approx(s.t[k])
        if over[:, j].any():
            summary = prof.violation_summary[name]
            assert summary["count"] == int(over[:, j].sum())
            assert summary["first_time"] == pytest.approx(s.t[np.argmax(over[:, j])])
            assert summary["worst"] == pytest.approx(prof.peak[j])
        else:
            assert name not in prof.violation_summary
    # at 50 rad/s² the UR5 motion of the README goes over the 150 N·m limit
    assert prof.violation_summary


def test_dataframe_and_plot(arm):
    pd = pytest.importorskip("pandas")
    run = arm.simulate([0.1, 0.0], duration=0.05, frames=["link2"])
    df = run.to_dataframe()
    assert list(df.columns) == ["t", "q.joint1", "q.joint2", "v.joint1", "v.joint2", "a.joint1",
                                "a.joint2", "tau.joint1", "tau.joint2", "kinetic_energy",
                                "potential_energy", "total_energy"]
    np.testing.assert_array_equal(df["q.joint2"].to_numpy(), run.q[:, 1])
    # the recorded frame poses are the forward kinematics of the recorded states
    np.testing.assert_allclose(run.poses["link2"], arm.frame_pose(run.q, "link2"), atol=1e-14)
    pytest.importorskip("matplotlib")
    import matplotlib
    matplotlib.use("Agg")
    fig = run.plot(("q", "energy"))
    assert len(fig.axes) == 2
