#!/usr/bin/env bash
# Generated inverse-dynamics code (screwdyn symbolic, issue 14) against Pinocchio's RNEA, side by
# side, on the same URDF (example-robot-data's UR5 and Panda), plus the time and size of every
# symbolic quantity.
#
#   bash bench/symbolic_vs_pinocchio.sh [ROUNDS]      # default 5 rounds
#
# 1. The setup shared with bench/compare.sh (bench/pinocchio_setup.sh): venv .venv-bench with
#    pin, example-robot-data and headers;
#    each URDF's joint tree exported with Pinocchio's parser; bench/pinocchio_bench.cpp compiled
#    with g++ -O3 -march=native -DNDEBUG.
# 2. screwdyn (release) writes `inverse_dynamics` in C for the same URDF; bench/symbolic_bench.c
#    times it compiled with cc -O3 -march=native (same states scheme, batches and calls as the
#    Pinocchio side).
# 3. ROUNDS alternating rounds; prints medians and the ratio generated / Pinocchio rnea
#    (median of per-round ratios), then, per robot and quantity, the operation count after CSE
#    and the generation time of code, and the terms and time of the expanded text form.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
ROUNDS=${1:-5}
BATCHES=${BATCHES:-21}
CALLS=${CALLS:-20000}
source bench/pinocchio_setup.sh

echo "building screwdyn (release) ..." >&2
cargo build --release -q -p screwdyn-cli
OURS=$ROOT/target/release/screwdyn

declare -A NQ=([ur5]=6 [panda]=9)
for r in ur5 panda; do
    "$OURS" symbolic "${URDF[$r]}" --quantity torque --format c --output "$OUT/${r}_tau.c"
    cc -O3 -march=native -DGENERATED="\"$OUT/${r}_tau.c\"" bench/symbolic_bench.c \
        -o "$OUT/${r}_symbolic_bench" -lm
done

: > "$OUT/symbolic_runs.jsonl"
for round in $(seq 1 "$ROUNDS"); do
    for r in ur5 panda; do
        echo "round $round/$ROUNDS: $r" >&2
        p=$("$PINBENCH" "$OUT/$r.txt" "$BATCHES" "$CALLS")
        o=$("$OUT/${r}_symbolic_bench" "${NQ[$r]}" "$BATCHES" "$CALLS")
        echo "{\"robot\": \"$r\", \"pinocchio\": $p, \"generated\": $o}" >> "$OUT/symbolic_runs.jsonl"
    done
done

"$VENV/bin/python" - "$OUT/symbolic_runs.jsonl" <<'PY'
import json, statistics, sys
runs = [json.loads(l) for l in open(sys.argv[1])]
print("| robot (nq) | generated C τ ns | Pinocchio rnea ns | ratio | per-round ratios |")
print("| --- | ---: | ---: | ---: | --- |")
for robot in ["ur5", "panda"]:
    rs = [r for r in runs if r["robot"] == robot]
    g = [r["generated"]["ns_per_call"] for r in rs]
    p = [r["pinocchio"]["ns_per_call"]["rnea"] for r in rs]
    ratios = [a / b for a, b in zip(g, p)]
    nq = rs[0]["pinocchio"]["nq"]
    print(f"| {robot} ({nq}) | {statistics.median(g):.1f} | {statistics.median(p):.1f} | "
          f"{statistics.median(ratios):.2f} | {' '.join(f'{x:.2f}' for x in ratios)} |")
PY

echo
echo "| model | quantity | ops after CSE | code time s | expanded terms | text time s |"
echo "| --- | --- | ---: | ---: | ---: | ---: |"
for m in builtin:ur5 builtin:panda; do
    for q in mass-matrix gravity torque coriolis; do
        t0=$(date +%s.%N)
        ops=$("$OURS" symbolic $m --quantity $q --format c | grep -o '[0-9]* operations' | cut -d' ' -f1)
        t1=$(date +%s.%N)
        if terms=$("$OURS" symbolic $m --quantity $q --max-terms 1000000 2>/dev/null | grep -o 'expanded form: [0-9]*' | cut -d' ' -f3); then :; else terms="-"; fi
        t2=$(date +%s.%N)
        printf '| %s | %s | %s | %.2f | %s | %.2f |\n' "$m" "$q" "$ops" "$(echo "$t1 - $t0" | bc)" "$terms" "$(echo "$t2 - $t1" | bc)"
    done
done
