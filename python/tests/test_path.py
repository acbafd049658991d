"""path: any periodic load path, as ``microslip path`` computes it."""

import json
import math

import numpy as np
import pytest

import microslip
from conftest import FIRST, case_of, run_cli

#: Two harmonics in P and in Q (the command line's test path).
TWO = {
    "P": [(0, "1", "0"), (1, "0.2", "0.1"), (2, "0.05", "-0.02")],
    "Q": [(0, "0.1", "0"), (1, "0.3", "-0.2"), (2, "0.1", "0.07")],
}
CONTACT = {"friction": "1", "lam": "1.2", "compliance": "persson:gamma=1,sigma=1"}


def test_two_harmonics_equal_the_cli(tmp_path):
    result = microslip.path(harmonics=TWO, **CONTACT)
    rows = ["k,P_cos,P_sin,Q_cos,Q_sin"] + [
        f"{k},{p[1]},{p[2]},{q[1]},{q[2]}"
        for k, (p, q) in enumerate(zip(TWO["P"], TWO["Q"], strict=True))
    ]
    file = tmp_path / "two.csv"
    file.write_text("\n".join(rows) + "\n")
    done = run_cli(
        "path", "--harmonics", str(file), "--friction", "1", "--lambda", "1.2",
        "--compliance", "persson:gamma=1,sigma=1", "--json",
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    report = json.loads(done.stdout)
    assert result.text == report["W"]
    assert (result.digits, result.provenance, result.drive) == (15, "certified", "force")
    assert result.digits_certified == 15
    assert result.loss_factor == pytest.approx(report["loss_factor"], rel=1e-12)
    assert result.loss_factor == pytest.approx(
        result.W / (math.pi * result.q_amplitude * result.u_amplitude), rel=1e-12
    )
    assert result.damping_ratio == pytest.approx(result.loss_factor / 2, rel=1e-15)
    harmonics = result.harmonics
    assert list(harmonics["k"]) == [0, 1, 2, 3]
    assert harmonics["Q_cos"][1] == pytest.approx(0.3, abs=1e-12)
    assert harmonics["Q_sin"][1] == pytest.approx(-0.2, abs=1e-12)
    steady = result.loop
    assert steady["theta"].shape == steady["Q"].shape == steady["u"].shape


def test_one_harmonic_gives_the_four_segment_w_and_samples_give_the_harmonics():
    """P = 1 + 0.4 cos θ, Q = 0.5 cos(θ − π/2) = 0.5 sin θ: the README's first cycle at φ = π/2."""
    one = {"P": [(0, 1, 0), (1, "0.4", 0)], "Q": [(1, 0, "0.5")]}
    by_path = microslip.path(
        harmonics=one, friction=1, lam=1, compliance=FIRST["compliance"], digits=15
    )
    case = case_of({**FIRST, "phi": "0.5pi"})
    assert by_path.text == microslip.dissipation(case, digits=15).text
    assert by_path.provenance == "certified"
    theta = 2 * np.pi * np.arange(16) / 16
    samples = {"P": 1 + 0.4 * np.cos(theta), "Q": 0.5 * np.sin(theta)}
    by_samples = microslip.path(samples=samples, friction=1, lam=1, compliance=FIRST["compliance"])
    assert by_samples.W == pytest.approx(by_path.W, rel=1e-13)


def test_displacement_driving_saturates_at_gross_slip_and_matches_aft():
    hertz = {"friction": "0.5", "lam": "1.2", "compliance": "hertz:r=1,estar=100"}
    small = microslip.path(
        harmonics={"P": [(0, 1, 0)], "u": [(1, "0.001", 0)]}, drive="displacement", **hertz
    )
    assert small.drive == "displacement"
    # The same element in harmonic-balance form: W = π Σ k (U_sin F_cos − U_cos F_sin).
    force, _ = microslip.aft(
        [0.001, 0.0], [1], 1.0, 0.5, hertz["compliance"], lam=1.2, time_points=1024
    )
    assert math.pi * (0.0 * force[0] - 0.001 * force[1]) == pytest.approx(small.W, rel=1e-6)
    large = microslip.path(
        harmonics={"P": [(0, 1, 0)], "u": [(1, "1", 0)]}, drive="displacement", **hertz
    )
    assert large.q_amplitude == pytest.approx(0.5, rel=1e-12)
    assert large.W > small.W


def test_refusals_name_the_problem():
    with pytest.raises(ValueError, match="gross slip"):
        microslip.path(harmonics={"P": [(0, 1, 0)], "Q": [(1, 2, 0)]}, **CONTACT)
    with pytest.raises(ValueError, match="exactly one of harmonics= and samples="):
        microslip.path(**CONTACT)
    with pytest.raises(ValueError, match="neither 'force' nor 'displacement'"):
        microslip.path(harmonics=TWO, drive="stress", **CONTACT)
    with pytest.raises(ValueError, match="'u'"):
        microslip.path(harmonics=TWO, drive="displacement", **CONTACT)
    with pytest.raises(ValueError, match="constant normal load|varying"):
        microslip.path(
            harmonics={"P": TWO["P"], "u": [(1, "0.001", 0)]}, drive="displacement", **CONTACT
        )


def test_a_force_driven_path_at_constant_load_is_proven():
    """Constant P: Masing's rule over the rainflow cycles of Q, each cycle's W enclosed."""
    constant = {"P": [(0, 1, 0)], "Q": [(1, "0.3", "0"), (2, "0.1", "0.05")]}
    result = microslip.path(harmonics=constant, **CONTACT)
    assert result.provenance == "certified"
    assert 12 <= result.digits_certified == result.digits <= 15
    precise = microslip.path(harmonics=constant, digits=25, **CONTACT)
    assert (precise.provenance, precise.digits_certified) == ("certified", 25)
    assert float(precise.text) == pytest.approx(result.W, rel=10.0**-result.digits_certified)
