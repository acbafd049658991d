#!/usr/bin/env python3
"""Arb's own integration of the four segment integrals beside microslip's certified W.

The four segment integrals in the cycle angle (src/dissipation/segments.rs,
proofs/four-segment.md) are integrated by python-flint's acb.integral (Arb's
acb_calc_integrate: rigorous Gauss-Legendre error bounds with bisection), one call per
segment, segment end points as balls, at 15, 30, 50 and 100 digits; beside it microslip's
certified W over its own pieces (split at the lowest loads, narrow peaks sinh-mapped), each
by Gauss-Legendre rules on Arb's Bernstein-ellipse bound at the fewest points it allows and
Arb's acb_calc_integrate where those need bisection (src/arb/gauss/), timed in process by
`examples/certified_timing.rs`.
Both enclosures must overlap.

Usage: benches/arb_side_by_side.py [CASE ...]   (all cases by default; optional
dependency: python-flint; not run in CI).
Times are the best of repeated runs over 0.4 s, one thread.
"""

import os
import re
import subprocess
import sys
import time

try:
    from flint import acb, arb, ctx
except ImportError:  # pragma: no cover
    sys.exit("this benchmark needs python-flint (pip install python-flint)")

# name, (p0, p1, q1, phi, f, lambda), v'(P) on acb with the analytic flag, microslip case
CASES = [
    ("persson", ("1", "0.4", "0.5", "0.4pi", "1", "1"), lambda P, a: 1 / P),
    ("power", ("1", "0.4", "0.5", "0.4pi", "1", "1"),
     lambda P, a: acb("0.5") * P.pow(acb("-0.5"), analytic=a)),
    ("hertz", ("1", "0.4", "0.5", "0.4pi", "1", "1"),
     # v' = (2/3)(9/16)^(1/3) P^(-1/3) for r = E* = 1
     lambda P, a: acb(2) / 3 * (acb(9) / 16).pow(acb(1) / 3) * P.pow(acb(-1) / 3, analytic=a)),
    ("power-sum", ("1", "0.4", "0.5", "0.4pi", "1", "1"),
     lambda P, a: P.pow(acb("-0.5"), analytic=a) + acb("0.5") * P.pow(acb("-1.5"), analytic=a)),
    ("near-separation", ("1", "0.999999", "0.0005", "0.5pi", "1", "1"), lambda P, a: 1 / P),
    ("near-separation-1e-9", ("1", "0.999999999", "1e-5", "0.5pi", "1", "1"), lambda P, a: 1 / P),
    ("near-gross-slip", ("1", "0.4", "0.8886569", "1.5", "1", "1"), lambda P, a: 1 / P),
]


def number(text):
    if text.endswith("pi"):
        return arb(text[:-2]) * arb.pi()
    return arb(text)


def arb_w(loads, slope):
    """W by one acb.integral per segment (v' itself: its constant part dissipates nothing)."""
    p0, p1, q1, phi, f, lam = (number(t) for t in loads)
    fp1 = f * p1
    theta_e = arb.atan2(q1 * phi.sin(), q1 * phi.cos() - fp1)
    delta = arb.atan2(2 * q1 * fp1 * phi.sin(), q1 * q1 - fp1 * fp1)
    sigma_plus = ((q1 * phi.cos() + fp1) ** 2 + (q1 * phi.sin()) ** 2).sqrt()
    sigma_minus = ((q1 * phi.cos() - fp1) ** 2 + (q1 * phi.sin()) ** 2).sqrt()
    p_t = p0 - (sigma_plus + sigma_minus) / (2 * f)
    pi = arb.pi()
    theta_c = theta_e + pi
    theta_b, theta_h = theta_c - delta, theta_c + delta
    load = lambda t: p0 + p1 * t.cos()
    rate = lambda t: -p1 * t.sin()
    offset = lambda t: q1 * (t - phi).cos()
    q_rate = lambda t: -q1 * (t - phi).sin()

    def eb(t, a):
        p_s = p_t + sigma_plus * ((t - theta_b) / 2).sin() ** 2 / f
        return offset(t) * (-f * slope(load(t), a) * rate(t) + slope(p_s, a) * sigma_plus * (t - theta_b).sin())

    def bc(t, a):
        return offset(t) * slope(load(t), a) * q_rate(t)

    def ch(t, a):
        p_y = load(2 * theta_c - t)
        return offset(t) * (f * slope(load(t), a) * rate(t) - slope(p_y, a) * sigma_minus * (t - theta_e).sin())

    def he(t, a):
        p_k = p_t + sigma_minus * ((t - theta_e) / 2).sin() ** 2 / f
        return offset(t) * (f * slope(load(t), a) * rate(t) - slope(p_k, a) * sigma_minus * (t - theta_e).sin())

    limits = [(eb, theta_e, theta_b), (bc, theta_b, theta_c), (ch, theta_c, theta_h), (he, theta_h, theta_e + 2 * pi)]
    return lam * sum(acb.integral(g, a, b).real for g, a, b in limits)


def best_of(run, seconds=0.4):
    best, started, value = float("inf"), time.perf_counter(), None
    while time.perf_counter() - started < seconds or value is None:
        t = time.perf_counter()
        value = run()
        best = min(best, time.perf_counter() - t)
    return best, value


def main():
    cases = [c for c in CASES if not sys.argv[1:] or c[0] in sys.argv[1:]]
    microslip = subprocess.run(
        ["cargo", "run", "--release", "--quiet", "--example", "certified_timing"] + [c[0] for c in cases],
        check=True, capture_output=True, text=True).stdout
    ours = {}
    for line in microslip.splitlines():
        m = re.match(r"(\S+) (\d+) ([\d.]+) ms  W = (\S+)", line)
        if m:
            ours[(m[1], int(m[2]))] = (float(m[3]), m[4])
    print(f"(load average {os.getloadavg()[0]:.1f} at the start)")
    print("| case | digits | Arb acb.integral, certified | microslip certified | microslip / Arb |")
    print("|---|---|---|---|---|")
    for name, loads, slope in cases:
        for digits in (15, 30, 50, 100):
            ctx.dps = digits + 5
            seconds, w = best_of(lambda: arb_w(loads, slope))
            ms, text = ours.get((name, digits), (float("nan"), "?"))
            if text != "?" and not w.overlaps(arb(text)) and not arb(text).contains(w.mid()):
                # the decimal is rounded: check it is within half a unit of its last digit
                unit = arb(10) ** (int(text.split("e")[1]) - digits + 1)
                assert abs(w.mid() - arb(text)) < unit, (name, digits, w, text)
            print(f"| {name} | {digits} | {seconds * 1e3:.2f} ms | {ms:.2f} ms | {ms / (seconds * 1e3):.2f} |")
    ctx.dps = 15


if __name__ == "__main__":
    main()
