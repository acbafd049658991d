"""aft: the harmonic-balance friction element, its exact Jacobian and its errors."""

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import microslip
from conftest import run_cli

HERTZ = "hertz:r=1,estar=100"
#: P = 1, f = 0.5, λ = 1.2: gross slip begins at u = g(fP) ≈ 0.023 for the Hertz contact.
CONTACT = {"p0": 1.0, "friction": 0.5, "compliance": HERTZ, "lam": 1.2}


def work_per_cycle(h, U, F):
    """∮ Q du = π Σ_k k (U_sin F_cos − U_cos F_sin) from the harmonics."""
    total, j = 0.0, 0
    for k in h:
        if k == 0:
            j += 1
            continue
        total += k * (U[j + 1] * F[j] - U[j] * F[j + 1])
        j += 2
    return np.pi * total


def shifted(h, coefficients, shift):
    """The harmonics of x(t + shift) from those of x(t)."""
    out, j = np.array(coefficients, dtype=float), 0
    for k in h:
        if k == 0:
            j += 1
            continue
        c, s = coefficients[j], coefficients[j + 1]
        out[j] = c * np.cos(k * shift) + s * np.sin(k * shift)
        out[j + 1] = s * np.cos(k * shift) - c * np.sin(k * shift)
        j += 2
    return out


def test_shapes_and_types():
    F, J = microslip.aft([1e-3, 1e-2, 0.0, 2e-3, 1e-3], [0, 1, 3], **CONTACT)
    assert F.shape == (5,) and J.shape == (5, 5)
    assert F.dtype == np.float64 and J.dtype == np.float64
    F, J = microslip.aft(
        np.array([1e-2, 0.0, 0.0, 3e-3]), np.array([1, 2]), **CONTACT, time_points=64
    )
    assert F.shape == (4,) and J.shape == (4, 4)


def test_jacobian_matches_central_differences():
    rng = np.random.default_rng(40)
    h = [0, 1, 3]
    for scale in [2e-3, 1e-2, 3e-2]:
        U = scale * rng.uniform(-1, 1, 5)
        F, J = microslip.aft(U, h, **CONTACT)
        step = 1e-6 * scale
        differences = np.empty((5, 5))
        for j in range(5):
            up, down = U.copy(), U.copy()
            up[j] += step
            down[j] -= step
            differences[:, j] = (
                microslip.aft(up, h, **CONTACT)[0] - microslip.aft(down, h, **CONTACT)[0]
            ) / (2 * step)
        assert np.max(np.abs(differences - J)) <= 1e-6 * np.max(np.abs(J))


def test_poissons_ratio_gives_lambda():
    U, h = [0.0, 8e-3, 2e-3], [0, 1]
    by_nu = microslip.aft(U, h, 1.0, 0.5, HERTZ, nu=0.3)
    by_lam = microslip.aft(U, h, 1.0, 0.5, HERTZ, lam=(2 - 0.3) / (2 * (1 - 0.3)))
    np.testing.assert_array_equal(by_nu[0], by_lam[0])
    np.testing.assert_array_equal(by_nu[1], by_lam[1])


def test_gross_slip_saturates_the_fundamental():
    # Far beyond gross slip Q = fP·sign(u̇) = −fP·sign(sin t) for u = cos t but for the
    # reversals (0.04 rad each at u1 = 100): a square wave whose fundamental is about
    # −(4fP/π) sin t, lagging by about half a reversal.
    F, J = microslip.aft([100.0, 0.0], [1], **CONTACT, time_points=1024)
    assert F[1] == pytest.approx(-4 * 0.5 / np.pi, rel=1e-3)
    assert 0 < F[0] < 0.02
    assert np.all(np.abs(J) < 1.0)


#: A normal load 1 + 0.3 cos t + 0.1 sin t + 0.05 sin 3t in the layout of h = [0, 1, 3].
SWING = np.array([0.0, 0.3, 0.1, 0.0, 0.05])


def central_differences(U, h, step, **contact):
    """dF/dU by central differences of step `step`."""
    columns = []
    for j in range(len(U)):
        up, down = U.copy(), U.copy()
        up[j] += step
        down[j] -= step
        upper = microslip.aft(up, h, **contact)[0]
        lower = microslip.aft(down, h, **contact)[0]
        columns.append((upper - lower) / (2 * step))
    return np.array(columns).T


def test_jacobian_matches_central_differences_under_a_varying_load():
    # From microslip to gross slip under the lowest load P = 0.6 (g(fP) ≈ 0.011 there).
    rng = np.random.default_rng(41)
    h = [0, 1, 3]
    for scale in [2e-3, 1e-2, 5e-2]:
        U = scale * rng.uniform(-1, 1, 5)
        F, J = microslip.aft(U, h, **CONTACT, p_harmonics=SWING)
        differences = central_differences(U, h, 1e-7 * scale, **CONTACT, p_harmonics=SWING)
        assert np.max(np.abs(J)) > 0
        assert np.max(np.abs(differences - J)) <= 1e-6 * np.max(np.abs(J))


def test_no_normal_harmonics_is_masings_element():
    U, h = [1e-3, 1e-2, 0.0, 2e-3, 1e-3], [0, 1, 3]
    masing = microslip.aft(U, h, **CONTACT)
    for zero in ([0.0] * 5, np.zeros(5)):
        F, J = microslip.aft(U, h, **CONTACT, p_harmonics=zero)
        np.testing.assert_array_equal(F, masing[0])
        np.testing.assert_array_equal(J, masing[1])


def test_a_tiny_normal_amplitude_is_close_to_masing():
    U, h = np.array([0.0, 5e-3, 1.5e-3, 5e-4, 0.0]), [0, 1, 3]
    masing, _ = microslip.aft(U, h, **CONTACT)
    tiny = np.array([0.0, 1e-7, 0.0, 0.0, 0.0])
    F, _ = microslip.aft(U, h, **CONTACT, p_harmonics=tiny, elements=1024)
    # The 1024-element bed: 9e-7 of the largest |F| measured.
    assert np.max(np.abs(F - masing)) <= 5e-6 * np.max(np.abs(masing))
    assert work_per_cycle(h, U, F) == pytest.approx(work_per_cycle(h, U, masing), rel=3e-4)


def test_the_work_per_cycle_is_the_simulations(tmp_path):
    # The same path through `microslip simulate --drive displacement` (extrapolated spring
    # bed, estimated error 1.5e-6): 1024 elements and time points within 2e-5 measured.
    U, h = np.array([0.0, 1e-2, 4e-3, 1.5e-3, -1e-3]), [0, 1, 3]
    F, _ = microslip.aft(U, h, **CONTACT, p_harmonics=SWING, time_points=1024, elements=1024)
    harmonics = tmp_path / "path.csv"
    harmonics.write_text(
        "k,P_cos,P_sin,u_cos,u_sin\n0,1,0,0,0\n1,0.3,0.1,0.01,0.004\n3,0,0.05,0.0015,-0.001\n"
    )
    flags = ["--friction", "0.5", "--lambda", "1.2", "--compliance", HERTZ, "--tolerance", "1e-4"]
    flags += ["--harmonics", str(harmonics), "--drive", "displacement", "--json"]
    done = run_cli("simulate", *flags)
    assert done.returncode == 0, done.stderr
    simulated = json.loads(done.stdout)["W_f64"]
    assert work_per_cycle(h, U, F) == pytest.approx(simulated, rel=2e-4)


@pytest.mark.parametrize(
    ("arguments", "message"),
    [
        ({"U": [0.0, 1e-3], "h": [1, -1]}, "harmonic -1 is negative"),
        ({"U": [0.0] * 4, "h": [2, 1]}, "strictly increasing"),
        ({"U": [0.0] * 2, "h": [0, 1]}, "need 3"),
        ({"U": [[0.0, 1e-3]], "h": [1]}, "2 dimensions"),
        ({"U": [0.0, np.inf], "h": [1]}, "coefficient 1 is inf"),
        ({"U": [0.0, 1e-3], "h": [1], "time_points": 2}, "more than 2 time points"),
        ({"U": [0.0, 1e-3], "h": [1], "p0": -1.0}, "normal load P = -1"),
        ({"U": [0.0, 1e-3], "h": [1], "compliance": "hertz:r=1"}, "estar"),
        ({"U": [0.0, 1e-3], "h": [1], "nu": 0.3}, "exactly one"),
        ({"U": [0.0, 1e-3], "h": [1], "lam": 3.0}, "outside"),
        (
            {"U": [0.0, 1e-3], "h": [1], "p_harmonics": [-1.5, 0.0]},
            "P = -0.5 at time point 0 is not positive",
        ),
        ({"U": [0.0, 1e-3], "h": [1], "p_harmonics": [0.1]}, "the normal load has 1 harmonic"),
        ({"U": [0.0, 1e-3], "h": [1], "p_harmonics": [[0.1, 0.0]]}, "p_harmonics has 2 dimensions"),
        ({"U": [0.0, 1e-3], "h": [1], "p_harmonics": [0.1, 0.0], "elements": 4}, "elements = 4"),
    ],
)
def test_bad_input_raises_one_line(arguments, message):
    call = {**CONTACT, **arguments}
    with pytest.raises(ValueError) as raised:
        microslip.aft(**call)
    assert message in str(raised.value)
    assert "\n" not in str(raised.value)


@settings(max_examples=40, deadline=None)
@given(
    U=st.lists(st.floats(-3e-2, 3e-2), min_size=5, max_size=5),
    samples=st.integers(0, 127),
)
def test_a_time_shift_turns_the_force_and_keeps_w(U, samples):
    h = [0, 1, 3]
    shift = 2 * np.pi * samples / 128
    F, _ = microslip.aft(U, h, **CONTACT)
    moved, _ = microslip.aft(shifted(h, U, shift), h, **CONTACT)
    np.testing.assert_allclose(moved, shifted(h, F, shift), rtol=0, atol=1e-12)
    w = work_per_cycle(h, U, F)
    # Friction only dissipates, and the force never exceeds fP.
    assert w >= -1e-15
    assert abs(F[0]) <= 0.5
    assert work_per_cycle(h, shifted(h, U, shift), moved) == pytest.approx(w, rel=1e-9, abs=1e-15)
