#!/usr/bin/env bash
# Inverse kinematics side by side (bench/ik_compare.py): screwdyn's Python package built in
# release, the Robotics Toolbox's C++ ik_LM and TRAC-IK, on the arms of example-robot-data.
# A throwaway venv under $TMPDIR; prints a Markdown table (BENCHMARKS.md, docs/ik.md).
# Usage: bench/ik_compare.sh [POSES]   (default 2000)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
venv=${IK_COMPARE_VENV:-${TMPDIR:-/tmp}/screwdyn-ik-compare}
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install -q numpy roboticstoolbox-python pytracik example-robot-data
fi
cargo build --release -p screwdyn-py --features screwdyn-py/extension-module --manifest-path "$root/Cargo.toml"
pkg=$(mktemp -d)
trap 'rm -rf "$pkg"' EXIT
cp -r "$root/crates/screwdyn-py/python/screwdyn" "$pkg/"
cp "$root/target/release/lib_screwdyn.so" "$pkg/screwdyn/_screwdyn.abi3.so"
# example-robot-data 6 ships the robots as data only (no Python module): found under the venv.
robots=$("$venv/bin/python" -c 'import pathlib, sys
p = pathlib.Path(sys.prefix).glob("lib/python3*/site-packages/cmeel.prefix/share/example-robot-data/robots")
print(next(p))')
PYTHONPATH="$pkg" "$venv/bin/python" -W ignore "$root/bench/ik_compare.py" "$robots" "${1:-2000}"
