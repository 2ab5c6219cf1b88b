#!/usr/bin/env python3
"""Writes models/ur5.toml (standard DH) and models/ur5.urdf from the UR5's published numbers.

Sources (facts, not files): Universal Robots, "DH parameters for calculations of kinematics and
dynamics" (UR5: d1 = 0.089159, a2 = -0.425, a3 = -0.39225, d4 = 0.10915, d5 = 0.09465,
d6 = 0.0823, alpha = [pi/2, 0, 0, pi/2, -pi/2, 0]; masses 3.7, 8.393, 2.33, 1.219, 1.219,
0.1879 kg; centres of mass in the DH link frames, the com values).
UR does not publish the rotational inertias: they are APPROXIMATED here as solid cylinders
(radius r, length L, axis noted beside each inertia; I_axis = m r^2 / 2,
I_perp = m (3 r^2 + L^2) / 12) about the published CoM. Joint limits: +-2 pi, 3.15 rad/s,
150 N m (joints 1-3) and 28 N m (joints 4-6), from the UR5 datasheet.
Run from models/: python3 scripts/ur5.py
"""
import math

PI = math.pi
NAMES = ["shoulder_pan", "shoulder_lift", "elbow", "wrist_1", "wrist_2", "wrist_3"]
LINKS = ["shoulder_link", "upper_arm_link", "forearm_link", "wrist_1_link", "wrist_2_link", "wrist_3_link"]
A = [0.0, -0.425, -0.39225, 0.0, 0.0, 0.0]
D = [0.089159, 0.0, 0.0, 0.10915, 0.09465, 0.0823]
ALPHA = [PI / 2, 0.0, 0.0, PI / 2, -PI / 2, 0.0]
MASS = [3.7, 8.393, 2.33, 1.219, 1.219, 0.1879]
COM = [[0.0, -0.02561, 0.00193], [0.2125, 0.0, 0.11336], [0.15, 0.0, 0.0265],
       [0.0, -0.0018, 0.01634], [0.0, 0.0018, 0.01634], [0.0, 0.0, -0.001159]]
# (radius, length, axis) of the cylinder approximating each link, axis in the DH link frame.
CYL = [(0.06, 0.15, "y"), (0.06, 0.425, "x"), (0.05, 0.39225, "x"),
       (0.04, 0.12, "z"), (0.04, 0.12, "z"), (0.0375, 0.0345, "z")]
EFFORT = [150.0, 150.0, 150.0, 28.0, 28.0, 28.0]


def cylinder(m, r, length, axis):
    a, p = m * r * r / 2, m * (3 * r * r + length * length) / 12
    d = {"x": (a, p, p), "y": (p, a, p), "z": (p, p, a)}[axis]
    return [d[0], 0.0, 0.0, d[1], 0.0, d[2]]  # ixx ixy ixz iyy iyz izz


def f(x):
    return repr(float(x) + 0.0)


def v(xs):
    return "[" + ", ".join(f(x) for x in xs) + "]"


INERTIA = [cylinder(MASS[i], *CYL[i]) for i in range(6)]
HEAD = __doc__.strip().splitlines()
toml = ["# UR5 as a standard DH table (docs/formats.md, "DH tables"), written by models/scripts/ur5.py."]
toml += ["# " + line if line else "#" for line in HEAD[1:-1]]
toml += ['format = "dh"', 'name = "ur5"', 'base = "base_link"', ""]
for i in range(6):
    toml += ["[[row]]", 'name = "%s_joint"' % NAMES[i], 'link = "%s"' % LINKS[i], 'type = "R"',
             "a = %s" % f(A[i]), "alpha = %s" % f(ALPHA[i]), "d = %s" % f(D[i]), "theta = 0.0",
             "limits = { lower = %s, upper = %s, velocity = 3.15, effort = %s }" % (f(-2 * PI), f(2 * PI), f(EFFORT[i])),
             "mass = %s" % f(MASS[i]), "com = %s" % v(COM[i]),
             "inertia = %s  # cylinder r = %s, L = %s along %s" % (v(INERTIA[i]), CYL[i][0], CYL[i][1], CYL[i][2]), ""]
toml += ["[[frame]]", 'name = "tool0"', 'link = "wrist_3_link"', ""]
open("ur5.toml", "w").write("\n".join(toml))

# URDF: link LINKS[i] is the body joint i turns, its frame on joint i's axis: the DH frame
# {i-1} turned by q_i (a URDF joint turns its child about an axis through the child's origin,
# so the child cannot sit at the DH frame {i}, which is a_i away from that axis). The DH frame
# {i} follows at D_i = Trans_z(d) Trans_x(a) Rot_x(alpha): the next joint's origin, and the
# frame the centre of mass and the inertia axes are given in (<inertial> origin D_i com, rpy
# alpha 0 0). Link, joint and frame names are those of the published UR5 URDF (Universal
# Robots' ur_description, as in example-robot-data).
def rot_x(alpha, c):
    ca, sa = math.cos(alpha), math.sin(alpha)
    return [c[0], ca * c[1] - sa * c[2], sa * c[1] + ca * c[2]]


def dh_origin(i):
    return '<origin xyz="%s 0 %s" rpy="%s 0 0"/>' % (f(A[i]), f(D[i]), f(ALPHA[i]))


u = ['<?xml version="1.0"?>', "<!-- UR5 written by models/scripts/ur5.py from Universal Robots' published DH",
     "     parameters, masses and centres of mass; rotational inertias approximated as solid",
     "     cylinders (see the script). Not derived from any third-party URDF file. -->",
     '<robot name="ur5">', '  <link name="base_link"/>']
for i in range(6):
    it = INERTIA[i]
    c = rot_x(ALPHA[i], COM[i])
    com = [c[0] + A[i], c[1], c[2] + D[i]]
    u += ['  <link name="%s">' % LINKS[i],
          '    <inertial>',
          '      <origin xyz="%s" rpy="%s 0 0"/>' % (" ".join(f(x) for x in com), f(ALPHA[i])),
          '      <mass value="%s"/>' % f(MASS[i]),
          '      <inertia ixx="%s" ixy="0" ixz="0" iyy="%s" iyz="0" izz="%s"/>' % (f(it[0]), f(it[3]), f(it[5])),
          '    </inertial>', '  </link>']
u += ['  <link name="tool0"/>']
for i in range(6):
    parent = "base_link" if i == 0 else LINKS[i - 1]
    origin = '<origin xyz="0 0 0" rpy="0 0 0"/>' if i == 0 else dh_origin(i - 1)
    u += ['  <joint name="%s_joint" type="revolute">' % NAMES[i],
          '    <parent link="%s"/>' % parent, '    <child link="%s"/>' % LINKS[i],
          '    ' + origin, '    <axis xyz="0 0 1"/>',
          '    <limit lower="%s" upper="%s" effort="%s" velocity="3.15"/>' % (f(-2 * PI), f(2 * PI), f(EFFORT[i])),
          '  </joint>']
u += ['  <joint name="wrist_3_link-tool0_fixed_joint" type="fixed">', '    <parent link="wrist_3_link"/>',
      '    <child link="tool0"/>', '    ' + dh_origin(5), '  </joint>', "</robot>", ""]
open("ur5.urdf", "w").write("\n".join(u))
