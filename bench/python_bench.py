#!/usr/bin/env python3
"""Side-by-side benchmark of the Python package against Pinocchio's Python bindings, in one run
(recorded in BENCHMARKS.md, "Python").

    python3 bench/python_bench.py            # from the repository root
    python3 bench/python_bench.py --states 100000 --no-venv

Both libraries load the same robot file, models/ur5.urdf. Measured:

1. per-call time from Python of rnea / crba / aba for one state, screwdyn (`ur5.rnea(q, v, a)`)
   against Pinocchio (`pin.rnea(model, data, q, v, a)`), median of repeated loops, the two alternating;
2. batch throughput on N = 10⁶ UR5 states, in rounds (`--rounds`) so that every ratio compares
   times taken within a few seconds of each other: screwdyn's batched call (all cores, GIL
   released) and with `threads=1` (our own single-thread Rust loop), each into a fresh array
   and into a reused one (`out=`), each the median of three calls, alternating; then a Python
   loop over Pinocchio that discards its results (`pin.crba(model, data, Q[k])`) and one that
   stores them in a preallocated array (`out[k] = pin.crba(model, data, Q[k])`, what a user
   who keeps them writes). Reported: the medians over the rounds of the times and of the per-round ratios.

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
    ap.add_argument("--rounds", type=int, default=3, help="rounds of the batch comparison")
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
    for name, ours, theirs_one, shape in [
        ("rnea", lambda th, out=None: ur5.rnea(Q, V, A, threads=th, out=out),
         lambda k: pin.rnea(model, data, Q[k], V[k], A[k]), (n, 6)),
        ("crba", lambda th, out=None: ur5.crba(Q, threads=th, out=out),
         lambda k: pin.crba(model, data, Q[k]), (n, 6, 6)),
        ("aba", lambda th, out=None: ur5.aba(Q, V, T, threads=th, out=out),
         lambda k: pin.aba(model, data, Q[k], V[k], T[k]), (n, 6)),
    ]:
        out = np.empty(shape)
        rounds = []
        for _ in range(args.rounds):
            # screwdyn, three calls each, alternating, median: all cores and one thread, each
            # into a fresh array and into `out`.
            fresh, reused, one, one_reused = (statistics.median(t) for t in alternating(
                [lambda: ours(None), lambda: ours(None, out), lambda: ours(1), lambda: ours(1, out)], 3))
            # Python loops over Pinocchio on the same states (rows are NumPy views, as a user
            # writes it): results discarded, then stored.
            t0 = time.perf_counter()
            for k in range(n):
                theirs_one(k)
            pin_loop = time.perf_counter() - t0
            t0 = time.perf_counter()
            for k in range(n):
                out[k] = theirs_one(k)
            pin_store = time.perf_counter() - t0
            rounds.append({"all_cores": fresh, "all_cores_out": reused, "one_thread": one,
                           "one_thread_out": one_reused, "pinocchio_loop": pin_loop,
                           "pinocchio_loop_storing": pin_store})
        med = lambda f: statistics.median(f(r) for r in rounds)  # noqa: E731
        batch[name] = {
            "states": n,
            "screwdyn_all_cores_s": med(lambda r: r["all_cores"]),
            "screwdyn_all_cores_out_s": med(lambda r: r["all_cores_out"]),
            "screwdyn_one_thread_s": med(lambda r: r["one_thread"]),
            "screwdyn_one_thread_out_s": med(lambda r: r["one_thread_out"]),
            "pinocchio_python_loop_s": med(lambda r: r["pinocchio_loop"]),
            "pinocchio_python_loop_storing_s": med(lambda r: r["pinocchio_loop_storing"]),
            "vs_pinocchio_loop": med(lambda r: r["pinocchio_loop"] / r["all_cores"]),
            "out_vs_pinocchio_loop": med(lambda r: r["pinocchio_loop"] / r["all_cores_out"]),
            "vs_pinocchio_loop_storing": med(lambda r: r["pinocchio_loop_storing"] / r["all_cores"]),
            "out_vs_pinocchio_loop_storing": med(lambda r: r["pinocchio_loop_storing"] / r["all_cores_out"]),
            "vs_single_thread": med(lambda r: r["one_thread"] / r["all_cores"]),
            "out_vs_single_thread_out": med(lambda r: r["one_thread_out"] / r["all_cores_out"]),
            "rounds_s": rounds,
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
    print(f"\nBatch of {n} states (seconds; medians over {args.rounds} rounds of times and of "
          "per-round ratios)\n")
    print("| function | screwdyn, all cores (fresh / `out=`) | screwdyn, 1 thread (fresh / `out=`) "
          "| pinocchio loop (discarding / storing) | vs loop discarding (fresh / `out=`) "
          "| vs loop storing (fresh / `out=`) | vs 1 thread (fresh / `out=`) |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for k, r in batch.items():
        print(f"| {k} | {r['screwdyn_all_cores_s']:.3f} / {r['screwdyn_all_cores_out_s']:.3f} | "
              f"{r['screwdyn_one_thread_s']:.3f} / {r['screwdyn_one_thread_out_s']:.3f} | "
              f"{r['pinocchio_python_loop_s']:.3f} / {r['pinocchio_python_loop_storing_s']:.3f} | "
              f"{r['vs_pinocchio_loop']:.1f}× / {r['out_vs_pinocchio_loop']:.1f}× | "
              f"{r['vs_pinocchio_loop_storing']:.1f}× / {r['out_vs_pinocchio_loop_storing']:.1f}× | "
              f"{r['vs_single_thread']:.2f}× / {r['out_vs_single_thread_out']:.2f}× |")
    if args.json:
        args.json.write_text(json.dumps(info, indent=2))


if __name__ == "__main__":
    main()
