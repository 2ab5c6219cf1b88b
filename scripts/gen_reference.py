#!/usr/bin/env python3
"""Generate Pinocchio reference fixtures for screwdyn's tests (issue 4).

Usage, from the repository root (needs Python >= 3.9 and network access to PyPI):

    python3 scripts/gen_reference.py            # creates .venv-pin, installs pin, regenerates
    python3 scripts/gen_reference.py --no-venv  # run in the current interpreter (pin installed)

The first form creates a throwaway virtual environment `.venv-pin` in the repository root
(git-ignored), runs `pip install pin example-robot-data` in it and re-executes this script
there. It writes one JSON file per robot to `crates/screwdyn/tests/fixtures/pinocchio/`:

* `ur5.json`   - UR5 from example-robot-data (`ur_description/urdf/ur5_robot.urdf`), fixed base;
* `panda.json` - Franka Panda (`panda_description/urdf/panda.urdf`), fixed base, with the two
                 prismatic finger joints (a tree with prismatic joints);
* `tree.json`  - a random branching tree built here with `pin.Model()`: revolute joints about
                 unaligned axes, prismatic joints along unaligned axes, random placements and
                 random physical inertias with the centre of mass off the joint origin.

Each state also carries `computeRNEADerivatives` / `computeABADerivatives` with body-fixed
external forces (issue 15; random on even states, drawn from a second generator so the states
themselves do not change).

Every spatial quantity is converted from Pinocchio's linear-first convention to screwdyn's
angular-first one (twists `(w, v)`, Jacobian rows `(angular; linear)`). The schema is
documented in `crates/screwdyn/tests/fixtures/pinocchio/README.md`. The output is
deterministic (fixed numpy seed) for a given Pinocchio / example-robot-data version.

Only numbers are written; the third-party URDF files are not copied into the repository (the
path they were read from is recorded for information).
"""

import argparse
import importlib.metadata
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT_DIR = os.path.join(ROOT, "crates", "screwdyn", "tests", "fixtures", "pinocchio")
VENV = os.path.join(ROOT, ".venv-pin")
SEED = 20240604
N_STATES = 20

# Which frames get Jacobians (every selected frame on a moving body gets its pose): frames on
# the leaves of each tree, which between them exercise every Jacobian column, plus one mid-chain
# body for the UR5; a short list keeps the files small.
JACOBIAN_FRAMES = {
    "ur5": ["forearm_link", "tool0"],
    "panda": ["panda_leftfinger", "panda_rightfinger"],
    "tree": ["tool4", "tool6", "tool8", "tool9"],
}

# URDFs inside the example-robot-data wheel.
URDFS = {
    "ur5": "robots/ur_description/urdf/ur5_robot.urdf",
    "panda": "robots/panda_description/urdf/panda.urdf",
}


def bootstrap():
    """Create .venv-pin, install pin and example-robot-data, re-run this script inside it."""
    py = os.path.join(VENV, "bin", "python")
    if not os.path.exists(py):
        subprocess.check_call([sys.executable, "-m", "venv", VENV])
    subprocess.check_call([py, "-m", "pip", "install", "-q", "--upgrade", "pip"])
    subprocess.check_call([py, "-m", "pip", "install", "-q", "pin", "example-robot-data"])
    os.execv(py, [py, os.path.abspath(__file__), "--no-venv"])


# ---------------------------------------------------------------------------------------------
# Conversion helpers (Pinocchio linear-first -> screwdyn angular-first).

SWAP = [3, 4, 5, 0, 1, 2]


def fl(x):
    return [float(v) for v in x]


def rows(m):
    return [fl(r) for r in m]


def se3_json(pin_se3):
    return {"rotation": rows(pin_se3.rotation), "translation": fl(pin_se3.translation)}


def angular_first_rows(j):
    """A 6xn matrix with linear rows first -> angular rows first."""
    return j[SWAP, :]


def inertia_json(inertia):
    return {
        "mass": float(inertia.mass),
        "com": fl(inertia.lever),
        "inertia_com": rows(inertia.inertia),  # rotational inertia about the CoM
    }


# ---------------------------------------------------------------------------------------------
# Models.


def erd_urdf_path(name):
    """Locate a URDF inside the installed example-robot-data distribution.

    example-robot-data 6.x on PyPI ships the robot files but no Python loader (no
    `example_robot_data.load`), so the file is found through the distribution's file list:
    the same URDF the former `load("ur5")` / `load("panda")` read.
    """
    dist = importlib.metadata.distribution("example-robot-data")
    want = "share/example-robot-data/" + URDFS[name]
    for f in dist.files or []:
        if str(f).endswith(want):
            return str(f.locate())
    raise RuntimeError(f"{want} not found in example-robot-data {dist.version}")


def random_rotation(rng):
    q = rng.normal(size=4)
    q /= np.linalg.norm(q)
    w, x, y, z = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def random_unit(rng):
    a = rng.normal(size=3)
    return a / np.linalg.norm(a)


def random_inertia(rng):
    """A physical inertia: a solid box of random size, mass and orientation, CoM off origin."""
    mass = rng.uniform(0.5, 3.0)
    a, b, c = rng.uniform(0.05, 0.4, size=3)
    principal = mass / 12.0 * np.array([b * b + c * c, a * a + c * c, a * a + b * b])
    r = random_rotation(rng)
    i_com = r @ np.diag(principal) @ r.T
    i_com = 0.5 * (i_com + i_com.T)
    com = rng.uniform(-0.15, 0.15, size=3)
    return pin.Inertia(mass, com, i_com)


def build_tree(rng):
    """A random branching tree, joints added in depth-first order (screwdyn's joint order).

    universe ─ j1 ─ j2 ─ j3 ─ j4
                  │    └ j5 ─ j6
                  └ j7 ─ j8
    universe ─ j9
    """
    parents = [0, 1, 2, 3, 2, 5, 1, 7, 0]
    prismatic = {3, 6, 8}  # 1-based joint indices that are prismatic (j8 is a leaf)
    model = pin.Model()
    model.name = "random_tree"
    for k, p in enumerate(parents, start=1):
        axis = random_unit(rng)
        if k in prismatic:
            jm = pin.JointModelPrismaticUnaligned(axis)
            lo, hi, eff = -0.5, 0.5, 100.0
        else:
            jm = pin.JointModelRevoluteUnaligned(axis)
            lo, hi, eff = -np.pi, np.pi, 50.0
        placement = pin.SE3(random_rotation(rng), rng.uniform(-0.5, 0.5, size=3))
        jid = model.addJoint(
            p,
            jm,
            placement,
            f"joint{k}",
            np.array([eff]),
            np.array([10.0]),
            np.array([lo]),
            np.array([hi]),
        )
        assert jid == k
        model.appendBodyToJoint(jid, random_inertia(rng), pin.SE3.Identity())
        jf = model.addJointFrame(jid, model.getFrameId(f"link{p}") if p > 0 else 0)
        model.addBodyFrame(f"link{k}", jid, pin.SE3.Identity(), jf)
    # Tool frames with random placements on the leaves (and on j2, a branching body).
    for k in (2, 4, 6, 8, 9):
        placement = pin.SE3(random_rotation(rng), rng.uniform(-0.3, 0.3, size=3))
        parent_frame = model.getFrameId(f"link{k}")
        frame = pin.Frame(f"tool{k}", k, parent_frame, placement, pin.FrameType.OP_FRAME)
        model.addFrame(frame)
    return model


# ---------------------------------------------------------------------------------------------
# Fixture.


def joint_kind_axis(model, data, j):
    """("revolute"|"prismatic", unit axis in the joint frame) from the motion subspace S."""
    s = np.array(data.joints[j].S).reshape(6)  # Pinocchio: (v, w)
    v, w = s[:3], s[3:]
    if np.linalg.norm(v) < 1e-12 and abs(np.linalg.norm(w) - 1) < 1e-12:
        return "revolute", w
    if np.linalg.norm(w) < 1e-12 and abs(np.linalg.norm(v) - 1) < 1e-12:
        return "prismatic", v
    raise RuntimeError(f"joint {model.names[j]} is neither revolute nor prismatic: S = {s}")


def body_frame_of_joint(model, j):
    """The BODY frame of the child link of joint j (its previous frame is joint j's frame)."""
    found = [
        f
        for f, fr in enumerate(model.frames)
        if fr.type == pin.FrameType.BODY
        and fr.parentJoint == j
        and model.frames[fr.parentFrame].type == pin.FrameType.JOINT
        and model.frames[fr.parentFrame].name == model.names[j]
    ]
    assert len(found) == 1, (model.names[j], found)
    f = found[0]
    assert model.frames[f].placement.isIdentity(1e-14), "child link frame must be the joint frame"
    return f


def describe(model, data):
    joints = []
    for j in range(1, model.njoints):
        assert model.nqs[j] == 1 and model.nvs[j] == 1, f"joint {model.names[j]}: nq != 1"
        kind, axis = joint_kind_axis(model, data, j)
        iq, iv = model.idx_qs[j], model.idx_vs[j]
        assert iq == j - 1 and iv == j - 1
        joints.append(
            {
                "name": model.names[j],
                "parent": None if model.parents[j] == 0 else int(model.parents[j]) - 1,
                "type": kind,
                "axis": fl(axis),
                "placement": se3_json(model.jointPlacements[j]),
                "body_name": model.frames[body_frame_of_joint(model, j)].name,
                "inertia": inertia_json(model.inertias[j]),
                "limits": {
                    "lower": float(model.lowerPositionLimit[iq]),
                    "upper": float(model.upperPositionLimit[iq]),
                    "velocity": float(model.velocityLimit[iv]),
                    "effort": float(model.effortLimit[iv]),
                },
            }
        )
    frames = []
    for fr in model.frames:
        if fr.type not in (pin.FrameType.BODY, pin.FrameType.OP_FRAME):
            continue
        frames.append(
            {
                "name": fr.name,
                "joint": None if fr.parentJoint == 0 else int(fr.parentJoint) - 1,
                "type": "body" if fr.type == pin.FrameType.BODY else "op",
                "placement": se3_json(fr.placement),
            }
        )
    names = [f["name"] for f in frames]
    assert len(set(names)) == len(names), "frame names must be unique"
    return joints, frames


def random_state(model, rng):
    lo, hi = model.lowerPositionLimit.copy(), model.upperPositionLimit.copy()
    unlimited = ~(np.isfinite(lo) & np.isfinite(hi)) | (hi - lo > 1e10)
    lo[unlimited], hi[unlimited] = -np.pi, np.pi
    q = rng.uniform(lo, hi)
    v = rng.normal(size=model.nv)
    a = rng.normal(size=model.nv)
    tau_in = 0.3 * model.effortLimit * rng.normal(size=model.nv)
    return q, v, a, tau_in


def random_fext(model, rng_fext, k):
    """External wrenches for state k: random on even states, zero on odd ones (angular first)."""
    w = np.zeros((model.nv, 6))
    if k % 2 == 0:
        w = rng_fext.normal(size=(model.nv, 6)) * np.array([2.0, 2.0, 2.0, 10.0, 10.0, 10.0])
    return w


def symmetric_upper(m):
    m = np.array(m)
    return np.triu(m) + np.triu(m, 1).T


def derivatives_json(model, data, q, v, a, tau_in, w):
    """computeRNEADerivatives / computeABADerivatives with body-fixed external forces.

    `w` holds one wrench per joint, angular first, in the joint (= body) frame; Pinocchio's
    `pin.Force` is linear first. Joint-space derivatives need no other conversion.
    """
    fext = [pin.Force.Zero()] + [pin.Force(wi[3:], wi[:3]) for wi in w]
    tau = pin.rnea(model, data, q, v, a, fext).copy()
    dq, dv, da = (np.array(x).copy() for x in pin.computeRNEADerivatives(model, data, q, v, a, fext))
    da = symmetric_upper(da)
    qdd = pin.aba(model, data, q, v, tau_in, fext).copy()
    ddq, ddv, minv = (np.array(x).copy() for x in pin.computeABADerivatives(model, data, q, v, tau_in, fext))
    minv = symmetric_upper(minv)
    assert np.allclose(minv @ da, np.eye(model.nv), atol=1e-8)
    return {
        "fext": rows(w),
        "tau_fext": fl(tau),
        "qdd_fext": fl(qdd),
        "dtau_dq": rows(dq),
        "dtau_dv": rows(dv),
        "dtau_da": rows(da),
        "dqdd_dq": rows(ddq),
        "dqdd_dv": rows(ddv),
        "minv": rows(minv),
    }


def state_json(model, data, q, v, a, tau_in, frame_names, jac_frames, w):
    tau = pin.rnea(model, data, q, v, a).copy()
    m = pin.crba(model, data, q).copy()
    m = np.triu(m) + np.triu(m, 1).T  # crba fills the upper triangle
    g = pin.computeGeneralizedGravity(model, data, q).copy()
    nle = pin.nonLinearEffects(model, data, q, v).copy()
    c = pin.computeCoriolisMatrix(model, data, q, v).copy()
    qdd = pin.aba(model, data, q, v, tau_in).copy()
    assert np.allclose(c @ v, nle - g, atol=1e-9)
    assert np.allclose(m @ qdd + nle, tau_in, atol=1e-8 * (1 + np.abs(tau_in).max()))

    pin.computeJointJacobians(model, data, q)
    pin.updateFramePlacements(model, data)
    poses, jw, jl, jlwa = {}, {}, {}, {}
    for name in frame_names:
        f = model.getFrameId(name)
        if model.frames[f].parentJoint != 0:  # frames on the base: pose = placement, constant
            poses[name] = rows(data.oMf[f].homogeneous)
    for name in jac_frames:
        f = model.getFrameId(name)
        for out, rf in (
            (jw, pin.ReferenceFrame.WORLD),
            (jl, pin.ReferenceFrame.LOCAL),
            (jlwa, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED),
        ):
            j = pin.getFrameJacobian(model, data, f, rf)
            out[name] = rows(angular_first_rows(j))
    return {
        "q": fl(q),
        "v": fl(v),
        "a": fl(a),
        "tau_in": fl(tau_in),
        "tau": fl(tau),
        "mass_matrix": rows(m),
        "gravity": fl(g),
        "nonlinear_effects": fl(nle),
        "coriolis_times_v": fl(nle - g),
        "coriolis_matrix": rows(c),
        "qdd": fl(qdd),
        "frame_poses": poses,
        "jacobians_world": jw,
        "jacobians_local": jl,
        "jacobians_local_world_aligned": jlwa,
        "derivatives": derivatives_json(model, data, q, v, a, tau_in, w),
    }


def fixture(robot, model, source, urdf_path, rng, rng_fext):
    assert model.nq == model.nv, f"{robot}: nq = {model.nq} != nv = {model.nv}"
    data = model.createData()
    pin.forwardKinematics(model, data, pin.neutral(model))
    joints, frames = describe(model, data)
    frame_names = [f["name"] for f in frames]
    jac_frames = JACOBIAN_FRAMES[robot]
    assert all(n in frame_names for n in jac_frames)
    states = []
    for k in range(N_STATES):
        q, v, a, tau_in = random_state(model, rng)
        w = random_fext(model, rng_fext, k)
        states.append(state_json(model, data, q, v, a, tau_in, frame_names, jac_frames, w))
    return {
        "robot": robot,
        "source": source,
        "pinocchio_version": pin.__version__,
        "example_robot_data_version": importlib.metadata.version("example-robot-data"),
        "urdf_path": urdf_path,
        "convention": "angular first: twists (w, v), Jacobian rows (angular; linear)",
        "seed": SEED,
        "gravity": fl(model.gravity.linear),
        "joints": joints,
        "frames": frames,
        "jacobian_frames": jac_frames,
        "states": states,
    }


def write(fx):
    os.makedirs(OUT_DIR, exist_ok=True)
    path = os.path.join(OUT_DIR, fx["robot"] + ".json")
    with open(path, "w") as f:
        json.dump(fx, f, separators=(",", ":"))
        f.write("\n")
    print(f"wrote {os.path.relpath(path, ROOT)} ({os.path.getsize(path) // 1024} KB)")


def main():
    rng = np.random.default_rng(SEED)
    # A second stream for the external wrenches, so that the states drawn from `rng` stay the
    # same as before the derivatives were added.
    rng_fext = np.random.default_rng(SEED + 1)
    for robot in ("ur5", "panda"):
        path = erd_urdf_path(robot)
        model = pin.buildModelFromUrdf(path)  # fixed base
        src = f"example-robot-data {URDFS[robot]}, pinocchio.buildModelFromUrdf (fixed base)"
        write(fixture(robot, model, src, path, rng, rng_fext))
    tree = build_tree(rng)
    src = "random tree built in scripts/gen_reference.py with pin.Model()"
    write(fixture("tree", tree, src, None, rng, rng_fext))


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument(
        "--no-venv", action="store_true", help="use the current interpreter (pin installed)"
    )
    if not parser.parse_args().no_venv:
        bootstrap()
    import numpy as np
    import pinocchio as pin

    main()
