"""W over broadcast parameter arrays: :func:`dissipation_many`."""

from __future__ import annotations

from typing import Any

import numpy as np

from . import _microslip


class Dissipations(np.ndarray):
    """W per row as a float64 array, NaN where a row gave none.

    ``errors`` maps the index of each failed row (a tuple, in the broadcast shape) to why
    it failed. An array derived from this one (a slice, a sum) has ``errors`` None: the
    reasons stay with the result itself.
    """

    errors: dict[tuple[int, ...], str] | None

    def __array_finalize__(self, obj: Any) -> None:
        self.errors = None


def _column(value: Any, shape: tuple[int, ...], field: str) -> Any:
    """A parameter as the sweep takes it: one text for every row, floats, or a text per row
    (each number read as :class:`~microslip.Case` reads it)."""
    values = np.asarray(value)
    if values.ndim == 0:
        return _microslip._decimal_text(values[()], field)
    values = np.broadcast_to(values, shape)
    if values.dtype.kind == "f":
        return np.ascontiguousarray(values, dtype=np.float64).ravel()
    return [_microslip._decimal_text(item, field) for item in values.ravel().tolist()]


def dissipation_many(
    p0: Any,
    p1: Any,
    q1: Any,
    phi: Any,
    friction: Any,
    lam: Any = None,
    nu: Any = None,
    compliance: Any = None,
    q0: Any = 0,
    digits: int | None = None,
    jobs: int | None = None,
    raise_on_error: bool = False,
    max_seconds: float = 60.0,
) -> Dissipations:
    """W for every combination of the broadcast parameters, as ``microslip batch`` gives it.

    Each parameter is a number, a decimal string, or an array-like of them; they broadcast
    as numpy arrays do (``compliance`` a SPEC string or an array of SPECs). Every row takes
    the path a single :func:`dissipation` takes, on ``jobs`` threads (default: one per core)
    with the GIL released; each row has ``max_seconds``. The result holds the printed W of
    each row as the nearest float (NaN where a row fails or not one digit is determined),
    with the reasons of failed rows in ``errors``; with ``raise_on_error`` the first failed
    row raises ``ValueError`` instead.
    """
    if compliance is None:
        raise TypeError(
            "dissipation_many needs compliance: a SPEC such as 'persson:gamma=1,sigma=1'"
        )
    if (lam is None) == (nu is None):
        raise ValueError(
            "give exactly one of the compliance ratio lam (λ) and Poisson's ratio nu (ν)"
        )
    given = {
        "p0": p0,
        "p1": p1,
        "q0": q0,
        "q1": q1,
        "phi": phi,
        "friction": friction,
        "lam": lam,
        "nu": nu,
        "compliance": compliance,
    }
    shape = np.broadcast_shapes(*(np.shape(value) for value in given.values() if value is not None))
    rows = int(np.prod(shape, dtype=np.int64))
    columns = {
        name: None if value is None else _column(value, shape, name)
        for name, value in given.items()
    }
    values, failures = _microslip.sweep(columns, rows, digits, max_seconds, jobs)
    result = values.reshape(shape).view(Dissipations)
    result.errors = {
        tuple(int(i) for i in np.unravel_index(row, shape)): reason for row, reason in failures
    }
    if raise_on_error and failures:
        row, reason = failures[0]
        index = tuple(int(i) for i in np.unravel_index(row, shape))
        raise ValueError(f"row {index}: {reason} ({len(failures)} of {rows} rows failed)")
    return result
