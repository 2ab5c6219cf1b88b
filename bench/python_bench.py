#!/usr/bin/env python3
"""Side-by-side benchmark of the Python package against Pinocchio's Python bindings, in one run
(recorded in BENCHMARKS.md, "Python").

    python3 bench/python_bench.py            # from the repository root
    python3 bench/python_bench.py --states 100000 --no-venv

Both libraries load the same robot file, models/ur5.urdf. Measured:

1. per-call time from Python of rnea / crba / aba for one state, screwdyn (`ur5.rnea(q, v, a)`)
   against Pinocchio (`pin.rnea(model, data, q, v, a)`), median of repeated loops, the two alternating;
2. batch throughput on N = 10⁶ UR5 states: screwdyn's batched call (all cores, GIL released)
   against a Python loop over Pinocchio and against screwdyn's own single-thread loop in Rust
   (`threads=1`).

Without Pinocchio in the current interpreter, the script creates .venv-pybench/ in the
repository root (git-ignored), installs `pin`, numpy and screwdyn (`pip install
./crates/screwdyn-py`, release build) there and re-executes itself.
"""

import argparse
import json
import os
import pathlib
import platform
import statistics
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
URDF = ROOT / "models" / "ur5.urdf"


def ensure_env(args):
    try:
        import pinocchio  # noqa: F401
        import screwdyn  # noqa: F401
        return
    except ImportError:
        if args.no_venv:
            raise
    venv = ROOT / ".venv-pybench"
    py = venv / "bin" / "python"
    if not py.exists():
        subprocess.check_call([sys.executable, "-m", "venv", str(venv)])
    subprocess.check_call([str(py), "-m", "pip", "install", "-q", "pin", "numpy"])
    subprocess.check_call([str(py), "-m", "pip", "install", "-q", str(ROOT / "crates" / "screwdyn-py")])
    os.execv(str(py), [str(py), __file__, "--no-venv"] + sys.argv[1:])


def alternating(fns, repeats):
    """Times each of ``fns`` (callables without arguments) once per repeat, in turn, so that a
    change of the machine's speed hits all of them alike. Returns the list of times per fn."""
    times = [[] for _ in fns]
    for _ in range(repeats):
        for t, fn in zip(times, fns):
            t0 = time.perf_counter_ns()
            fn()
            t.append((time.perf_counter_ns() - t0) * 1e-9)
    return times


def ratio(num, den):
    """Median of the per-repeat ratios ``num[i] / den[i]``."""
    return statistics.median(a / b for a, b in zip(num, den))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--states", type=int, default=1_000_000)
    ap.add_argument("--calls", type=int, default=20_000)
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--no-venv", action="store_true")
    ap.add_argument("--json", type=pathlib.Path, help="also write the results as JSON")
    args = ap.parse_args()
    ensure_env(args)

    import numpy as np
    import pinocchio as pin

    import screwdyn

    ur5 = screwdyn.load(str(URDF))
    model = pin.buildModelFromUrdf(str(URDF))
    data = model.createData()
    assert model.nq == ur5.nq == 6
    rng = np.random.default_rng(1)
    q, v, a = rng.uniform(-3, 3, 6), rng.normal(size=6), rng.normal(size=6)
    tau = ur5.rnea(q, v, a)
    # same robot, same numbers (Pinocchio's joint order is the URDF's depth-first order too)
    assert np.allclose(pin.rnea(model, data, q, v, a), tau, atol=1e-9), "the two models differ"
    assert np.allclose(pin.crba(model, data, q), ur5.crba(q), atol=1e-9) or np.allclose(
        np.triu(pin.crba(model, data, q)), np.triu(ur5.crba(q)), atol=1e-9)
    assert np.allclose(pin.aba(model, data, q, v, tau), a, atol=1e-8)

    def loop(f):
        def run(n):
            for _ in range(n):
                f()
        return run

    per_call = {}
    for name, ours, theirs in [
        ("rnea", lambda: ur5.rnea(q, v, a), lambda: pin.rnea(model, data, q, v, a)),
        ("crba", lambda: ur5.crba(q), lambda: pin.crba(model, data, q)),
        ("aba", lambda: ur5.aba(q, v, tau), lambda: pin.aba(model, data, q, v, tau)),
    ]:
        t_ours, t_pin = alternating([lambda: loop(ours)(args.calls), lambda: loop(theirs)(args.calls)],
                                    args.repeats)
        # Median and best of the repeats (timeit's advice: the best is the least disturbed).
        per_call[name] = {"screwdyn_ns": statistics.median(t_ours) * 1e9 / args.calls,
                          "pinocchio_ns": statistics.median(t_pin) * 1e9 / args.calls,
                          "ratio": ratio(t_pin, t_ours),
                          "screwdyn_best_ns": min(t_ours) * 1e9 / args.calls,
                          "pinocchio_best_ns": min(t_pin) * 1e9 / args.calls,
                          "best_ratio": min(t_pin) / min(t_ours)}

    n = args.states
    Q, V, A = rng.uniform(-3, 3, (n, 6)), rng.normal(size=(n, 6)), rng.normal(size=(n, 6))
    T = ur5.rnea(Q, V, A)
    batch = {}
    for name, ours, theirs_one, args_n in [
        ("rnea", lambda th: ur5.rnea(Q, V, A, threads=th), lambda k: pin.rnea(model, data, Q[k], V[k], A[k]), (Q, V, A)),
        ("crba", lambda th: ur5.crba(Q, threads=th), lambda k: pin.crba(model, data, Q[k]), (Q,)),
        ("aba", lambda th: ur5.aba(Q, V, T, threads=th), lambda k: pin.aba(model, data, Q[k], V[k], T[k]), (Q, V, T)),
    ]:
        # All cores and one thread alternate (5 repeats, median of per-repeat ratios); the
        # Python loop over Pinocchio (seconds per pass) runs once.
        t_all, t_one = alternating([lambda: ours(None), lambda: ours(1)], 5)
        t0 = time.perf_counter()
        # Python loop over Pinocchio on the same states (rows are NumPy views, as a user writes it)
        for k in range(n):
            theirs_one(k)
        t_pin = time.perf_counter() - t0
        batch[name] = {
            "states": n,
            "screwdyn_all_cores_s": statistics.median(t_all),
            "screwdyn_one_thread_s": statistics.median(t_one),
            "pinocchio_python_loop_s": t_pin,
            "vs_pinocchio_loop": t_pin / statistics.median(t_all),
            "vs_single_thread": ratio(t_one, t_all),
        }

    info = {
        "machine": f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}",
        "load_average_at_end": os.getloadavg(),
        "pinocchio": pin.__version__,
        "screwdyn": screwdyn.__version__,
        "model": str(URDF.relative_to(ROOT)),
        "per_call": per_call,
        "batch": batch,
    }
    print(f"UR5 ({info['model']}), {info['machine']}, pinocchio {info['pinocchio']}, "
          f"load average {', '.join(f'{x:.1f}' for x in info['load_average_at_end'])}\n")
    print("Per call from Python (median ns per call; ratio > 1: screwdyn faster)\n")
    print("| function | screwdyn (median) | pinocchio (median) | pinocchio / screwdyn (median of ratios) "
          "| screwdyn (best) | pinocchio (best) | pinocchio / screwdyn (best) |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for k, r in per_call.items():
        print(f"| {k} | {r['screwdyn_ns']:.0f} | {r['pinocchio_ns']:.0f} | {r['ratio']:.2f} "
              f"| {r['screwdyn_best_ns']:.0f} | {r['pinocchio_best_ns']:.0f} | {r['best_ratio']:.2f} |")
    print(f"\nBatch of {n} states (seconds)\n")
    print("| function | screwdyn, all cores | screwdyn, 1 thread | Python loop over pinocchio "
          "| vs pinocchio loop | vs 1 thread |")
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    for k, r in batch.items():
        print(f"| {k} | {r['screwdyn_all_cores_s']:.3f} | {r['screwdyn_one_thread_s']:.3f} | "
              f"{r['pinocchio_python_loop_s']:.3f} | {r['vs_pinocchio_loop']:.1f}× | "
              f"{r['vs_single_thread']:.2f}× |")
    if args.json:
        args.json.write_text(json.dumps(info, indent=2))


if __name__ == "__main__":
    main()
