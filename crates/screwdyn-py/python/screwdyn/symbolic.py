"""Symbolic equations of motion as SymPy expressions (SymPy is the optional extra
``pip install 'screwdyn[sympy]'``).

>>> import screwdyn, screwdyn.symbolic as sym
>>> arm = screwdyn.load("builtin:planar2")
>>> M = sym.mass_matrix(arm, symbols="all")          # the two-link arm
>>> M[1, 1]
L2**2*m2

The expressions are derived by the library's symbolic engine (``screwdyn::symbolic::derive``,
the same engine as ``screwdyn symbolic``), not by SymPy: joint transforms make every quantity a
polynomial in ``cos θ_i``, ``sin θ_i`` (``θ_j`` for prismatic joints), ``θ̇``, ``θ̈`` and the
parameters, which the engine keeps in a canonical form (``sin² = 1 − cos²``) — so a 6-axis
arm's ``M(θ)`` takes milliseconds and needs no ``simplify``. The polynomials cross into Python
term by term (coefficient and exponents of each variable), and this module builds the SymPy
objects from that structure; nothing is parsed from printed text.

**Symbols.** Joint variables are ``theta1 … thetan`` (``θ``), ``thetadot1 …`` (``θ̇``) and
``thetaddot1 …`` (``θ̈``), 1-based as in docs/notation.md, plain :class:`sympy.Symbol` objects
so ``sympy.diff`` works (SymPy prints them as ``θ₁``, ``θ̇₁``, ``θ̈₁`` in LaTeX). Parameters
kept symbolic carry the engine's names: ``m1, m2, L1, L2, g`` for
``builtin:planar2``; ``m_<link>``, ``Ixx_<link>``, ``cx_<link>``, ``g``, ``a_<i>``, ``d_<i>``
(standard-DH joints) or ``px_<i>`` … for other models. :func:`joint_symbols` and
:attr:`Derivation.symbols` return the symbol objects.

**Coefficients.** The engine's coefficients are float64. A coefficient that is an integer or a
simple fraction (denominator ≤ 64, e.g. ``½`` of the kinetic energy) becomes an exact SymPy
``Integer``/``Rational``; any other (a product of numeric parameters, ``9.81 · 0.425``) stays a
``Float`` with the full double precision.

``symbols`` selects the parameters kept as symbols, as ``screwdyn symbolic --symbols``:
``""``/``"none"`` (all numeric, the default), ``"all"``, groups ``"mass"``, ``"com"``,
``"inertia"``, ``"gravity"``, ``"lengths"``, ``"armature"`` (``Ia_<i>``), or names
``"m_link1,a_2"``, comma-separated.

Bad input (an unknown quantity or symbol name, a frame that does not exist, an expression
past ``max_terms``) raises ``ValueError`` with the library's sentence.
"""

from __future__ import annotations

import fractions
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

from . import _screwdyn

__all__ = [
    "QUANTITIES",
    "Derivation",
    "derive",
    "joint_symbols",
    "mass_matrix",
    "coriolis_matrix",
    "coriolis_times_velocity",
    "gravity_torque",
    "inverse_dynamics",
    "torque",
    "forward_kinematics",
    "jacobian",
    "energy",
    "regressor",
]

#: The quantities of :func:`derive` (the CLI's ``--quantity`` values).
QUANTITIES = ("mass-matrix", "coriolis", "gravity", "torque", "fk", "jacobian", "energy",
              "regressor")

#: Default cap on the terms of one expanded expression (the library's default).
DEFAULT_MAX_TERMS: int = _screwdyn.SYMBOLIC_DEFAULT_MAX_TERMS


def _sympy():
    try:
        import sympy
    except ImportError as e:  # pragma: no cover - exercised only without SymPy
        raise ImportError(
            "screwdyn.symbolic needs SymPy: install it with pip install 'screwdyn[sympy]' "
            "(or pip install sympy)") from e
    return sympy


def joint_symbols(model) -> Tuple[List[Any], List[Any], List[Any]]:
    """The joint variables of ``model`` as SymPy symbols: ``(θ, θ̇, θ̈)``, three lists of
    ``theta<i>``, ``thetadot<i>``, ``thetaddot<i>`` (``i`` = 1 … nq, model joint order)."""
    sp = _sympy()
    n = model.nq
    return ([sp.Symbol(f"theta{i}") for i in range(1, n + 1)],
            [sp.Symbol(f"thetadot{i}") for i in range(1, n + 1)],
            [sp.Symbol(f"thetaddot{i}") for i in range(1, n + 1)])


def _number(sp, c: float):
    """A float64 coefficient as an exact SymPy number when it is an integer or a simple
    fraction, else a full-precision Float."""
    if c == int(c) and abs(c) < 2.0 ** 53:
        return sp.Integer(int(c))
    f = fractions.Fraction(c).limit_denominator(64)
    if float(f) == c:
        return sp.Rational(f.numerator, f.denominator)
    return sp.Float(c)


class Derivation:
    """The result of :func:`derive`: SymPy matrices and the symbols they use.

    Attributes: ``quantity`` (the generated function's name, e.g. ``"mass_matrix"``),
    ``model`` (its name), ``joints`` (joint names), ``matrices`` (name → :class:`sympy.Matrix`:
    ``M``; ``C`` and ``Cθ̇``; ``g``; ``τ``; ``H``; ``J``; ``K`` and ``P``; ``Y``), ``q``, ``v``,
    ``a`` (the joint symbols), ``symbols`` (parameter name → Symbol, for the parameters kept
    symbolic), ``values`` (Symbol → the model's value of that parameter) and ``parameters``
    (every parameter of the model: name, value, symbolic, group, meaning).
    """

    def __init__(self, model, data: Dict[str, Any]):
        sp = _sympy()
        self.model: str = data["model"]
        self.joints: List[str] = list(data["joints"])
        self.quantity: str = data["quantity"]
        self.parameters: List[Dict[str, Any]] = list(data["params"])
        self.q, self.v, self.a = joint_symbols(model)
        self.symbols: Dict[str, Any] = {}
        self.values: Dict[Any, float] = {}
        params: List[Any] = []
        for p in self.parameters:
            if p["symbolic"]:
                s = sp.Symbol(p["name"])
                self.symbols[p["name"]] = s
                self.values[s] = p["value"]
                params.append(s)
            else:
                params.append(None)
        trig: Dict[Tuple[str, Tuple[int, ...]], Any] = {}

        def base(kind: str, idx):
            if kind == "p":
                return params[idx]
            if kind in ("c", "s"):
                key = (kind, idx)
                if key not in trig:
                    angle = sp.Add(*[self.q[i] for i in idx])
                    trig[key] = sp.cos(angle) if kind == "c" else sp.sin(angle)
                return trig[key]
            return {"q": self.q, "v": self.v, "a": self.a}[kind][idx]

        def poly(terms):
            out = []
            for coef, mono in terms:
                factors = [_number(sp, coef)]
                factors += [base(k, i) ** e if e != 1 else base(k, i) for k, i, e in mono]
                out.append(sp.Mul(*factors))
            return sp.Add(*out)

        self.matrices: Dict[str, Any] = {}
        for name, rows, cols, entries in data["matrices"]:
            self.matrices[name] = sp.Matrix(rows, cols, [poly(t) for t in entries])

    @property
    def matrix(self):
        """The first (main) matrix: ``M``, ``C``, ``g``, ``τ``, ``H``, ``J``, ``K`` or ``Y``."""
        return next(iter(self.matrices.values()))

    def __getitem__(self, name: str):
        return self.matrices[name]

    def evaluate(self, name: Optional[str] = None, q=None, v=None, a=None):
        """Matrix ``name`` (default: the main one) as a NumPy array at the state
        ``(q, v, a)`` (zeros where not given), the symbolic parameters at the model's values."""
        import numpy as np

        sp = _sympy()
        n = len(self.q)
        mat = self.matrix if name is None else self.matrices[name]
        subs = dict(self.values)
        for syms, x in ((self.q, q), (self.v, v), (self.a, a)):
            x = np.zeros(n) if x is None else np.asarray(x, dtype=float)
            subs.update(zip(syms, x.tolist()))
        f = sp.lambdify(list(subs), mat, "numpy")
        return np.asarray(f(*subs.values()), dtype=float)

    def __repr__(self) -> str:
        names = ", ".join(self.matrices)
        syms = ", ".join(self.symbols) or "none"
        return (f"Derivation({self.quantity} of {self.model}: {names}; symbols: {syms})")

    def _repr_latex_(self) -> str:
        sp = _sympy()
        parts = [f"{_latex_name(k)} = {sp.latex(m)}" for k, m in self.matrices.items()]
        return "$\\displaystyle " + ",\\quad ".join(parts) + "$"


def _latex_name(name: str) -> str:
    return {"Cθ̇": "C\\dot{\\theta}", "τ": "\\tau"}.get(name, name)


def derive(model, quantity: str, *, symbols: str = "", frame: Union[str, int, None] = None,
           reference: str = "local", coriolis: str = "closed-form",
           max_terms: int = DEFAULT_MAX_TERMS) -> Derivation:
    """Derives ``quantity`` of ``model`` symbolically (the library's symbolic engine, as
    ``screwdyn symbolic MODEL --quantity …``).

    quantity: ``"mass-matrix"`` (``M(θ)``), ``"coriolis"`` (``C(θ, θ̇)`` and ``C θ̇``),
        ``"gravity"`` (``g(θ)``), ``"torque"`` (``τ(θ, θ̇, θ̈)``), ``"fk"`` (``H_f^0(θ)``),
        ``"jacobian"`` (6 × n, angular rows first), ``"energy"`` (``K`` and ``P``) or
        ``"regressor"`` (``Y``, ``τ = Y π``); underscores are accepted for hyphens.
    symbols: the parameters kept as symbols (see the module documentation).
    frame: the frame of ``fk`` and ``jacobian``, by name or index (default: the last body's
        frame).
    reference: the Jacobian's reference, ``"local"``, ``"world"`` or ``"world-aligned"``.
    coriolis: ``"closed-form"`` (the stacked closed form's own ``C``) or ``"christoffel"`` (``Ṁ − 2C``
        skew-symmetric).
    max_terms: the largest number of terms of one expanded expression; a larger one raises
        ValueError naming the limit.
    """
    _sympy()
    data = _screwdyn._symbolic_derive(model, str(quantity), str(symbols), frame,
                                      str(reference), str(coriolis), int(max_terms))
    return Derivation(model, data)


def mass_matrix(model, symbols: str = "", **options):
    """``M(θ)`` as an n × n :class:`sympy.Matrix` (the two-link arm's is the textbook one)."""
    return derive(model, "mass-matrix", symbols=symbols, **options)["M"]


def coriolis_matrix(model, symbols: str = "", form: str = "closed-form", **options):
    """``C(θ, θ̇)``, n × n: ``form="closed-form"`` (the stacked closed form's own ``C``) or
    ``"christoffel"`` (Christoffel symbols, ``Ṁ − 2C`` skew-symmetric)."""
    return derive(model, "coriolis", symbols=symbols, coriolis=form, **options)["C"]


def coriolis_times_velocity(model, symbols: str = "", **options):
    """The velocity terms ``C(θ, θ̇) θ̇``, n × 1 (the same for both forms of ``C``)."""
    return derive(model, "coriolis", symbols=symbols, **options)["Cθ̇"]


def gravity_torque(model, symbols: str = "", **options):
    """``g(θ)``, n × 1."""
    return derive(model, "gravity", symbols=symbols, **options)["g"]


def inverse_dynamics(model, symbols: str = "", **options):
    """``τ(θ, θ̇, θ̈) = M θ̈ + C θ̇ + g``, n × 1."""
    return derive(model, "torque", symbols=symbols, **options)["τ"]


torque = inverse_dynamics


def forward_kinematics(model, frame: Union[str, int, None] = None, symbols: str = "", **options):
    """``H_f^0(θ)`` of ``frame`` (default: the last body's frame), 4 × 4."""
    return derive(model, "fk", symbols=symbols, frame=frame, **options)["H"]


def jacobian(model, frame: Union[str, int, None] = None, reference: str = "local", symbols: str = "",
             **options):
    """The 6 × n Jacobian of ``frame`` (angular rows first) in ``reference``."""
    return derive(model, "jacobian", symbols=symbols, frame=frame, reference=reference,
                  **options)["J"]


def energy(model, symbols: str = "", **options):
    """``(K, P)``: kinetic energy ``½ θ̇ᵀ M θ̇`` and potential energy, SymPy expressions."""
    d = derive(model, "energy", symbols=symbols, **options)
    return d["K"][0, 0], d["P"][0, 0]


def regressor(model, symbols: str = "", **options):
    """The regressor ``Y(θ, θ̇, θ̈)``, n × 10n, with ``τ = Y π`` for the standard parameters
    ``π`` of :meth:`screwdyn.Model.inertial_parameters`."""
    return derive(model, "regressor", symbols=symbols, **options)["Y"]
