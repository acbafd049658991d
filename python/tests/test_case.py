"""Case: exact decimals from numbers and strings, validated on construction with the
command line's messages."""

from decimal import Decimal

import numpy as np
import pytest

import microslip
from conftest import run_cli

PERSSON = "persson:gamma=1,sigma=1"


def test_numbers_are_read_as_exact_decimals():
    case = microslip.Case(
        p0=np.int64(3),
        p1=0.1,
        q1=Decimal("1E-3"),
        phi="0.4pi",
        friction=1,
        lam=1.5,
        compliance=PERSSON,
    )
    assert (case.p0, case.p1, case.q1, case.phi, case.friction, case.lam) == (
        "3",
        "0.1",
        "0.001",
        "0.4pi",
        "1",
        "1.5",
    )
    assert case.q0 == "0" and case.nu is None
    # A float is its shortest round-trip decimal, not its binary expansion.
    assert microslip.Case(1, 1 / 3, 0.2, 1.2, 1, PERSSON, lam=1).p1 == repr(1 / 3)
    assert microslip.Case(1, np.array(0.25), np.float32(0.1), 1, 1, PERSSON, lam=1).q1 == repr(
        float(np.float32(0.1))
    )
    assert microslip.Case(1, "0.4", "0.2", "1.2", "1", PERSSON, nu="0.3", q0=-0.05).q0 == "-0.05"


def test_gross_slip_raises_value_error_naming_it_with_the_cli_message():
    flags = [
        "--p0",
        "1",
        "--p1",
        "0.4",
        "--q1",
        "1.5",
        "--phi",
        "0.4pi",
        "--friction",
        "1",
        "--lambda",
        "1",
        "--compliance",
        PERSSON,
    ]
    done = run_cli("dissipation", *flags)
    assert done.returncode == 2
    with pytest.raises(ValueError, match="^gross slip") as raised:
        microslip.Case(p0=1, p1=0.4, q1=1.5, phi="0.4pi", friction=1, lam=1, compliance=PERSSON)
    assert done.stderr.strip() == f"microslip: {raised.value}"


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"p0": "abc"}, r"^P0 \(p0\): 'abc' is not a decimal number"),
        ({"p1": "1"}, "separat"),
        ({"lam": "3"}, "λ"),
        ({"compliance": "persson:gamma=0,sigma=1"}, "gamma"),
        ({"compliance": "table:no-such-table.csv"}, "no-such-table.csv"),
        ({"nu": "0.3"}, "exactly one of"),
        ({"phi": float("nan")}, "the phase φ = 'nan' is not a phase"),
    ],
)
def test_input_outside_the_theory_is_refused(change, message):
    given = dict(p0=1, p1=0.4, q1=0.2, phi="0.4pi", friction=1, lam=1, compliance=PERSSON)
    given.update(change)
    with pytest.raises(ValueError, match=message):
        microslip.Case(**given)


def test_what_is_not_a_number_is_a_type_error():
    with pytest.raises(TypeError, match="p0: a boolean is not a number"):
        microslip.Case(p0=True, p1=0.4, q1=0.2, phi=1, friction=1, lam=1, compliance=PERSSON)
    with pytest.raises(TypeError, match="p1: a boolean is not a number"):
        microslip.Case(p0=1, p1=np.True_, q1=0.2, phi=1, friction=1, lam=1, compliance=PERSSON)
    with pytest.raises(TypeError, match="friction: list is not a number"):
        microslip.Case(p0=1, p1=0.4, q1=0.2, phi=1, friction=[1], lam=1, compliance=PERSSON)
