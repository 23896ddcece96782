"""The array predicates on chunked dask arrays: local scheduler (default) and, when
dask.distributed is installed, an in-process cluster passed as ``client``."""

import numpy as np
import pytest

from quadric_contact import relative_position as relative_position_batch
from quadric_contact import transversal_contact as transversal_contact_batch
from quadric_contact.exact.errors import ShapeError
from quadric_contact.modes import CertifiedMode
from quadric_contact.testing.samples import random_pairs

da = pytest.importorskip("dask.array")


@pytest.fixture(scope="module")
def data():
    E, Q, _ = random_pairs(600, np.random.default_rng(12))
    return E.reshape(20, 30, 4, 4), Q[:30]


@pytest.mark.parametrize("predicate", [transversal_contact_batch, relative_position_batch])
def test_local_scheduler_matches_the_in_memory_result(data, predicate):
    E, Q = data
    ref = predicate(E, Q)
    dE = da.from_array(E, chunks=(7, 11, 4, 4))
    dQ = da.from_array(Q, chunks=(13, 2, 4))  # the 4x4 axes are rechunked whole
    mode = CertifiedMode()
    got = predicate(dE, dQ, mode=mode)
    assert isinstance(got, np.ndarray) and got.dtype == np.int8
    assert (got == ref).all()
    assert mode.counts.total == E.shape[0] * E.shape[1]  # counted across chunks (threads)
    assert (predicate(dE, Q[0]) == predicate(E, Q[0])).all()


def test_lazy_result_and_errors(data):
    E, Q = data
    lazy = transversal_contact_batch(da.from_array(E, chunks=(5, 30, 4, 4)), Q, compute=False)
    assert isinstance(lazy, da.Array) and lazy.shape == (20, 30)
    assert (lazy.compute() == transversal_contact_batch(E, Q)).all()
    with pytest.raises(ShapeError):
        transversal_contact_batch(da.zeros((3, 4, 5)), Q)
    with pytest.raises(ShapeError):
        transversal_contact_batch(da.from_array(E), Q[:7])


def test_distributed_client(data):
    distributed = pytest.importorskip("dask.distributed")
    E, Q = data
    with distributed.Client(
        processes=False, n_workers=1, threads_per_worker=2, dashboard_address=None
    ) as client:
        got = transversal_contact_batch(da.from_array(E, chunks=(10, 30, 4, 4)), Q, client=client)
    assert (got == transversal_contact_batch(E, Q)).all()
