"""Any periodic load path: :func:`path`."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from . import _microslip

_DRIVEN = {"force": "Q", "displacement": "u"}


def _text(value: Any, field: str) -> str:
    """A number as the exact decimal the command line would read (a float as its repr)."""
    return str(_microslip._decimal_text(value, field))


def _harmonics_csv(harmonics: Any, driven: str) -> str:
    """``k,P_cos,P_sin,{driven}_cos,{driven}_sin`` text from a mapping of
    ``(k, cos, sin)`` rows keyed ``'P'`` and ``driven``, or from a table whose columns are
    those five."""
    if isinstance(harmonics, Mapping):
        missing = [key for key in ("P", driven) if key not in harmonics]
        if missing:
            raise ValueError(f"harmonics needs the keys 'P' and '{driven}'; missing {missing}")
        unknown = sorted(set(harmonics) - {"P", driven})
        if unknown:
            raise ValueError(
                f"harmonics has keys {unknown}; with this drive only 'P' and '{driven}' are read"
            )
        rows: dict[int, list[str]] = {}
        for column, key in ((0, "P"), (2, driven)):
            for row in harmonics[key]:
                if len(row) != 3:
                    raise ValueError(f"harmonics['{key}'] rows are (k, cos, sin); got {row!r}")
                k = int(row[0])
                if k < 0 or k != row[0]:
                    raise ValueError(
                        f"harmonics['{key}'] has k = {row[0]!r}; k is a whole number ≥ 0"
                    )
                cells = rows.setdefault(k, ["0", "0", "0", "0"])
                if cells[column] != "0" or cells[column + 1] != "0":
                    raise ValueError(f"harmonics['{key}'] gives k = {k} twice")
                cells[column] = _text(row[1], f"{key}_cos")
                cells[column + 1] = _text(row[2], f"{key}_sin")
        lines = [",".join([str(k), *rows[k]]) for k in sorted(rows)]
    else:
        table = np.asarray(harmonics, dtype=object)
        if table.ndim != 2 or table.shape[1] != 5:
            raise ValueError(
                f"harmonics is a mapping of (k, cos, sin) rows or a table of 5 columns "
                f"k, P_cos, P_sin, {driven}_cos, {driven}_sin; got shape {table.shape}"
            )
        names = ("k", "P_cos", "P_sin", f"{driven}_cos", f"{driven}_sin")
        lines = [
            ",".join(_text(value, name) for value, name in zip(row, names, strict=True))
            for row in table.tolist()
        ]
    header = f"k,P_cos,P_sin,{driven}_cos,{driven}_sin"
    return "\n".join([header, *lines]) + "\n"


def _samples_csv(samples: Any, driven: str) -> str:
    """``P,{driven}`` text from a mapping of two equal-length sequences or a two-column table."""
    if isinstance(samples, Mapping):
        missing = [key for key in ("P", driven) if key not in samples]
        if missing:
            raise ValueError(f"samples needs the keys 'P' and '{driven}'; missing {missing}")
        columns = [
            np.asarray(samples["P"], dtype=object).ravel(),
            np.asarray(samples[driven], dtype=object).ravel(),
        ]
        if len(columns[0]) != len(columns[1]):
            counts = f"{len(columns[0])} and {len(columns[1])}"
            raise ValueError(f"samples['P'] and samples['{driven}'] have {counts} values")
        table = list(zip(columns[0].tolist(), columns[1].tolist(), strict=True))
    else:
        array = np.asarray(samples, dtype=object)
        if array.ndim != 2 or array.shape[1] != 2:
            raise ValueError(
                f"samples is a mapping or a table of 2 columns P, {driven}; got shape {array.shape}"
            )
        table = array.tolist()
    lines = [f"{_text(p, 'P')},{_text(x, driven)}" for p, x in table]
    return "\n".join([f"P,{driven}", *lines]) + "\n"


def path(
    harmonics: Any = None,
    samples: Any = None,
    *,
    drive: str = "force",
    friction: Any,
    compliance: str,
    lam: Any = None,
    nu: Any = None,
    digits: int | None = None,
    max_seconds: float = 60.0,
    harmonics_out: int = 3,
) -> _microslip.PathResult:
    """W, the amplitudes, the damping, the harmonics and the loop of a contact under any
    periodic load path, as ``microslip path`` computes them.

    Give the path as ``harmonics`` — a mapping ``{'P': [(k, cos, sin), ...], 'Q': [...]}``
    (``'u'`` in place of ``'Q'`` with ``drive='displacement'``), or a table of columns
    ``k, P_cos, P_sin, Q_cos, Q_sin`` — or as ``samples`` of one period at equal steps
    (``{'P': [...], 'Q': [...]}`` or a two-column table), taken as their trigonometric
    interpolant. Numbers are exact decimals: strings are read as written, floats as their
    ``repr``. ``drive='displacement'`` prescribes the tangential displacement u at constant
    P (Masing's rules; Q saturates at ±fP). At constant P, force- or displacement-driven,
    W is proven (a rigorous enclosure: the 12–15 digits f64 intervals prove without
    ``digits``); otherwise it carries the digits on which two working precisions agree (15
    without ``digits``; agreement, not a proof, and the answer says why). The other outputs
    are f64 estimates. Input the theory does not cover raises ``ValueError`` naming it.
    """
    if drive not in _DRIVEN:
        raise ValueError(f"drive '{drive}' is neither 'force' nor 'displacement'")
    if (harmonics is None) == (samples is None):
        raise ValueError("give the path as exactly one of harmonics= and samples=")
    driven = _DRIVEN[drive]
    contents = (
        _harmonics_csv(harmonics, driven)
        if harmonics is not None
        else _samples_csv(samples, driven)
    )
    return _microslip._path_of_text(
        contents,
        drive,
        _text(friction, "friction"),
        compliance,
        lam=None if lam is None else _text(lam, "lam"),
        nu=None if nu is None else _text(nu, "nu"),
        digits=digits,
        max_seconds=max_seconds,
        harmonics_out=harmonics_out,
    )
