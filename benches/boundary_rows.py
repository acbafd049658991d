"""Random cycles within 1e-15 to 1e-40 of a boundary (separation, gross slip, λ, ν), both sides.

    python3 benches/boundary_rows.py rows SEED N rows.csv
    microslip batch --input rows.csv --output default.csv -q
    microslip batch --input rows.csv --output digits.csv --digits 20 -q
    python3 benches/boundary_rows.py compare rows.csv default.csv digits.csv

`rows` writes the cycles with the truth (column `valid`) decided independently by mpmath at 300
digits; `compare` counts the rows where either mode decides otherwise, and the rows whose default W
is not the proven W rounded to its digits (proofs/boundaries.md).
"""

import csv
import random
import sys

import mpmath

mpmath.mp.dps = 300

COMPLIANCES = ["persson:gamma=1,sigma=1", "power:c=1,beta=-1.5", "hertz:r=1,estar=1", "exp:a=1,c=0.5,d=0.1"]
PHASES = {
    "pi/2": mpmath.pi / 2,
    "pi/3": mpmath.pi / 3,
    "0.4pi": mpmath.mpf(2) / 5 * mpmath.pi,
    "1.1": mpmath.mpf("1.1"),
    "pi+1e-12": mpmath.pi + mpmath.mpf("1e-12"),
    "2.5": mpmath.mpf("2.5"),
}


def decimal(x: mpmath.mpf) -> str:
    """x to 45 significant digits."""
    return mpmath.nstr(x, 45, min_fixed=-1, max_fixed=-1)


def amplitudes(q1: mpmath.mpf, fp1: mpmath.mpf, phase: mpmath.mpf) -> tuple[mpmath.mpf, mpmath.mpf]:
    """σ₋ and σ₊, the amplitudes of Q − fP and −Q − fP."""
    cross = 2 * q1 * fp1 * mpmath.cos(phase)
    return mpmath.sqrt(q1**2 + fp1**2 - cross), mpmath.sqrt(q1**2 + fp1**2 + cross)


def row(index: int) -> dict[str, str]:
    """One cycle near a boundary, and whether the theory covers it."""
    kind = random.choice(["sep", "slip", "lambda", "nu"])
    eps = mpmath.mpf(10) ** (-random.randint(15, 40))
    side = random.choice([1, -1])
    f = mpmath.mpf(random.choice(["0.3", "1", "0.001", "1.7"]))
    p1 = mpmath.mpf(random.uniform(0.1, 0.8))
    q1 = f * p1 * mpmath.mpf(random.uniform(0.1, 0.6))
    phi = random.choice(list(PHASES))
    lam, nu, q0 = "1", "", mpmath.mpf(0)
    if kind == "sep":
        p1 = 1 - side * eps
        q1 = f * abs(1 - p1) * mpmath.mpf("0.3")
    elif kind == "lambda":
        lam = decimal(mpmath.mpf(random.choice([1, 2])) + side * eps)
    elif kind == "nu":
        lam, nu = "", decimal(mpmath.mpf(2) / 3 - side * eps) if random.random() < 0.8 else decimal(-side * eps)
    p1_text, q1_text = decimal(p1), decimal(q1)
    p1, q1 = mpmath.mpf(p1_text), mpmath.mpf(q1_text)
    minus, plus = amplitudes(q1, f * p1, PHASES[phi])
    if kind == "slip":
        # Q0 at a limit of the friction cone, moved in or out by eps·fP0.
        q0 = f - minus - side * eps * f if random.random() < 0.5 else -(f - plus - side * eps * f)
    q0_text = decimal(q0) if q0 != 0 else "0"
    q0 = mpmath.mpf(q0_text)
    valid = 1 - p1 > 0 and q0 - f + minus < 0 and -q0 - f + plus < 0
    valid = valid and (1 <= mpmath.mpf(lam) <= 2 if lam else 0 <= mpmath.mpf(nu) <= mpmath.mpf(2) / 3)
    return {
        "id": f"{kind}-{index}",
        "p0": "1",
        "p1": p1_text,
        "q0": q0_text,
        "q1": q1_text,
        "phi": phi,
        "friction": mpmath.nstr(f, 10),
        "lambda": lam,
        "nu": nu,
        "compliance": random.choice(COMPLIANCES),
        "valid": str(int(valid)),
    }


def write_rows(seed: int, count: int, path: str) -> None:
    random.seed(seed)
    rows = [row(i) for i in range(count)]
    with open(path, "w", newline="") as out:
        writer = csv.DictWriter(out, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


def read(path: str) -> dict[str, dict[str, str]]:
    with open(path, newline="") as file:
        return {r["id"]: r for r in csv.DictReader(file)}


def rounds_to(printed: str, proven: str) -> bool:
    """Whether `printed` is `proven` rounded to as many significant digits."""
    digits = len(printed.split("e")[0].replace(".", "").replace("-", "").lstrip("0"))
    return mpmath.mpf(mpmath.nstr(mpmath.mpf(proven), digits)) == mpmath.mpf(printed)


def compare(rows_path: str, default_path: str, digits_path: str) -> int:
    rows, default, digits = read(rows_path), read(default_path), read(digits_path)
    decided_otherwise = wrong_digits = answered = 0
    for key, truth in rows.items():
        valid = truth["valid"] == "1"
        decided_otherwise += sum(bool(mode[key]["W"]) != valid for mode in (default, digits))
        if default[key]["W"] and digits[key]["W"]:
            answered += 1
            wrong_digits += not rounds_to(default[key]["W"], digits[key]["W"])
    print(
        f"rows {len(rows)}, answered in both modes {answered}, "
        f"decided otherwise than mpmath {decided_otherwise}, wrong default digits {wrong_digits}"
    )
    return int(decided_otherwise + wrong_digits > 0)


if __name__ == "__main__":
    match sys.argv[1:]:
        case ["rows", seed, count, path]:
            write_rows(int(seed), int(count), path)
        case ["compare", rows_path, default_path, digits_path]:
            sys.exit(compare(rows_path, default_path, digits_path))
        case _:
            sys.exit(__doc__)
