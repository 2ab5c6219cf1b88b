"""screwdyn: robot kinematics, dynamics and simulation in screw-theory notation (docs/notation.md:
twists and wrenches angular first, ``V = (ω, v)``, ``W = (m, f)``, as in Lynch & Park's *Modern
Robotics*), for NumPy, Jupyter and clusters.

>>> import screwdyn
>>> arm = screwdyn.load("builtin:planar2")
>>> arm.rnea([0.0, 0.0], [0.0, 0.0], [0.0, 0.0])   # two-link arm: g(0) = [3 g, g]
array([29.43,  9.81])

Every per-state function takes one state (``q`` of shape ``(nq,)``) or ``N`` stacked states
(``(N, nq)``) and then returns stacked results, computed in Rust over all cores with the GIL
released. Bad shapes or values raise ``ValueError`` with the library's one-sentence message; a
bad robot file raises ``screwdyn.ModelError``. Models pickle, so they travel to worker processes
(see ``screwdyn.dask``). pandas, matplotlib and dask are optional and imported lazily.
"""

from __future__ import annotations

import math

import numpy as np

from . import _screwdyn, se3
from ._screwdyn import Model, ModelError, Trajectory, builtin_names, load, load_string
from ._view import View
from ._results import (
    BaseParameters,
    ClosedForm,
    Identification,
    IkResult,
    LagrangeCoefficients,
    RneaTrace,
    SimResult,
    TorqueProfile,
)

__version__ = _screwdyn.__version__

__all__ = [
    "Model",
    "ModelError",
    "Trajectory",
    "Trapezoid",
    "Quintic",
    "Waypoints",
    "PD",
    "ComputedTorque",
    "TorqueSeries",
    "ConstantTorque",
    "Disturbance",
    "ClosedForm",
    "LagrangeCoefficients",
    "RneaTrace",
    "SimResult",
    "TorqueProfile",
    "BaseParameters",
    "Identification",
    "IkResult",
    "View",
    "load",
    "load_string",
    "builtin_names",
    "se3",
]


# --------------------------------------------------------------------------- trajectories

def Trapezoid(q0, qf, vmax, amax, synchronised: bool = True) -> Trajectory:
    """Trapezoidal velocity profiles from ``q0`` to ``qf`` under per-joint limits ``vmax``
    (rad/s) and ``amax`` (rad/s²), each one value per joint or one number for every joint (as
    ``Trapezoid(q0, qf, vmax=1.0, amax=2.0)``); see :meth:`Trajectory.trapezoid`."""
    return Trajectory.trapezoid(q0, qf, vmax, amax, synchronised)


def Quintic(q0, qf, duration: float, v0=None, vf=None, a0=None, af=None) -> Trajectory:
    """Quintic polynomials from ``(q0, v0, a0)`` to ``(qf, vf, af)`` in ``duration`` seconds;
    see :meth:`Trajectory.quintic`."""
    return Trajectory.quintic(q0, qf, duration, v0, vf, a0, af)


def Waypoints(times, points) -> Trajectory:
    """Piecewise quintics through ``points`` ``(K, nq)`` at ``times`` ``(K,)``; see
    :meth:`Trajectory.waypoints`."""
    return Trajectory.waypoints(times, points)


# --------------------------------------------------------------------------- controllers
# Each describes itself by ``_spec()`` as ``(kind, arguments…)``, which the native
# ``Model.simulate`` reads (and ``Disturbance`` as ``(link, wrench, start, end, in_world)``).

class ConstantTorque:
    """A constant joint torque (N·m / N)."""

    def __init__(self, tau):
        self.tau = np.asarray(tau, dtype=float)

    def _spec(self):
        return ("constant", self.tau)

    def __repr__(self):
        return f"ConstantTorque({self.tau.tolist()})"


def _gains(x):
    return None if x is None else np.asarray(x, dtype=float)


def _list(x):
    return None if x is None else x.tolist()


class PD:
    """PD control with gravity compensation, ``τ = Kp (q* − q) − Kd q̇ + g(q)``; the target and
    the gains are one value per joint or one number for every joint. Gains left ``None`` take the library's defaults, ``Kp = ω² M_ii(q*)``, ``Kd = 2ω M_ii(q*)`` (ω = 10
    rad/s: each joint critically damped)."""

    def __init__(self, target, kp=None, kd=None):
        self.target = np.asarray(target, dtype=float)
        self.kp = _gains(kp)
        self.kd = _gains(kd)

    def _spec(self):
        return ("pd", self.target, self.kp, self.kd)

    def __repr__(self):
        return f"PD(target={self.target.tolist()}, kp={_list(self.kp)}, kd={_list(self.kd)})"


class ComputedTorque:
    """Computed-torque control tracking ``reference`` (a :class:`Trajectory`):
    ``τ = RNEA(q, q̇, q̈_d + Kd (q̇_d − q̇) + Kp (q_d − q))``. Gains left ``None`` take the
    library's defaults ``Kp = ω²``, ``Kd = 2ω`` (ω = 10 rad/s)."""

    def __init__(self, reference: Trajectory, kp=None, kd=None):
        if not isinstance(reference, Trajectory):
            raise TypeError("ComputedTorque needs a screwdyn.Trajectory as reference")
        self.reference = reference
        self.kp = _gains(kp)
        self.kd = _gains(kd)

    def _spec(self):
        return ("computed_torque", self.reference, self.kp, self.kd)

    def __repr__(self):
        return f"ComputedTorque({self.reference!r}, kp={_list(self.kp)}, kd={_list(self.kd)})"


class TorqueSeries:
    """Torques interpolated linearly between samples ``values`` ``(K, nq)`` at ``times``."""

    def __init__(self, times, values):
        self.times = np.asarray(times, dtype=float)
        self.values = np.asarray(values, dtype=float)

    def _spec(self):
        return ("series", self.times, self.values)

    def __repr__(self):
        return f"TorqueSeries({len(self.times)} samples)"


class Disturbance:
    """An external wrench ``(m, f)`` on ``link`` during ``[start, end)`` seconds, written in the
    link frame (``frame="local"``) or in the base frame (``frame="world"``). ``link`` is a link
    name (one attached by a fixed joint included) or an index in ``Model.link_names``."""

    def __init__(self, link, wrench, start: float = 0.0, end: float = math.inf, frame: str = "local"):
        if frame not in ("local", "world"):
            raise ValueError(f"a disturbance is written in the 'local' or 'world' frame, not '{frame}'")
        self.link = link
        self.wrench = np.asarray(wrench, dtype=float)
        self.start = float(start)
        self.end = float(end)
        self.frame = frame

    def _spec(self):
        return (self.link, self.wrench, self.start, self.end, self.frame == "world")

    def __repr__(self):
        return (f"Disturbance({self.link!r}, {self.wrench.tolist()}, start={self.start}, "
                f"end={self.end}, frame={self.frame!r})")


# --------------------------------------------------------------------------- functions
# ``screwdyn.rnea(model, q, v, a)`` etc., for those who write Pinocchio-style code.

def _functional(name):
    def f(model: Model, *args, **kwargs):
        return getattr(model, name)(*args, **kwargs)

    f.__name__ = name
    f.__qualname__ = name
    f.__doc__ = (f"``screwdyn.{name}(model, ...)`` is ``model.{name}(...)``.\n\n"
                 + (getattr(Model, name).__doc__ or ""))
    return f


_FUNCTIONS = [
    "frame_pose", "frame_poses", "frame_jacobian", "link_jacobian", "frame_twist",
    "frame_acceleration", "frame_jdot_qdot", "rnea", "inverse_dynamics", "crba", "mass_matrix",
    "mass_matrix_inverse", "coriolis_matrix", "gravity_torque", "nonlinear_effects",
    "forward_dynamics", "aba", "kinetic_energy", "potential_energy", "total_energy", "power",
    "center_of_mass", "closed_form", "lagrange_coefficients", "mass_matrix_derivatives",
    "effective_inertia", "rnea_trace", "simulate", "torque_profile", "rnea_derivatives",
    "aba_derivatives", "regressor", "inertial_parameters", "parameter_names", "base_parameters",
    "identify", "view",
]
for _name in _FUNCTIONS:
    globals()[_name] = _functional(_name)
__all__ += _FUNCTIONS
del _name
