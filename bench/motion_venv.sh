#!/usr/bin/env bash
# Makes the throwaway virtual environment of bench/motion_compare.py: toppra (TOPP-RA),
# ruckig (jerk-limited profiles) and pin (Pinocchio, whose RNEA gives toppra its torques), from
# PyPI, in $VENV (default .venv-motion, git-ignored), then runs the comparison with the release
# build of the Python extension.
#
#   bash bench/motion_venv.sh            # venv, release builds, comparison table on stdout
set -euo pipefail
cd "$(dirname "$0")/.."
VENV="${VENV:-.venv-motion}"
if [[ ! -x "$VENV/bin/python" ]]; then
    python3 -m venv "$VENV"
    "$VENV/bin/pip" install -q numpy scipy toppra ruckig pin
fi
cargo build -q --release -p screwdyn-cli -p screwdyn-py --features screwdyn-py/extension-module
pkg=$(mktemp -d)
trap 'rm -rf "$pkg"' EXIT
cp -r crates/screwdyn-py/python/screwdyn "$pkg/"
cp target/release/lib_screwdyn.so "$pkg/screwdyn/_screwdyn.abi3.so"
PYTHONPATH="$pkg" "$VENV/bin/python" bench/motion_compare.py target/release/screwdyn
