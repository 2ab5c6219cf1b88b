"""Time-optimal and jerk-limited timing side by side with toppra and Ruckig (issue 27).

Run through bench/motion_venv.sh (a throwaway venv with toppra, ruckig and pin from PyPI, and
the release build of the extension). For UR5 and Panda paths of 3–5 waypoints (the not-a-knot
cubic spline through them in the joint-space chord length, the same for both: toppra's
SplineInterpolator is scipy's CubicSpline, whose default ends are not-a-knot), within each
robot's joint velocity and effort limits (and the Panda's published acceleration limits):

- the duration of screwdyn's timing on a grid of 1000 intervals and refined (its default), and
  of toppra's at 250, 1000 and 4000 grid intervals (toppra with the interpolation
  discretization, torque from Pinocchio's RNEA on the same robot exported as URDF);
- the largest torque, as a fraction of the limit, along each result sampled every 0.1 ms
  (Pinocchio's RNEA for both): how far each goes over a limit between its grid points;
- the computation time in-process (median of 5), and of the whole CLI run of screwdyn, as CPU
  time (the machine is shared).

Then Ruckig against Trajectory.jerk_limited on random rest-to-rest UR5 motions: durations
(equal to 1e-6 s) and time per call.
"""

import resource
import subprocess
import sys
import tempfile
import time

import numpy as np
import pinocchio as pin
import ruckig
import toppra as ta
import toppra.algorithm as algo
import toppra.constraint as constraint

import screwdyn

ta.setup_logging("WARNING")

PATHS = {
    "ur5": {
        "3 waypoints": [[0.0, -1.57, 1.57, -1.57, -1.57, 0.0],
                        [1.0, -1.0, 1.0, -1.0, -1.2, 0.8],
                        [2.0, -1.5, 2.0, -2.0, -1.0, 1.5]],
        "4 waypoints": [[0.0, -1.8, 1.4, -1.2, -1.6, 0.0],
                        [0.8, -1.2, 1.0, -1.4, -1.6, 0.5],
                        [1.6, -1.6, 1.8, -1.0, -1.2, 1.0],
                        [2.2, -1.0, 1.2, -1.6, -1.6, 0.3]],
        "5 waypoints": [[-1.0, -2.0, 2.0, -1.5, -1.5, 0.0],
                        [-0.3, -1.5, 1.2, -1.0, -1.2, 0.6],
                        [0.4, -1.0, 0.6, -0.8, -1.6, 1.2],
                        [1.0, -1.4, 1.5, -1.6, -2.0, 0.4],
                        [1.8, -0.8, 0.8, -1.2, -1.4, -0.4]],
    },
    "panda": {
        "3 waypoints": [[0.0, -0.5, 0.0, -2.0, 0.0, 1.5, 0.8],
                        [0.8, 0.2, -0.3, -1.5, 0.4, 2.0, 0.2],
                        [1.5, -0.3, 0.3, -2.4, -0.3, 1.8, -0.5]],
        "5 waypoints": [[-1.0, -0.3, 0.2, -2.2, 0.1, 1.6, 0.0],
                        [-0.4, 0.3, -0.2, -1.6, 0.5, 2.2, 0.6],
                        [0.2, 0.0, 0.3, -2.0, -0.2, 1.4, 1.2],
                        [0.8, -0.4, -0.1, -2.6, 0.3, 1.9, 0.4],
                        [1.4, 0.2, 0.2, -1.8, -0.4, 2.4, -0.3]],
    },
}
PANDA_AMAX = [15.0, 7.5, 10.0, 12.5, 15.0, 20.0, 20.0]
SAMPLE = 1e-4
EXE = sys.argv[1] if len(sys.argv) > 1 else "target/release/screwdyn"


def median_time(f, n=5):
    """Median CPU time (s) of this process and its children over n calls, and the last result:
    CPU time, not wall time, because the benchmark machine is shared (a wall clock counts the
    time other processes hold the cores)."""
    def cpu():
        own = time.process_time()
        kids = resource.getrusage(resource.RUSAGE_CHILDREN)
        return own + kids.ru_utime + kids.ru_stime
    times, out = [], None
    for _ in range(n):
        t0 = cpu()
        out = f()
        times.append(cpu() - t0)
    return float(np.median(times)), out


def pinocchio_model(name):
    urdf = subprocess.run([EXE, "export", f"builtin:{name}", "--to", "urdf"],
                          check=True, capture_output=True, text=True).stdout
    model = pin.buildModelFromXML(urdf)
    return model, model.createData()


def chord(points):
    d = np.linalg.norm(np.diff(points, axis=0), axis=1)
    return np.concatenate([[0.0], np.cumsum(d)])


def worst_torque(model, data, effort, q, v, a):
    """max over samples and joints of |τ_j| / τmax_j, τ by Pinocchio's RNEA."""
    worst = 0.0
    for k in range(len(q)):
        tau = pin.rnea(model, data, q[k], v[k], a[k])
        worst = max(worst, float(np.max(np.abs(tau) / effort)))
    return worst


def toppra_timing(model, data, points, vmax, amax, effort, intervals):
    ss = chord(points)
    path = ta.SplineInterpolator(ss, points)
    cons = []
    if np.all(np.isfinite(vmax)):
        cons.append(constraint.JointVelocityConstraint(np.column_stack([-vmax, vmax])))
    if amax is not None:
        cons.append(constraint.JointAccelerationConstraint(np.column_stack([-amax, amax])))
    cons.append(constraint.JointTorqueConstraint(
        lambda q, qd, qdd: pin.rnea(model, data, q, qd, qdd),
        np.column_stack([-effort, effort]), np.zeros(len(effort)),
        discretization_scheme=constraint.DiscretizationType.Interpolation))
    instance = algo.TOPPRA(cons, path, gridpoints=np.linspace(ss[0], ss[-1], intervals + 1),
                           parametrizer="ParametrizeConstAccel")
    return instance.compute_trajectory(0, 0)


def topp_rows():
    print("| robot | path | limits | screwdyn 1000 (s) | screwdyn refined (s, grid) | toppra 250 / 1000 / 4000 (s) "
          "| duration vs toppra 1000 | max τ/τmax − 1, screwdyn | max τ/τmax − 1, toppra 1000 "
          "| CPU screwdyn 1000 (ms) | CPU toppra 1000 (ms) | ratio | CLI run, CPU (ms) | CLI / toppra |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for name, paths in PATHS.items():
        robot = screwdyn.load(f"builtin:{name}")
        model, data = pinocchio_model(name)
        effort = np.array(model.effortLimit)
        vmax = np.array(model.velocityLimit)
        amax = np.array(PANDA_AMAX) if name == "panda" else None
        # The two models agree: RNEA at a random state.
        rng = np.random.default_rng(1)
        q, v, a = (rng.uniform(-1, 1, model.nq) for _ in range(3))
        assert np.allclose(robot.rnea(q, v, a), pin.rnea(model, data, q, v, a), atol=1e-9)
        cases = [(label, pts, True) for label, pts in paths.items()]
        cases += [(label, pts, False) for label, pts in list(paths.items())[:2]]
        model_vmax = vmax
        for label, pts, with_speed in cases:
            pts = np.array(pts)
            vmax = model_vmax if with_speed else np.full(len(model_vmax), np.inf)
            kw = dict(vmax=vmax, effort=effort)
            if amax is not None:
                kw["amax"] = amax
            ours_t, ours = median_time(lambda: screwdyn.Trajectory.time_optimal(robot, pts, grid=1000, **kw))
            refined = screwdyn.Trajectory.time_optimal(robot, pts, **kw)
            grid_refined = len(refined.phase_plane()[0]) - 1
            theirs_t, theirs = median_time(lambda: toppra_timing(model, data, pts, vmax, amax, effort, 1000))
            conv = [toppra_timing(model, data, pts, vmax, amax, effort, n).duration for n in (250, 4000)]
            ts = np.arange(0.0, ours.duration, SAMPLE)
            w_ours = worst_torque(model, data, effort, *ours.sample(ts))
            ts_t = np.arange(0.0, theirs.duration, SAMPLE)
            w_theirs = worst_torque(model, data, effort, theirs(ts_t), theirs(ts_t, 1), theirs(ts_t, 2))
            with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
                names = [model.names[j] for j in range(1, model.njoints)]
                f.write(",".join(f"q.{n}" for n in names) + "\n")
                for p in pts:
                    f.write(",".join(repr(float(x)) for x in p) + "\n")
            cli = [EXE, "torque-profile", f"builtin:{name}", "--trajectory", "time-optimal",
                   "--waypoints", f.name, "--grid", "1000", "--format", "json"]
            if not with_speed:
                cli += ["--vmax", "inf"]
            if amax is not None:
                cli += ["--amax", ",".join(map(str, amax))]
            cli_t, _ = median_time(lambda: subprocess.run(cli, check=True, capture_output=True))
            limits = ("speed, " if with_speed else "") + ("accel., " if amax is not None else "") + "torque"
            print(f"| {name} | {label} | {limits} | {ours.duration:.4f} | {refined.duration:.4f} ({grid_refined}) "
                  f"| {conv[0]:.4f} / {theirs.duration:.4f} / {conv[1]:.4f} "
                  f"| {100 * (ours.duration / theirs.duration - 1):+.3f} % "
                  f"| {100 * (w_ours - 1):+.4f} % | {100 * (w_theirs - 1):+.4f} % | {1e3 * ours_t:.2f} | {1e3 * theirs_t:.1f} "
                  f"| {ours_t / theirs_t:.3f} | {1e3 * cli_t:.1f} | {cli_t / theirs_t:.3f} |")


def ruckig_rows(cases=20):
    rng = np.random.default_rng(7)
    dof = 6
    worst, t_ours, t_theirs = 0.0, [], []
    for _ in range(cases):
        q0, qf = rng.uniform(-3, 3, dof), rng.uniform(-3, 3, dof)
        vmax, amax, jmax = rng.uniform(1, 4, dof), rng.uniform(2, 20, dof), rng.uniform(10, 200, dof)
        inp = ruckig.InputParameter(dof)
        inp.current_position, inp.target_position = list(q0), list(qf)
        inp.current_velocity = inp.current_acceleration = [0.0] * dof
        inp.target_velocity = inp.target_acceleration = [0.0] * dof
        inp.max_velocity, inp.max_acceleration, inp.max_jerk = list(vmax), list(amax), list(jmax)
        otg, traj = ruckig.Ruckig(dof), ruckig.Trajectory(dof)
        t0 = time.process_time()
        for _ in range(100):
            otg.calculate(inp, traj)
        t_theirs.append((time.process_time() - t0) / 100)
        t0 = time.process_time()
        for _ in range(100):
            ours = screwdyn.Trajectory.jerk_limited(q0, qf, vmax, amax, jmax)
        t_ours.append((time.process_time() - t0) / 100)
        worst = max(worst, abs(ours.duration - traj.duration))
    print(f"\nRuckig, {cases} random rest-to-rest UR5-sized motions (6 joints): largest duration "
          f"difference {worst:.2e} s; per call screwdyn {1e6 * np.median(t_ours):.1f} µs, "
          f"Ruckig {1e6 * np.median(t_theirs):.1f} µs (medians, Python calls included)")


if __name__ == "__main__":
    from importlib.metadata import version
    print(f"toppra {version('toppra')}, ruckig {version('ruckig')}, pin {version('pin')}\n")
    topp_rows()
    ruckig_rows()
