#!/usr/bin/env bash
# How much two cores of this machine give over one, for our kind of code, independent of any
# threading library: the same single-threaded program (examples/sim_bench.rs, a 10 s UR5 run)
# timed alone, then as two processes started together. Throughput of the pair over one alone =
# 2 × alone / paired; on two independent cores it is ≈ 2, on two hyperthreads of one core
# ≈ 1.1–1.4. This is the ceiling any multi-threaded batch (the Python package's `threads=None`)
# can reach against its own single thread here.
#
#   bash bench/core_scaling.sh [ROUNDS]     # default 7
set -euo pipefail
cd "$(dirname "$0")/.."
ROUNDS=${1:-7}
cargo build -q --release -p screwdyn --example sim_bench
bench=./target/release/examples/sim_bench
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
time_of() { python3 -c 'import json,sys; print(json.load(sys.stdin)["median_s"])'; }
: > "$tmp/alone"; : > "$tmp/pair"
for _ in $(seq "$ROUNDS"); do
    "$bench" builtin:ur5 --repeat 3 | time_of >> "$tmp/alone"
    "$bench" builtin:ur5 --repeat 3 > "$tmp/a.json" &
    "$bench" builtin:ur5 --repeat 3 | time_of >> "$tmp/pair"
    wait
    time_of < "$tmp/a.json" >> "$tmp/pair"
done
alone=$(median < "$tmp/alone")
pair=$(median < "$tmp/pair")
python3 -c "import sys; a, p = float(sys.argv[1]), float(sys.argv[2]); print(f'one process alone {a:.4f} s, each of two together {p:.4f} s: two cores give {2 * a / p:.2f}x one core ({sys.argv[3]} CPUs online)')" "$alone" "$pair" "$(nproc)"
