"""dissipation(case): the command line's W, digits, enclosure and segments; proven digits
on request; the conversions to mpmath and python-flint."""

import sys

import mpmath
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import microslip
from conftest import COMPLIANCES, FIRST, case_of, cli_json


def assert_as_cli(answer: microslip.Answer, report: dict) -> None:
    assert answer.text == report["W"]
    assert answer.value == float(report["W"])
    assert answer.value_f64 == report["W_f64"]
    assert answer.digits == report["digits"]
    assert answer.digits_certified == report["digits_certified"]
    assert answer.provenance == report["provenance"]
    assert answer.precision_bits == report["precision_bits"]
    assert answer.enclosure == (tuple(report["enclosure"]) if report["enclosure"] else None)
    assert answer.method == report["method"]
    assert answer.error_estimate == report["error_estimate"]
    assert answer.segments == report["segments"]


def test_the_first_w_of_the_readme():
    answer = microslip.dissipation(case_of(FIRST))
    # Proven by default: the 13 digits a rigorous enclosure in f64 intervals gives.
    assert answer.text == "4.062475792458e-1"
    assert answer.digits == 13
    assert answer.provenance == "certified" and answer.proven
    assert list(answer.segments) == ["EB", "BC", "CH", "HE"]
    assert answer.segments["HE"] == "2.96789577125e-1"
    assert_as_cli(answer, cli_json("dissipation", FIRST))


def decimal(low: float, high: float) -> st.SearchStrategy[str]:
    return st.floats(low, high, allow_nan=False).map(lambda x: f"{x:.6g}")


@st.composite
def cases(draw) -> dict[str, str]:
    """Cases in the theory: P1 < P0 and Q1 well inside the friction limit."""
    p0 = draw(decimal(0.5, 5))
    p1 = draw(st.floats(0.05, 0.9).map(lambda r: f"{r * float(p0):.6g}"))
    friction = draw(decimal(0.3, 1.5))
    slack = float(friction) * (float(p0) - float(p1))
    q1 = draw(st.floats(0.01, 0.45).map(lambda r: f"{r * slack:.6g}"))
    return {
        "p0": p0,
        "p1": p1,
        "q1": q1,
        "phi": draw(decimal(0.05, 3.1)),
        "friction": friction,
        "lambda": draw(decimal(1, 2)),
        "compliance": draw(st.sampled_from(COMPLIANCES)),
    }


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(cases())
def test_random_cases_equal_the_cli(case):
    assert_as_cli(microslip.dissipation(case_of(case)), cli_json("dissipation", case))


def test_thirty_digits_are_proven_and_enclosed():
    case = case_of(FIRST)
    answer = microslip.dissipation(case, digits=30)
    assert answer.digits == 30 and answer.provenance == "certified" and answer.proven
    assert answer.digits_certified == 30
    mantissa = answer.text.split("e")[0].replace(".", "").lstrip("-")
    assert len(mantissa) == 30
    lower, upper = answer.enclosure
    with mpmath.workdps(60):
        low, high, mid = mpmath.mpf(lower), mpmath.mpf(upper), mpmath.mpf(answer.text)
        # Every point of the enclosure rounds to the 30 digits printed.
        assert low <= high and high - low < mpmath.mpf("1e-30") * abs(mid)
        assert abs(mid - low) <= mpmath.mpf("0.5e-30") and abs(high - mid) <= mpmath.mpf("0.5e-30")
        # The default answer's enclosure holds the 30-digit one.
        default = microslip.dissipation(case)
        default_low, default_high = (mpmath.mpf(end) for end in default.enclosure)
        assert default_low <= low and high <= default_high
    assert_as_cli(answer, cli_json("dissipation", FIRST, "--digits", "30"))
    interval, value = answer.to_mpmath(interval=True), answer.to_mpmath()
    with mpmath.workdps(60):
        # All 30 digits printed, and more: the mpf carries the decimal to 35 digits at least.
        assert abs(value - mpmath.mpf(answer.text)) < mpmath.mpf("1e-35") * abs(value)
        assert mpmath.mpf(interval.a) <= mpmath.mpf(lower) and mpmath.mpf(upper) <= interval.b


def test_an_exact_zero_is_exact():
    case = case_of({**FIRST, "compliance": "const:c=2"})
    answer = microslip.dissipation(case, digits=20)
    assert (answer.text, answer.value, answer.provenance, answer.enclosure) == (
        "0",
        0.0,
        "exact",
        None,
    )
    assert answer.segments == {"EB": "0", "BC": "0", "CH": "0", "HE": "0"}


def test_out_of_time_is_a_runtime_error_and_bad_budgets_value_errors():
    case = case_of(FIRST)
    with pytest.raises(RuntimeError, match="digit"):
        microslip.dissipation(case, digits=1000, max_seconds=0.01)
    for seconds in (0, -1, float("nan"), 2e6):
        with pytest.raises(ValueError, match="max_seconds"):
            microslip.dissipation(case, max_seconds=seconds)
    with pytest.raises(ValueError, match="1001"):
        microslip.dissipation(case, digits=1001)


def test_to_arb_encloses_the_value():
    flint = pytest.importorskip("flint")
    answer = microslip.dissipation(case_of(FIRST), digits=25)
    ball = answer.to_arb()
    assert isinstance(ball, flint.arb)
    lower, upper = answer.enclosure
    previous, flint.ctx.prec = flint.ctx.prec, 256
    try:
        assert ball.contains(flint.arb(lower)) and ball.contains(flint.arb(upper))
        assert ball.rad() < flint.arb("1e-25")
    finally:
        flint.ctx.prec = previous


def test_to_arb_without_python_flint_names_the_package(monkeypatch):
    monkeypatch.setitem(sys.modules, "flint", None)
    answer = microslip.dissipation(case_of(FIRST))
    with pytest.raises(ImportError, match="python-flint"):
        answer.to_arb()
