"""Export to MJCF, checked by MuJoCo itself: the `mujoco` package loads the text of
``Model.to_mjcf()`` and its mass matrix ``qM`` (armature included), bias forces ``qfrc_bias``
(``C q̇ + g``) and body and site poses agree with screwdyn's at random states to 1e-9 relative.
"""

import numpy as np
import pytest

import screwdyn

mujoco = pytest.importorskip("mujoco")

RTOL = 1e-9  # observed: within 1e-13

# A DH homework arm (standard DH, a prismatic joint, a joint axis off the body origin in the
# exported body frames) with armatures, damping, friction, limits and a tool frame.
DH_ARM = """
format = "dh"
name = "dh_arm"
gravity = [0, 0, -9.81]
[[row]]
type = "R"
a = 0.3
alpha = 1.5707963267948966
d = 0.4
armature = 0.3
damping = 0.4
friction = 0.1
limits = { lower = -3, upper = 3, effort = 80 }
mass = 3.0
com = [-0.15, 0.0, 0.02]
inertia = [0.02, 0.001, 0.0, 0.05, 0.002, 0.04]
[[row]]
type = "R"
a = 0.5
theta = 0.2
armature = 0.15
mass = 2.0
com = [-0.25, 0.01, 0.0]
inertia = [0.01, 0.0, 0.001, 0.04, 0.0, 0.045]
[[row]]
type = "P"
alpha = -1.5707963267948966
theta = 0.1
armature = 0.05
limits = { lower = 0.0, upper = 0.3, effort = 100 }
mass = 1.0
com = [0.0, 0.0, -0.05]
inertia = [0.004, 0.0, 0.0, 0.004, 0.0, 0.002]
[[row]]
type = "C"
d = 0.1
alpha = 0.7
armature = 0.01
mass = 0.5
com = [0.01, 0.02, 0.03]
inertia = [0.001, 0.0001, 0.0, 0.0012, 0.0, 0.0008]
[[frame]]
name = "tool"
link = "link4"
pose = { xyz = [0.0, 0.05, 0.12], rpy = [0.3, -0.2, 0.9] }
"""

# A branched native description with armature on every joint and a frame on the base.
BRANCHED = """
format = "screwdyn"
name = "forked"
gravity = [0.0, -9.81, -1.0]
[[body]]
name = "trunk"
parent = "base"
type = "revolute"
home = { xyz = [0, 0, 0.5], rpy = [0.1, 0, 0] }
screw_in_parent = [0, 0, 1, 0, 0, 0]
armature = 0.2
mass = 4.0
com = [0, 0, 0.2]
inertia = [0.1, 0, 0, 0.1, 0, 0.05]
[[body]]
name = "left"
parent = "trunk"
type = "revolute"
home = { xyz = [0, 0.2, 0.4], rpy = [0.3, 0.2, -0.1] }
screw_in_child = [1, 0, 0, 0, 0.05, -0.02]
armature = 0.1
mass = 1.5
com = [0.1, 0.0, 0.0]
inertia = [0.01, 0.001, 0, 0.02, 0, 0.02]
[[body]]
name = "right"
parent = "trunk"
type = "prismatic"
home = { xyz = [0, -0.2, 0.4] }
screw_in_child = [0, 0, 0, 0, 0.6, 0.8]
armature = 0.05
limits = { lower = -0.1, upper = 0.2, effort = 50 }
mass = 1.0
com = [0.0, 0.0, 0.1]
inertia = [0.01, 0, 0, 0.01, 0, 0.005]
[[frame]]
name = "camera"
link = "base"
pose = { xyz = [0.3, 0.1, 1.2], rpy = [0, 0.5, 0] }
[[frame]]
name = "gripper"
link = "left"
pose = { xyz = [0.2, 0, 0], rpy = [0.1, 0.2, 0.3] }
"""


def models():
    return [
        # Point masses: MuJoCo needs the file's boundmass/boundinertia (1e-14).
        ("planar2", screwdyn.load("builtin:planar2")),
        ("ur5", screwdyn.load("builtin:ur5")),
        ("panda", screwdyn.load("builtin:panda")),
        ("branched", screwdyn.load("builtin:branched")),
        ("dh", screwdyn.load_string(DH_ARM, "toml", name="dh_arm.toml")),
        ("forked", screwdyn.load_string(BRANCHED, "toml", name="forked.toml")),
    ]


def close(a, b, what):
    a, b = np.asarray(a), np.asarray(b)
    scale = max(1.0, float(np.max(np.abs(b))))
    err = float(np.max(np.abs(a - b)))
    assert err <= RTOL * scale, f"{what}: error {err} (scale {scale})\n{a}\n{b}"


def full_mass_matrix(mj, data):
    """``qM`` as a dense matrix (``mj_fullM`` changed its arguments in MuJoCo 4)."""
    dst = np.zeros((mj.nv, mj.nv))
    try:
        mujoco.mj_fullM(mj, data, dst)
    except TypeError:
        mujoco.mj_fullM(mj, dst, data.qM)
    return dst


def pose(xpos, xmat):
    h = np.eye(4)
    h[:3, :3] = np.asarray(xmat).reshape(3, 3)
    h[:3, 3] = xpos
    return h


@pytest.mark.parametrize("name,model", models(), ids=lambda x: x if isinstance(x, str) else "")
def test_mujoco_agrees_with_the_exported_model(name, model):
    mj = mujoco.MjModel.from_xml_string(model.to_mjcf())
    data = mujoco.MjData(mj)
    nq = model.nq
    assert (mj.nq, mj.nv) == (nq, nq)
    # MuJoCo's coordinate of each screwdyn joint, by name.
    dof = [mj.joint(j).dofadr[0] for j in model.joint_names]
    qadr = [mj.joint(j).qposadr[0] for j in model.joint_names]
    assert sorted(dof) == list(range(nq))
    # The armature went through.
    close(mj.dof_armature[dof], model.armature, "armature")
    rng = np.random.default_rng(7)
    body_frames = set(model.link_names)
    checked_sites = 0
    for _ in range(5):
        q = rng.uniform(-1.5, 1.5, nq)
        lower, upper = model.lower_limits, model.upper_limits
        q = np.where(np.isfinite(lower) & np.isfinite(upper), np.clip(q, lower, upper), q)
        v = rng.uniform(-2.0, 2.0, nq)
        data.qpos[qadr] = q
        data.qvel[dof] = v
        mujoco.mj_forward(mj, data)
        full = full_mass_matrix(mj, data)
        close(full[np.ix_(dof, dof)], model.mass_matrix(q), f"{name} qM")
        close(data.qfrc_bias[dof], model.nonlinear_effects(q, v), f"{name} qfrc_bias")
        for frame in model.frame_names:
            h = model.frame_pose(q, frame)
            if frame in body_frames:
                b = mj.body(frame).id
                got = pose(data.xpos[b], data.xmat[b])
            elif mujoco.mj_name2id(mj, mujoco.mjtObj.mjOBJ_SITE, frame) >= 0:
                s = mj.site(frame).id
                got = pose(data.site_xpos[s], data.site_xmat[s])
                checked_sites += 1
            else:
                # The base frame is MuJoCo's world.
                got = np.eye(4)
            close(got, h, f"{name} pose of {frame}")
    if name in ("dh", "forked"):
        assert checked_sites > 0


def test_limits_damping_friction_and_motors_reach_mujoco():
    model = screwdyn.load_string(DH_ARM, "toml", name="dh_arm.toml")
    # The TOML's armature keys, read-only on the model.
    assert list(model.armature) == [0.3, 0.15, 0.05, 0.01]
    with pytest.raises(AttributeError):
        model.armature = [0.0] * 4
    mj = mujoco.MjModel.from_xml_string(model.to_mjcf())
    j1, j3 = mj.joint("joint1"), mj.joint("joint3")
    assert j1.limited[0] and j3.limited[0] and not mj.joint("joint4").limited[0]
    close(j1.range, [-3.0, 3.0], "range")
    close(mj.dof_damping[j1.dofadr], [0.4], "damping")
    close(mj.dof_frictionloss[j1.dofadr], [0.1], "frictionloss")
    assert mj.nu == 2
    close(mj.actuator("joint1").forcerange, [-80.0, 80.0], "forcerange")
    close(mj.actuator("joint3").forcerange, [-100.0, 100.0], "forcerange")
    # MuJoCo's passive damping force is −d q̇ on joint 1.
    data = mujoco.MjData(mj)
    data.qvel[:] = [1.5, 0.0, 0.0, 0.0]
    mujoco.mj_forward(mj, data)
    close(data.qfrc_passive[j1.dofadr], [-0.4 * 1.5], "passive damping")


def test_helical_joints_cannot_be_exported():
    text = """
format = "screwdyn"
[[body]]
name = "nut"
parent = "base"
joint = "screw"
type = "helical"
pitch = 0.01
screw_in_parent = [0, 0, 1, 0, 0, 0.01]
mass = 1.0
"""
    m = screwdyn.load_string(text, "toml", name="nut.toml")
    with pytest.raises(ValueError, match="joint 'screw' is helical"):
        m.to_mjcf()
