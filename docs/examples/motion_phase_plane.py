"""Draws docs/motion_phase_plane_ur5.png: the phase plane (s, ṡ) of the time-optimal timing of
the UR5 through docs/examples/ur5_waypoints.csv, with the speed limit curve and the limit that
is active at each grid point.

    python docs/examples/motion_phase_plane.py [OUT.png]
"""

import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import screwdyn  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent
out = sys.argv[1] if len(sys.argv) > 1 else str(HERE.parent / "motion_phase_plane_ur5.png")
ur5 = screwdyn.load("builtin:ur5")
points = np.loadtxt(HERE / "ur5_waypoints.csv", delimiter=",", skiprows=1)
timed = screwdyn.Trajectory.time_optimal(ur5, points)
s, sd, t = timed.phase_plane()
q, v, a = timed.sample(t)
tau = ur5.rnea(q, v, a)
vmax = np.full(6, 3.15)
effort = np.array([150.0, 150.0, 150.0, 28.0, 28.0, 28.0])
# q̇ = q'(s) ṡ, so the speed limit ṡ ≤ min_j vmax_j / |q'_j| is ṡ · min_j vmax_j / |q̇_j|.
with np.errstate(divide="ignore", invalid="ignore"):
    sd_max = np.where(sd > 0, sd * np.min(vmax / np.abs(v), axis=1), np.nan)
speed = np.max(np.abs(v) / vmax, axis=1)
torque = np.max(np.abs(tau) / effort, axis=1)

fig, ax = plt.subplots(figsize=(9, 4.5))
ax.plot(s, sd_max, color="0.6", lw=1, ls="--", label="speed limit: min_j vmax_j / |q'_j(s)|")
ax.plot(s, sd, color="k", lw=1.2, label="time-optimal ṡ(s)")
on_torque = torque > 0.999 - 1e-4
on_speed = (speed > 0.999 - 1e-4) & ~on_torque
ax.scatter(s[on_torque], sd[on_torque], s=6, color="tab:red", label="a torque limit active", zorder=3)
ax.scatter(s[on_speed], sd[on_speed], s=6, color="tab:blue", label="a speed limit active", zorder=3)
ax.set_xlabel("s (path parameter: joint-space chord length, rad)")
ax.set_ylabel("ṡ (1/s)")
ax.set_ylim(0, 1.15 * np.nanmax(sd))
ax.set_title(f"UR5 through 4 waypoints: the fastest timing, {timed.duration:.3f} s")
ax.grid(alpha=0.3)
ax.legend(loc="upper left", fontsize=8)
fig.tight_layout()
fig.savefig(out, dpi=110)
print(f"{out}: duration {timed.duration:.6f} s")
