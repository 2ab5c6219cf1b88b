#!/usr/bin/env bash
# Simulation speed, side by side with MuJoCo: 10 s at 1 kHz, RK4, passive UR5 and Panda released
# from rest, no joint effects on our side, contacts and limits disabled on MuJoCo's.
# Installs mujoco from PyPI into a throwaway venv; builds screwdyn's example and CLI in release
# mode and MuJoCo's own C loop (bench/mj_step_loop.c, against the libmujoco and headers of the
# wheel); runs them in alternating rounds (ROUNDS, default 7) and prints median seconds of
#   lib      screwdyn's library loop (examples/sim_bench.rs, recording only the end state),
#   cli      the whole `screwdyn simulate ... --record-every 1000 --output run.csv` process, the
#            program as `cargo build --release` / `cargo install` link it (dynamically),
#   static   the same with the statically linked program of `cargo build-static` (Linux with
#            glibc on x86-64 only; .cargo/config.toml),
#   mj C     MuJoCo's C `mj_step` loop,
#   rollout  MuJoCo through Python's `mujoco.rollout`,
# and the ratios lib/mj C, cli/mj C, static/mj C (medians of per-round ratios) and lib/rollout
# (lower is faster for screwdyn). Below each model's row, what the CLI process costs besides simulating:
# the same command with --duration 0 and `/bin/true` (the floor of any process started from
# Python), timed in the same rounds after the others (medians).
set -euo pipefail
cd "$(dirname "$0")/.."
# MJ_VENV: an existing venv with mujoco and numpy to use instead of .venv-mujoco.
venv=${MJ_VENV:-.venv-mujoco}
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/python" -c 'import mujoco, numpy' 2>/dev/null || "$venv/bin/pip" install -q mujoco numpy
mj=$("$venv/bin/python" -c 'import mujoco, os; print(os.path.dirname(mujoco.__file__))')
lib=$(ls "$mj"/libmujoco.so.* | head -n 1)
cargo build -q --release -p screwdyn --example sim_bench
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Both programs, one after the other into target/release (the second build relinks it).
static=""
if [ "$(uname -sm)" = "Linux x86_64" ] && ldd --version 2>&1 | grep -qi glibc; then
  cargo -q build-static
  cp target/release/screwdyn "$tmp/screwdyn-static"
  static="$tmp/screwdyn-static"
fi
cargo build -q --release -p screwdyn-cli
cc -O2 -o "$tmp/mj_step_loop" bench/mj_step_loop.c -I"$mj/include" "$lib" -Wl,-rpath,"$mj" -lm
rounds=${ROUNDS:-7}
printf '%-6s %8s %8s %8s %8s %8s %10s %10s %12s %12s %s\n' model "lib (s)" "cli (s)" "static" \
  "mj C (s)" "rollout" "lib/mj C" "cli/mj C" "static/mj C" "lib/rollout" "max |Δq| at 0.2 s"
for robot in ur5 panda; do
  ./target/release/examples/sim_bench "builtin:$robot" --repeat 1 --duration 0.2 > "$tmp/$robot-short.json"
  ./target/release/examples/sim_bench "builtin:$robot" --repeat 1 --urdf "$tmp/$robot.urdf" > "$tmp/$robot.json"
  q0=$("$venv/bin/python" -c 'import json,sys; print(",".join(repr(x) for x in json.load(open(sys.argv[1]))["q0"]))' "$tmp/$robot.json")
  "$tmp/mj_step_loop" "$tmp/$robot.urdf" 200 1 "$q0" > "$tmp/$robot-c-short.json"
  "$venv/bin/python" bench/sim_vs_mujoco.py "$tmp/$robot.urdf" "$tmp/$robot.json" "$tmp/$robot-short.json" > "$tmp/$robot-cmp.json"
  "$venv/bin/python" - "$tmp" "$robot" "$q0" "$rounds" "$static" <<'PY'
import json, statistics, subprocess, sys, time
tmp, robot, q0, rounds, static = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), sys.argv[5]
r = json.load(open(f"{tmp}/{robot}-cmp.json"))
short = json.load(open(f"{tmp}/{robot}-short.json"))
c_short = json.load(open(f"{tmp}/{robot}-c-short.json"))
# The whole CLI process: start, load, simulate 10 s, write every 1000th step, exit.
cmd = ["./target/release/screwdyn", "simulate", f"builtin:{robot}", "--duration", "10",
       "--dt", "0.001", "--integrator", "rk4", "--no-effects", "--q0", q0,
       "--record-every", "1000", "--output", f"{tmp}/{robot}-run.csv", "--format", "json"]
def run(args):
    return json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)
# Rounds alternate the three so that a change of the machine's speed (other jobs, the VM's
# neighbours) hits all of them alike; each ratio is the median of the per-round ratios.
lib, mjc, cli, stat, cli0, stat0, true = [], [], [], [], [], [], []
cmd0 = cmd.copy()
cmd0[cmd.index("--duration") + 1] = "0"
scmd, scmd0 = [static] + cmd[1:], [static] + cmd0[1:]
def timed(runs, args):
    start = time.perf_counter()
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
    runs.append(time.perf_counter() - start)
for k in range(rounds):
    lib.append(run(["./target/release/examples/sim_bench", f"builtin:{robot}", "--repeat", "1"])["median_s"])
    mjc.append(run([f"{tmp}/mj_step_loop", f"{tmp}/{robot}.urdf", "10000", "1", q0])["median_s"])
    # The two programs in turns, each first in every other round.
    for runs, args in ((cli, cmd), (stat, scmd))[:: 1 if k % 2 == 0 else -1]:
        if args[0]:
            timed(runs, args)
    for runs, args in ((cli0, cmd0), (true, ["/bin/true"])):
        timed(runs, args)
    if static:
        timed(stat0, scmd0)
med = statistics.median
roll = r["mujoco_median_s"]
lib_c = med(a / b for a, b in zip(lib, mjc))
cli_c = med(a / b for a, b in zip(cli, mjc))
stat_c, stat_s = (med(a / b for a, b in zip(stat, mjc)), med(stat)) if static else (float("nan"), float("nan"))
dq = max(abs(a - b) for a, b in zip(short["final_q"], c_short["final_q"]))
print(f"{robot:<6} {med(lib):8.4f} {med(cli):8.4f} {stat_s:8.4f} {med(mjc):8.4f} {roll:8.4f} {lib_c:10.3f} "
      f"{cli_c:10.3f} {stat_c:12.3f} {med(lib) / roll:12.3f} {dq:.2e}  (MuJoCo {json.load(open(f'{tmp}/{robot}-c-short.json')).get('mujoco_version', '')})")
print(f"       per-round lib/mj C: {' '.join(f'{a / b:.3f}' for a, b in zip(lib, mjc))}")
print(f"       per-round cli/mj C: {' '.join(f'{a / b:.3f}' for a, b in zip(cli, mjc))}")
if static:
    print(f"       per-round static/mj C: {' '.join(f'{a / b:.3f}' for a, b in zip(stat, mjc))}")
print(f"       cli --duration 0: {med(cli0) * 1e3:.2f} ms, /bin/true: {med(true) * 1e3:.2f} ms, "
      f"cli - lib: {med(a - b for a, b in zip(cli, lib)) * 1e3:.2f} ms")
if static:
    print(f"       static --duration 0: {med(stat0) * 1e3:.2f} ms, "
          f"static - lib: {med(a - b for a, b in zip(stat, lib)) * 1e3:.2f} ms")
PY
done
