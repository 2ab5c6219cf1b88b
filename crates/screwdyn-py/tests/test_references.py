"""Pinocchio's reference names WORLD, LOCAL and LOCAL_WORLD_ALIGNED are accepted wherever a
reference is taken, and mean what the table of docs/from-pinocchio.md says."""

import numpy as np
import pytest

import screwdyn
import screwdyn.symbolic
from screwdyn import se3

Q = np.array([0.3, -1.1, 0.8, -0.4, 1.2, 0.6])
V = np.linspace(-0.5, 0.5, 6)
OURS = {"WORLD": "world", "LOCAL": "local", "LOCAL_WORLD_ALIGNED": "world-aligned"}


@pytest.fixture(scope="module")
def ur5():
    return screwdyn.load("builtin:ur5")


@pytest.mark.parametrize("call", [
    lambda m, r: m.frame_jacobian(Q, "tool0", r),
    lambda m, r: m.frame_twist(Q, V, "tool0", r),
    lambda m, r: m.frame_acceleration(Q, V, V, "tool0", r),
    lambda m, r: m.frame_jdot_qdot(Q, V, "tool0", r),
    lambda m, r: screwdyn.frame_jacobian(m, Q, "tool0", r),
], ids=["frame_jacobian", "frame_twist", "frame_acceleration", "frame_jdot_qdot", "function"])
@pytest.mark.parametrize("pinocchio", list(OURS))
def test_pinocchio_names_are_ours(ur5, call, pinocchio):
    np.testing.assert_array_equal(call(ur5, pinocchio), call(ur5, OURS[pinocchio]))


def test_the_three_jacobians_are_related_by_the_frame_pose(ur5):
    H = ur5.frame_pose(Q, "tool0")
    local = ur5.frame_jacobian(Q, "tool0", "LOCAL")  # body Jacobian J_f^{f,0}
    world = ur5.frame_jacobian(Q, "tool0", "WORLD")  # space Jacobian J^{0,0}
    aligned = ur5.frame_jacobian(Q, "tool0", "LOCAL_WORLD_ALIGNED")
    np.testing.assert_allclose(world, se3.Ad(H) @ local, atol=1e-12)
    R = np.kron(np.eye(2), H[:3, :3])  # the body twist's halves rotated into base axes
    np.testing.assert_allclose(aligned, R @ local, atol=1e-12)
    # LOCAL_WORLD_ALIGNED: ω and the velocity of the frame origin, by finite differences.
    h = 1e-6
    Hp, Hm = ur5.frame_pose(Q + h * V, "tool0"), ur5.frame_pose(Q - h * V, "tool0")
    np.testing.assert_allclose((aligned @ V)[3:], (Hp[:3, 3] - Hm[:3, 3]) / (2 * h), atol=1e-8)


def test_the_symbolic_jacobian_takes_them_too():
    pytest.importorskip("sympy")
    arm = screwdyn.load("builtin:planar2")
    for pin, ours in OURS.items():
        assert screwdyn.symbolic.jacobian(arm, reference=pin) == \
            screwdyn.symbolic.jacobian(arm, reference=ours)


def test_an_unknown_reference_names_the_choices(ur5):
    with pytest.raises(ValueError, match="world, local, world-aligned, WORLD, LOCAL or LOCAL_WORLD_ALIGNED"):
        ur5.frame_jacobian(Q, "tool0", "GLOBAL")
