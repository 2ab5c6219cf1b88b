#!/usr/bin/env bash
# Simulation speed, side by side with MuJoCo (issue 5's benchmark): 10 s at 1 kHz, RK4,
# passive UR5 and Panda released from rest, contacts and limits disabled on the MuJoCo side.
# Installs mujoco from PyPI into a throwaway venv, builds screwdyn's example in release mode,
# runs the two one after the other and prints median seconds and the ratio screwdyn/MuJoCo.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=.venv-mujoco
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/pip" install -q mujoco numpy
cargo build -q --release -p screwdyn --example sim_bench
tmp=$(mktemp -d)
printf '%-8s %14s %14s %8s %s\n' model "screwdyn (s)" "MuJoCo (s)" ratio "max |Δq| at 0.2 s"
for robot in ur5 panda; do
  ./target/release/examples/sim_bench "builtin:$robot" --repeat 1 --duration 0.2 > "$tmp/$robot-short.json"
  ./target/release/examples/sim_bench "builtin:$robot" --repeat 7 --urdf "$tmp/$robot.urdf" > "$tmp/$robot.json"
  "$venv/bin/python" bench/sim_vs_mujoco.py "$tmp/$robot.urdf" "$tmp/$robot.json" "$tmp/$robot-short.json" > "$tmp/$robot-cmp.json"
  "$venv/bin/python" - "$tmp/$robot-cmp.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
print(f"{r['model']:<8} {r['screwdyn_median_s']:14.4f} {r['mujoco_median_s']:14.4f} {r['ratio']:8.3f} {r['max_abs_q_difference_at_0.2s']:.2e}  (MuJoCo {r['mujoco_version']})")
PY
done
