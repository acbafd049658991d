#!/usr/bin/env python3
"""W for v' = a·exp(−P/c) + d by Arb's own integration of the four segments (python-flint's
acb.integral, through benches/arb_side_by_side.py), at loads of many decay loads c.

d dissipates nothing and W is linear in v', so W = exp(−Plow/c)·W[a·exp(−(P − Plow)/c)]
with Plow = P0 − P1: Arb integrates the second, of ordinary size, and the factor is
applied as a decimal exponent. Independent of microslip's pieces, maps and bounds.

Usage: benches/arb_decay_loads.py P0 P1 Q1 PHI F LAMBDA A C [DIGITS]
(optional dependency: python-flint; not run in CI).
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from arb_side_by_side import arb_w  # noqa: E402
from flint import acb, arb, ctx  # noqa: E402

p0, p1, q1, phi, f, lam, a, c = sys.argv[1:9]
ctx.dps = int(sys.argv[9]) if len(sys.argv) > 9 else 25
low, amplitude, decay = arb(p0) - arb(p1), arb(a), arb(c)
shifted = arb_w((p0, p1, q1, phi, f, lam), lambda P, _: acb(amplitude) * (-(P - acb(low)) / acb(decay)).exp())
log10 = -(low / decay) / arb(10).log()
exponent = int(log10.floor().mid().floor().unique_fmpz())
print(f"W = {shifted * arb(10) ** (log10 - exponent)} e{exponent}")
