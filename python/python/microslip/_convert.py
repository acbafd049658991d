"""An :class:`~microslip.Answer` in the number types of mpmath and python-flint."""

from __future__ import annotations

import math
from typing import Any


def _needs(package: str, module: str, what: str) -> Any:
    try:
        return __import__(module)
    except ImportError as error:
        raise ImportError(f"{what} needs the package {package}: pip install {package}") from error


def _decimal_digits(answer: Any) -> int:
    """Enough decimal digits to carry the printed digits and the enclosure's ends."""
    ends = answer.enclosure or ("0", "0")
    longest = max(len(answer.text or ""), *(len(end) for end in ends))
    return max(20, longest + 5)


def to_mpmath(answer: Any, interval: bool = False) -> Any:
    """The printed value as an ``mpmath.mpf`` with all its digits, or with ``interval`` the
    enclosure as an ``mpmath.iv.mpf`` (a point for an exact value)."""
    mpmath = _needs("mpmath", "mpmath", "Answer.to_mpmath")
    dps = _decimal_digits(answer)
    if interval:
        lower, upper = answer.enclosure or (answer.text, answer.text)
        previous = mpmath.iv.prec
        mpmath.iv.dps = dps
        try:
            return mpmath.iv.mpf([lower, upper])
        finally:
            mpmath.iv.prec = previous
    if answer.text is None:
        raise ValueError("not one digit of this value is determined: use to_mpmath(interval=True)")
    with mpmath.workdps(dps):
        return mpmath.mpf(answer.text)


def to_arb(answer: Any) -> Any:
    """The enclosure as a python-flint ``arb`` ball (exactly 0 for an exact zero)."""
    flint = _needs("python-flint", "flint", "Answer.to_arb")
    if answer.enclosure is None:
        return flint.arb(answer.text)
    bits = math.ceil(_decimal_digits(answer) * math.log2(10)) + 10
    previous = flint.ctx.prec
    flint.ctx.prec = max(previous, bits)
    try:
        lower, upper = (flint.arb(end) for end in answer.enclosure)
        return lower.union(upper)
    finally:
        flint.ctx.prec = previous
