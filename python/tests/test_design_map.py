"""The Dask design map of python/examples/design_map.py on a small grid: the same values as
one ``dissipation_many`` call. Skipped where dask is not installed (the test job does not
install it)."""

import importlib.util
from pathlib import Path

import numpy as np
import pytest

import microslip

dask = pytest.importorskip("dask")

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "design_map.py"


def load_example():
    spec = importlib.util.spec_from_file_location("design_map", EXAMPLE)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_the_design_map_equals_one_sweep():
    example = load_example()
    q1, phi = example.grid(12)
    lazy = example.design_map(q1, phi, chunk=5)
    assert lazy.shape == (12, 12) and lazy.chunks == ((5, 5, 2), (5, 5, 2))
    with dask.config.set(scheduler="threads"):
        w = lazy.compute()
    expected = microslip.dissipation_many(q1=q1[:, None], phi=phi[None, :], **example.CYCLE)
    np.testing.assert_array_equal(w, np.asarray(expected))
    assert np.isfinite(w).all() and (w > 0).all()
