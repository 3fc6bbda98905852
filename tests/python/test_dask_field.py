"""examples/dask_field.py on a LocalCluster of two worker processes gives the same table as a
plain loop over the same sequences."""
import os
import sys

import pytest

import cropsight as cs

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "examples"))
import dask_field  # noqa: E402


def test_dask_equals_plain_loop(tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    sequences = []
    for seed in (21, 22, 23):
        out = str(tmp_path / f"seq{seed}")
        cs.simulate.broccoli(out, variety="uk", frames=3, seed=seed)
        sequences.append(out)
    plain = dask_field.run_plain(sequences)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        spread = dask_field.run_dask(sequences, client)
    assert plain and spread == plain
    assert {row["sequence"] for row in plain} == set(sequences)
