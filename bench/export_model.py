#!/usr/bin/env python3
"""Reads a fixed-base URDF with Pinocchio's Python bindings and writes its joint tree as plain
text for bench/pinocchio_bench.cpp (bench/compare.sh runs this).

Why not parse the URDF in C++: the `pin` wheel's URDF parser is a compiled library built with
its own flags; a benchmark compiled with -march=native (wider Eigen alignment) cannot share
`pinocchio::Model` objects with it safely. A text hand-over keeps the C++ side header-only.

One line per joint, in Pinocchio's joint order:
  type parent  p(3)  R(9, row-major)  mass  lever(3)  I_c(9, row-major)  axis(3)  lower upper
`type` is Pinocchio's short name (JointModelRZ, JointModelPY, JointModelRevoluteUnaligned, ...);
`axis` is the joint's motion axis (angular part for revolute, linear part for prismatic).
"""
import sys

import numpy as np
import pinocchio as pin


def main(urdf, out):
    model = pin.buildModelFromUrdf(urdf)
    lines = [model.name]
    for j in range(1, model.njoints):
        jm = model.joints[j]
        if jm.nq != 1 or jm.nv != 1:
            sys.exit(f"joint {model.names[j]}: only one-coordinate joints are supported")
        jd = jm.createData()
        jm.calc(jd, np.zeros(model.nq))
        s = np.array(jd.S).reshape(6)  # linear first
        kind = jm.shortname()
        axis = s[3:] if np.linalg.norm(s[3:]) > 0.5 else s[:3]
        m = model.jointPlacements[j]
        inertia = model.inertias[j]
        iq = jm.idx_q
        row = [kind, model.parents[j]]
        row += list(m.translation) + list(m.rotation.reshape(9))
        row += [inertia.mass] + list(inertia.lever) + list(np.array(inertia.inertia).reshape(9))
        row += list(axis) + [model.lowerPositionLimit[iq], model.upperPositionLimit[iq]]
        lines.append(" ".join(repr(float(x)) if not isinstance(x, str) else x for x in row))
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
