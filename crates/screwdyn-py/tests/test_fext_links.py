"""External wrenches on any link, links attached by a fixed joint included (the UR5 URDF's
``tool0`` hangs from the last moving link by fixed joints, with an offset)."""

import pathlib

import numpy as np
import pytest

import screwdyn

ROOT = pathlib.Path(__file__).resolve().parents[3]
W = np.array([0.3, -0.2, 0.5, 4.0, -1.0, 2.5])
Q = np.array([0.3, -1.1, 0.8, -0.4, 1.2, 0.6])


@pytest.fixture(scope="module")
def ur5():
    return screwdyn.load(ROOT / "models" / "ur5.urdf")


def test_a_wrench_on_a_fixed_joint_link_is_minus_its_jacobian_transpose(ur5):
    zero = np.zeros(6)
    assert "tool0" not in ur5.link_names  # merged into wrist_3_link
    g = ur5.rnea(Q, zero, zero)
    # Statics: τ = g − J_fᵀ W^{f} (the tool's body Jacobian, LOCAL) and τ = g − J^{0,0ᵀ} W^{0}.
    tau = ur5.rnea(Q, zero, zero, fext={"tool0": W})
    np.testing.assert_allclose(tau, g - ur5.frame_jacobian(Q, "tool0", "local").T @ W, atol=1e-10)
    tau_world = ur5.rnea(Q, zero, zero, fext_world={"tool0": W})
    np.testing.assert_allclose(tau_world, g - ur5.frame_jacobian(Q, "tool0", "world").T @ W, atol=1e-10)


def test_a_wrench_on_a_fixed_joint_link_equals_it_moved_to_the_parent(ur5):
    # W^{b} = Ad_{H_b^f}ᵀ W^{f}, with H_b^f from the two frame poses; Ad built here from R, p.
    body = ur5.link_names[-1]  # the moving link tool0 is merged into
    pose_b = ur5.frame_pose(Q, body)
    pose_f = ur5.frame_pose(Q, "tool0")
    h_bf = np.linalg.inv(pose_f) @ pose_b  # pose of the body frame in the tool frame
    assert np.linalg.norm(h_bf[:3, 3]) > 0.05  # a real offset: the move is not the identity
    r, p = h_bf[:3, :3], h_bf[:3, 3]
    hat = np.array([[0, -p[2], p[1]], [p[2], 0, -p[0]], [-p[1], p[0], 0]])
    ad = np.block([[r, np.zeros((3, 3))], [hat @ r, r]])
    moved = ad.T @ W
    v, a = np.full(6, 0.2), np.linspace(-1, 1, 6)
    np.testing.assert_allclose(
        ur5.rnea(Q, v, a, fext={"tool0": W}),
        ur5.rnea(Q, v, a, fext={body: moved}),
        atol=1e-10,
    )
    np.testing.assert_allclose(
        ur5.aba(Q, v, np.ones(6), fext={"tool0": W}),
        ur5.aba(Q, v, np.ones(6), fext={body: moved}),
        atol=1e-9,
    )
    # A simulation disturbance takes the same links.
    runs = [
        ur5.simulate(Q, np.zeros(6), duration=0.02, dt=0.01,
                     disturbances=[screwdyn.Disturbance(link, w)])
        for link, w in (("tool0", W), (body, moved))
    ]
    np.testing.assert_allclose(runs[0].q, runs[1].q, atol=1e-12)


def test_wrench_links_that_cannot_carry_one(ur5):
    with pytest.raises(ValueError, match="fixed to the base"):
        ur5.rnea(Q, fext={"base_link": W})
    with pytest.raises(ValueError, match="the model has no link named 'hand'"):
        ur5.rnea(Q, fext={"hand": W})
