"""Joint springs (MJCF `stiffness`, `springref`) against MuJoCo: the passive torque screwdyn's
simulation applies, −k (q − q_spring) − b q̇, is MuJoCo's qfrc_passive at the same states; the
springs stay out of the bias forces (qfrc_bias); and a short passive run with classical RK4 at
the same step follows mujoco's mj_step with integrator="RK4".

The file is written here: a hinge arm in degrees with springs from a default class, an own
springref, a slide joint with a spring, damping and armature, gravity on, contacts off.
"""

import mujoco
import numpy as np

import screwdyn

SPRINGS = """<mujoco model="springs">
  <compiler angle="degree" autolimits="true"/>
  <option timestep="{dt}" integrator="RK4" gravity="0.5 -0.3 -9.81">
    <flag contact="disable"/>
  </option>
  <default>
    <joint damping="0.3" armature="0.02"/>
    <default class="spring"><joint stiffness="25" springref="20"/></default>
  </default>
  <worldbody>
    <body name="upper" pos="0 0 0.5" euler="10 0 0">
      <joint name="shoulder" class="spring" axis="0 1 0"/>
      <geom type="capsule" fromto="0 0 0 0.4 0 0" size="0.04"/>
      <body name="fore" pos="0.4 0 0">
        <joint name="elbow" axis="0 1 0" stiffness="8" springref="-35" damping="0.1"/>
        <geom type="box" size="0.15 0.03 0.02" pos="0.15 0 0"/>
        <body name="slider" pos="0.3 0 0">
          <joint name="slide" type="slide" axis="1 0 0" stiffness="40" springref="0.05" damping="1.5"/>
          <geom type="sphere" size="0.05" mass="0.4"/>
          <site name="tip" pos="0.05 0 0"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>
"""

ONLY_PASSIVE = {"saturate": False, "damping": True, "springs": True, "friction": False,
                "position_limits": False}


def load(tmp_path, dt=1e-3):
    path = tmp_path / "springs.xml"
    path.write_text(SPRINGS.format(dt=dt))
    return screwdyn.load(str(path)), mujoco.MjModel.from_xml_path(str(path))


def test_the_springs_are_read_as_mujoco_compiles_them(tmp_path):
    m, mj = load(tmp_path)
    np.testing.assert_allclose(m.stiffness, mj.jnt_stiffness, rtol=0, atol=0)
    # qpos_spring holds the springrefs, the hinges' converted to radians.
    np.testing.assert_allclose(m.springref, mj.qpos_spring, rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose(m.damping, mj.dof_damping, rtol=0, atol=0)


def test_the_passive_torque_is_qfrc_passive_and_not_in_the_bias(tmp_path):
    m, mj = load(tmp_path)
    data = mujoco.MjData(mj)
    # The torque screwdyn applied in a passive run (no command: τ = the joint effects), at each
    # recorded state, against MuJoCo's qfrc_passive and qfrc_bias at that state.
    run = m.simulate([0.9, -0.4, 0.12], [1.0, -2.0, 0.3], duration=0.3, dt=1e-3,
                     effects=ONLY_PASSIVE, record_every=25)
    assert len(run.t) > 5
    for q, v, tau in zip(run.q, run.v, run.tau):
        data.qpos[:] = q
        data.qvel[:] = v
        mujoco.mj_forward(mj, data)
        scale = float(np.max(np.abs(data.qfrc_passive)))
        assert np.max(np.abs(tau - data.qfrc_passive)) <= 1e-12 * scale
        bias = m.nonlinear_effects(q, v)
        assert np.max(np.abs(bias - data.qfrc_bias)) <= 1e-9 * np.max(np.abs(data.qfrc_bias))


def test_a_passive_rk4_run_follows_mj_step(tmp_path):
    dt, steps = 1e-3, 500
    m, mj = load(tmp_path, dt)
    data = mujoco.MjData(mj)
    q0, v0 = np.array([0.9, -0.4, 0.12]), np.array([1.0, -2.0, 0.3])
    data.qpos[:] = q0
    data.qvel[:] = v0
    run = m.simulate(q0, v0, duration=steps * dt, dt=dt, integrator="rk4",
                     effects=ONLY_PASSIVE, record_every=50)
    k = 0
    for i in range(steps + 1):
        if k < len(run.t) and abs(run.t[k] - data.time) < dt / 2:
            np.testing.assert_allclose(run.q[k], data.qpos, rtol=0, atol=1e-9)
            np.testing.assert_allclose(run.v[k], data.qvel, rtol=0, atol=1e-8)
            k += 1
        if i < steps:
            mujoco.mj_step(mj, data)
    assert k == len(run.t) and run.t[-1] > 0.45
    # The springs matter here: without them the run ends elsewhere.
    free = m.simulate(q0, v0, duration=steps * dt, dt=dt, integrator="rk4",
                      effects=dict(ONLY_PASSIVE, springs=False), record_every=50)
    assert np.max(np.abs(free.q[-1] - data.qpos)) > 1e-2


def test_the_exported_mjcf_gives_mujoco_the_same_springs(tmp_path):
    m, mj = load(tmp_path)
    back = mujoco.MjModel.from_xml_string(m.to_mjcf())
    np.testing.assert_allclose(back.jnt_stiffness, mj.jnt_stiffness, rtol=0, atol=0)
    np.testing.assert_allclose(back.qpos_spring, mj.qpos_spring, rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose(back.dof_damping, mj.dof_damping, rtol=0, atol=0)
