#!/usr/bin/env python3
"""Load every URDF of the `example-robot-data` package with Pinocchio and with screwdyn.

Usage, from the repository root (needs Python >= 3.9, cargo, and network access to PyPI):

    python3 scripts/check_published_urdfs.py            # creates .venv-pin, installs, checks
    python3 scripts/check_published_urdfs.py --no-venv  # pin + example-robot-data installed here

Like `gen_reference.py`, the first form creates the throwaway virtual environment `.venv-pin`
(git-ignored) in the repository root, runs `pip install pin example-robot-data` in it (about
400 MB with the meshes) and re-executes this script there.

For each URDF in the installed package the script

* builds a fixed-base model with `pinocchio.buildModelFromUrdf(path)`;
* loads the file with the screwdyn command-line program (`screwdyn info FILE --format json`,
  built once with `cargo build -p screwdyn-cli`, or given with `--screwdyn PATH`);
* compares the two: both load, and they have the same set of moving joints (names), so the
  same number of coordinates (screwdyn's `nq` is Pinocchio's `nv`: a continuous joint has one
  coordinate here, two — cos, sin — in Pinocchio's `nq`).

It writes the result, one row per file, as a markdown table to `docs/published-urdfs.md`
(`--output` to change) and exits with status 1 when a file that Pinocchio loads does not load
in screwdyn or gives other joints. Warnings screwdyn prints on stderr while loading (physically
inconsistent inertias and the like) are counted in the table, not treated as failures. CI does
not run this script (the package is large); the committed table records its last result.
"""

import argparse
import importlib.metadata
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
VENV = os.path.join(ROOT, ".venv-pin")
DOC = os.path.join(ROOT, "docs", "published-urdfs.md")
PREFIX = "share/example-robot-data/robots/"


def bootstrap(argv):
    """Create .venv-pin, install pin and example-robot-data, re-run this script inside it."""
    py = os.path.join(VENV, "bin", "python")
    if not os.path.exists(py):
        subprocess.check_call([sys.executable, "-m", "venv", VENV])
    subprocess.check_call([py, "-m", "pip", "install", "-q", "--upgrade", "pip"])
    subprocess.check_call([py, "-m", "pip", "install", "-q", "pin", "example-robot-data"])
    os.execv(py, [py, os.path.abspath(__file__), "--no-venv", *argv])


def urdf_files():
    """(relative name, absolute path) of every URDF in the installed example-robot-data."""
    dist = importlib.metadata.distribution("example-robot-data")
    out = []
    for f in dist.files or []:
        s = str(f)
        if s.endswith(".urdf") and PREFIX in s:
            out.append((s.split(PREFIX, 1)[1], str(f.locate())))
    return sorted(out), dist.version


def build_screwdyn():
    subprocess.check_call(["cargo", "build", "-q", "-p", "screwdyn-cli"], cwd=ROOT)
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(ROOT, "target"))
    return os.path.join(target, "debug", "screwdyn")


def pinocchio_joints(pin, path):
    """(moving joint names, nq, nv) of Pinocchio's fixed-base model, or an error string."""
    try:
        m = pin.buildModelFromUrdf(path)
    except Exception as e:  # noqa: BLE001 - any failure is a result to report
        return None, str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
    names = [m.names[i] for i in range(1, m.njoints) if m.joints[i].nv > 0]
    return (names, m.nq, m.nv), None


def screwdyn_joints(exe, path):
    """(moving joint names, nq, warning lines) from `screwdyn info`, or an error string."""
    p = subprocess.run(
        [exe, "info", path, "--format", "json"], capture_output=True, text=True, timeout=600
    )
    err = [line for line in p.stderr.splitlines() if line.strip()]
    if p.returncode != 0:
        return None, (err[0] if err else f"exit status {p.returncode}").removeprefix("screwdyn: ")
    info = json.loads(p.stdout)
    names = [j["name"] for j in info["joints"]]
    return (names, info["nq"], len(err)), None


def shorten(text, n=160):
    text = text.replace("|", "\\|").replace(ROOT + os.sep, "")
    return text if len(text) <= n else text[: n - 1] + "…"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--no-venv", action="store_true", help="use the current interpreter")
    ap.add_argument("--screwdyn", help="the screwdyn program (default: build it with cargo)")
    ap.add_argument("--output", default=DOC, help="markdown file to write")
    args, rest = ap.parse_known_args()
    if not args.no_venv:
        bootstrap(sys.argv[1:])
    import pinocchio as pin

    exe = args.screwdyn or build_screwdyn()
    files, erd_version = urdf_files()
    rows, failures, pin_loaded = [], [], 0
    for name, path in files:
        pj, perr = pinocchio_joints(pin, path)
        sj, serr = screwdyn_joints(exe, path)
        serr = serr and serr.replace(path, name)
        perr = perr and perr.replace(path, name)
        if pj is None:
            result = "not loaded by Pinocchio: " + shorten(perr)
            rows.append((name, "-", sj[1] if sj else "-", "-", result))
            continue
        pin_loaded += 1
        names, nq, nv = pj
        if sj is None:
            result = "**FAIL** screwdyn refuses: " + shorten(serr)
            failures.append((name, result))
            rows.append((name, f"{nq} / {nv}", "-", "-", result))
            continue
        snames, snq, warnings = sj
        if set(snames) != set(names) or snq != nv:
            only_pin = sorted(set(names) - set(snames))
            only_us = sorted(set(snames) - set(names))
            result = "**FAIL** joints differ: " + shorten(
                f"only in Pinocchio {only_pin}, only in screwdyn {only_us}"
            )
            failures.append((name, result))
        else:
            result = "ok, same moving joints"
        rows.append((name, f"{nq} / {nv}", snq, warnings, result))
        print(f"{name}: {result}", file=sys.stderr)

    lines = [
        "# Published URDF files",
        "",
        "Every URDF file of the `example-robot-data` package (version "
        f"{erd_version}), loaded as a fixed-base model by Pinocchio {pin.__version__} "
        "(`pinocchio.buildModelFromUrdf`) and by screwdyn (`screwdyn info FILE`). Written by "
        "`scripts/check_published_urdfs.py` (see `scripts/README.md`); the files themselves are "
        "not part of this repository.",
        "",
        f"Of {len(files)} files, Pinocchio loads {pin_loaded}; "
        + (
            f"screwdyn loads {pin_loaded - len(failures)} of those with the same moving joints "
            f"and fails on {len(failures)}."
            if failures
            else f"screwdyn loads all {pin_loaded} of those, with the same moving joints."
        ),
        "",
        "Columns: Pinocchio's `nq / nv` (a continuous joint has two position coordinates in "
        "Pinocchio, one in screwdyn), screwdyn's `nq` (one per moving joint, equal to "
        "Pinocchio's `nv`), the number of warnings screwdyn printed while loading (physically "
        "inconsistent inertias and similar findings, one line per body; `screwdyn check FILE` "
        "lists them), and the result. \"Same moving joints\" compares the sets of joint names.",
        "",
        "| file | Pinocchio nq / nv | screwdyn nq | warnings | result |",
        "| --- | --- | --- | --- | --- |",
    ]
    for name, pn, sn, w, result in rows:
        lines.append(f"| `{name}` | {pn} | {sn} | {w} | {result} |")
    os.makedirs(os.path.dirname(os.path.abspath(args.output)), exist_ok=True)
    with open(args.output, "w") as f:
        f.write("\n".join(lines) + "\n")
    print(
        f"{pin_loaded} files loaded by Pinocchio, {len(failures)} failing in screwdyn; "
        f"table written to {os.path.relpath(args.output, ROOT)}",
        file=sys.stderr,
    )
    for name, result in failures:
        print(f"  {name}: {result}", file=sys.stderr)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
