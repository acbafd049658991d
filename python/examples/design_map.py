"""A design map of W over a million load cycles with Dask: Q1 × φ on a 1000 × 1000 grid,
computed block by block by ``microslip.dissipation_many`` on a Dask cluster.

Usage:
    python python/examples/design_map.py                      # a local cluster, one worker per core
    python python/examples/design_map.py tcp://host:8786      # the same map on a running cluster
    python python/examples/design_map.py --size 200           # a 200 × 200 grid

Each block is one ``dissipation_many`` call with the GIL released; a worker computes its
blocks on one thread (``jobs=1``) so that the cluster's workers, not the sweep, divide the
cores. Needs ``pip install "dask[distributed]"``.
"""

from __future__ import annotations

import argparse
import os
import time
from typing import Any

import numpy as np

import microslip

#: The contact and the fixed part of the cycle: the first W of the project's README.
CYCLE = {
    "p0": 1.0,
    "p1": 0.4,
    "friction": 1.0,
    "lam": 1.0,
    "compliance": "persson:gamma=1,sigma=1",
}


def w_block(q1: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """W on one block of the grid (Q1 down the rows, φ along the columns); NaN where a
    cycle leaves the theory (gross slip)."""
    return np.asarray(microslip.dissipation_many(q1=q1, phi=phi, jobs=1, **CYCLE))


def design_map(q1: np.ndarray, phi: np.ndarray, chunk: int = 100) -> Any:
    """W over the grid q1 × phi as a lazy Dask array of ``chunk`` × ``chunk`` blocks:
    ``.compute()`` it on whichever scheduler or cluster is active."""
    import dask.array as da

    rows = da.from_array(q1[:, None], chunks=(chunk, 1))
    columns = da.from_array(phi[None, :], chunks=(1, chunk))
    return da.map_blocks(w_block, rows, columns, dtype=np.float64)


def grid(size: int) -> tuple[np.ndarray, np.ndarray]:
    """Q1 from 0.01 to 0.5 (near gross slip at φ ≈ 0) and φ over (0, π)."""
    return np.linspace(0.01, 0.5, size), np.linspace(0.0, np.pi, size + 2)[1:-1]


def main() -> None:
    from dask.distributed import Client, LocalCluster

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scheduler", nargs="?", help="a cluster's scheduler address")
    parser.add_argument("--size", type=int, default=1000, help="grid points along each axis")
    parser.add_argument("--chunk", type=int, default=100, help="grid points along each block side")
    arguments = parser.parse_args()
    if arguments.scheduler:
        client = Client(arguments.scheduler)
    else:
        cores = os.cpu_count() or 1
        client = Client(LocalCluster(n_workers=cores, threads_per_worker=1, processes=True))
    with client:
        threads = sum(client.nthreads().values())
        q1, phi = grid(arguments.size)
        started = time.perf_counter()
        w = design_map(q1, phi, arguments.chunk).compute()
        elapsed = time.perf_counter() - started
    failed = int(np.isnan(w).sum())
    print(
        f"{w.size} cycles in {elapsed:.1f} s ({elapsed / w.size * 1e6:.0f} µs each) on "
        f"{threads} worker threads; "
        f"W from {np.nanmin(w):.6g} to {np.nanmax(w):.6g}; {failed} cycles outside the theory"
    )


if __name__ == "__main__":
    main()
