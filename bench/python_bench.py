#!/usr/bin/env python3
"""Side-by-side benchmark of the Python package against Pinocchio's Python bindings, in one run
(recorded in BENCHMARKS.md, "Issue 31: from Python").

    bash bench/python_bench.sh                 # builds the extension, makes the venv, runs this
    python3 bench/python_bench.py              # from the repository root (pip-installs screwdyn)
    python3 bench/python_bench.py --states 100000 --no-venv

Both libraries load the same robot files, example-robot-data's UR5 and Panda URDFs (the files
bench/compare.sh uses). Measured:

1. per-call time from Python of one state, on UR5 and Panda, screwdyn against Pinocchio:
   `m.rnea(q, v, a)` / `pin.rnea(model, data, q, v, a)`, `m.aba(q, v, tau)` / `pin.aba(…)`,
   `m.crba(q)` / `pin.crba(model, data, q)`, `m.frame_pose(q, f)` /
   `pin.forwardKinematics(model, data, q); pin.updateFramePlacement(model, data, f)` and
   `m.frame_jacobian(q, f, "world")` / `pin.computeFrameJacobian(model, data, q, f, pin.WORLD)`
   (the tip frame, by index on both sides); loops of `--calls` calls, the two alternating,
   `--repeats` times; reported: medians, bests, and the median of the per-repeat ratios
   screwdyn / Pinocchio (below 1: screwdyn faster);
2. batch throughput on N = 10⁶ UR5 states, in rounds (`--rounds`) so that every ratio compares
   times taken within a few seconds of each other: screwdyn's batched call (all cores, GIL
   released) and with `threads=1` (our own single-thread Rust loop), each into a fresh array
   and into a reused one (`out=`), each the median of three calls, alternating; then a Python
   loop over Pinocchio that discards its results (`pin.rnea(model, data, Q[k], V[k], A[k])`) and
   one that stores them in a preallocated array (`out[k] = pin.rnea(…)`, what a user who keeps
   them writes). Reported: the medians over the rounds of the times and of the per-round ratios.

The machine's load average (`os.getloadavg`, what `uptime` prints) is recorded at the start and
at the end: other processes on the machine change every absolute number, and the ratios less.

Without Pinocchio in the current interpreter, the script creates .venv-pybench/ in the
repository root (git-ignored), installs `pin`, `example-robot-data`, numpy and screwdyn (`pip
install ./crates/screwdyn-py`, release build) there and re-executes itself;
bench/python_bench.sh does the same with the extension built by cargo into target/bench-py.
"""

import argparse
import glob
import json
import os
import pathlib
import platform
import statistics
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
ROBOTS = {"ur5": "ur_description/urdf/ur5_robot.urdf", "panda": "panda_description/urdf/panda.urdf"}


def urdf(robot):
    """example-robot-data's file of `robot` in the running interpreter's environment."""
    pattern = os.path.join(sys.prefix, "lib", "python3*", "site-packages", "cmeel.prefix", "share",
                           "example-robot-data", "robots")
    found = glob.glob(pattern)
    if not found:
        sys.exit("example-robot-data is not installed in this environment (pip install example-robot-data)")
    return os.path.join(found[0], ROBOTS[robot])


def ensure_env(args):
    try:
        import example_robot_data  # noqa: F401
    except ImportError:
        pass
    try:
        import pinocchio  # noqa: F401
        import screwdyn  # noqa: F401
        urdf("ur5")
        return
    except (ImportError, SystemExit):
        if args.no_venv:
            raise
    venv = ROOT / ".venv-pybench"
    py = venv / "bin" / "python"
    if not py.exists():
        subprocess.check_call([sys.executable, "-m", "venv", str(venv)])
    subprocess.check_call([str(py), "-m", "pip", "install", "-q", "pin", "numpy", "example-robot-data"])
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


def per_call_cases(robot, np, pin, screwdyn, rng):
    """The five one-state calls on `robot`, each as (name, ours, theirs), after checking that the
    two libraries compute the same numbers on the same file."""
    path = urdf(robot)
    m = screwdyn.load(path)
    model = pin.buildModelFromUrdf(path)
    data = model.createData()
    assert model.nq == m.nq, "the two models differ"
    q, v, a = rng.uniform(-1, 1, m.nq), rng.normal(size=m.nq), rng.normal(size=m.nq)
    tip = model.frames[-1].name
    fid, ours_f = model.getFrameId(tip), m.frame_names.index(tip)
    tau = m.rnea(q, v, a)
    # same robot, same numbers (Pinocchio's joint order is the URDF's depth-first order too;
    # its crba fills the upper triangle)
    assert np.allclose(pin.rnea(model, data, q, v, a), tau, atol=1e-9), "the two models differ"
    assert np.allclose(np.triu(pin.crba(model, data, q)), np.triu(m.crba(q)), atol=1e-9)
    assert np.allclose(pin.aba(model, data, q, v, tau), a, atol=1e-8)
    pin.forwardKinematics(model, data, q)
    assert np.allclose(pin.updateFramePlacement(model, data, fid).homogeneous, m.frame_pose(q, ours_f), atol=1e-12)
    assert np.allclose(pin.computeFrameJacobian(model, data, q, fid, pin.WORLD)[[3, 4, 5, 0, 1, 2]],
                       m.frame_jacobian(q, ours_f, "world"), atol=1e-12)

    def pin_pose():
        pin.forwardKinematics(model, data, q)
        return pin.updateFramePlacement(model, data, fid)

    return [
        ("rnea", lambda: m.rnea(q, v, a), lambda: pin.rnea(model, data, q, v, a)),
        ("aba", lambda: m.aba(q, v, tau), lambda: pin.aba(model, data, q, v, tau)),
        ("crba", lambda: m.crba(q), lambda: pin.crba(model, data, q)),
        ("frame_pose", lambda: m.frame_pose(q, ours_f), pin_pose),
        ("frame_jacobian", lambda: m.frame_jacobian(q, ours_f, "world"),
         lambda: pin.computeFrameJacobian(model, data, q, fid, pin.WORLD)),
    ]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--states", type=int, default=1_000_000)
    ap.add_argument("--calls", type=int, default=5_000)
    ap.add_argument("--repeats", type=int, default=31)
    ap.add_argument("--rounds", type=int, default=3, help="rounds of the batch comparison")
    ap.add_argument("--no-venv", action="store_true")
    ap.add_argument("--json", type=pathlib.Path, help="also write the results as JSON")
    args = ap.parse_args()
    ensure_env(args)

    import numpy as np
    import pinocchio as pin

    import screwdyn

    load_at_start = os.getloadavg()
    rng = np.random.default_rng(1)

    def loop(f, n):
        def run():
            for _ in range(n):
                f()
        return run

    per_call = {}
    for robot in ROBOTS:
        for name, ours, theirs in per_call_cases(robot, np, pin, screwdyn, rng):
            t_ours, t_pin = alternating([loop(ours, args.calls), loop(theirs, args.calls)], args.repeats)
            per_call[f"{robot} {name}"] = {
                "screwdyn_ns": statistics.median(t_ours) * 1e9 / args.calls,
                "pinocchio_ns": statistics.median(t_pin) * 1e9 / args.calls,
                "ratio": ratio(t_ours, t_pin),
                "screwdyn_best_ns": min(t_ours) * 1e9 / args.calls,
                "pinocchio_best_ns": min(t_pin) * 1e9 / args.calls,
                "best_ratio": min(t_ours) / min(t_pin),
            }

    path = urdf("ur5")
    ur5 = screwdyn.load(path)
    model = pin.buildModelFromUrdf(path)
    data = model.createData()
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

    load_at_end = os.getloadavg()
    info = {
        "machine": f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}",
        "load_average_at_start": load_at_start,
        "load_average_at_end": load_at_end,
        "pinocchio": pin.__version__,
        "screwdyn": screwdyn.__version__,
        "models": {r: os.path.relpath(urdf(r), sys.prefix) for r in ROBOTS},
        "per_call": per_call,
        "batch": batch,
    }
    loads = lambda x: ", ".join(f"{v:.2f}" for v in x)  # noqa: E731
    print(f"{info['machine']}, pinocchio {info['pinocchio']}, example-robot-data URDFs; "
          f"load average (1, 5, 15 min) at start {loads(load_at_start)}, at end {loads(load_at_end)}\n")
    print(f"Per call from Python, one state (ns per call; {args.repeats} alternating loops of "
          f"{args.calls} calls; ratio < 1: screwdyn faster)\n")
    print("| robot, function | screwdyn (median / best) | pinocchio (median / best) "
          "| screwdyn / pinocchio (median of ratios) | (best / best) |")
    print("| --- | ---: | ---: | ---: | ---: |")
    for k, r in per_call.items():
        print(f"| {k} | {r['screwdyn_ns']:.0f} / {r['screwdyn_best_ns']:.0f} "
              f"| {r['pinocchio_ns']:.0f} / {r['pinocchio_best_ns']:.0f} | {r['ratio']:.2f} "
              f"| {r['best_ratio']:.2f} |")
    print(f"\nBatch of {n} UR5 states (seconds; medians over {args.rounds} rounds of times and of "
          "per-round ratios; ratio > 1: screwdyn faster)\n")
    print("| function | screwdyn, all cores (fresh / `out=`) | screwdyn, 1 thread (fresh / `out=`) "
          "| pinocchio loop (discarding / storing) | loop discarding / screwdyn (fresh / `out=`) "
          "| loop storing / screwdyn (fresh / `out=`) | 1 thread / all cores (fresh / `out=`) |")
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
