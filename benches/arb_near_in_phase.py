#!/usr/bin/env python3
"""Arb's own integration of the four segment integrals near in phase (φ → 0), to set
beside `microslip dissipation ... --phi PHI --digits DIGITS` (Persson v' = 1/P, P0 = f = λ = 1,
P1 = 0.4): prints Arb's ball of W and the CPU seconds it took in process.

Usage: benches/arb_near_in_phase.py DIGITS PHI Q1   (needs python-flint; not run in CI)
"""

import importlib.util
import sys
import time
from pathlib import Path

spec = importlib.util.spec_from_file_location(
    "side", Path(__file__).with_name("arb_side_by_side.py")
)
side = importlib.util.module_from_spec(spec)
spec.loader.exec_module(side)

digits, phi, q1 = int(sys.argv[1]), sys.argv[2], sys.argv[3]
side.ctx.dps = digits + 5
started = time.process_time()
w = side.arb_w(("1", "0.4", q1, phi, "1", "1"), lambda P, a: 1 / P)
print(w.str(20), f"{time.process_time() - started:.3f} s")
