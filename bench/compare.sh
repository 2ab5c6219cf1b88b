#!/usr/bin/env bash
# Side-by-side per-call timing of screwdyn and Pinocchio on the same URDFs (issue 7).
#
#   bash bench/compare.sh [ROUNDS]        # ROUNDS comparison rounds (default 3)
#
# Environment: BATCHES (default 21) and CALLS (default 20000) per algorithm and round.
#
# 1. Creates a throwaway venv .venv-bench (git-ignored) and installs from PyPI: pin (Pinocchio 4),
#    example-robot-data (the UR5 and Panda URDFs), cmeel-eigen and cmeel-urdfdom-headers
#    (headers the pin wheel's own headers need).
# 2. Exports each URDF's joint tree with Pinocchio's Python URDF parser (bench/export_model.py)
#    and compiles bench/pinocchio_bench.cpp — ours — against Pinocchio's headers only, with
#    g++ -O3 -march=native -DNDEBUG.
# 3. Builds `screwdyn` in release (lto = "fat", codegen-units = 1) with
#    RUSTFLAGS="-C target-cpu=native" into target/bench-native (the normal build stays
#    portable: target-cpu=native is only used here, so both sides get the same CPU flags).
# 4. Runs, ROUNDS times and alternating, `pinocchio_bench` and `screwdyn bench` on UR5, Panda
#    (fixed base) and chain200, a 200-joint serial chain whose URDF bench/chain_urdf.py writes
#    (revolute joints about alternating axes, varied offsets, masses and inertias; loaded by each
#    library's own URDF parser like the arms; CHAIN_BATCHES, default 5, batches of CHAIN_CALLS,
#    default 100, calls, as one call there costs up to milliseconds), then prints per-call medians (median over rounds of the per-round medians)
#    and the ratio ours / Pinocchio for fk, jacobians, rnea, crba, aba, rnea_derivatives
#    (computeRNEADerivatives) and aba_derivatives (computeABADerivatives). The ratio is the
#    median of the per-round ratios: each round's two numbers were taken seconds apart, so a
#    burst of load from another process on this shared machine hits fewer ratios than medians.
#
# BASELINE=<commit> also builds that commit of screwdyn (same flags, from `git archive` into
# target/bench-baseline) and times it in every round next to the other two, adding the columns
# "baseline ns" and "vs baseline" (ours / baseline, median of per-round ratios): a before/after
# measurement of a change taken in one run, so a machine whose speed moves between sessions does
# not pass for a regression.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
ROUNDS=${1:-3}
BATCHES=${BATCHES:-21}
CALLS=${CALLS:-20000}
CHAIN_BATCHES=${CHAIN_BATCHES:-5}
CHAIN_CALLS=${CHAIN_CALLS:-100}
source bench/pinocchio_setup.sh
URDF[chain200]=$OUT/chain200.urdf
"$VENV/bin/python" bench/chain_urdf.py 200 "${URDF[chain200]}"
"$VENV/bin/python" bench/export_model.py "${URDF[chain200]}" "$OUT/chain200.txt"

echo "building screwdyn (release, target-cpu=native) ..." >&2
RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR=$ROOT/target/bench-native \
    cargo build --release -q -p screwdyn-cli
OURS=$ROOT/target/bench-native/release/screwdyn

BASE=""
if [ -n "${BASELINE:-}" ]; then
    SRC=$ROOT/target/bench-baseline/src
    rm -rf "$SRC" && mkdir -p "$SRC"
    git archive "$BASELINE" | tar -x -C "$SRC"
    # The unpacked files carry the commit's time, which can be older than the last baseline
    # build of another commit: cargo would then reuse that build. Touched when the commit changed.
    STAMP=$ROOT/target/bench-baseline/commit
    WANT=$(git rev-parse "$BASELINE^{commit}")
    if [ "$(cat "$STAMP" 2>/dev/null)" != "$WANT" ]; then
        find "$SRC" -type f -exec touch {} +
    fi
    echo "building screwdyn at $BASELINE (release, target-cpu=native) ..." >&2
    (cd "$SRC" && RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR=$ROOT/target/bench-baseline/target \
        cargo build --release -q -p screwdyn-cli)
    echo "$WANT" > "$STAMP"
    BASE=$ROOT/target/bench-baseline/target/release/screwdyn
fi

: > "$OUT/runs.jsonl"
for round in $(seq 1 "$ROUNDS"); do
    for r in ur5 panda chain200; do
        echo "round $round/$ROUNDS: $r" >&2
        nb=$BATCHES nc=$CALLS
        if [ "$r" = chain200 ]; then nb=$CHAIN_BATCHES nc=$CHAIN_CALLS; fi
        p=$("$PINBENCH" "$OUT/$r.txt" "$nb" "$nc")
        o=$("$OURS" bench "${URDF[$r]}" --format json --batches "$nb" --calls "$nc")
        b=null
        if [ -n "$BASE" ]; then
            b=$("$BASE" bench "${URDF[$r]}" --format json --batches "$nb" --calls "$nc")
        fi
        echo "{\"robot\": \"$r\", \"round\": $round, \"pinocchio\": $p, \"screwdyn\": $o, \"baseline\": $b}" >> "$OUT/runs.jsonl"
    done
done

"$VENV/bin/python" - "$OUT/runs.jsonl" <<'EOF'
import json, statistics, sys
runs = [json.loads(l) for l in open(sys.argv[1])]
algos = ["fk", "jacobians", "rnea", "crba", "aba", "rnea_derivatives", "aba_derivatives"]
base = runs[0]["baseline"] is not None
extra = f"{'baseline ns':>13}{'vs baseline':>13}" if base else ""
print(f"{'robot (nq)':<11}{'algorithm':<17}{'screwdyn ns':>13}{'Pinocchio ns':>14}{'ratio':>8}{extra}   per-round ratios")
for robot in ["ur5", "panda", "chain200"]:
    rs = [r for r in runs if r["robot"] == robot]
    nq = rs[0]["screwdyn"]["nq"]
    assert nq == rs[0]["pinocchio"]["nq"], "both sides must load the same joints"
    for a in algos:
        ours = statistics.median(r["screwdyn"]["ns_per_call"][a] for r in rs)
        pin = statistics.median(r["pinocchio"]["ns_per_call"][a] for r in rs)
        extra = ""
        if base:
            # A baseline older than a row's algorithm has no number for it.
            have = [r for r in rs if a in r["baseline"]["ns_per_call"]]
            if have:
                b = statistics.median(r["baseline"]["ns_per_call"][a] for r in have)
                vs = statistics.median(r["screwdyn"]["ns_per_call"][a] / r["baseline"]["ns_per_call"][a] for r in have)
                extra = f"{b:>13.1f}{vs:>13.2f}"
            else:
                extra = f"{'-':>13}{'-':>13}"
        ratios = [r["screwdyn"]["ns_per_call"][a] / r["pinocchio"]["ns_per_call"][a] for r in rs]
        per = " ".join(f"{x:.2f}" for x in ratios)
        name = f"{robot} ({nq})"
        print(f"{name:<11}{a:<17}{ours:>13.1f}{pin:>14.1f}{statistics.median(ratios):>8.2f}{extra}   {per}")
EOF
