"""series, small_amplitude and simulate: what the command line prints."""

import numpy as np
import pytest

import microslip
from conftest import FIRST, case_of, cli_json, run_cli


def test_series_equals_the_cli():
    result = microslip.series(case_of(FIRST), 4)
    report = cli_json("series", FIRST, "--order", "4")
    assert result.dissipation.text == report["W"]
    assert [s.text for s in result.partial_sums] == [s["value"] for s in report["partial_sums"]]
    assert [d.text for d in result.differences] == [d["value"] for d in report["differences"]]
    assert [s.enclosure for s in result.partial_sums] == [
        tuple(s["enclosure"]) for s in report["partial_sums"]
    ]
    assert all(s.provenance == "certified" for s in result.partial_sums)
    # The proven remainders, as the command line prints them (3 digits rounded up there).
    bounds = [float(s["remainder_bound"]) for s in report["partial_sums"]]
    assert all(
        b <= printed <= b * 1.011
        for b, printed in zip(result.remainder_bounds, bounds, strict=True)
    )
    assert result.lower_bound_of_w == [s["lower_bound_of_w"] for s in report["partial_sums"]]
    assert result.series_w.text == report["series_w"]["value"]
    w = result.dissipation.value
    for partial, bound, below in zip(
        result.partial_sums, result.remainder_bounds, result.lower_bound_of_w, strict=True
    ):
        assert abs(w - partial.value) <= bound
        assert not below or w >= partial.value
    with pytest.raises(ValueError, match="order"):
        microslip.series(case_of(FIRST), 0)


def test_small_amplitude_equals_the_cli():
    answer = microslip.small_amplitude(2, "0.4pi", digits=25)
    report = cli_json("small-amplitude", {"rho": "2", "phi": "0.4pi"}, "--digits", "25")
    assert (answer.text, answer.digits, answer.provenance) == (report["I"], 25, "certified")
    assert answer.enclosure == tuple(report["enclosure"])
    nothing = microslip.small_amplitude("0.5", "pi")
    assert (nothing.value, nothing.provenance) == (0.0, "exact")
    done = run_cli("small-amplitude", "--rho", "-1", "--phi", "1")
    with pytest.raises(ValueError) as raised:
        microslip.small_amplitude(-1, 1)
    assert done.returncode == 2 and done.stderr.strip() == f"microslip: {raised.value}"


def test_simulate_agrees_with_w_within_its_estimate():
    case = case_of(FIRST)
    simulation = microslip.simulate(case, elements=100, steps=300, tolerance=1e-3)
    w = microslip.dissipation(case).value
    assert simulation.W.provenance == "simulated"
    assert abs(simulation.W.value_f64 - w) <= 3 * simulation.estimated_rel_error * w
    report = cli_json(
        "simulate", FIRST, "--elements", "100", "--steps", "300", "--tolerance", "1e-3"
    )
    assert simulation.W.text == report["W"] and simulation.W.value_f64 == report["W_f64"]
    loop = simulation.loop
    assert set(loop) == {"theta", "P", "Q", "u"}
    assert len({len(column) for column in loop.values()}) == 1
    np.testing.assert_allclose(loop["P"], 1 + 0.4 * np.cos(loop["theta"]), atol=1e-12)
    with pytest.raises(RuntimeError, match="tolerance"):
        microslip.simulate(case, elements=20, steps=40, tolerance=1e-12)
