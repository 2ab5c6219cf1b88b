"""Result classes: arrays from the native module with notebook displays, pandas DataFrames and
matplotlib plots. pandas and matplotlib are imported only when asked for."""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence

import numpy as np


def _num(x: float) -> str:
    if x == 0:
        return "0"
    return f"{x:.6g}"


def _bmatrix(m: np.ndarray) -> str:
    m = np.atleast_2d(m)
    rows = [" & ".join(_num(x) for x in row) for row in m]
    return r"\begin{bmatrix}" + r" \\ ".join(rows) + r"\end{bmatrix}"


def _six(x: np.ndarray) -> str:
    """A twist or wrench as ``(a, b, c | d, e, f)``: angular (moment) part first."""
    a = ", ".join(_num(v) for v in x[:3])
    b = ", ".join(_num(v) for v in x[3:])
    return f"({a} | {b})"


def _six_tex(x: np.ndarray) -> str:
    return r"\begin{pmatrix}" + ", ".join(_num(v) for v in x[:3]) + r" \mid " + \
        ", ".join(_num(v) for v in x[3:]) + r"\end{pmatrix}"


def _pandas():
    try:
        import pandas
    except ImportError as e:  # pragma: no cover - exercised only without pandas
        raise ImportError("to_dataframe() needs pandas: pip install screwdyn[pandas]") from e
    return pandas


def _pyplot():
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:  # pragma: no cover - exercised only without matplotlib
        raise ImportError("plot() needs matplotlib: pip install screwdyn[plot]") from e
    return plt


class ClosedForm:
    """The stacked closed form of docs/notation.md at one state. Attributes are NumPy arrays:

    ``A`` (6n×6n, block ``(i, λ(i)) = Ad_{H_{λ(i)}^i}``), ``L = (I − A)⁻¹``, ``S`` (6n×n),
    ``inertia`` (𝔍, 6n×6n), ``ad_S_qdot``, ``V = L S θ̇``, ``ad_V``, ``J = L S``, ``J_dot``,
    ``Vdot_base``, ``M = Sᵀ Lᵀ 𝔍 L S``, ``C`` (the closed form's own factorisation),
    ``C_christoffel`` (the one with ``Ṁ − 2C`` skew-symmetric, as ``coriolis_matrix``), ``g``.
    """

    _ORDER = ["A", "L", "S", "inertia", "J", "M", "C", "g"]
    _TEX = {"A": r"A(\theta)", "L": r"L(\theta) = (I - A)^{-1}", "S": "S",
            "inertia": r"\mathfrak{J}", "J": r"J = L S", "M": r"M = S^T L^T \mathfrak{J} L S",
            "C": r"C(\theta, \dot\theta)", "g": r"g(\theta)"}

    def __init__(self, model, data: Dict[str, Any]):
        self.joint_names: List[str] = model.joint_names
        self.q: np.ndarray = data["q"]
        self.qdot: np.ndarray = data["qdot"]
        self.A: np.ndarray = data["A"]
        self.L: np.ndarray = data["L"]
        self.S: np.ndarray = data["S"]
        self.inertia: np.ndarray = data["inertia"]
        self.ad_S_qdot: np.ndarray = data["ad_S_qdot"]
        self.V: np.ndarray = data["V"]
        self.ad_V: np.ndarray = data["ad_V"]
        self.J: np.ndarray = data["J"]
        self.J_dot: np.ndarray = data["J_dot"]
        self.Vdot_base: np.ndarray = data["Vdot_base"]
        self.M: np.ndarray = data["M"]
        self.C: np.ndarray = data["C"]
        self.C_christoffel: np.ndarray = data["C_christoffel"]
        self.g: np.ndarray = data["g"]

    def to_dict(self) -> Dict[str, np.ndarray]:
        """Every array by name."""
        return {k: v for k, v in vars(self).items() if isinstance(v, np.ndarray)}

    def to_sympy(self) -> Dict[str, Any]:
        """Every array as a ``sympy.Matrix`` (for pretty printing next to a hand derivation;
        needs sympy: ``pip install screwdyn[sympy]``)."""
        try:
            import sympy
        except ImportError as e:  # pragma: no cover - exercised only without sympy
            raise ImportError("to_sympy() needs sympy: pip install screwdyn[sympy]") from e
        return {k: sympy.Matrix(v.reshape(v.shape[0], -1)) for k, v in self.to_dict().items()}

    def __repr__(self) -> str:
        n = len(self.joint_names)
        return f"ClosedForm(n={n}, q={self.q.tolist()}, qdot={self.qdot.tolist()})"

    def _repr_markdown_(self) -> str:
        out = [f"**Closed form** at $\\theta$ = {self.q.tolist()}, "
               f"$\\dot\\theta$ = {self.qdot.tolist()} (joints: {', '.join(self.joint_names)})", ""]
        for k in self._ORDER:
            out.append(f"$${self._TEX[k]} = {_bmatrix(getattr(self, k))}$$")
        return "\n".join(out)


class LagrangeCoefficients:
    """The Lagrangian coefficients at one state: ``D_ij`` (n×n), ``D_ijk`` (n×n×n,
    ``D_ijk[i, j, k]``, 0-based) and ``D_i`` (n), so that
    ``τ_i = Σ_j D_ij q̈_j + Σ_jk D_ijk q̇_j q̇_k + D_i``."""

    def __init__(self, model, data: Dict[str, Any]):
        self.joint_names: List[str] = model.joint_names
        self.q: np.ndarray = data["q"]
        self.D_ij: np.ndarray = data["D_ij"]
        self.D_ijk: np.ndarray = data["D_ijk"]
        self.D_i: np.ndarray = data["D_i"]

    def __repr__(self) -> str:
        return f"LagrangeCoefficients(n={len(self.joint_names)}, q={self.q.tolist()})"

    def _repr_markdown_(self) -> str:
        n = len(self.joint_names)
        out = [f"**Lagrangian coefficients** at $\\theta$ = {self.q.tolist()}", "",
               f"$$D_{{ij}} = {_bmatrix(self.D_ij)}$$"]
        for i in range(n):
            out.append(f"$$D_{{{i + 1}jk}} = {_bmatrix(self.D_ijk[i])}$$")
        out.append(f"$$D_i = {_bmatrix(self.D_i[:, None])}$$")
        return "\n".join(out)


class RneaTrace:
    """The recursive Newton–Euler iterations at one state (docs/notation.md).

    Per link ``i`` (0-based arrays, 1-based in the display, as in docs/notation.md): ``home``
    (``H_i^{λ(i)}(0)``), ``screw`` (``S_i^{i,λ(i)}``), ``pose_in_parent``
    (``H_i^{λ(i)}(θ_i) = H_i^{λ(i)}(0) e^{S̃_i θ_i}``), ``parent_twist`` /
    ``parent_twist_dot`` (``Ad_{H_{λ(i)}^i} V_{λ(i)}``, ``Ad V̇_{λ(i)}``), ``twist``
    (``V_i^{i,0}``), ``twist_dot`` (``V̇_i^{i,0}``), ``inertia`` (``𝔍^{i,i}``), ``inertial``
    (``𝔍 V̇ − ad_Vᵀ 𝔍 V``), ``external`` (``W_ext^{i,i}``), ``from_children``, ``wrench``
    (``W_{λ(i)}^{i,i}``, the wrench of the parent on link i) and ``tau``
    (``τ_i = S_iᵀ W_i``). ``base_acceleration`` is ``V̇_0 = (0, −g)``. Computed by the
    library's ``dynamics::rnea_trace``.
    """

    def __init__(self, data: Dict[str, Any]):
        self.joint_names: List[str] = list(data["joint_names"])
        self.link_names: List[str] = list(data["link_names"])
        self.parents: List[Optional[int]] = list(data["parents"])
        for k in ("q", "v", "a", "gravity", "base_acceleration", "screw", "home", "inertia",
                  "pose_in_parent", "parent_twist", "parent_twist_dot", "twist", "twist_dot",
                  "inertial", "external", "wrench", "tau"):
            setattr(self, k, data[k])
        #: per link, child index → ``Ad_{H_i^c}ᵀ W_c`` (the child's wrench carried back)
        self.from_children: List[Dict[int, np.ndarray]] = list(data["from_children"])

    def _parent(self, i: int) -> str:
        p = self.parents[i]
        return "0" if p is None else str(p + 1)

    def __repr__(self) -> str:
        return f"RneaTrace(n={len(self.joint_names)}, tau={self.tau.tolist()})"

    def __str__(self) -> str:
        n = len(self.joint_names)
        lines = ["Forward iterations, i = 1 … n (V_0 = 0, V̇_0 = (0, −g) = "
                 f"{_six(self.base_acceleration)}):"]
        for i in range(n):
            p = self._parent(i)
            lines.append(f"  i = {i + 1} ({self.joint_names[i]}, λ(i) = {p}), "
                         f"θ = {_num(self.q[i])}, θ̇ = {_num(self.v[i])}, θ̈ = {_num(self.a[i])}")
            lines.append(f"    S_{i + 1} = {_six(self.screw[i])}")
            for r in range(4):
                row = " ".join(f"{_num(x):>12}" for x in self.pose_in_parent[i][r])
                lines.append(f"    {'H_' + str(i + 1) + '^' + p + ' =' if r == 0 else '':>10} [{row} ]")
            lines.append(f"    V_{i + 1} = Ad V_{p} + S θ̇ = {_six(self.twist[i])}")
            lines.append(f"    V̇_{i + 1} = Ad V̇_{p} − ad_(Sθ̇) Ad V_{p} + S θ̈ = {_six(self.twist_dot[i])}")
        lines.append("Backward iterations, i = n … 1:")
        for i in reversed(range(n)):
            lines.append(f"  i = {i + 1} ({self.joint_names[i]})")
            lines.append(f"    𝔍 V̇ − ad_Vᵀ 𝔍 V = {_six(self.inertial[i])}")
            if np.any(self.external[i]):
                lines.append(f"    W_ext = {_six(self.external[i])}")
            for c, w in self.from_children[i].items():
                lines.append(f"    Ad_(H_{i + 1}^{c + 1})ᵀ W_{c + 1} = {_six(w)}")
            lines.append(f"    W_{i + 1} = 𝔍 V̇ − ad_Vᵀ 𝔍 V − W_ext + Σ Ad_{{H_c}}ᵀ W_c = {_six(self.wrench[i])}")
            lines.append(f"    τ_{i + 1} = S_{i + 1}ᵀ W_{i + 1} = {_num(self.tau[i])}")
        return "\n".join(lines)

    def _repr_markdown_(self) -> str:
        n = len(self.joint_names)
        out = ["**Recursive Newton–Euler**, step by step, at "
               f"$\\theta$ = {self.q.tolist()}, $\\dot\\theta$ = {self.v.tolist()}, "
               f"$\\ddot\\theta$ = {self.a.tolist()}", "",
               "*Forward iterations*, $i = 1 \\dots n$, with $V_0 = 0$ and "
               f"$\\dot V_0 = (0, -g) = {_six_tex(self.base_acceleration)}$:", ""]
        for i in range(n):
            k, p = i + 1, self._parent(i)
            out.append(f"- $i = {k}$ ({self.joint_names[i]}, $\\lambda({k}) = {p}$), "
                       f"$S_{k}^{{{k},{p}}} = {_six_tex(self.screw[i])}$")
            out.append(f"  $$H_{k}^{{{p}}}(\\theta_{k}) = H_{k}^{{{p}}}(0)\\, e^{{\\tilde S_{k} \\theta_{k}}} = "
                       f"{_bmatrix(self.pose_in_parent[i])}$$")
            out.append(f"  $$V_{k}^{{{k},0}} = \\mathrm{{Ad}}_{{H_{p}^{k}}} V_{p} + S_{k} \\dot\\theta_{k} = "
                       f"{_six_tex(self.twist[i])}$$")
            out.append(f"  $$\\dot V_{k}^{{{k},0}} = \\mathrm{{Ad}}_{{H_{p}^{k}}} \\dot V_{p} - "
                       f"\\mathrm{{ad}}_{{S_{k} \\dot\\theta_{k}}} \\mathrm{{Ad}}_{{H_{p}^{k}}} V_{p} + "
                       f"S_{k} \\ddot\\theta_{k} = {_six_tex(self.twist_dot[i])}$$")
        out += ["", "*Backward iterations*, $i = n \\dots 1$:", ""]
        for i in reversed(range(n)):
            k, p = i + 1, self._parent(i)
            ext = " - W_{ext}" if np.any(self.external[i]) else ""
            out.append(f"- $i = {k}$: $$\\mathfrak{{J}}^{{{k},{k}}} \\dot V_{k} - \\mathrm{{ad}}^T_{{V_{k}}} "
                       f"\\mathfrak{{J}}^{{{k},{k}}} V_{k} = {_six_tex(self.inertial[i])}$$")
            for c, w in self.from_children[i].items():
                out.append(f"  $$\\mathrm{{Ad}}^T_{{H_{k}^{{{c + 1}}}}} W_{{{k}}}^{{{c + 1},{c + 1}}} = {_six_tex(w)}$$")
            out.append(f"  $$W_{{{p}}}^{{{k},{k}}} = \\mathfrak{{J}}^{{{k},{k}}} \\dot V_{k} - "
                       f"\\mathrm{{ad}}^T_{{V_{k}}} \\mathfrak{{J}}^{{{k},{k}}} V_{k}{ext} + "
                       f"\\sum_c \\mathrm{{Ad}}^T_{{H_{k}^c}} W_c = {_six_tex(self.wrench[i])}$$")
            out.append(f"  $$\\tau_{k} = (S_{k}^{{{k},{p}}})^T W_{{{p}}}^{{{k},{k}}} = {_num(self.tau[i])}$$")
        return "\n".join(out)


class SimResult:
    """A recorded simulation: ``t`` (T,), ``q``, ``v``, ``a``, ``tau`` (T, nq),
    ``kinetic_energy``, ``potential_energy``, ``total_energy`` (T,), ``poses`` (frame →
    (T, 4, 4)) and ``events``: what happened at the joints' position limits, one dict each
    (``kind`` ``"start_outside"`` or ``"contact"``, ``t``, ``joint``, ``side`` ``"lower"`` or
    ``"upper"``, ``bound``, ``position``, ``velocity``) — a joint that starts outside its limits
    is not moved inside, its limit stop pushes it back; each contact with a limit stop is listed
    once. ``to_dataframe()`` gives the CLI's CSV columns; ``plot()`` draws them."""

    def __init__(self, data: Dict[str, Any]):
        self.joint_names: List[str] = list(data["joints"])
        self.t: np.ndarray = data["t"]
        self.q: np.ndarray = data["q"]
        self.v: np.ndarray = data["v"]
        self.a: np.ndarray = data["a"]
        self.tau: np.ndarray = data["tau"]
        self.kinetic_energy: np.ndarray = data["kinetic_energy"]
        self.potential_energy: np.ndarray = data["potential_energy"]
        self.total_energy: np.ndarray = data["total_energy"]
        self.poses: Dict[str, np.ndarray] = dict(data["poses"])
        self.events: List[Dict[str, Any]] = list(data.get("events", []))

    def __len__(self) -> int:
        return len(self.t)

    def save(self, path) -> None:
        """Writes the run as the file ``screwdyn simulate --output`` writes, by the library's
        writers (atomically): CSV for ``.csv`` (columns ``t``, ``q.<joint>``, ``v.<joint>``,
        ``a.<joint>``, ``tau.<joint>``, the energies) or JSON for ``.json``. Recorded frame
        poses are not written. ``Model.view(run=path)`` animates the file."""
        from ._view import save_run

        save_run(self, path)

    def __repr__(self) -> str:
        end = self.t[-1] if len(self.t) else 0.0
        return f"SimResult({len(self)} samples, t = 0 … {end:g} s, joints={self.joint_names})"

    def to_dataframe(self):
        """A pandas DataFrame with columns ``t``, ``q.<joint>``, ``v.<joint>``, ``a.<joint>``,
        ``tau.<joint>``, ``kinetic_energy``, ``potential_energy``, ``total_energy`` (needs
        pandas)."""
        pd = _pandas()
        cols: Dict[str, np.ndarray] = {"t": self.t}
        for key in ("q", "v", "a", "tau"):
            arr = getattr(self, key)
            for j, name in enumerate(self.joint_names):
                cols[f"{key}.{name}"] = arr[:, j]
        for key in ("kinetic_energy", "potential_energy", "total_energy"):
            cols[key] = getattr(self, key)
        return pd.DataFrame(cols)

    def plot(self, quantities: Sequence[str] = ("q", "v", "tau"), *, fig=None):
        """Plots the chosen quantities (``q``, ``v``, ``a``, ``tau``, ``energy``) against time,
        one panel each (needs matplotlib). Returns the figure."""
        plt = _pyplot()
        units = {"q": "position (rad | m)", "v": "velocity (rad/s | m/s)",
                 "a": "acceleration (rad/s² | m/s²)", "tau": "torque (N·m | N)",
                 "energy": "energy (J)"}
        for k in quantities:
            if k not in units:
                raise ValueError(f"unknown quantity '{k}' (use {', '.join(units)})")
        if fig is None:
            fig = plt.figure(figsize=(8, 2.5 * len(quantities)))
        axes = fig.subplots(len(quantities), 1, sharex=True, squeeze=False)[:, 0]
        for ax, k in zip(axes, quantities):
            if k == "energy":
                for e in ("kinetic_energy", "potential_energy", "total_energy"):
                    ax.plot(self.t, getattr(self, e), label=e.replace("_", " "))
            else:
                arr = getattr(self, k)
                for j, name in enumerate(self.joint_names):
                    ax.plot(self.t, arr[:, j], label=name)
            ax.set_ylabel(units[k])
            ax.legend(loc="best", fontsize="small")
            ax.grid(True, alpha=0.3)
        axes[-1].set_xlabel("time (s)")
        fig.tight_layout()
        return fig


class TorqueProfile:
    """Inverse dynamics along a trajectory: ``samples`` (a :class:`SimResult`), ``peak`` torque
    per joint and when (``peak_time``), ``rms``, ``effort_limit``, ``violations`` (every sample
    over a limit: dicts ``joint``, ``t``, ``tau``, ``limit``) and ``violation_summary`` (joint →
    ``count``, ``first_time``, ``worst``; the library's statistics)."""

    def __init__(self, data: Dict[str, Any]):
        self.samples = SimResult(data["samples"])
        self.peak: np.ndarray = data["peak"]
        self.peak_time: np.ndarray = data["peak_time"]
        #: joint name → ``{"count", "first_time", "worst"}`` for joints over their limit
        self.violation_summary: Dict[str, Dict[str, float]] = dict(data["violation_summary"])
        self.rms: np.ndarray = data["rms"]
        self.effort_limit: np.ndarray = data["effort_limit"]
        self.violations: List[Dict[str, Any]] = list(data["violations"])

    @property
    def joint_names(self) -> List[str]:
        return self.samples.joint_names

    def save(self, path) -> None:
        """Writes the samples as a run file (see :meth:`SimResult.save`)."""
        self.samples.save(path)

    def __repr__(self) -> str:
        return (f"TorqueProfile({len(self.samples)} samples, peak={np.round(self.peak, 6).tolist()}, "
                f"{len(self.violations)} violations)")

    def summary(self):
        """Peak, RMS and limit per joint as a pandas DataFrame (needs pandas)."""
        pd = _pandas()
        return pd.DataFrame({"peak": self.peak, "rms": self.rms, "effort_limit": self.effort_limit},
                            index=pd.Index(self.joint_names, name="joint"))

    def to_dataframe(self):
        """The samples as a DataFrame (see :meth:`SimResult.to_dataframe`)."""
        return self.samples.to_dataframe()

    def _repr_markdown_(self) -> str:
        rows = ["| joint | peak | RMS | limit |", "| --- | ---: | ---: | ---: |"]
        for j, name in enumerate(self.joint_names):
            rows.append(f"| {name} | {_num(self.peak[j])} | {_num(self.rms[j])} | "
                        f"{_num(self.effort_limit[j])} |")
        rows.append("")
        rows.append(f"{len(self.violations)} samples over an effort limit.")
        return "\n".join(rows)

    def plot(self, *, fig=None):
        """Torque per joint against time with the effort limits dashed (needs matplotlib)."""
        fig = self.samples.plot(("tau",), fig=fig)
        ax = fig.axes[0]
        for j, lim in enumerate(self.effort_limit):
            if np.isfinite(lim):
                color = ax.lines[j].get_color()
                ax.axhline(lim, color=color, linestyle="--", linewidth=0.8)
                ax.axhline(-lim, color=color, linestyle="--", linewidth=0.8)
        return fig


class BaseParameters:
    """The identifiable (base) combinations of the standard inertial parameters (library
    ``identification::BaseParameters``): ``expressions`` (one readable combination per base
    parameter, e.g. ``mx_link2 + m_link2``), ``independent`` (the standard parameter leading
    each), ``standard_names`` (every standard parameter, the columns of ``Model.regressor``),
    ``combination_matrix`` ``K`` (``π_b = K π``) and ``model_values`` (``K π`` of the model's own
    parameters)."""

    def __init__(self, data: Dict[str, Any]):
        self.expressions: List[str] = list(data["expressions"])
        self.independent: List[str] = list(data["independent"])
        self.standard_names: List[str] = list(data["standard_names"])
        self.combination_matrix: np.ndarray = data["combination_matrix"]
        self.model_values: np.ndarray = data["model_values"]

    def __len__(self) -> int:
        return len(self.expressions)

    def __repr__(self) -> str:
        return f"BaseParameters({len(self)} of {len(self.standard_names)} standard parameters)"


class Identification(BaseParameters):
    """Least-squares estimate of the base parameters from a log (library
    ``identification::LeastSquares``): ``values`` (``π̂_b``, in the order of ``expressions``),
    ``std_dev`` (``σ √diag((W_iᵀ W_i)⁻¹)``), ``sigma`` (RMS torque residual corrected for the
    degrees of freedom), ``condition_number`` of the base regressor, ``samples``; and, as
    :class:`BaseParameters`, the expressions, ``K`` and the model's own ``model_values`` to
    compare with."""

    def __init__(self, data: Dict[str, Any]):
        super().__init__(data)
        self.values: np.ndarray = data["values"]
        self.std_dev: np.ndarray = data["std_dev"]
        self.sigma: float = float(data["sigma"])
        self.condition_number: float = float(data["condition_number"])
        self.samples: int = int(data["samples"])

    def __repr__(self) -> str:
        return (f"Identification({len(self)} base parameters from {self.samples} samples, "
                f"σ = {self.sigma:.3g}, cond = {self.condition_number:.3g})")

    def to_dataframe(self):
        """Estimate, standard deviation and the model's value per base parameter (pandas)."""
        pd = _pandas()
        return pd.DataFrame({"estimate": self.values, "std_dev": self.std_dev,
                             "model": self.model_values},
                            index=pd.Index(self.expressions, name="base parameter"))

    def _repr_markdown_(self) -> str:
        rows = ["| base parameter | estimate | σ | model |", "| --- | ---: | ---: | ---: |"]
        for e, x, s, m in zip(self.expressions, self.values, self.std_dev, self.model_values):
            rows.append(f"| {e} | {_num(x)} | {_num(s)} | {_num(m)} |")
        rows.append("")
        rows.append(f"{self.samples} samples, σ = {_num(self.sigma)}, condition number "
                    f"{_num(self.condition_number)}.")
        return "\n".join(rows)


class IkResult:
    """What ``Model.inverse_kinematics`` found: ``q`` ((nq,) or (N, nq)), ``success``,
    ``iterations``, ``restarts``, ``position_error`` (m), ``orientation_error`` (rad) and
    ``failure`` (None, "unreachable", "limits" or "budget"): scalars for one target, NumPy
    arrays (``failure`` a list) for a batch. ``success`` is true only when forward kinematics
    of ``q`` reaches the target within both tolerances and every joint is within its limits.
    """

    def __init__(self, data: Dict[str, Any]):
        batch = bool(data["batch"])
        self.q: np.ndarray = data["q"]
        if batch:
            self.success = np.asarray(data["success"], dtype=bool)
            self.iterations = np.asarray(data["iterations"], dtype=np.int64)
            self.restarts = np.asarray(data["restarts"], dtype=np.int64)
            self.position_error = np.asarray(data["position_error"], dtype=float)
            self.orientation_error = np.asarray(data["orientation_error"], dtype=float)
            self.failure = list(data["failure"])
        else:
            self.success = bool(data["success"][0])
            self.iterations = int(data["iterations"][0])
            self.restarts = int(data["restarts"][0])
            self.position_error = float(data["position_error"][0])
            self.orientation_error = float(data["orientation_error"][0])
            self.failure = data["failure"][0]

    def __repr__(self) -> str:
        if isinstance(self.success, np.ndarray):
            return (f"IkResult({self.success.sum()} of {self.success.size} succeeded, "
                    f"max position_error={self.position_error.max():.3g} m, "
                    f"max orientation_error={self.orientation_error.max():.3g} rad)")
        return (f"IkResult(success={self.success}, q={np.array2string(self.q, precision=6)}, "
                f"position_error={self.position_error:.3g} m, "
                f"orientation_error={self.orientation_error:.3g} rad, failure={self.failure!r})")
