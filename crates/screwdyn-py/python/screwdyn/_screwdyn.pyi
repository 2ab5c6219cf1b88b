"""Type stubs of the native module screwdyn._screwdyn (re-exported by ``screwdyn``).

Conventions: float64 NumPy arrays in model joint order; a per-joint parameter (limits, gains,
damping, friction, a trajectory's end points) is one value per joint or one number for all; one state ``(nq,)`` or ``N`` stacked
states ``(N, nq)`` (a single argument is broadcast against stacked ones); twists and wrenches
angular first ``(ω, v)`` / ``(m, f)``; SI units and radians. ``threads=None`` uses all cores,
``threads=1`` the calling thread only. ``out=`` (NumPy's convention) takes a float64,
C-contiguous, writeable array of exactly the result's shape that shares no memory with the
inputs; the result is written into it and it is returned (no fresh allocation, for logs
processed chunk after chunk). Its contents are unspecified after an error.
"""

import os
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from ._results import (BaseParameters, ClosedForm, Identification, IkResult, LagrangeCoefficients,
                       RneaTrace, SimResult, TorqueProfile)
from ._view import View

ArrayLike = npt.ArrayLike
FloatArray = npt.NDArray[np.float64]
FrameRef = Union[str, int]
Wrenches = Mapping[Union[str, int], ArrayLike]

__version__: str

class ModelError(ValueError):
    """A robot description that cannot be loaded; the message names the file and line."""

def load(path_or_builtin: Union[str, os.PathLike[str]], *, strict: bool = False) -> Model:
    """Loads a .urdf / .toml (dh, modified-dh, poe, screwdyn) file or ``builtin:<name>``."""

def load_string(text: str, format: Optional[str] = None, *, name: str = "<string>",
                strict: bool = False) -> Model:
    """Loads a description from text; ``format`` is ``"urdf"`` or ``"toml"`` (guessed if None)."""

def builtin_names() -> List[str]: ...

VIEW_DEFAULT_MAX_TRIANGLES: int
VIEW_DEFAULT_MAX_SAMPLES: int
SYMBOLIC_DEFAULT_MAX_TERMS: int

# Private entry points of the Python layer (screwdyn.symbolic, SimResult.save, View.save); use
# those instead.
def _symbolic_derive(model: Model, quantity: str, symbols: str, frame: Optional[FrameRef],
                     reference_frame: str, coriolis: str, max_terms: int) -> Dict[str, Any]: ...
def _save_recording(path: str, result: Union[SimResult, TorqueProfile]) -> None: ...
def _write_text_atomically(path: str, text: str) -> None: ...
# The native half of screwdyn.se3 (use that module).
def _se3_exp(twist: ArrayLike) -> FloatArray: ...
def _se3_log(H: ArrayLike) -> FloatArray: ...
def _se3_adjoint(H: ArrayLike) -> FloatArray: ...
def _se3_ad(twist: ArrayLike) -> FloatArray: ...
def _se3_inverse(H: ArrayLike) -> FloatArray: ...
def _se3_from_quaternion(q: ArrayLike, translation: Optional[ArrayLike] = None) -> FloatArray: ...
def _se3_to_quaternion(H: ArrayLike) -> FloatArray: ...
def _se3_from_rpy(rpy: ArrayLike, translation: Optional[ArrayLike] = None) -> FloatArray: ...
def _se3_to_rpy(H: ArrayLike) -> FloatArray: ...

class Model:
    """A robot model (immutable except for ``gravity``); pickles."""

    name: str
    nq: int
    nv: int
    nbodies: int
    joint_names: List[str]
    joint_types: List[str]
    link_names: List[str]
    frame_names: List[str]
    keyframe_names: List[str]
    parents: List[Optional[int]]
    lower_limits: FloatArray
    upper_limits: FloatArray
    velocity_limits: FloatArray
    effort_limits: FloatArray
    damping: FloatArray
    friction: FloatArray
    armature: FloatArray
    """Rotor inertias reflected to the joints (kg·m² or kg), added to the mass matrix's diagonal."""
    stiffness: FloatArray
    """Joint spring stiffnesses ``k`` (MuJoCo's ``stiffness``); simulation applies ``−k (q − springref)``."""
    springref: FloatArray
    """The joint springs' rest positions (rad or m; MuJoCo's ``springref``)."""
    screw_axes: FloatArray
    """``S_i^{i,λ(i)}``, (nq, 6)."""
    spatial_inertias: FloatArray
    """``𝔍^{i,i}``, (nq, 6, 6)."""
    gravity: FloatArray
    """(3,) m/s² in the base frame; settable."""
    total_mass: float
    physical_problems: List[str]
    """Physical-consistency findings of the description (empty for a consistent model)."""

    configuration_ranges: FloatArray
    """(nq, 2) rows ``[lo, hi]`` random configurations are drawn from: the limits, an infinite
    bound replaced by ∓π (revolute, continuous, helical) or ∓1 m (prismatic)."""

    def with_joint_friction(self, damping: ArrayLike, friction: ArrayLike) -> Model:
        """Each one value per joint or one number for every joint."""
    def to_urdf(self) -> str: ...
    def to_mjcf(self) -> str:
        """MJCF (MuJoCo) text: armature, limits, damping, friction, springs, motors, frames as sites."""
    def keyframe(self, name: str) -> FloatArray: ...

    # frames and joints by name or index (every method taking a frame takes either)
    def frame_id(self, frame: FrameRef) -> int:
        """The index of a frame in ``frame_names`` (Pinocchio's ``getFrameId``)."""
    def frame_name(self, frame: FrameRef) -> str:
        """``frame_names[i]``."""
    def joint_id(self, joint: FrameRef) -> int:
        """The index of a joint in ``joint_names`` (its coordinate in ``q``)."""

    # configurations to start from
    def neutral(self) -> FloatArray:
        """(nq,): zero, or the point of the joint's range nearest zero when zero is outside it."""
    def random_configuration(self, rng: Union[np.random.Generator, int, None] = None,
                             n: Optional[int] = None) -> FloatArray:
        """(nq,) or (n, nq), uniform over ``configuration_ranges``; ``rng`` a NumPy Generator,
        an int seed (screwdyn's SplitMix64: the same on every machine) or None (fresh)."""

    # kinematics
    def frame_pose(self, q: ArrayLike, frame: FrameRef, *, threads: Optional[int] = None,
                   out: Optional[FloatArray] = None) -> FloatArray:
        """(4, 4) or (N, 4, 4)."""
    def frame_poses(self, q: ArrayLike, *, threads: Optional[int] = None) -> Dict[str, FloatArray]: ...
    def inverse_kinematics(self, frame: FrameRef, target: ArrayLike, q0: Optional[ArrayLike] = None, *,
                           seed: int = 0, threads: Optional[int] = None, position_only: bool = False,
                           position_tolerance: Optional[float] = None,
                           orientation_tolerance: Optional[float] = None,
                           max_iterations: Optional[int] = None,
                           max_restarts: Optional[int] = None) -> IkResult:
        """Joint positions putting ``frame`` at ``target`` ((4, 4) or (N, 4, 4), world frame);
        q0 (nq,) or (N, nq). Scalars for one target, arrays for a batch (GIL released)."""
    def inverse_kinematics_all(self, frame: FrameRef, target: ArrayLike,
                               q0: Optional[ArrayLike] = None) -> FloatArray:
        """Every closed-form solution within the limits, refined and checked: (M, nq), nearest q0 first."""
    def frame_jacobian(self, q: ArrayLike, frame: FrameRef, reference: str = "world", *,
                       threads: Optional[int] = None, out: Optional[FloatArray] = None) -> FloatArray:
        """(6, nq) or (N, 6, nq), angular rows first; reference world | local | world-aligned (or WORLD | LOCAL | LOCAL_WORLD_ALIGNED)."""
    def link_jacobian(self, q: ArrayLike, link: FrameRef, *, threads: Optional[int] = None,
                      out: Optional[FloatArray] = None) -> FloatArray: ...
    def frame_twist(self, q: ArrayLike, v: ArrayLike, frame: FrameRef, reference: str = "world", *,
                    threads: Optional[int] = None, out: Optional[FloatArray] = None) -> FloatArray:
        """(6,) or (N, 6), (ω, v); reference as in frame_jacobian."""
    def frame_acceleration(self, q: ArrayLike, v: ArrayLike, a: ArrayLike, frame: FrameRef,
                           reference: str = "world", *, threads: Optional[int] = None,
                           out: Optional[FloatArray] = None) -> FloatArray: ...
    def frame_jdot_qdot(self, q: ArrayLike, v: ArrayLike, frame: FrameRef, reference: str = "world", *,
                        threads: Optional[int] = None, out: Optional[FloatArray] = None) -> FloatArray: ...

    # dynamics
    def rnea(self, q: ArrayLike, v: Optional[ArrayLike] = None, a: Optional[ArrayLike] = None, *,
             fext: Optional[Wrenches] = None, fext_world: Optional[Wrenches] = None,
             tip_wrenches: Optional[Wrenches] = None, threads: Optional[int] = None,
             out: Optional[FloatArray] = None) -> FloatArray:
        """τ (N·m / N), (nq,) or (N, nq)."""
    def inverse_dynamics(self, q: ArrayLike, v: Optional[ArrayLike] = None, a: Optional[ArrayLike] = None, *,
                         fext: Optional[Wrenches] = None, fext_world: Optional[Wrenches] = None,
                         tip_wrenches: Optional[Wrenches] = None, threads: Optional[int] = None,
                         out: Optional[FloatArray] = None) -> FloatArray: ...
    def crba(self, q: ArrayLike, *, threads: Optional[int] = None,
             out: Optional[FloatArray] = None) -> FloatArray:
        """M(q), (nq, nq) or (N, nq, nq)."""
    def mass_matrix(self, q: ArrayLike, *, threads: Optional[int] = None,
                    out: Optional[FloatArray] = None) -> FloatArray: ...
    def mass_matrix_inverse(self, q: ArrayLike, *, threads: Optional[int] = None,
                            out: Optional[FloatArray] = None) -> FloatArray: ...
    def coriolis_matrix(self, q: ArrayLike, v: ArrayLike, *, threads: Optional[int] = None,
                        out: Optional[FloatArray] = None) -> FloatArray: ...
    def gravity_torque(self, q: ArrayLike, *, threads: Optional[int] = None,
                       out: Optional[FloatArray] = None) -> FloatArray: ...
    def nonlinear_effects(self, q: ArrayLike, v: ArrayLike, *, threads: Optional[int] = None,
                          out: Optional[FloatArray] = None) -> FloatArray: ...
    def forward_dynamics(self, q: ArrayLike, v: ArrayLike, tau: ArrayLike, *, method: str = "aba",
                         fext: Optional[Wrenches] = None, fext_world: Optional[Wrenches] = None,
                         tip_wrenches: Optional[Wrenches] = None, threads: Optional[int] = None,
                         out: Optional[FloatArray] = None) -> FloatArray:
        """q̈ (rad/s²), method aba | crba | walker-orin."""
    def aba(self, q: ArrayLike, v: ArrayLike, tau: ArrayLike, *, fext: Optional[Wrenches] = None,
            fext_world: Optional[Wrenches] = None, tip_wrenches: Optional[Wrenches] = None,
            threads: Optional[int] = None, out: Optional[FloatArray] = None) -> FloatArray: ...
    def kinetic_energy(self, q: ArrayLike, v: ArrayLike, *, threads: Optional[int] = None,
                       out: Optional[FloatArray] = None) -> Union[float, FloatArray]: ...
    def potential_energy(self, q: ArrayLike, *, threads: Optional[int] = None,
                         out: Optional[FloatArray] = None) -> Union[float, FloatArray]: ...
    def total_energy(self, q: ArrayLike, v: ArrayLike, *, threads: Optional[int] = None,
                     out: Optional[FloatArray] = None) -> Union[float, FloatArray]: ...
    def power(self, tau: ArrayLike, v: ArrayLike, *, threads: Optional[int] = None,
              out: Optional[FloatArray] = None) -> Union[float, FloatArray]: ...
    def center_of_mass(self, q: ArrayLike, *, threads: Optional[int] = None,
                       out: Optional[FloatArray] = None) -> FloatArray: ...

    # the closed form, Lagrangian coefficients and RNEA trace (one state)
    def closed_form(self, q: ArrayLike, v: Optional[ArrayLike] = None) -> ClosedForm: ...
    def lagrange_coefficients(self, q: ArrayLike) -> LagrangeCoefficients: ...
    def mass_matrix_derivatives(self, q: ArrayLike) -> FloatArray:
        """[k, i, j] = ∂M_ij/∂q_k."""
    def effective_inertia(self, q: ArrayLike, joint: FrameRef,
                          free: Union[None, str, Sequence[FrameRef]] = None) -> float: ...
    def rnea_trace(self, q: ArrayLike, v: Optional[ArrayLike] = None, a: Optional[ArrayLike] = None, *,
                   fext: Optional[Wrenches] = None, fext_world: Optional[Wrenches] = None,
                   tip_wrenches: Optional[Wrenches] = None) -> RneaTrace: ...

    # derivatives, regressor, identification (docs/derivatives.md)
    def rnea_derivatives(self, q: ArrayLike, v: ArrayLike, a: ArrayLike, *,
                         fext: Optional[Wrenches] = None, fext_world: Optional[Wrenches] = None,
                         tip_wrenches: Optional[Wrenches] = None,
                         threads: Optional[int] = None) -> Tuple[FloatArray, FloatArray, FloatArray]:
        """(∂τ/∂q, ∂τ/∂q̇, M), each (nq, nq) or (N, nq, nq); [i, j] = ∂τ_i/∂x_j."""
    def aba_derivatives(self, q: ArrayLike, v: ArrayLike, tau: ArrayLike, *,
                        fext: Optional[Wrenches] = None, fext_world: Optional[Wrenches] = None,
                        tip_wrenches: Optional[Wrenches] = None,
                        threads: Optional[int] = None) -> Tuple[FloatArray, FloatArray, FloatArray]:
        """(∂q̈/∂q, ∂q̈/∂q̇, M⁻¹), each (nq, nq) or (N, nq, nq)."""
    def regressor(self, q: ArrayLike, v: Optional[ArrayLike] = None, a: Optional[ArrayLike] = None, *,
                  threads: Optional[int] = None) -> FloatArray:
        """Y (nq, 10 nq) or (N, nq, 10 nq): rnea(q, v, a) = Y @ inertial_parameters()."""
    def inertial_parameters(self, friction: bool = False) -> FloatArray:
        """π: m, mx, my, mz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz per body (body frame origin)."""
    def parameter_names(self, friction: bool = False) -> List[str]: ...
    def base_parameters(self, friction: bool = False, *, states: int = 100,
                        seed: int = 1) -> BaseParameters: ...
    def identify(self, q: ArrayLike, v: ArrayLike, a: ArrayLike, tau: ArrayLike, *,
                 friction: bool = False, states: int = 100, seed: int = 1) -> Identification:
        """Least squares of the base parameters from stacked (N, nq) samples."""

    # 3-D view (the page of `screwdyn view`)
    def view(self, q: Optional[ArrayLike] = None,
             run: Union[None, str, os.PathLike[str], SimResult, TorqueProfile] = None, *,
             urdf: Union[None, str, os.PathLike[str]] = None,
             package_path: Union[str, os.PathLike[str], Sequence[Union[str, os.PathLike[str]]]] = (),
             max_triangles: int = 200000, max_samples: int = 1000, title: Optional[str] = None,
             width: Union[int, str] = "100%", height: Union[int, str] = 600) -> View: ...

    # simulation
    def simulate(self, q0: ArrayLike, v0: Optional[ArrayLike] = None, *, duration: float = 1.0,
                 dt: float = 1e-3, controller: Any = None, integrator: str = "rk4",
                 rtol: float = 1e-8, atol: float = 1e-10, method: str = "aba",
                 effects: Union[None, bool, Dict[str, Any]] = None, disturbances: Sequence[Any] = (),
                 record_every: int = 1, frames: Sequence[FrameRef] = (),
                 progress: Optional[Callable[[float], None]] = None) -> SimResult: ...
    def torque_profile(self, trajectory: Trajectory, dt: float = 0.01) -> TorqueProfile: ...

    def __eq__(self, other: object) -> bool: ...
    def __reduce__(self) -> Tuple[Any, ...]: ...

class Trajectory:
    """A joint-space trajectory. Per-joint arguments (end points, limits, boundary velocities
    and accelerations) are one value per joint or one number for every joint."""

    duration: float
    nq: int

    @staticmethod
    def trapezoid(q0: ArrayLike, qf: ArrayLike, vmax: ArrayLike, amax: ArrayLike,
                  synchronised: bool = True) -> Trajectory: ...
    @staticmethod
    def quintic(q0: ArrayLike, qf: ArrayLike, duration: float, v0: Optional[ArrayLike] = None,
                vf: Optional[ArrayLike] = None, a0: Optional[ArrayLike] = None,
                af: Optional[ArrayLike] = None) -> Trajectory: ...
    @staticmethod
    def waypoints(times: ArrayLike, points: ArrayLike) -> Trajectory: ...
    @staticmethod
    def time_optimal(model: Model, waypoints: ArrayLike, s: Optional[ArrayLike] = None,
                     vmax: Optional[ArrayLike] = None, amax: Optional[ArrayLike] = None,
                     effort: Optional[ArrayLike] = None,
                     grid: Optional[int] = None) -> Trajectory: ...
    @staticmethod
    def jerk_limited(q0: ArrayLike, qf: ArrayLike, vmax: ArrayLike, amax: ArrayLike,
                     jmax: ArrayLike) -> Trajectory: ...
    @staticmethod
    def linear(model: Model, frame: FrameRef, q0: ArrayLike, target: ArrayLike,
               speed: Optional[float] = None) -> Trajectory: ...
    @staticmethod
    def circular(model: Model, frame: FrameRef, q0: ArrayLike, via: ArrayLike,
                 target: ArrayLike, speed: Optional[float] = None) -> Trajectory: ...
    def phase_plane(self) -> Tuple[FloatArray, FloatArray, FloatArray]: ...
    def sample(self, t: ArrayLike) -> Tuple[FloatArray, FloatArray, FloatArray]: ...
    def cruise_speeds(self) -> FloatArray: ...
