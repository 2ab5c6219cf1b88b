#!/usr/bin/env bash
# What recording every step costs (issue 12: at most half again the integration itself).
#
#   bash bench/record_cost.sh [ROUNDS]     # default 5 rounds
#
# Builds the library example examples/sim_bench.rs and the CLI in release mode, then times,
# alternating in each round, a passive 10 s run at 1 kHz (RK4, ABA, no joint effects) of the
# builtin UR5 and Panda:
#   integrate   the library loop recording only the end state,
#   lib csv     the same loop streaming every step (10 001 rows) to a CSV file
#               (simulate_into + CsvSampleWriter, as `screwdyn simulate --output` does),
#   cli end     the whole `screwdyn simulate ... --record-every 100000 --output run.csv` process,
#   cli csv     the whole process writing every step (`--record-every 1`),
# and prints the medians and the ratios lib csv / integrate and cli csv / cli end.
set -euo pipefail
cd "$(dirname "$0")/.."
ROUNDS=${1:-5}
cargo build -q --release -p screwdyn --example sim_bench
cargo build -q --release -p screwdyn-cli
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 - "$tmp" "$ROUNDS" <<'PY'
import json, statistics, subprocess, sys, time
tmp, rounds = sys.argv[1], int(sys.argv[2])
bench = "./target/release/examples/sim_bench"
cli = "./target/release/screwdyn"
print(f"{'model':<7}{'integrate (s)':>15}{'lib csv (s)':>13}{'ratio':>7}{'cli end (s)':>13}{'cli csv (s)':>13}{'ratio':>7}   rows")
for robot in ["ur5", "panda"]:
    times = {k: [] for k in ["integrate", "lib", "cli_end", "cli_csv"]}
    q0 = json.loads(subprocess.run([bench, f"builtin:{robot}", "--repeat", "1", "--duration", "0"],
                                   check=True, capture_output=True, text=True).stdout)["q0"]
    q0 = ",".join(repr(x) for x in q0)
    for _ in range(rounds):
        for key, extra in [("integrate", []), ("lib", ["--record-every", "1", "--csv", f"{tmp}/lib.csv"])]:
            out = subprocess.run([bench, f"builtin:{robot}", "--repeat", "1", *extra],
                                 check=True, capture_output=True, text=True).stdout
            times[key].append(json.loads(out)["median_s"])
        for key, every in [("cli_end", "100000"), ("cli_csv", "1")]:
            cmd = [cli, "simulate", f"builtin:{robot}", "--duration", "10", "--dt", "0.001",
                   "--integrator", "rk4", "--no-effects", "--q0", q0, "--record-every", every,
                   "--output", f"{tmp}/cli.csv", "--format", "json"]
            start = time.perf_counter()
            subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
            times[key].append(time.perf_counter() - start)
    rows = sum(1 for _ in open(f"{tmp}/cli.csv")) - 1
    m = {k: statistics.median(v) for k, v in times.items()}
    print(f"{robot:<7}{m['integrate']:>15.4f}{m['lib']:>13.4f}{m['lib'] / m['integrate']:>7.2f}"
          f"{m['cli_end']:>13.4f}{m['cli_csv']:>13.4f}{m['cli_csv'] / m['cli_end']:>7.2f}   {rows}")
PY
