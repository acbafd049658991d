"""`dissipation_many` per row in process against `microslip batch` per row on the same rows
(the issue's target: at most 1.2× the batch).

Usage: python python/benches/sweep_against_batch.py [rows]   (default 20000)

The rows are the test suite's random rows (python/tests/test_sweep.py, seed 40). Prints the
wall and CPU time per row of each, best of three, and the machine's load average. The
command line is target/release/microslip (or $MICROSLIP_CLI), built by
`cargo build --release`.
"""

from __future__ import annotations

import csv
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests"))

from test_sweep import random_rows, sweep  # noqa: E402

import microslip  # noqa: E402
from conftest import FIELDS, cli_path  # noqa: E402


def children_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def own_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def write_rows(rows: dict, path: Path) -> None:
    with path.open("w", newline="") as file:
        writer = csv.writer(file)
        writer.writerow(FIELDS)
        for i in range(len(rows["p0"])):
            writer.writerow(
                [
                    str(rows[name][i]) if name == "compliance" else repr(float(rows[name][i]))
                    for name in FIELDS
                ]
            )


def main() -> None:
    count = int(sys.argv[1]) if len(sys.argv) > 1 else 20000
    rows = random_rows(count, seed=40)
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores; {count} rows")
    with tempfile.TemporaryDirectory() as directory:
        path = Path(directory) / "rows.csv"
        write_rows(rows, path)
        command = [str(cli_path()), "batch", "--input", str(path), "--output", "/dev/null", "-q"]
        batch = []
        for _ in range(3):
            wall, cpu = time.perf_counter(), children_cpu()
            subprocess.run(command, check=False)
            batch.append((time.perf_counter() - wall, children_cpu() - cpu))
    python = []
    for _ in range(3):
        wall, cpu = time.perf_counter(), own_cpu()
        values = sweep(rows)
        python.append((time.perf_counter() - wall, own_cpu() - cpu))
    assert isinstance(values, microslip.Dissipations)
    for name, runs in [("microslip batch", batch), ("dissipation_many", python)]:
        wall = min(run[0] for run in runs) / count
        cpu = min(run[1] for run in runs) / count
        print(f"{name:18} {wall * 1e6:8.1f} µs wall {cpu * 1e6:8.1f} µs CPU per row")
    ratio = min(run[1] for run in python) / min(run[1] for run in batch)
    print(f"dissipation_many / batch (CPU): {ratio:.2f}")


if __name__ == "__main__":
    main()
