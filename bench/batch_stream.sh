#!/usr/bin/env bash
# Batch --input throughput and memory: `screwdyn rnea builtin:ur5 --input states.csv` on 10^5
# and 10^6 random UR5 states (q, v, a columns: 18 numbers per row, Python's repr of uniform
# [-1, 1) numbers), CSV and JSON output to /dev/null, timed with /usr/bin/time -v (wall, CPU,
# peak RSS); then the bare compute cost from `screwdyn bench builtin:ur5 --algorithms rnea`.
# The ratio batch / (bench ns × rows) is the overhead of reading, parsing and writing.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build -q --release -p screwdyn-cli
exe=./target/release/screwdyn
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
python3 - "$tmp" <<'PY'
import random, sys
random.seed(1)
names = ["shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint",
         "wrist_2_joint", "wrist_3_joint"]
header = ",".join(f"{k}.{j}" for k in "qva" for j in names) + "\n"
for n, name in [(10**5, "1e5"), (10**6, "1e6")]:
    with open(f"{sys.argv[1]}/states_{name}.csv", "w") as f:
        f.write(header)
        for _ in range(n):
            f.write(",".join(repr(random.uniform(-1, 1)) for _ in range(18)) + "\n")
PY
printf '%-6s %-5s %10s %10s %12s\n' rows format "wall (s)" "cpu (s)" "peak RSS (MB)"
for n in 1e5 1e6; do
  for fmt in csv json; do
    /usr/bin/time -v "$exe" rnea builtin:ur5 --input "$tmp/states_$n.csv" --format $fmt \
      > /dev/null 2> "$tmp/time.txt"
    python3 - "$tmp/time.txt" "$n" "$fmt" <<'PY'
import re, sys
t = open(sys.argv[1]).read()
def get(key):
    return re.search(re.escape(key) + r"[^:]*:\s*(\S+)", t).group(1)
wall = get("Elapsed (wall clock) time")
parts = [float(p) for p in wall.split(":")]
secs = sum(p * 60 ** i for i, p in enumerate(reversed(parts)))
cpu = float(get("User time")) + float(get("System time"))
rss = int(get("Maximum resident set size")) / 1024
print(f"{sys.argv[2]:<6} {sys.argv[3]:<5} {secs:10.2f} {cpu:10.2f} {rss:12.1f}")
PY
  done
done
"$exe" bench builtin:ur5 --algorithms rnea --format json
