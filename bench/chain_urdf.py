#!/usr/bin/env python3
"""Writes the URDF of a long serial chain for the per-call comparison (bench/compare.sh):

    python3 bench/chain_urdf.py N OUT.urdf

N revolute joints, the axis cycling through z, y, x (so no two neighbours share an axis), every
joint origin offset from its parent's by a different vector, one origin in four also turned
(a roll or a yaw), and every link's mass, centre of mass and rotational inertia (with products
of inertia) different. Deterministic: the values come from the joint index, not from a random
generator, so both libraries and every run load the same robot.
"""
import math
import sys


def link(i):
    """Mass, centre of mass and inertia tensor (ixx iyy izz ixy ixz iyz) of link i, physical
    (a box of varied size, slightly turned)."""
    m = 0.4 + 0.15 * (i % 7)
    a, b, c = 0.04 + 0.01 * (i % 5), 0.05 + 0.01 * (i % 3), 0.12 + 0.02 * (i % 4)
    ixx, iyy, izz = m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12
    # Small products of inertia keep the tensor positive definite (diagonally dominant).
    p = 0.05 * min(ixx, iyy, izz)
    com = (0.01 * ((i % 3) - 1), 0.005 * ((i % 5) - 2), 0.03 + 0.01 * (i % 4))
    return m, com, (ixx, iyy, izz, p * ((i % 3) - 1), -p, p * ((i % 2) * 2 - 1))


def main(n, out):
    axes = ["0 0 1", "0 1 0", "1 0 0"]
    lines = ['<?xml version="1.0"?>', f'<robot name="chain{n}">', '  <link name="base_link"/>']
    for i in range(1, n + 1):
        m, com, (ixx, iyy, izz, ixy, ixz, iyz) = link(i)
        lines += [
            f'  <link name="l{i}">',
            "    <inertial>",
            f'      <origin xyz="{com[0]:.6g} {com[1]:.6g} {com[2]:.6g}" rpy="0 0 0"/>',
            f'      <mass value="{m:.6g}"/>',
            f'      <inertia ixx="{ixx:.9g}" iyy="{iyy:.9g}" izz="{izz:.9g}" '
            f'ixy="{ixy:.9g}" ixz="{ixz:.9g}" iyz="{iyz:.9g}"/>',
            "    </inertial>",
            "  </link>",
        ]
        parent = "base_link" if i == 1 else f"l{i - 1}"
        xyz = (0.02 * ((i % 3) - 1), 0.015 * ((i % 4) - 1.5), 0.08 + 0.01 * (i % 5))
        rpy = {0: "0 0 0", 1: f"{math.pi / 2!r} 0 0", 2: "0 0 0", 3: f"0 0 {-math.pi / 3!r}"}[i % 4]
        lines += [
            f'  <joint name="j{i}" type="revolute">',
            f'    <parent link="{parent}"/>',
            f'    <child link="l{i}"/>',
            f'    <origin xyz="{xyz[0]:.6g} {xyz[1]:.6g} {xyz[2]:.6g}" rpy="{rpy}"/>',
            f'    <axis xyz="{axes[i % 3]}"/>',
            '    <limit lower="-3.14" upper="3.14" effort="100" velocity="3"/>',
            "  </joint>",
        ]
    lines.append("</robot>")
    with open(out, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(int(sys.argv[1]), sys.argv[2])
