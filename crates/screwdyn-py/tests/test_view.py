"""Model.view: the page of `screwdyn view` (the view library's render_html) from Python. The DOM
text is checked as the Rust/CLI tests check it (joint list, run duration); a SimResult run and
the same run written to CSV by the library's writer embed the same data; bad input raises."""

import base64
import html
import json
import re

import numpy as np
import pytest

import screwdyn


def page_data(page: str):
    """The JSON the page embeds for its script (`<script id="data">`)."""
    m = re.search(r'<script id="data" type="application/json">(.*?)</script>', page, re.S)
    assert m, "the page has no data block"
    return json.loads(m.group(1).replace("<\\/", "</"))


def joints_in_dom(page: str):
    return re.findall(r'<li data-joint="\d+">([^<]*)</li>', page)


def duration_in_dom(page: str):
    return re.search(r'<span id="duration">([^<]*)</span>', page).group(1)


@pytest.fixture(scope="module")
def arm():
    return screwdyn.load("builtin:planar2")


@pytest.fixture(scope="module")
def run(arm):
    # 0.5 s of the arm falling from rest, recorded every 1 ms: 501 samples.
    return arm.simulate([0.3, -0.2], duration=0.5, dt=1e-3)


def test_page_lists_joints_and_shows_a_configuration(arm):
    v = arm.view(q=[0.3, 0.5])
    assert v.html.startswith("<!DOCTYPE html>")
    assert joints_in_dom(v.html) == arm.joint_names
    assert duration_in_dom(v.html) == ""  # no run
    data = page_data(v.html)
    assert data["joints"] == arm.joint_names and data["q0"] == [0.3, 0.5]
    assert data["run"] is None and v.samples == 0
    assert v.warnings == [] and v.triangles > 0
    # The UR5 (a DH model: skeleton) lists its six joints in order.
    ur5 = screwdyn.load("builtin:ur5")
    assert joints_in_dom(ur5.view().html) == ur5.joint_names


def test_sim_result_and_its_csv_embed_the_same_run(arm, run, tmp_path):
    assert len(run) == 501
    from_result = arm.view(run=run)
    path = tmp_path / "run.csv"
    run.save(path)
    header = path.read_text().splitlines()[0]
    assert header.startswith("t,q.joint1,q.joint2,v.joint1")  # the CLI's columns
    from_csv = arm.view(run=path)
    from_str = arm.view(run=str(path))
    a, b = page_data(from_result.html)["run"], page_data(from_csv.html)["run"]
    assert a is not None and a == b
    assert from_csv.html == from_str.html
    # The run's duration in the DOM (rounded to µs as the library prints it), 0.5 s.
    assert duration_in_dom(from_result.html) == "0.5"
    assert float(duration_in_dom(from_result.html)) == pytest.approx(run.t[-1] - run.t[0])
    # 501 samples, strided to the default cap of 1000: all kept; a cap of 11 keeps 11.
    assert from_result.samples == 501
    assert arm.view(run=run, max_samples=11).samples == 11
    # JSON written by the library reads back to the same run as well.
    jpath = tmp_path / "run.json"
    run.save(jpath)
    assert page_data(arm.view(run=jpath).html)["run"] == a


def test_torque_profile_run(arm):
    traj = screwdyn.Quintic([0, 0], [1.0, -0.5], 2.0)
    prof = arm.torque_profile(traj, dt=0.01)
    v = arm.view(run=prof)
    assert duration_in_dom(v.html) == "2"
    assert v.samples == len(prof.samples)


def test_notebook_display_and_save(arm, tmp_path):
    v = arm.view(q=[0.1, 0.2], title='arm "A" & <b>', height=400)
    out = v._repr_html_()
    assert out.startswith("<iframe srcdoc=\"") and out.endswith("</iframe>")
    srcdoc = re.match(r'<iframe srcdoc="([^"]*)"', out).group(1)
    # Escaped so that no quote ends the attribute, and unescaping gives the page back exactly.
    assert '"' not in srcdoc and "<" not in srcdoc
    assert html.unescape(srcdoc) == v.html
    assert "height: 400px" in out and "width: 100%" in out
    assert "arm &quot;A&quot; &amp; &lt;b&gt;" in v.html  # the title escaped in the page
    path = tmp_path / "robot.html"
    v.save(path)
    assert path.read_text(encoding="utf-8") == v.html
    assert [p.name for p in tmp_path.iterdir()] == ["robot.html"]  # no temporary file left
    assert "View(" in repr(v)
    with pytest.raises(OSError):
        v.save(tmp_path / "no-such-dir" / "robot.html")


def test_urdf_visuals_and_missing_mesh_warning(tmp_path):
    urdf = tmp_path / "bot.urdf"
    urdf.write_text("""<robot name="bot">
      <link name="base"><visual><geometry><box size="0.2 0.2 0.1"/></geometry></visual></link>
      <link name="arm">
        <visual><geometry><mesh filename="meshes/missing.stl"/></geometry></visual>
        <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
      </link>
      <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
        <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="5" velocity="1"/></joint>
    </robot>""")
    m = screwdyn.load(urdf)
    v = m.view()
    assert joints_in_dom(v.html) == ["shoulder"]
    # The missing mesh is a warning (and a stand-in box), not a failure.
    assert v.warning_kinds == ["mesh-missing"]
    assert "missing.stl" in v.warnings[0]


def test_bad_input(arm, run, tmp_path):
    with pytest.raises(ValueError, match="q has 3 values"):
        arm.view(q=[0, 0, 0])
    with pytest.raises(ValueError, match="not a finite number|NaN|finite"):
        arm.view(q=[0, np.nan])
    with pytest.raises(ValueError, match="q cannot be combined with run"):
        arm.view(q=[0, 0], run=run)
    ur5 = screwdyn.load("builtin:ur5")
    with pytest.raises(ValueError, match="are not the model's"):
        ur5.view(run=run)
    path = tmp_path / "run.csv"
    run.save(path)
    with pytest.raises(ValueError, match="q.shoulder_pan_joint|shoulder_pan_joint"):
        ur5.view(run=path)
    bad = tmp_path / "bad.csv"
    bad.write_text("t,q.joint1,q.joint2\n0,0,0\n0.1,nan,0\n")
    with pytest.raises(ValueError, match="not a finite number"):
        arm.view(run=bad)
    with pytest.raises(FileNotFoundError):
        arm.view(run=tmp_path / "none.csv")
    with pytest.raises(ValueError, match=r"\.csv or \.json"):
        run.save(tmp_path / "run.txt")
    with pytest.raises(TypeError):
        arm.view(run=42)
    with pytest.raises(ValueError, match="triangle cap"):
        arm.view(max_triangles=0)


def test_mjcf_model_draws_its_visual_geoms_in_their_colours(tmp_path):
    # Two visual geoms (a box of half-sizes 0.1 0.2 0.3 in its material's red, a sphere in its
    # own rgba) and a collision capsule in group 3, which MuJoCo's viewer hides by default.
    xml = tmp_path / "two.xml"
    xml.write_text(
        """<mujoco model="two"><asset><material name="red" rgba="1 0 0 1"/></asset>
  <worldbody><body name="b"><joint name="j" axis="0 0 1"/>
    <geom type="box" size="0.1 0.2 0.3" material="red"/>
    <geom type="sphere" size="0.05" pos="0 0 0.5" rgba="0 0 1 0.5"/>
    <geom type="capsule" size="0.2 0.4" group="3"/>
  </body></worldbody></mujoco>"""
    )
    d = page_data(screwdyn.load(str(xml)).view().html)
    robot = [p for p in d["parts"] if p["g"] == "robot"]
    assert [p["c"] for p in robot] == [[1.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 0.5]]
    # The box's corners in its body frame: ±(0.1, 0.2, 0.3).
    box = np.frombuffer(base64.b64decode(d["meshes"][robot[0]["m"]]["p"]), "<f4")
    t = np.array(robot[0]["t"]).reshape(3, 4)
    placed = box.reshape(-1, 3) @ t[:, :3].T + t[:, 3]
    np.testing.assert_allclose(placed.max(axis=0), [0.1, 0.2, 0.3], rtol=1e-6)
    np.testing.assert_allclose(placed.min(axis=0), [-0.1, -0.2, -0.3], rtol=1e-6)
