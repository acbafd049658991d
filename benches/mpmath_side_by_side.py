#!/usr/bin/env python3
"""W by mpmath's tanh-sinh beside microslip's certified digits (--digits).

The same four segment integrals in the cycle angle (src/dissipation/segments.rs,
proofs/four-segment.md) are integrated by mpmath.quad (tanh-sinh, split at the same
lowest-load points) at 15, 30, 50 and 100 digits, for three cases; microslip computes the
same W to the same number of certified digits (proven by an Arb enclosure), timed as a whole process and per row of a
batch (node tables warm). Both are compared with a 130-digit value from microslip.

Usage: benches/mpmath_side_by_side.py [path/to/microslip]   (optional dependency: mpmath;
not run in CI). mpmath is timed with its caches warm (one run first, then the best of 3);
the batch per-row time is (t(N + 1 rows) - t(1 row)) / N on one thread.

Besides the certified digits, microslip's single run at a fixed precision with its
error estimate (no verifying run, node tables warm) is timed in process by the criterion
group `single_run` of benches/dissipation.rs, which this script runs with cargo: that is
the like-for-like comparison with one mpmath run (goal >= 20x at 50 and 100 digits; >= 10x
for the digits per row, set when --digits meant two runs agreeing).
"""

import json
import os
import re
import subprocess
import sys
import tempfile
import time

try:
    import mpmath
    from mpmath import mp
except ImportError:  # pragma: no cover
    sys.exit("this benchmark needs mpmath (pip install mpmath)")

from four_segments import segment_pieces

CASES = [
    # name, flags, v'(P) for mpmath
    ("persson", dict(p0="1", p1="0.4", q0="0", q1="0.5", phi="0.4pi", friction="1", **{"lambda": "1"},
                     compliance="persson:gamma=1,sigma=1"), lambda P: 1 / P),
    ("power", dict(p0="1", p1="0.4", q0="0", q1="0.5", phi="0.4pi", friction="1", **{"lambda": "1"},
                   compliance="power:c=0.5,beta=-0.5"), lambda P: mpmath.mpf("0.5") * P ** mpmath.mpf("-0.5")),
    ("hertz", dict(p0="1", p1="0.4", q0="0.1", q1="0.3", phi="0.3pi", friction="0.5", **{"lambda": "1.2"},
                   compliance="hertz:r=1,estar=1"),
     lambda P: mpmath.mpf(2) / 3 * mpmath.cbrt(mpmath.mpf(9) / 16) * P ** (mpmath.mpf(-1) / 3)),
]
DIGITS = [15, 30, 50, 100]
REFERENCE_DIGITS = 130


def number(text):
    """A decimal, or a multiple of pi written '0.4pi'."""
    if text.endswith("pi"):
        return mpmath.mpf(text[:-2] or 1) * mp.pi
    return mpmath.mpf(text)


def mpmath_w(flags, slope):
    """W = lambda * sum of the four segment integrals, by mpmath.quad at the current precision."""
    P0, P1, Q1 = number(flags["p0"]), number(flags["p1"]), number(flags["q1"])
    f, lam, phi = number(flags["friction"]), number(flags["lambda"]), number(flags["phi"])
    pieces = segment_pieces(P0, P1, Q1, f, phi, slope, mpmath, mp.pi)
    return lam * sum(mpmath.quad(integrand, points, method="tanh-sinh") for integrand, points in pieces)


def flag_args(flags):
    return [item for key, value in flags.items() for item in (f"--{key}", value)]


def microslip_json(binary, flags, digits):
    out = subprocess.run([binary, "dissipation", "--json", "--digits", str(digits), *flag_args(flags)],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def whole_process_seconds(binary, flags, digits, repeats=5):
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        subprocess.run([binary, "dissipation", "--digits", str(digits), *flag_args(flags)],
                       check=True, capture_output=True)
        best = min(best, time.perf_counter() - start)
    return best


def batch_seconds(binary, flags, digits, rows, directory):
    path = os.path.join(directory, f"rows-{rows}.csv")
    with open(path, "w") as handle:
        handle.write(",".join(flags) + "\n")
        for _ in range(rows):
            handle.write(",".join(f'"{v}"' for v in flags.values()) + "\n")
    env = dict(os.environ, RAYON_NUM_THREADS="1")
    best = float("inf")
    for _ in range(3):
        start = time.perf_counter()
        subprocess.run([binary, "batch", "--input", path, "--output", "-", "--digits", str(digits)],
                       check=True, capture_output=True, env=env)
        best = min(best, time.perf_counter() - start)
    return best


UNITS = {"s": 1.0, "ms": 1e-3, "µs": 1e-6, "us": 1e-6, "ns": 1e-9}


def single_runs():
    """{(case, digits): (seconds, W, error estimate)} from `cargo bench --bench dissipation -- single_run`."""
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    out = subprocess.run(["cargo", "bench", "--bench", "dissipation", "--", "single_run"],
                         cwd=root, check=True, capture_output=True, text=True).stdout
    values = {}
    for line in out.splitlines():
        if line.startswith("single-run "):
            _, name, digits, w, estimate = line.split()
            values[(name, int(digits))] = (w, float(estimate))
    runs = {}
    for name, digits, middle, unit in re.findall(
            r"single_run/(\w+)/(\d+)\s+time:\s+\[\S+ \S+ (\S+) (\S+)", out):
        w, estimate = values[(name, int(digits))]
        runs[(name, int(digits))] = (float(middle) * UNITS[unit], w, estimate)
    return runs


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(__file__), "..", "target", "release", "microslip")
    singles = single_runs()
    print(f"{'case':<8} {'digits':>6} {'mpmath s':>10} {'mpmath err':>10} {'process s':>10} "
          f"{'row s':>9} {'ms err':>9} {'mpmath/row':>10} {'single s':>10} {'single err':>10} "
          f"{'estimate':>9} {'mpmath/single':>13}")
    with tempfile.TemporaryDirectory() as directory:
        for name, flags, slope in CASES:
            mp.dps = REFERENCE_DIGITS + 10
            reference = mpmath.mpf(microslip_json(binary, flags, REFERENCE_DIGITS)["W"])
            for digits in DIGITS:
                mp.dps = digits
                mpmath_w(flags, slope)  # warm mpmath's node caches at this precision
                best, value = float("inf"), None
                for _ in range(3):
                    start = time.perf_counter()
                    value = mpmath_w(flags, slope)
                    best = min(best, time.perf_counter() - start)
                mp.dps = REFERENCE_DIGITS + 10
                mpmath_error = abs(value - reference) / abs(reference)
                ours = mpmath.mpf(microslip_json(binary, flags, digits)["W"])
                our_error = abs(ours - reference) / abs(reference)
                process = whole_process_seconds(binary, flags, digits)
                rows = 40 if digits <= 50 else 20
                per_row = (batch_seconds(binary, flags, digits, rows + 1, directory)
                           - batch_seconds(binary, flags, digits, 1, directory)) / rows
                single, single_w, estimate = singles[(name, digits)]
                single_error = abs(mpmath.mpf(single_w) - reference) / abs(reference)
                print(f"{name:<8} {digits:>6} {best:>10.4f} {float(mpmath_error):>10.1e} {process:>10.4f} "
                      f"{per_row:>9.4f} {float(our_error):>9.1e} {best / per_row:>10.1f} {single:>10.5f} "
                      f"{float(single_error):>10.1e} {estimate / float(abs(reference)):>9.1e} "
                      f"{best / single:>13.1f}", flush=True)


if __name__ == "__main__":
    main()
