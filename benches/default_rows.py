"""Random rows of four hard classes for the proven default: 0 wrong digits, every row proven.

    python3 benches/default_rows.py rows SEED N rows.csv
    microslip batch --input rows.csv --output default.csv -q
    microslip batch --input rows.csv --output digits.csv --digits 30 -q
    python3 benches/default_rows.py compare default.csv digits.csv

The classes (a quarter each): ordinary cycles of every family; sums whose terms cancel (a power law
or Hertz minus 0.9 to 0.999999 of itself); steep power laws (β from −1 to −6) within 1e-3 to 1e-9
of separation; exponentials across 10 to 2,000 decay lengths. Every row lies inside the theory
(no gross slip, decided by mpmath at 60 digits). `compare` counts the default rows that are not
proven (provenance other than `certified` or `exact`), and those whose printed W is not the
`--digits 30` W rounded to the default's digits (proofs/printing.md).
"""

import csv
import random
import sys

import mpmath

mpmath.mp.dps = 60


def amplitudes_fit(p0: float, p1: str, q1: str, phi: float, friction: float) -> bool:
    """Whether |Q| < fP through the cycle (Q0 = 0): both σ± = |Q1 e^{iφ} ∓ fP1| below fP0."""
    fp1 = friction * mpmath.mpf(p1)
    q = mpmath.mpf(q1)
    cross = 2 * q * fp1 * mpmath.cos(phi)
    worst = max(mpmath.sqrt(q**2 + fp1**2 - cross), mpmath.sqrt(q**2 + fp1**2 + cross))
    return worst < friction * p0 * (1 - mpmath.mpf("1e-6"))


def ordinary(rng: random.Random) -> tuple[str, str, str]:
    family = rng.choice(
        [
            "persson:gamma=1,sigma=1",
            f"power:c=1,beta={rng.uniform(-3, -0.2):.4f}",
            "hertz:r=1,estar=1",
            f"exp:a=1,c={rng.uniform(0.3, 3):.4f},d=0.1",
            f"power:c=1,beta=-0.5+power:c={rng.uniform(0.1, 2):.3f},beta=-1.5",
        ]
    )
    p1 = f"{rng.uniform(0.02, 0.9):.6g}"
    return p1, f"{rng.uniform(0.01, 1.5) * float(p1):.6g}", family


def cancelling(rng: random.Random) -> tuple[str, str, str]:
    keep = 10 ** -rng.uniform(1, 6)
    k = f"{1 - keep:.8f}"
    if rng.random() < 0.5:
        beta = f"{rng.uniform(-3, -0.5):.3f}"
        family = f"power:c=1,beta={beta}+power:c=-{k},beta={beta}"
    else:
        family = f"-{k}*hertz:r=1,estar=1+hertz:r=1,estar=1"
    p1 = f"{rng.uniform(0.05, 0.8):.6g}"
    return p1, f"{rng.uniform(0.01, 1.5) * float(p1):.6g}", family


def near_separation(rng: random.Random) -> tuple[str, str, str]:
    gap = 10 ** -rng.uniform(3, 9)
    p1 = f"{1 - gap:.12f}"
    family = f"power:c=1,beta={rng.uniform(-6, -1):.3f}"
    return p1, f"{rng.uniform(0.01, 1) * gap:.6g}", family


def decay_lengths(rng: random.Random) -> tuple[str, str, str]:
    c = 10 ** -rng.uniform(1, 3.3)
    p1 = f"{rng.uniform(0.02, 0.6):.6g}"
    return p1, f"{rng.uniform(0.01, 1.5) * float(p1):.6g}", f"exp:a=1,c={c:.6g},d=0.001"


CLASSES = [ordinary, cancelling, near_separation, decay_lengths]


def rows(seed: int, count: int, path: str) -> None:
    rng = random.Random(seed)
    with open(path, "w", newline="") as out:
        writer = csv.writer(out)
        writer.writerow(["id", "p0", "p1", "q0", "q1", "phi", "friction", "lambda", "compliance"])
        written = 0
        while written < count:
            make = CLASSES[written % len(CLASSES)]
            p1, q1, family = make(rng)
            phi = rng.uniform(0.01, 3.13)
            friction = rng.uniform(0.1, 1.5)
            if not amplitudes_fit(1.0, p1, q1, phi, friction):
                continue
            lam = f"{rng.uniform(1, 2):.4f}"
            writer.writerow([f"{make.__name__}-{written}", "1", p1, "0", q1, f"{phi:.6f}", f"{friction:.5f}", lam, family])
            written += 1


def compare(default_path: str, digits_path: str) -> None:
    with open(default_path) as a, open(digits_path) as b:
        default_rows, digit_rows = list(csv.DictReader(a)), list(csv.DictReader(b))
    unproven, wrong, failed, counted = [], [], [], 0
    by_class: dict[str, int] = {}
    for row, truth in zip(default_rows, digit_rows, strict=True):
        if row["error"] or truth["error"]:
            failed.append((row["id"], row["error"] or truth["error"]))
            continue
        counted += 1
        kind = row["id"].rsplit("-", 1)[0]
        by_class[kind] = by_class.get(kind, 0) + 1
        if row["provenance"] not in ("certified", "exact"):
            unproven.append((row["id"], row["provenance"]))
        printed, exact = row["W"], mpmath.mpf(truth["W"])
        digits = len(printed.split("e")[0].replace("-", "").replace(".", "").lstrip("0")) or 1
        rounded = mpmath.nstr(exact, digits, min_fixed=1, max_fixed=0, strip_zeros=False)
        if mpmath.mpf(rounded) != mpmath.mpf(printed):
            wrong.append((row["id"], printed, truth["W"]))
    print(f"{counted} rows compared ({', '.join(f'{k} {v}' for k, v in sorted(by_class.items()))}); {len(failed)} failed")
    print(f"not proven: {len(unproven)}; wrong digits: {len(wrong)}")
    for item in (unproven + wrong + failed)[:20]:
        print("  ", *item)


if __name__ == "__main__":
    if sys.argv[1:2] == ["rows"]:
        rows(int(sys.argv[2]), int(sys.argv[3]), sys.argv[4])
    elif sys.argv[1:2] == ["compare"]:
        compare(sys.argv[2], sys.argv[3])
    else:
        sys.exit(__doc__)
