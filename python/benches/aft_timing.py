"""Cost of one `microslip.aft` call against the target of 50 µs: h = [0, 1, 3], 128 time
points, a displacement reaching about half the way to gross slip, for several compliances.

Usage: python python/benches/aft_timing.py [calls]   (default 20000 calls per compliance)

Prints the best of five runs per compliance in wall time and in CPU time of this process,
with the machine's load average: on a shared machine the CPU time is the better measure of
what an idle one would take.
"""

from __future__ import annotations

import os
import sys
import time
import timeit

import numpy as np

import microslip

COMPLIANCES = [
    "hertz:r=1,estar=100",
    "persson:gamma=0.01,sigma=1",
    "power:c=0.02,beta=-0.5",
    "power:c=0.02,beta=-1.5",
    "exp:a=0.02,c=1,d=0.01",
]
H = np.array([0, 1, 3])
U = np.array([1e-3, 1e-2, 0.0, 2e-3, 1e-3])
CONTACT = {"p0": 1.0, "friction": 0.5, "lam": 1.2, "time_points": 128}


def main() -> None:
    calls = int(sys.argv[1]) if len(sys.argv) > 1 else 20000
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores; {calls} calls per run")
    for spec in COMPLIANCES:

        def call(spec: str = spec) -> None:
            microslip.aft(U, H, compliance=spec, **CONTACT)

        wall, cpu = [], []
        for _ in range(5):
            started = time.process_time()
            wall.append(timeit.timeit(call, number=calls) / calls)
            cpu.append((time.process_time() - started) / calls)
        print(f"{spec:32} {min(wall) * 1e6:7.1f} µs wall {min(cpu) * 1e6:7.1f} µs CPU per call")


if __name__ == "__main__":
    main()
