"""Frames by name or by index everywhere a frame is taken; frame_id, frame_name, joint_id."""

import pathlib

import numpy as np
import pytest

import screwdyn
import screwdyn.symbolic

ROOT = pathlib.Path(__file__).resolve().parents[3]
Q = np.array([0.3, -1.1, 0.8, -0.4, 1.2, 0.6])
V = np.linspace(-0.5, 0.5, 6)


@pytest.fixture(scope="module")
def ur5():
    return screwdyn.load(ROOT / "models" / "ur5.urdf")


def test_frame_id_and_frame_name_follow_frame_names(ur5):
    for i, name in enumerate(ur5.frame_names):
        assert ur5.frame_id(name) == i and ur5.frame_name(i) == name
        assert ur5.frame_id(np.int64(i)) == i
    for i, name in enumerate(ur5.joint_names):
        assert ur5.joint_id(name) == i
    with pytest.raises(ValueError, match="the model has no frame named 'hand'"):
        ur5.frame_id("hand")
    n = len(ur5.frame_names)
    with pytest.raises(ValueError, match=f"frame index {n} is out of range"):
        ur5.frame_name(n)
    with pytest.raises(TypeError, match=r"a frame is given by its name \(str\) or its index \(int\)"):
        ur5.frame_id(1.5)


@pytest.mark.parametrize("call", [
    lambda m, f: m.frame_pose(Q, f),
    lambda m, f: m.frame_jacobian(Q, f, "LOCAL"),
    lambda m, f: m.frame_twist(Q, V, f, "world"),
    lambda m, f: m.frame_acceleration(Q, V, V, f, "local"),
    lambda m, f: m.frame_jdot_qdot(Q, V, f, "LOCAL_WORLD_ALIGNED"),
    lambda m, f: m.rnea(Q, V, V, tip_wrenches={f: np.arange(6.0)}),
    lambda m, f: m.simulate(Q, duration=0.002, dt=0.001, frames=[f]).poses,
], ids=["frame_pose", "frame_jacobian", "frame_twist", "frame_acceleration", "frame_jdot_qdot",
        "tip_wrenches", "simulate_frames"])
def test_every_frame_argument_takes_a_name_or_an_index(ur5, call):
    index = ur5.frame_names.index("tool0")
    by_name, by_index = call(ur5, "tool0"), call(ur5, index)
    if isinstance(by_name, dict):
        assert list(by_name) == list(by_index) == ["tool0"]
        by_name, by_index = by_name["tool0"], by_index["tool0"]
    np.testing.assert_array_equal(by_name, by_index)


def test_links_by_name_or_index(ur5):
    body = ur5.link_names[-1]
    k = len(ur5.link_names) - 1
    np.testing.assert_array_equal(ur5.link_jacobian(Q, body), ur5.link_jacobian(Q, k))
    w = {body: np.arange(6.0)}
    np.testing.assert_array_equal(ur5.rnea(Q, fext=w), ur5.rnea(Q, fext={k: np.arange(6.0)}))


def test_symbolic_frames_by_name_or_index():
    pytest.importorskip("sympy")
    arm = screwdyn.load("builtin:planar2")
    k = arm.frame_names.index("link1")
    by_index = screwdyn.symbolic.forward_kinematics(arm, frame=k)
    assert by_index == screwdyn.symbolic.forward_kinematics(arm, frame="link1")
    assert by_index != screwdyn.symbolic.forward_kinematics(arm)  # the default: the last body
