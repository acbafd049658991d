#!/usr/bin/env python3
"""Arb's own integration of one case's four segment integrals as a whole process, to set
beside `microslip dissipation --digits N` under `/usr/bin/time` (CPU of the whole process,
node tables included).

Usage: /usr/bin/time -f "%U user %S sys" benches/arb_whole_process.py DIGITS CASE
with CASE a name of benches/arb_side_by_side.py's CASES (needs python-flint; not run in CI).
"""

import importlib.util
import sys
from pathlib import Path

spec = importlib.util.spec_from_file_location("side", Path(__file__).with_name("arb_side_by_side.py"))
side = importlib.util.module_from_spec(spec)
spec.loader.exec_module(side)

digits, name = int(sys.argv[1]), sys.argv[2]
loads, slope = next((case[1], case[2]) for case in side.CASES if case[0] == name)
side.ctx.dps = digits + 5
print(side.arb_w(loads, slope).str(20))
