"""Errors are Python exceptions with the library's one-sentence messages; no panic crosses."""

import numpy as np
import pytest

import screwdyn


@pytest.fixture(scope="module")
def arm():
    return screwdyn.load("builtin:planar2")


def test_bad_shapes_and_values(arm):
    with pytest.raises(ValueError, match=r"^q has 3 values, the model has 2 joints: joint1, joint2$"):
        arm.rnea([1, 2, 3], [0, 0], [0, 0])
    with pytest.raises(ValueError, match=r"^v has 1 values, the model has 2 joints"):
        arm.rnea([1, 2], [0], [0, 0])
    with pytest.raises(ValueError, match=r"q has shape \(4, 3\), expected \(N, 2\)"):
        arm.crba(np.zeros((4, 3)))
    with pytest.raises(ValueError, match=r"q has shape \(2, 2, 2\), expected \(2,\) for one state or \(N, 2\)"):
        arm.crba(np.zeros((2, 2, 2)))
    with pytest.raises(ValueError, match=r"^q contains a non-finite value \(NaN\) at position 1$"):
        arm.gravity_torque([0.0, np.nan])
    with pytest.raises(ValueError, match=r"^state 2: q contains a non-finite value"):
        arm.gravity_torque([[0, 0], [0, 0], [np.inf, 0]])
    with pytest.raises(ValueError, match=r"v has 2 states but q has 3"):
        arm.nonlinear_effects(np.zeros((3, 2)), np.zeros((2, 2)))
    with pytest.raises(ValueError, match="unknown reference 'space'"):
        arm.frame_jacobian([0, 0], "link2", "space")
    with pytest.raises(ValueError, match="unknown forward-dynamics method 'lu'"):
        arm.forward_dynamics([0, 0], [0, 0], [0, 0], method="lu")
    with pytest.raises(ValueError, match="the model has no frame named 'tip'"):
        arm.frame_pose([0, 0], "tip")
    with pytest.raises(ValueError, match="frame index 7 is out of range"):
        arm.frame_pose([0, 0], 7)
    with pytest.raises(ValueError, match="the model has no link named 'link9'"):
        arm.rnea([0, 0], fext={"link9": np.zeros(6)})
    with pytest.raises(ValueError, match=r"a wrench of fext has shape \(5,\), expected \(6,\)"):
        arm.rnea([0, 0], fext={"link2": np.zeros(5)})
    with pytest.raises(ValueError, match="closed_form takes one state"):
        arm.closed_form(np.zeros((3, 2)))
    with pytest.raises(ValueError, match="threads must be a positive"):
        arm.rnea(np.zeros((3, 2)), threads=0)
    with pytest.raises(ValueError, match="gravity contains a non-finite value"):
        arm.gravity = [0, np.nan, 0]
    with pytest.raises(ValueError, match="could not convert string to float"):
        arm.rnea("not numbers")


def test_model_properties_are_read_only(arm):
    # properties are copies: writing into one would change nothing, so NumPy refuses it
    with pytest.raises(ValueError, match="read-only"):
        arm.gravity[1] = 0.0
    with pytest.raises(ValueError, match="read-only"):
        arm.effort_limits[0] = 1.0
    np.testing.assert_array_equal(arm.gravity, [0, -9.81, 0])


def test_singular_mass_matrix_names_the_joint():
    text = """
format = "dh"
[[row]]
type = "R"
a = 1.0
mass = 0.0
"""
    m = screwdyn.load_string(text, "toml")
    assert m.physical_problems  # a massless moving leaf is a finding, not a load error
    with pytest.raises(screwdyn.ModelError, match="mass"):
        screwdyn.load_string(text, "toml", strict=True)
    with pytest.raises(ValueError, match="joint"):
        m.forward_dynamics([0.0], [0.0], [1.0], method="crba")


def test_loading_errors(tmp_path):
    with pytest.raises(FileNotFoundError, match="nothing.urdf: cannot be read"):
        screwdyn.load(tmp_path / "nothing.urdf")
    bad = tmp_path / "bad.urdf"
    bad.write_text('<robot name="r">\n  <link name="a"/>\n  <joint name="j" type="revolute">\n'
                   '    <parent link="a"/>\n  </joint>\n</robot>\n')
    with pytest.raises(screwdyn.ModelError, match=r"bad.urdf:3"):
        screwdyn.load(str(bad))
    assert issubclass(screwdyn.ModelError, ValueError)
    with pytest.raises(screwdyn.ModelError, match=r"^arm.toml:2:"):
        screwdyn.load_string('format = "dh"\nrows = 3\n', "toml", name="arm")
    with pytest.raises(screwdyn.ModelError, match="unknown model format"):
        screwdyn.load("robot.xyz")
    with pytest.raises(screwdyn.ModelError, match="planar2"):
        screwdyn.load("builtin:nope")
    with pytest.raises(ValueError, match="unknown format 'yaml'"):
        screwdyn.load_string("x", "yaml")


def test_a_rust_panic_becomes_runtime_error():
    with pytest.raises(RuntimeError, match="internal error in screwdyn.*deliberate panic"):
        screwdyn._screwdyn._panic_for_tests()
    # also from a rayon worker thread with the GIL released
    with pytest.raises(RuntimeError, match="deliberate panic in a worker thread"):
        screwdyn._screwdyn._panic_in_batch_for_tests()
    # and the module still works afterwards
    assert screwdyn.load("builtin:pendulum").nq == 1


def test_results_that_overflow_are_errors_not_nan():
    # Finite inputs too large for double precision: the library's rule (the CLI's too) says
    # the NaN or inf they produce is an error naming the entry, and the state in a batch.
    ur5 = screwdyn.load("builtin:ur5")
    z = np.zeros(6)
    with pytest.raises(ValueError, match=r"the result \(entry \d\) is not finite"):
        ur5.rnea(z, np.full(6, 1e200), z)
    with pytest.raises(ValueError, match="too large for double precision"):
        ur5.forward_dynamics(z, z, np.full(6, 1e308))
    v = np.zeros((3, 6))
    v[1] = 1e200
    with pytest.raises(ValueError, match=r"^state 1: the result \(entry \d\) is not finite"):
        ur5.rnea(np.zeros((3, 6)), v, np.zeros((3, 6)))
    # large but representable results are returned
    assert np.isfinite(ur5.rnea(z, np.full(6, 1e100), z)).all()


def test_pinocchio_reference_names_and_messages_quote_the_input():
    ur5 = screwdyn.load("builtin:ur5")
    q = np.zeros(6)
    np.testing.assert_array_equal(ur5.frame_jacobian(q, "tool0", "LOCAL_WORLD_ALIGNED"),
                                  ur5.frame_jacobian(q, "tool0", "world-aligned"))
    np.testing.assert_array_equal(ur5.frame_jacobian(q, "tool0", "WORLD"),
                                  ur5.frame_jacobian(q, "tool0", "world"))
    with pytest.raises(ValueError, match="'LOCAL_WORLD'"):
        ur5.frame_jacobian(q, "tool0", "LOCAL_WORLD")
