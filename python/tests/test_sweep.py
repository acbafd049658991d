"""dissipation_many: the command line's batch digit for digit, numpy broadcasting, failed
rows, threads and the GIL."""

from __future__ import annotations

import csv
import io
import threading

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import microslip
from conftest import COMPLIANCES, FIELDS, run_cli

PERSSON = "persson:gamma=1,sigma=1"


def random_rows(count: int, seed: int) -> dict[str, np.ndarray]:
    """Random cases, about one in twenty-five outside the friction limit (gross slip)."""
    rng = np.random.default_rng(seed)
    p0 = rng.uniform(0.5, 5, count)
    p1 = p0 * rng.uniform(0.05, 0.9, count)
    friction = rng.uniform(0.3, 1.5, count)
    q1 = friction * (p0 - p1) * rng.uniform(0.01, 0.5, count)
    gross = rng.random(count) < 0.04
    q1[gross] = friction[gross] * (p0[gross] + p1[gross]) * 1.1
    return {
        "p0": p0,
        "p1": p1,
        "q0": friction * (p0 - p1) * rng.uniform(-0.3, 0.3, count),
        "q1": q1,
        "phi": rng.uniform(0.05, 3.1, count),
        "friction": friction,
        "lambda": rng.uniform(1, 2, count),
        "compliance": np.array(COMPLIANCES)[rng.integers(0, len(COMPLIANCES), count)],
    }


def cli_batch(rows: dict[str, np.ndarray], tmp_path, *flags: str) -> list[dict[str, str]]:
    """The CLI batch of the rows, each number written as Python's repr of the float."""
    path = tmp_path / "rows.csv"
    count = len(rows["p0"])
    with path.open("w", newline="") as file:
        writer = csv.writer(file)
        writer.writerow(FIELDS)
        for i in range(count):
            writer.writerow(
                [
                    str(rows[name][i]) if name == "compliance" else repr(float(rows[name][i]))
                    for name in FIELDS
                ]
            )
    done = run_cli("batch", "--input", str(path), "--output", "-", *flags)
    # Exit 1 says that some rows failed; each says why in its error column.
    assert done.returncode in (0, 1) and done.stdout, done.stderr
    return list(csv.DictReader(io.StringIO(done.stdout)))


def sweep(rows: dict[str, np.ndarray], **options) -> microslip.Dissipations:
    given = {("lam" if name == "lambda" else name): value for name, value in rows.items()}
    return microslip.dissipation_many(**given, **options)


def test_two_thousand_rows_equal_the_cli_batch_digit_for_digit(tmp_path):
    rows = random_rows(2000, seed=40)
    expected = cli_batch(rows, tmp_path)
    W = sweep(rows)
    assert W.shape == (2000,) and W.dtype == np.float64
    failed = {
        (i,): row["error"].split(": ", 1)[1] for i, row in enumerate(expected) if row["error"]
    }
    assert 40 <= len(failed) <= 130, "the random rows include gross slip"
    assert W.errors == failed
    assert all("gross slip" in reason for reason in failed.values())
    printed = np.array([float(row["W"]) if row["W"] else np.nan for row in expected])
    np.testing.assert_array_equal(W, printed)


def test_digits_rows_equal_the_cli_batch_with_digits(tmp_path):
    rows = {name: values[:12] for name, values in random_rows(12, seed=7).items()}
    expected = cli_batch(rows, tmp_path, "--digits", "20")
    printed = np.array([float(row["W"]) if row["W"] else np.nan for row in expected])
    np.testing.assert_array_equal(sweep(rows, digits=20), printed)
    assert {row["provenance"] for row in expected if row["W"]} <= {"certified", "exact"}


def test_parameters_broadcast_as_numpy_arrays_do():
    q1 = np.array([0.1, 0.3, 0.5])[:, None]
    phi = np.array([0.5, 1.0, 2.0, 3.0])
    compliance = np.array([PERSSON, "hertz:r=1,estar=1", PERSSON, "power:c=1,beta=-0.5"])
    W = microslip.dissipation_many(
        p0=1, p1=0.4, q1=q1, phi=phi, friction=1, lam=1, compliance=compliance
    )
    assert W.shape == (3, 4) and W.errors == {}
    for i in range(3):
        for j in range(4):
            case = microslip.Case(
                1, 0.4, float(q1[i, 0]), float(phi[j]), 1, str(compliance[j]), lam=1
            )
            assert W[i, j] == microslip.dissipation(case).value
    scalar = microslip.dissipation_many(1, 0.4, 0.5, "0.4pi", 1, lam=1, compliance=PERSSON)
    one = microslip.dissipation(microslip.Case(1, 0.4, 0.5, "0.4pi", 1, PERSSON, lam=1))
    assert scalar.shape == () and float(scalar) == one.value
    texts = microslip.dissipation_many(
        ["1", "2"], "0.4", "0.5", ["0.4pi", "72deg"], 1, nu="0.5", compliance=PERSSON
    )
    assert texts.shape == (2,)
    assert (
        texts[1]
        == microslip.dissipation(
            microslip.Case("2", "0.4", "0.5", "72deg", 1, PERSSON, nu="0.5")
        ).value
    )
    with pytest.raises(ValueError, match="shape mismatch|broadcast"):
        microslip.dissipation_many([1, 2], 0.4, [0.1, 0.2, 0.3], 1, 1, lam=1, compliance=PERSSON)


def test_failed_rows_are_nan_with_reasons_or_raise():
    q1 = np.array([0.2, 1.5, 0.3, 2.0])
    W = microslip.dissipation_many(1, 0.4, q1, "0.4pi", 1, lam=1, compliance=PERSSON)
    assert np.isnan(W).tolist() == [False, True, False, True]
    assert sorted(W.errors) == [(1,), (3,)]
    assert W.errors[(1,)].startswith("gross slip")
    assert W[:2].errors is None  # a derived array does not claim the result's reasons
    with pytest.raises(ValueError, match=r"^row \(1,\): gross slip.*\(2 of 4 rows failed\)"):
        microslip.dissipation_many(
            1, 0.4, q1, "0.4pi", 1, lam=1, compliance=PERSSON, raise_on_error=True
        )
    with pytest.raises(ValueError, match="exactly one of"):
        microslip.dissipation_many(1, 0.4, q1, "0.4pi", 1, compliance=PERSSON)
    bad = microslip.dissipation_many(1, 0.4, 0.2, ["0.4pi", "later"], 1, lam=1, compliance=PERSSON)
    assert np.isnan(bad[1]) and "'later' is not a phase" in bad.errors[(1,)]


def test_one_thread_or_two_give_the_same_values_and_jobs_are_checked():
    rows = {name: values[:200] for name, values in random_rows(200, seed=3).items()}
    np.testing.assert_array_equal(sweep(rows, jobs=1), sweep(rows, jobs=2))
    for jobs in (0, 1025):
        with pytest.raises(ValueError, match=f"jobs = {jobs}: give a whole number of threads"):
            sweep(rows, jobs=jobs)


def test_the_gil_is_released_while_rows_are_computed():
    rows = random_rows(3000, seed=5)
    done = threading.Event()
    result = {}

    def work():
        result["W"] = sweep(rows, jobs=1)
        done.set()

    worker = threading.Thread(target=work)
    worker.start()
    ticks = 0
    while not done.is_set():
        ticks += 1
    worker.join()
    assert result["W"].shape == (3000,)
    # Had the sweep held the GIL, this thread would have stood still while it ran.
    assert ticks > 10_000


@settings(max_examples=25, deadline=None)
@given(
    tenths=st.integers(1, 9),
    q1=st.sampled_from(["0.05", "0.2", "0.45"]),
    compliance=st.sampled_from(COMPLIANCES),
)
def test_the_mirror_image_phi_plus_pi_gives_the_same_w(tenths, q1, compliance):
    # φ + π traces the same ellipse backwards in Q (paper, Section 3): the same W, read
    # exactly from the decimals as written.
    W = microslip.dissipation_many(
        1, 0.4, q1, [f"0.{tenths}pi", f"1.{tenths}pi", f"-0.{10 - tenths}pi"], 1, lam=1,
        compliance=compliance,
    )  # fmt: skip
    assert W.errors == {}
    # Each prints the 12–15 digits its own enclosure proves: equal to those digits.
    assert W[1] == pytest.approx(W[0], rel=1e-11) and W[2] == pytest.approx(W[0], rel=1e-11)
