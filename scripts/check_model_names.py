#!/usr/bin/env python3
"""Checks that the shipped robots use the link and joint names of the published URDFs.

Usage, from the repository root, with the `example-robot-data` package installed in the
Python that runs it (`pip install example-robot-data`, about 400 MB with its meshes):

    python3 scripts/check_model_names.py                    # builds the CLI with cargo
    python3 scripts/check_model_names.py --screwdyn PATH    # or uses this screwdyn program

For each robot below, the names screwdyn reports (`screwdyn info MODEL --format json`: moving
joints, links, frames) for `builtin:<name>` and for every file of `models/` describing it are
compared with the `<joint>` and `<link>` names of the published URDF:

* the moving joints are the published URDF's revolute and prismatic joints of the arm
  (the Panda's finger joints are left out: the shipped Panda is the arm alone);
* every link and frame name of the shipped models is a `<link>` of the published URDF;
* the builtin and the files in `models/` have the same names.

Exits with status 1 and one line per difference; 0 (with a note) when example-robot-data is
not installed, so that it can run anywhere. CI does not install the package.
"""

import argparse
import importlib.metadata
import json
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PREFIX = "share/example-robot-data/robots/"

# builtin name -> (published URDF in example-robot-data, model files in models/, joint names
# of the published URDF that the shipped model leaves out)
ROBOTS = {
    "ur5": ("ur_description/urdf/ur5_robot.urdf", ["ur5.toml", "ur5.urdf"], set()),
    "panda": (
        "panda_description/urdf/panda.urdf",
        ["panda.toml"],
        {"panda_finger_joint1", "panda_finger_joint2"},
    ),
}


def published(relative):
    """(moving joint names, link names) of a URDF of the installed example-robot-data."""
    dist = importlib.metadata.distribution("example-robot-data")
    for f in dist.files or []:
        if str(f).endswith(PREFIX + relative):
            root = ET.parse(str(f.locate())).getroot()
            joints = [
                j.get("name")
                for j in root.iter("joint")
                if j.get("type") in ("revolute", "continuous", "prismatic")
            ]
            links = [link.get("name") for link in root.iter("link")]
            return joints, links
    raise SystemExit(f"{relative} is not in example-robot-data {dist.version}")


def ours(exe, model):
    """(moving joint names, link names, frame names) screwdyn reports for `model`."""
    out = subprocess.run(
        [exe, "info", model, "--format", "json"],
        check=True,
        capture_output=True,
        text=True,
    ).stdout
    info = json.loads(out)
    joints = [j["name"] for j in info["joints"]]
    links = [b["name"] for b in info["bodies"]]
    frames = [f["name"] if isinstance(f, dict) else f for f in info["frames"]]
    return joints, links, frames


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--screwdyn", help="the screwdyn program (default: build it with cargo)")
    args = ap.parse_args()
    try:
        version = importlib.metadata.version("example-robot-data")
    except importlib.metadata.PackageNotFoundError:
        print("example-robot-data is not installed: nothing to compare (pip install example-robot-data)")
        return 0
    exe = args.screwdyn
    if exe is None:
        subprocess.check_call(["cargo", "build", "-q", "-p", "screwdyn-cli"], cwd=ROOT)
        target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
        exe = os.path.join(target, "debug", "screwdyn")
    problems = []
    for name, (urdf, files, left_out) in ROBOTS.items():
        pub_joints, pub_links = published(urdf)
        want_joints = [j for j in pub_joints if j not in left_out]
        models = [f"builtin:{name}"] + [os.path.join(ROOT, "models", f) for f in files]
        first = None
        for model in models:
            joints, links, frames = ours(exe, model)
            label = os.path.relpath(model, ROOT) if os.path.isabs(model) else model
            if joints != want_joints:
                problems.append(f"{label}: joints {joints}, published {want_joints}")
            for n in sorted(set(links) | set(frames)):
                if n not in pub_links:
                    problems.append(f"{label}: '{n}' is not a link of the published {urdf}")
            if first is None:
                first = (label, joints, links, frames)
            elif (joints, links, frames) != first[1:]:
                problems.append(f"{label}: other names than {first[0]}")
        print(f"{name}: {len(models)} descriptions against {urdf} (example-robot-data {version})")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
