#!/usr/bin/env python3
"""microslip's batch beside the loop a Python user would write: scipy.integrate.quad over
the four segment integrals of every row.

The rows are ordinary cycles (Persson, two power laws, an exponential; P0 = 1 and random
P1, Q1, phi, f, lambda, seeded). microslip runs them as one whole process on one thread
(`microslip batch --jobs 1`), proving 12-15 digits of every W; the Python loop integrates
the same four segment integrals in the cycle angle (src/dissipation/segments.rs,
proofs/four-segment.md) with `scipy.integrate.quad`, split at the lowest-load points, once
with quad's default tolerances (about 8 digits) and once asking for 12 digits
(epsrel = 1e-12), the digits microslip proves. The loop is timed in its own process
without the interpreter's start-up; both W columns are compared with microslip's. On a
shared machine the CPU ratio is the fairer figure.

Usage: benches/scipy_quad_loop.py [ROWS] [path/to/microslip]   (default 20000 rows;
needs numpy and scipy, not run in CI). Issue target: microslip <= 0.35x the loop's time.
"""

import csv
import math
import os
import random
import subprocess
import sys
import tempfile
import time
import warnings

try:
    from scipy.integrate import IntegrationWarning, quad
except ImportError:  # pragma: no cover
    sys.exit("this benchmark needs scipy (pip install scipy)")

from four_segments import segment_pieces

# quad warns where 1e-12 is beyond its own error estimate; the values are compared instead.
warnings.simplefilter("ignore", IntegrationWarning)

FAMILIES = [
    ("persson:gamma=1,sigma=1", lambda P: 1.0 / P),
    ("power:c=0.5,beta=-0.5", lambda P: 0.5 * P ** -0.5),
    ("power:c=1,beta=-1.5", lambda P: P ** -1.5),
    ("exp:a=1,c=0.5,d=0.2", lambda P: math.exp(-P / 0.5) + 0.2),
]


def rows(count, seed=2026):
    """Ordinary cycles inside the theory: no separation (P1 <= 0.5), no gross slip (rho <= 0.6)."""
    draw = random.Random(seed)
    for i in range(count):
        f = round(0.5 + 0.7 * draw.random(), 2)
        p1 = round(0.1 + 0.4 * draw.random(), 4)
        q1 = round((0.1 + 0.5 * draw.random()) * f * p1, 4)
        phi = round(0.05 + 0.9 * draw.random(), 3)
        lam = round(1 + draw.random(), 3)
        yield dict(id=f"r{i}", p0="1", p1=f"{p1}", q0="0", q1=f"{q1}", phi=f"{phi}pi", friction=f"{f}",
                   **{"lambda": f"{lam}"}, compliance=FAMILIES[i % len(FAMILIES)][0])


def scipy_w(row, slope, epsrel):
    """W = lambda * (EB + BC + CH + HE), each by scipy's quad."""
    P0, P1, Q1 = float(row["p0"]), float(row["p1"]), float(row["q1"])
    f, lam, phi = float(row["friction"]), float(row["lambda"]), float(row["phi"][:-2]) * math.pi
    options = dict(epsabs=0.0, epsrel=epsrel, limit=200) if epsrel else {}
    total = 0.0
    for integrand, points in segment_pieces(P0, P1, Q1, f, phi, slope, math, math.pi):
        total += quad(integrand, points[0], points[-1], points=points[1:-1] or None, **options)[0]
    return lam * total


def main():
    count = int(sys.argv[1]) if len(sys.argv) > 1 else 20000
    binary = sys.argv[2] if len(sys.argv) > 2 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "target", "release", "microslip")
    table = list(rows(count))
    slopes = dict(FAMILIES)
    with tempfile.TemporaryDirectory() as directory:
        source, result = os.path.join(directory, "rows.csv"), os.path.join(directory, "w.csv")
        with open(source, "w", newline="") as handle:
            writer = csv.DictWriter(handle, fieldnames=list(table[0]))
            writer.writeheader()
            writer.writerows(table)
        started = time.perf_counter()
        cpu = os.times()
        subprocess.run([binary, "batch", "--quiet", "--jobs", "1", "--input", source, "--output", result], check=True)
        after = os.times()
        ours = time.perf_counter() - started
        ours_cpu = (after.children_user - cpu.children_user) + (after.children_system - cpu.children_system)
        with open(result, newline="") as handle:
            printed = {line["id"]: line for line in csv.DictReader(handle)}
    print(f"{count} rows; microslip batch --jobs 1 (whole process, 12-15 proven digits): "
          f"{ours:.2f} s wall, {ours_cpu:.2f} s CPU")
    for name, epsrel in [("quad defaults", None), ("quad epsrel=1e-12", 1e-12)]:
        started, started_cpu = time.perf_counter(), time.process_time()
        values = [scipy_w(row, slopes[row["compliance"]], epsrel) for row in table]
        loop, loop_cpu = time.perf_counter() - started, time.process_time() - started_cpu
        worst = max(abs(w - float(printed[row["id"]]["W"])) / abs(float(printed[row["id"]]["W"]))
                    for w, row in zip(values, table))
        print(f"scipy loop, {name}: {loop:.2f} s wall, {loop_cpu:.2f} s CPU; largest relative difference "
              f"from microslip {worst:.1e}; microslip / loop = {ours / loop:.2f} (wall), "
              f"{ours_cpu / loop_cpu:.2f} (CPU)")


if __name__ == "__main__":
    main()
