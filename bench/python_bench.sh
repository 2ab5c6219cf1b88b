#!/usr/bin/env bash
# Python per-call and batch comparison with Pinocchio's Python bindings (BENCHMARKS.md, "Issue
# 31: from Python"), from a checkout, in one command:
#
#   bash bench/python_bench.sh                     # all of bench/python_bench.py's defaults
#   bash bench/python_bench.sh --rounds 5 --json run.json
#
# 1. a throwaway venv .venv-pybench (git-ignored) with pin, example-robot-data and numpy;
# 2. the extension built by cargo in the release profile the wheel uses (fat LTO, portable: no
#    target-cpu), into its own target directory target/bench-py, and the package assembled
#    from it as maturin lays it out (python/screwdyn plus screwdyn/_screwdyn.abi3.so);
# 3. bench/python_bench.py on that package, its arguments passed through.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
cd "$ROOT"
VENV=$ROOT/.venv-pybench
if [ ! -x "$VENV/bin/python" ]; then
    python3 -m venv "$VENV"
fi
"$VENV/bin/pip" install -q pin example-robot-data numpy

echo "building the extension (release) ..." >&2
CARGO_TARGET_DIR=$ROOT/target/bench-py cargo build --release -q -p screwdyn-py \
    --features screwdyn-py/extension-module
PKG=$ROOT/target/bench-py/pkg
rm -rf "$PKG"
mkdir -p "$PKG"
cp -r crates/screwdyn-py/python/screwdyn "$PKG/"
cp target/bench-py/release/lib_screwdyn.so "$PKG/screwdyn/_screwdyn.abi3.so"

PYTHONPATH=$PKG "$VENV/bin/python" bench/python_bench.py --no-venv "$@"
