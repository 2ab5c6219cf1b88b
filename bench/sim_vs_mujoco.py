"""Times MuJoCo on the same passive simulation as `examples/sim_bench.rs`.

10 s at 1 kHz, RK4, contacts and joint limits disabled, released from rest at the same q0.
MuJoCo runs through `mujoco.rollout` (its C loop), so Python's per-step overhead is not counted
against it. Also checks that both simulators describe the same physics: the joint positions
after 0.2 s (before the falling arm turns chaotic) must agree.

Usage: python sim_vs_mujoco.py ROBOT.urdf OURS.json [OURS_SHORT.json]
Prints one JSON line.
"""

import json
import sys
import time

import mujoco
import numpy as np
from mujoco import rollout


def load(urdf, q0):
    m = mujoco.MjModel.from_xml_path(urdf)
    m.opt.timestep = 1e-3
    m.opt.integrator = mujoco.mjtIntegrator.mjINT_RK4
    m.opt.disableflags |= mujoco.mjtDisableBit.mjDSBL_CONTACT | mujoco.mjtDisableBit.mjDSBL_LIMIT
    d = mujoco.MjData(m)
    if m.nq != len(q0):
        sys.exit(f"MuJoCo sees {m.nq} coordinates, screwdyn {len(q0)}")
    d.qpos[:] = q0
    return m, d


def run(m, d, nstep, repeat):
    """Rolls out `nstep` steps from d's state `repeat` times; returns wall times and the end qpos."""
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    state = np.zeros(mujoco.mj_stateSize(m, spec))
    mujoco.mj_getState(m, d, state, spec)
    seconds, last = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        states, _ = rollout.rollout(m, d, state, nstep=nstep)
        seconds.append(time.perf_counter() - start)
        last = states
    # FULLPHYSICS layout: time, qpos, qvel, ...
    q_end = last[0, -1, 1 : 1 + m.nq]
    return seconds, q_end


def main():
    urdf, ours_path = sys.argv[1], sys.argv[2]
    ours = json.load(open(ours_path))
    m, d = load(urdf, ours["q0"])
    seconds, _ = run(m, d, 10_000, len(ours["seconds"]))
    m, d = load(urdf, ours["q0"])  # rollout leaves d at its end state: start afresh
    out = {
        "model": ours["model"],
        "mujoco_version": mujoco.__version__,
        "mujoco_seconds": seconds,
        "mujoco_median_s": float(np.median(seconds)),
        "screwdyn_median_s": ours["median_s"],
        "ratio": ours["median_s"] / float(np.median(seconds)),
    }
    if len(sys.argv) > 3:
        short = json.load(open(sys.argv[3]))
        _, q_short = run(m, d, 200, 1)
        out["max_abs_q_difference_at_0.2s"] = float(np.max(np.abs(q_short - np.array(short["final_q"]))))
    print(json.dumps(out))


if __name__ == "__main__":
    main()
