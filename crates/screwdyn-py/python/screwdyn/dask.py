"""Batch functions over Dask arrays and DataFrames, partition by partition.

A log of 10⁸ states does not fit one process. Dask splits it into chunks; each worker process
runs the batched Rust function on its chunks (over its own cores) and the model travels to the
workers by pickling. Needs the ``dask`` extra: ``pip install screwdyn[dask]``.

Arrays::

    import dask.array as da, screwdyn, screwdyn.dask as sdask
    ur5 = screwdyn.load("builtin:ur5")
    q = da.from_zarr("log.zarr/q")            # (N, 6), chunked along the rows
    tau = sdask.map_states(ur5, "rnea", q, v, a)   # lazy (N, 6)
    tau.to_zarr("log.zarr/tau")               # or tau.compute()

DataFrames (the CLI's column names: ``q.<joint>``, ``v.<joint>``, ``a.<joint>``,
``tau.<joint>``; a missing column is zero)::

    import dask.dataframe as dd
    df = dd.read_parquet("log/*.parquet")
    out = sdask.map_dataframe(ur5, "rnea", df)     # columns tau.<joint>

On a real cluster nothing changes but the client: start a scheduler and workers
(``dask scheduler`` and ``dask worker tcp://host:8786`` on each machine, or dask-jobqueue /
dask-kubernetes for Slurm, PBS or Kubernetes), install ``screwdyn`` on every worker, and connect
with ``distributed.Client("tcp://host:8786")`` before calling the functions above. Set
``threads`` to the cores per worker process if a worker runs several processes.
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from ._screwdyn import Model

#: Per-state functions and the joint-space arguments they take, in order, with the shape of
#: one result: "n" is nq, "s" a scalar, 3/6 fixed widths.
FUNCTIONS: Dict[str, Tuple[Tuple[str, ...], Tuple[Any, ...], str]] = {
    # name: (arguments, result shape per state, result key for DataFrames)
    "rnea": (("q", "v", "a"), ("n",), "tau"),
    "inverse_dynamics": (("q", "v", "a"), ("n",), "tau"),
    "forward_dynamics": (("q", "v", "tau"), ("n",), "qdd"),
    "aba": (("q", "v", "tau"), ("n",), "qdd"),
    "gravity_torque": (("q",), ("n",), "gravity_torque"),
    "nonlinear_effects": (("q", "v"), ("n",), "nonlinear_effects"),
    "crba": (("q",), ("n", "n"), "mass_matrix"),
    "mass_matrix": (("q",), ("n", "n"), "mass_matrix"),
    "mass_matrix_inverse": (("q",), ("n", "n"), "mass_matrix_inverse"),
    "coriolis_matrix": (("q", "v"), ("n", "n"), "coriolis_matrix"),
    "kinetic_energy": (("q", "v"), (), "kinetic_energy"),
    "potential_energy": (("q",), (), "potential_energy"),
    "total_energy": (("q", "v"), (), "total_energy"),
    "center_of_mass": (("q",), (3,), "center_of_mass"),
}


def _dims(shape: Sequence[Any], nq: int) -> Tuple[int, ...]:
    return tuple(nq if d == "n" else d for d in shape)


def _spec(name: str, kwargs: Dict[str, Any]):
    if name not in FUNCTIONS:
        raise ValueError(f"unknown batch function '{name}' (known: {', '.join(FUNCTIONS)})")
    if "out" in kwargs:
        raise ValueError("out= does not apply to Dask: every partition makes its own result")
    return FUNCTIONS[name]


def _block(model: Model, name: str, kwargs: Dict[str, Any], *blocks: np.ndarray) -> np.ndarray:
    """One chunk: the batched Rust function on stacked states (runs on a worker)."""
    out = getattr(model, name)(*[np.ascontiguousarray(b, dtype=float) for b in blocks], **kwargs)
    out = np.asarray(out, dtype=float)
    if out.ndim == 0:  # a single state in the chunk
        out = out.reshape(1)
    return out


def map_states(model: Model, name: str, *arrays, **kwargs):
    """Maps ``model.<name>`` over Dask arrays of stacked states (each ``(N, nq)``, chunked
    along the rows only; they are rechunked to full rows if needed). Returns a lazy Dask array
    ``(N,)``, ``(N, nq)`` or ``(N, nq, nq)``; keyword arguments (``method=``, ``fext=``,
    ``threads=``…) are passed to the function. The model is pickled into the task graph."""
    import dask.array as da

    args, shape, _ = _spec(name, kwargs)
    if len(arrays) != len(args):
        raise ValueError(f"{name} takes {len(args)} stacked arrays ({', '.join(args)}), got {len(arrays)}")
    nq = model.nq
    arrays = [da.asarray(a) for a in arrays]
    for a, what in zip(arrays, args):
        if a.ndim != 2 or a.shape[1] != nq:
            raise ValueError(f"{what} has shape {a.shape}, expected (N, {nq}) stacked states")
    n = arrays[0].shape[0]
    if any(a.shape[0] != n for a in arrays):
        raise ValueError("the stacked arrays need the same number of rows")
    rows = arrays[0].chunks[0]
    arrays = [a.rechunk({0: rows, 1: -1}) for a in arrays]
    out_dims = _dims(shape, nq)
    chunks = (rows,) + tuple((d,) for d in out_dims)
    drop = [] if len(out_dims) >= 1 else [1]
    new = list(range(2, 1 + len(out_dims))) if len(out_dims) > 1 else []
    return da.map_blocks(
        _block, model, name, kwargs, *arrays,
        dtype=float, chunks=chunks, drop_axis=drop, new_axis=new or None,
        meta=np.empty((0,) * (1 + len(out_dims)), dtype=float),
    )


def _columns(key: str, shape: Tuple[int, ...], names: List[str]) -> List[str]:
    if len(shape) == 0:
        return [key]
    if len(shape) == 1 and len(names) == shape[0]:
        return [f"{key}.{j}" for j in names]
    if len(shape) == 1:
        return [f"{key}.{c}" for c in "xyz"[: shape[0]]]
    return [f"{key}.{r}.{c}" for r in names for c in names]


def _frame_block(df, model: Model, name: str, kwargs: Dict[str, Any]):
    import pandas as pd

    args, shape, key = _spec(name, kwargs)
    names = model.joint_names
    stacked = []
    for a in args:
        cols = [f"{a}.{j}" for j in names]
        block = np.zeros((len(df), model.nq))
        for k, c in enumerate(cols):
            if c in df.columns:
                block[:, k] = df[c].to_numpy(dtype=float)
        stacked.append(block)
    out = _block(model, name, kwargs, *stacked) if len(df) else np.zeros((0,) + _dims(shape, model.nq))
    out = out.reshape(len(df), -1)
    return pd.DataFrame(out, index=df.index, columns=_columns(key, _dims(shape, model.nq), names))


def map_dataframe(model: Model, name: str, df, **kwargs):
    """Maps ``model.<name>`` over a Dask (or pandas) DataFrame with the CLI's columns
    (``q.<joint>``, ``v.<joint>``, ``a.<joint>``, ``tau.<joint>``; a missing column is zero),
    partition by partition. Returns a DataFrame with the same index and the result columns
    (``tau.<joint>``, ``qdd.<joint>``, ``mass_matrix.<row>.<col>``, ``kinetic_energy``…)."""
    args, shape, key = _spec(name, kwargs)
    try:
        import dask.dataframe as dd
    except ImportError:  # pragma: no cover
        dd = None
    if dd is not None and isinstance(df, dd.DataFrame):
        import pandas as pd

        cols = _columns(key, _dims(shape, model.nq), model.joint_names)
        meta = pd.DataFrame({c: pd.Series(dtype=float) for c in cols})
        return df.map_partitions(_frame_block, model, name, kwargs, meta=meta)
    return _frame_block(df, model, name, kwargs)


def _ik_block(model: Model, frame: Any, kwargs: Dict[str, Any], targets: np.ndarray) -> np.ndarray:
    """One chunk of (n, 4, 4) targets: ``inverse_kinematics`` on it, packed as (n, nq + 3)
    columns q, success, position_error, orientation_error (runs on a worker)."""
    t = np.ascontiguousarray(targets, dtype=float)
    if t.shape[0] == 0:
        return np.zeros((0, model.nq + 3))
    r = model.inverse_kinematics(frame, t, **kwargs)
    return np.column_stack([r.q, r.success, r.position_error, r.orientation_error])


def map_inverse_kinematics(model: Model, frame: Any, targets, **kwargs):
    """``model.inverse_kinematics(frame, …)`` over a Dask array of targets ``(N, 4, 4)``
    (chunked along the rows only), chunk by chunk on the workers; ``kwargs`` as that method's
    (``q0`` one ``(nq,)`` start for all, ``seed``, ``threads``, ``position_only``, tolerances).
    Returns lazy arrays ``(q, success, position_error, orientation_error)``: ``(N, nq)``,
    ``(N,)`` bool, ``(N,)``, ``(N,)``. Each answer is the one of its target alone, so the
    chunking does not change it. A bad target raises when computed, naming it within its chunk.
    """
    import dask.array as da

    if targets.ndim != 3 or tuple(targets.shape[1:]) != (4, 4):
        raise ValueError(f"targets must be an (N, 4, 4) Dask array, got shape {targets.shape}")
    targets = targets.rechunk({1: 4, 2: 4})
    n = model.nq
    packed = da.map_blocks(
        _ik_block, model, frame, kwargs, targets,
        dtype=float, drop_axis=2, chunks=(targets.chunks[0], (n + 3,)),
        meta=np.empty((0, 0), dtype=float),
    )
    return (packed[:, :n], packed[:, n].astype(bool), packed[:, n + 1], packed[:, n + 2])
