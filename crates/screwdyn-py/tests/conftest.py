"""Shared helpers: the Pinocchio fixtures of the Rust tests, rebuilt through a library path.

The fixtures (crates/screwdyn/tests/fixtures/pinocchio/*.json, written by
scripts/gen_reference.py) give each robot as joints with H_c^p(0), the screw axis in the child
frame and the inertia; that is exactly the native TOML format (format = "screwdyn"), so the
tests write that TOML and load it with screwdyn.load_string, as the Rust tests rebuild the
robots with ModelBuilder.
"""

import json
import pathlib

import numpy as np
import pytest

import screwdyn

ROOT = pathlib.Path(__file__).resolve().parents[3]
FIXTURES = ROOT / "crates" / "screwdyn" / "tests" / "fixtures" / "pinocchio"
ROBOTS = ["ur5", "panda", "tree"]
BASE = "universe"


def _arr(x):
    return "[" + ", ".join(repr(float(v)) for v in x) + "]"


def _pose(p):
    rows = ", ".join(_arr(r) for r in p["rotation"])
    return f"{{ xyz = {_arr(p['translation'])}, rotation = [{rows}] }}"


def _limit(x):
    x = float(x)
    if np.isinf(x):
        return "inf" if x > 0 else "-inf"
    return repr(x)


def fixture_toml(fx):
    """The fixture's robot in the native TOML format."""
    out = ['format = "screwdyn"', f'name = "{fx["robot"]}"', f'base = "{BASE}"',
           f"gravity = {_arr(fx['gravity'])}"]
    joints = fx["joints"]
    link_of = lambda j: BASE if j is None else joints[j]["body_name"]
    for j in joints:
        ax = j["axis"]
        screw = list(ax) + [0, 0, 0] if j["type"] == "revolute" else [0, 0, 0] + list(ax)
        i = j["inertia"]
        ic = i["inertia_com"]
        lim = j["limits"]
        out += [
            "[[body]]",
            f'name = "{j["body_name"]}"',
            f'parent = "{link_of(j["parent"])}"',
            f'joint = "{j["name"]}"',
            f'type = "{j["type"]}"',
            f"home = {_pose(j['placement'])}",
            f"screw_in_child = {_arr(screw)}",
            f"limits = {{ lower = {_limit(lim['lower'])}, upper = {_limit(lim['upper'])}, "
            f"velocity = {_limit(lim['velocity'])}, effort = {_limit(lim['effort'])} }}",
            f"mass = {float(i['mass'])!r}",
            f"com = {_arr(i['com'])}",
            f"inertia = {_arr([ic[0][0], ic[0][1], ic[0][2], ic[1][1], ic[1][2], ic[2][2]])}",
        ]
    bodies = {j["body_name"] for j in joints}
    for f in fx["frames"]:
        if f["name"] in bodies:
            continue
        out += ["[[frame]]", f'name = "{f["name"]}"', f'link = "{link_of(f["joint"])}"',
                f"pose = {_pose(f['placement'])}"]
    return "\n".join(out) + "\n"


def read_fixture(name):
    return json.loads((FIXTURES / f"{name}.json").read_text())


def fixture_model(name):
    fx = read_fixture(name)
    return screwdyn.load_string(fixture_toml(fx), "toml", name=f"{name}-fixture"), fx


@pytest.fixture(params=ROBOTS)
def robot(request):
    return fixture_model(request.param)


def stack(fx, key):
    return np.array([s[key] for s in fx["states"]], dtype=float)
