"""screwdyn.dask on a distributed.LocalCluster with 2 worker processes: the model travels by
pickling, every partition runs the batched Rust function, and the result equals the
single-process batch exactly."""

import numpy as np
import pytest

import screwdyn

da = pytest.importorskip("dask.array")
dd = pytest.importorskip("dask.dataframe")
distributed = pytest.importorskip("distributed")
pd = pytest.importorskip("pandas")

import screwdyn.dask as sdask  # noqa: E402


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    c = distributed.Client(cluster)
    yield c
    c.close()
    cluster.close()


def test_arrays_on_two_worker_processes(client):
    ur5 = screwdyn.load("builtin:ur5")
    ur5.gravity = [0.0, 0.0, -9.80665]  # a changed model must arrive unchanged on the workers
    rng = np.random.default_rng(11)
    n = 20_000
    q, v, a = rng.uniform(-3, 3, (n, 6)), rng.normal(size=(n, 6)), rng.normal(size=(n, 6))
    dq, dv, dA = (da.from_array(x, chunks=(3_000, 6)) for x in (q, v, a))
    tau = sdask.map_states(ur5, "rnea", dq, dv, dA)
    assert tau.shape == (n, 6) and tau.npartitions > 2
    np.testing.assert_array_equal(tau.compute(), ur5.rnea(q, v, a))
    m = sdask.map_states(ur5, "crba", dq)
    assert m.shape == (n, 6, 6)
    np.testing.assert_array_equal(m.compute(), ur5.crba(q))
    ke = sdask.map_states(ur5, "kinetic_energy", dq, dv)
    np.testing.assert_array_equal(ke.compute(), ur5.kinetic_energy(q, v))
    qdd = sdask.map_states(ur5, "forward_dynamics", dq, dv, dA, method="crba")
    np.testing.assert_array_equal(qdd.compute(), ur5.forward_dynamics(q, v, a, method="crba"))
    # the work really ran in the two worker processes
    assert len(client.scheduler_info()["workers"]) == 2


def test_dataframes_on_two_worker_processes(client):
    arm = screwdyn.load("builtin:planar2")
    rng = np.random.default_rng(5)
    n = 5_000
    cols = {}
    for key in ("q", "v", "a"):
        for j in arm.joint_names:
            cols[f"{key}.{j}"] = rng.normal(size=n)
    del cols["a.joint2"]  # a missing column is zero, as in the CLI
    frame = pd.DataFrame(cols)
    ddf = dd.from_pandas(frame, npartitions=4)
    out = sdask.map_dataframe(arm, "rnea", ddf).compute()
    assert list(out.columns) == ["tau.joint1", "tau.joint2"]
    q = frame[["q.joint1", "q.joint2"]].to_numpy()
    v = frame[["v.joint1", "v.joint2"]].to_numpy()
    a = np.column_stack([frame["a.joint1"].to_numpy(), np.zeros(n)])
    np.testing.assert_array_equal(out.to_numpy(), arm.rnea(q, v, a))
    mm = sdask.map_dataframe(arm, "mass_matrix", ddf).compute()
    assert list(mm.columns)[:2] == ["mass_matrix.joint1.joint1", "mass_matrix.joint1.joint2"]
    np.testing.assert_array_equal(mm.to_numpy().reshape(n, 2, 2), arm.crba(q))


def test_unknown_function_is_refused():
    arm = screwdyn.load("builtin:planar2")
    with pytest.raises(ValueError, match="unknown batch function 'fk'"):
        sdask.map_states(arm, "fk", da.zeros((4, 2)))


def test_out_is_refused_for_dask():
    ur5 = screwdyn.load("builtin:ur5")
    q = da.zeros((10, 6), chunks=5)
    with pytest.raises(ValueError, match="out= does not apply to Dask"):
        sdask.map_states(ur5, "crba", q, out=np.empty((10, 6, 6)))
