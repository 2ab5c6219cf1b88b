"""A notebook-style walk through screwdyn from Python (run it as a script or paste the cells
into Jupyter):

1. the classic two-link planar arm: the stacked closed form M(θ), C(θ, θ̇), g(θ) (notation of
   docs/notation.md) against the textbook formulas, the step-by-step RNEA trace, a simulation with a plot and its 3-D
   animation, the same M(θ) symbolically (SymPy) and the derivatives of the dynamics;
2. a UR5 log: inverse dynamics and mass matrices of a batch of recorded states in one call.

Writes two_link_simulation.png (when matplotlib is installed) and two_link_run.html into the
working directory or into the directory given as the first argument.
"""

import math
import pathlib
import sys
import time

import numpy as np

import screwdyn

out_dir = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(".")

# %% 1. The two-link planar arm: m1 = m2 = 1 kg at the link ends, L1 = L2 = 1 m,
# gravity along −y.
arm = screwdyn.load("builtin:planar2")
print(arm)

q = np.array([0.3, 0.5])
qd = np.array([1.0, -1.0])
qdd = np.array([0.5, 0.2])

# %% The stacked closed form: M = Sᵀ Lᵀ 𝔍 L S, C, g as arrays.
cf = arm.closed_form(q, qd)
m1 = m2 = L1 = L2 = 1.0
c2, s2 = math.cos(q[1]), math.sin(q[1])
M_hand = np.array([[m1 * L1**2 + m2 * (L1**2 + 2 * L1 * L2 * c2 + L2**2), m2 * (L1 * L2 * c2 + L2**2)],
                   [m2 * (L1 * L2 * c2 + L2**2), m2 * L2**2]])
print("M(θ) from the closed form:\n", cf.M)
print("M(θ) by hand (textbook):\n", M_hand)
assert np.allclose(cf.M, M_hand, atol=1e-12)
h = m2 * L1 * L2 * s2
print("C(θ, θ̇) θ̇ =", cf.C @ qd, " by hand:", [-h * qd[1] ** 2 - 2 * h * qd[0] * qd[1], h * qd[0] ** 2])

# %% The Lagrangian coefficients and effective inertias.
lc = arm.lagrange_coefficients(q)
print("D_ijk[0] =\n", lc.D_ijk[0])
print("effective inertia of joint 1, joint 2 locked:", arm.effective_inertia(q, "joint1"),
      " joint 2 free:", arm.effective_inertia(q, "joint1", free="all"))

# %% The recursive Newton–Euler algorithm, iteration by iteration (in Jupyter, just evaluate
# `trace` to see it typeset like the lecture).
trace = arm.rnea_trace(q, qd, qdd)
print(trace)
assert np.allclose(trace.tau, arm.rnea(q, qd, qdd))

# %% Simulate: PD with gravity compensation brings the arm from rest to (0.5, −0.3).
run = arm.simulate([0.0, 0.0], duration=3.0, dt=1e-3,
                   controller=screwdyn.PD([0.5, -0.3], kp=[100, 100], kd=[40, 40]),
                   record_every=10)
print(run, "final q =", run.q[-1])
try:
    import matplotlib

    matplotlib.use("Agg")
    fig = run.plot(("q", "tau", "energy"))
    fig.savefig(out_dir / "two_link_simulation.png", dpi=80)
    print("plot written to", out_dir / "two_link_simulation.png")
except ImportError:
    print("(install matplotlib for the plot: pip install screwdyn[plot])")

# A Python function as controller: gravity compensation only, so the arm stays where it is.
hold = arm.simulate([0.4, 0.2], duration=0.5, controller=lambda t, q, v: arm.gravity_torque(q),
                    effects=False)
print("held at", hold.q[-1])

# %% See it: the run as a 3-D animation (in Jupyter, evaluate `view` to show it inline).
view = arm.view(run=run)
view.save(out_dir / "two_link_run.html")
print(view, "written to", out_dir / "two_link_run.html")

# %% The same equations symbolically (needs SymPy: pip install screwdyn[sympy]).
try:
    import sympy

    import screwdyn.symbolic as sym

    M_sym = sym.mass_matrix(arm, symbols="all")
    m1, m2, L1, L2 = sympy.symbols("m1 m2 L1 L2")
    c2 = sympy.cos(sympy.Symbol("theta2"))
    by_hand = m1 * L1**2 + m2 * (L1**2 + 2 * L1 * L2 * c2 + L2**2)
    print("M11 =", M_sym[0, 0], " (by hand:", by_hand, ")")
    assert sympy.expand(M_sym[0, 0] - by_hand) == 0
    print("g(θ) =", list(sym.gravity_torque(arm, symbols="all")))
except ImportError:
    print("(install SymPy for the symbolic equations: pip install screwdyn[sympy])")

# %% Derivatives of the dynamics for optimal control: ∂τ/∂q, ∂τ/∂q̇ and M in one pass.
dtau_dq, dtau_dv, M_d = arm.rnea_derivatives(q, qd, qdd)
print("∂τ/∂q =\n", dtau_dq)
assert np.allclose(dtau_dv, 2 * arm.coriolis_matrix(q, qd)) and np.allclose(M_d, cf.M)

# %% 2. A UR5 log: one row per recorded state (here synthetic: 200 000 states of a slow sweep).
ur5 = screwdyn.load("builtin:ur5")
t = np.linspace(0.0, 100.0, 200_000)
log_q = 0.8 * np.sin(np.outer(t, [0.3, 0.5, 0.7, 1.1, 1.3, 1.7]))
log_v = np.gradient(log_q, t, axis=0)
log_a = np.gradient(log_v, t, axis=0)

start = time.perf_counter()
tau = ur5.rnea(log_q, log_v, log_a)          # (N, 6), all cores, GIL released
M = ur5.crba(log_q)                          # (N, 6, 6)
elapsed = time.perf_counter() - start
print(f"UR5 log: {len(t)} states, inverse dynamics and mass matrices in {elapsed:.3f} s")
print("peak |τ| per joint:", np.round(np.max(np.abs(tau), axis=0), 3))
print("within effort limits:", bool(np.all(np.abs(tau) <= ur5.effort_limits)))
# a batch row is the per-state call, to round-off (the batch kernels fuse multiply-adds)
one = ur5.rnea(log_q[1234], log_v[1234], log_a[1234])
assert np.allclose(tau[1234], one, rtol=0, atol=1e-12 * np.max(np.abs(one)))
try:
    df = screwdyn.load("builtin:ur5").simulate(log_q[0], duration=0.01).to_dataframe()
    print(df.iloc[:3, :4])
except ImportError:
    pass
