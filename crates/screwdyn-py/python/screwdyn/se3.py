"""Pose helpers over plain NumPy arrays, in the notation of docs/notation.md.

A pose ``H = [[R, p], [0, 1]]`` is a ``(4, 4)`` float array: the frame's orientation ``R`` and
origin ``p`` in the reference frame (``H_c^p``, the same matrices ``Model.frame_pose`` returns).
Twists are angular first, ``V = (ω, v)``; wrenches moment first, ``W = (m, f)``. Compose poses
with ``@``. Every function is computed by the library's ``spatial`` module.

>>> import numpy as np
>>> from screwdyn import se3
>>> H = se3.exp([0, 0, np.pi / 2, 1, 0, 0])       # a quarter turn about z, then along the arc
>>> np.allclose(se3.log(H), [0, 0, np.pi / 2, 1, 0, 0])
True
>>> se3.to_quaternion(se3.from_rpy([0, 0, np.pi / 2])).round(6)   # (w, x, y, z), scalar first
array([0.707107, 0.      , 0.      , 0.707107])

Rotations by angles follow URDF: ``rpy = (roll, pitch, yaw)`` about the fixed x, y, z axes,
``R = Rz(yaw) Ry(pitch) Rx(roll)``. Quaternions are ``(w, x, y, z)``, **scalar first** (as
Pinocchio's ``Quaternion(w, x, y, z)`` constructor and Eigen's; SciPy's ``as_quat`` puts it last).

Bad input raises ``ValueError`` with one sentence: a wrong shape, a NaN or infinity, a rotation
part that is not orthonormal with determinant +1 (within 1e-6), a bottom row other than
``(0, 0, 0, 1)``, a zero quaternion.
"""

from __future__ import annotations

from typing import Optional

import numpy as np
import numpy.typing as npt

from . import _screwdyn

__all__ = ["exp", "log", "Ad", "ad", "inverse", "from_quaternion", "to_quaternion", "from_rpy",
           "to_rpy"]

FloatArray = npt.NDArray[np.float64]


def exp(twist: npt.ArrayLike) -> FloatArray:
    """``e^{[ξ]}``: the ``(4, 4)`` pose reached by following the twist ``ξ = (ω, v)`` ``(6,)``
    for unit time (a joint with screw axis ``S`` at ``θ``: ``exp(S * θ)``)."""
    return _screwdyn._se3_exp(twist)


def log(H: npt.ArrayLike) -> FloatArray:
    """The twist ``ξ = (ω, v)`` ``(6,)`` with ``exp(ξ) = H`` and ``|ω| ≤ π``."""
    return _screwdyn._se3_log(H)


def Ad(H: npt.ArrayLike) -> FloatArray:
    """``Ad_H`` ``(6, 6)`` = ``[[R, 0], [[p] R, R]]``: ``Ad_H @ V`` is the twist ``V`` written in
    the moving frame, now written in the reference frame (``Ad_H [V] = H [V] H⁻¹``);
    ``Ad_H.T @ W`` moves a wrench the other way."""
    return _screwdyn._se3_adjoint(H)


def ad(twist: npt.ArrayLike) -> FloatArray:
    """``ad_V`` ``(6, 6)`` = ``[[[ω], 0], [[v], [ω]]]`` of the twist ``V = (ω, v)``: the Lie
    bracket, ``ad_V @ X = [V, X]``."""
    return _screwdyn._se3_ad(twist)


def inverse(H: npt.ArrayLike) -> FloatArray:
    """``H⁻¹ = [[Rᵀ, −Rᵀ p], [0, 1]]`` ``(4, 4)``."""
    return _screwdyn._se3_inverse(H)


def from_quaternion(q: npt.ArrayLike, translation: Optional[npt.ArrayLike] = None) -> FloatArray:
    """The ``(4, 4)`` pose of the quaternion ``q = (w, x, y, z)`` (**scalar first**; normalised)
    and the origin ``translation`` ``(3,)`` (default zero)."""
    return _screwdyn._se3_from_quaternion(q, translation)


def to_quaternion(H: npt.ArrayLike) -> FloatArray:
    """The unit quaternion ``(w, x, y, z)`` (**scalar first**, ``w ≥ 0``) of a ``(4, 4)`` pose's
    rotation or of a ``(3, 3)`` rotation matrix."""
    return _screwdyn._se3_to_quaternion(H)


def from_rpy(rpy: npt.ArrayLike, translation: Optional[npt.ArrayLike] = None) -> FloatArray:
    """The ``(4, 4)`` pose of URDF's ``rpy = (roll, pitch, yaw)``, ``R = Rz(yaw) Ry(pitch)
    Rx(roll)``, and the origin ``translation`` ``(3,)`` (default zero)."""
    return _screwdyn._se3_from_rpy(rpy, translation)


def to_rpy(H: npt.ArrayLike) -> FloatArray:
    """URDF's ``(roll, pitch, yaw)`` of a ``(4, 4)`` pose's rotation or of a ``(3, 3)``
    rotation matrix, ``R = Rz(yaw) Ry(pitch) Rx(roll)``, pitch in ``[−π/2, π/2]`` (at
    ``|pitch| = π/2`` roll is 0 and yaw carries the turn)."""
    return _screwdyn._se3_to_rpy(H)
