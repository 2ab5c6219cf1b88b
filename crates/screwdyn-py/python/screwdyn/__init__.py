"""screwdyn: robot kinematics, dynamics and simulation in the screw-theory notation of the
lecture notes (twists and wrenches angular first, ``V = (ω, v)``, ``W = (m, f)``), for NumPy,
Jupyter and clusters.

>>> import screwdyn
>>> arm = screwdyn.load("builtin:planar2")
>>> arm.rnea([0.0, 0.0], [0.0, 0.0], [0.0, 0.0])   # seed 003: g(0) = [3 g, g]
array([29.43,  9.81])

Every per-state function takes one state (``q`` of shape ``(nq,)``) or ``N`` stacked states
(``(N, nq)``) and then returns stacked results, computed in Rust over all cores with the GIL
released. Bad shapes or values raise ``ValueError`` with the library's one-sentence message; a
bad robot file raises ``screwdyn.ModelError``. Models pickle, so they travel to worker processes
(see ``screwdyn.dask``). pandas, matplotlib and dask are optional and imported lazily.
"""

from __future__ import annotations

import math
from typing import Any, Callable, Dict, Iterable, List, Optional, Sequence, Union

import numpy as np

from . import _screwdyn
from ._screwdyn import Model, ModelError, Trajectory, builtin_names, load, load_string
from ._view import View
from . import _view
from ._results import (
    BaseParameters,
    ClosedForm,
    Identification,
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
    "View",
    "load",
    "load_string",
    "builtin_names",
]


# --------------------------------------------------------------------------- trajectories

def Trapezoid(q0, qf, vmax, amax, synchronised: bool = True) -> Trajectory:
    """Trapezoidal velocity profiles from ``q0`` to ``qf`` under per-joint limits ``vmax``
    (rad/s) and ``amax`` (rad/s²); see :meth:`Trajectory.trapezoid`."""
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
    """PD control with gravity compensation, ``τ = Kp (q* − q) − Kd q̇ + g(q)``. Gains left
    ``None`` take the library's defaults, ``Kp = ω² M_ii(q*)``, ``Kd = 2ω M_ii(q*)`` (ω = 10
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
    link frame (``frame="local"``) or in the base frame (``frame="world"``)."""

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


def _controller_spec(controller):
    if controller is None or callable(controller) and not hasattr(controller, "_spec"):
        return controller
    if hasattr(controller, "_spec"):
        return controller._spec()
    return ("constant", np.asarray(controller, dtype=float))


# --------------------------------------------------------------------------- Model methods
# Defined in Python on top of the native methods: results wrapped in display classes and the
# keyword-argument front ends; no computation happens here.

def _closed_form(self, q, v=None) -> ClosedForm:
    """The seeds' closed form at one state ``(q, v)``: ``A(θ)``, ``L = (I − A)⁻¹``, ``S``, ``𝔍``,
    ``J = L S``, ``M = Sᵀ Lᵀ 𝔍 L S``, ``C``, ``g`` as arrays (a :class:`ClosedForm`)."""
    return ClosedForm(self, self._closed_form(q, v))


def _lagrange(self, q) -> LagrangeCoefficients:
    """Seed 004's Lagrangian coefficients at one state: ``D_ij`` (inertias), ``D_ijk``
    (Coriolis/centrifugal) and ``D_i`` (gravity), as a :class:`LagrangeCoefficients`."""
    return LagrangeCoefficients(self, self._lagrange(q))


def _trace(self, q, v=None, a=None, *, fext=None, fext_world=None, tip_wrenches=None) -> RneaTrace:
    """The recursive Newton–Euler algorithm of seeds 000/002 step by step at one state: the
    forward iterations (poses, twists, accelerations) and the backward ones (wrenches,
    torques), as an :class:`RneaTrace` that displays like the lecture in a notebook."""
    return RneaTrace(self._rnea_trace(q, v, a, fext=fext, fext_world=fext_world,
                                      tip_wrenches=tip_wrenches))


def _simulate(self, q0, v0=None, *, duration: float = 1.0, dt: float = 1e-3, controller=None,
              integrator: str = "rk4", rtol: float = 1e-8, atol: float = 1e-10,
              method: str = "aba", effects: Union[None, bool, Dict[str, Any]] = None,
              disturbances: Sequence[Disturbance] = (), record_every: int = 1,
              frames: Sequence[Union[str, int]] = (),
              progress: Optional[Callable[[float], None]] = None) -> SimResult:
    """Simulates the robot from ``(q0, v0)`` for ``duration`` seconds (seed 004 §6.4).

    controller: ``None`` (zero torque), an array (constant torque), :class:`PD`,
        :class:`ComputedTorque`, :class:`TorqueSeries`, or a callable ``f(t, q, v) -> tau``
        (called with the GIL held; an exception it raises stops the run and propagates).
    integrator: ``"euler"`` (semi-implicit), ``"rk4"`` or ``"dopri5"`` (adaptive, ``rtol``,
        ``atol``; ``dt`` is then the output interval).
    method: forward dynamics ``"aba"``, ``"crba"`` or ``"walker-orin"``.
    effects: joint effects added to the commanded torque: ``None``/``True`` for the library's
        defaults (effort saturation, viscous damping, smoothed Coulomb friction, position limits
        as stiff spring–dampers), ``False`` for none, or a dict of fields (``saturate``,
        ``damping``, ``friction``, ``position_limits``, ``friction_smoothing``,
        ``limit_time_constant``, ``limit_damping_ratio``).
    disturbances: :class:`Disturbance` wrenches on links during time windows.
    record_every: keep every k-th step; frames: frames whose poses are recorded.
    Returns a :class:`SimResult` (arrays ``t``, ``q``, ``v``, ``a``, ``tau``, energies, poses).
    """
    if v0 is None:
        v0 = np.zeros(self.nq)
    rec = self._simulate(q0, v0, _controller_spec(controller),
                         [d._spec() if isinstance(d, Disturbance) else d for d in disturbances],
                         float(duration), float(dt), integrator, float(rtol), float(atol), method,
                         effects, int(record_every), list(frames), progress)
    return SimResult(rec)


def _torque_profile(self, trajectory: Trajectory, dt: float = 0.01) -> TorqueProfile:
    """Inverse dynamics along ``trajectory`` every ``dt`` seconds (end included) — seed 003's
    "how much torque to accelerate from rest to a constant velocity and stop again" — with
    peak and RMS torque per joint against the effort limits (a :class:`TorqueProfile`)."""
    return TorqueProfile(self._torque_profile(trajectory, float(dt)))


def _rnea_derivatives(self, q, v, a, *, fext=None, fext_world=None, tip_wrenches=None,
                      threads=None):
    """First-order derivatives of the inverse dynamics ``τ = RNEA(q, v, a)`` (docs/derivatives.md):
    ``(dtau_dq, dtau_dv, M)`` with ``dtau_dq[i, j] = ∂τ_i/∂q_j``, ``dtau_dv = ∂τ/∂q̇`` and
    ``M = ∂τ/∂q̈``, each ``(nq, nq)`` — ``(N, nq, nq)`` for stacked states (views into one
    ``(N, 3, nq, nq)`` array). Computed analytically in one forward and one backward pass in the
    base frame (Lie brackets with the joint screws). External wrenches as in :meth:`rnea`:
    ``fext`` and ``tip_wrenches`` move with their link, ``fext_world`` stays fixed in space."""
    d = _screwdyn._rnea_derivatives(self, q, v, a, fext, fext_world, tip_wrenches, threads)
    return d[..., 0, :, :], d[..., 1, :, :], d[..., 2, :, :]


def _aba_derivatives(self, q, v, tau, *, fext=None, fext_world=None, tip_wrenches=None,
                     threads=None):
    """First-order derivatives of the forward dynamics ``q̈ = ABA(q, v, τ)``:
    ``(dqdd_dq, dqdd_dv, Minv)`` with ``∂q̈/∂q = −M⁻¹ ∂τ/∂q``, ``∂q̈/∂q̇ = −M⁻¹ ∂τ/∂q̇`` (at
    ``q̈ = ABA(q, v, τ)``) and ``Minv = M⁻¹ = ∂q̈/∂τ``, each ``(nq, nq)`` or ``(N, nq, nq)``.
    External wrenches as in :meth:`rnea`. A singular mass matrix raises ValueError."""
    d = _screwdyn._aba_derivatives(self, q, v, tau, fext, fext_world, tip_wrenches, threads)
    return d[..., 0, :, :], d[..., 1, :, :], d[..., 2, :, :]


def _regressor(self, q, v=None, a=None, *, threads=None):
    """The joint-torque regressor ``Y(q, q̇, q̈)``, ``(nq, 10 nq)`` (``(N, nq, 10 nq)``): the
    inverse dynamics (with gravity, no external wrench or friction) is linear in the standard
    parameters, ``rnea(q, v, a) = Y @ inertial_parameters()``. Columns ``10 k … 10 k + 9``
    belong to body ``k``: ``m, mx, my, mz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz`` (first moment and
    inertia about the body frame origin, body axes; names in :meth:`parameter_names`)."""
    z = np.zeros(self.nq)
    return _screwdyn._regressor(self, q, z if v is None else v, z if a is None else a, threads)


def _inertial_parameters(self, friction: bool = False) -> np.ndarray:
    """The standard parameters ``π`` of the model, ``(10 nq,)`` in the order of the
    regressor's columns (then ``fv``, ``fc`` per joint: the joints' damping and Coulomb
    friction, when ``friction=True``)."""
    return _screwdyn._inertial_parameters(self, bool(friction))


def _parameter_names(self, friction: bool = False) -> List[str]:
    """Names of the standard parameters: ``<parameter>_<link>`` (``m_link1``, ``Izz_link2``),
    then ``fv_<joint>``, ``fc_<joint>`` with ``friction``."""
    return _screwdyn._parameter_names(self, bool(friction))


def _base_parameters(self, friction: bool = False, *, states: int = 100,
                     seed: int = 1) -> BaseParameters:
    """The base (identifiable) parameters, found numerically from the regressor stacked at
    ``states`` random states (QR with column pivoting in a fixed preferred order; the same as
    ``screwdyn regressor --base``): a :class:`BaseParameters` with readable expressions and
    ``K`` (``π_b = K π``)."""
    return BaseParameters(_screwdyn._base_parameters(self, bool(friction), int(states), int(seed)))


def _identify(self, q, v, a, tau, *, friction: bool = False, states: int = 100,
              seed: int = 1) -> Identification:
    """Least-squares identification of the base parameters from stacked samples ``q``, ``v``,
    ``a``, ``tau`` of shape ``(N, nq)`` (the library's streaming QR, as ``screwdyn identify``):
    an :class:`Identification` with the estimates, their standard deviations, ``sigma`` and
    the condition number. ``friction=True`` adds ``fv q̇ + fc sign(q̇)`` per joint. Raises
    ValueError for too few samples or a log that does not excite every base parameter
    (condition number above 1e10), naming it."""
    return Identification(_screwdyn._identify(self, q, v, a, tau, bool(friction), int(states),
                                              int(seed)))


for _name, _f in {
    "closed_form": _closed_form,
    "lagrange_coefficients": _lagrange,
    "rnea_trace": _trace,
    "simulate": _simulate,
    "torque_profile": _torque_profile,
    "rnea_derivatives": _rnea_derivatives,
    "aba_derivatives": _aba_derivatives,
    "regressor": _regressor,
    "inertial_parameters": _inertial_parameters,
    "parameter_names": _parameter_names,
    "base_parameters": _base_parameters,
    "identify": _identify,
    "view": _view.view,
}.items():
    _f.__name__ = _name
    _f.__qualname__ = f"Model.{_name}"
    setattr(Model, _name, _f)


# Pinocchio-style aliases.
Model.inverse_dynamics = Model.rnea
Model.mass_matrix = Model.crba


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
del _name, _f
