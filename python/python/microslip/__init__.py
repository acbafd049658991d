"""microslip: frictional (microslip) energy dissipation W per load cycle in elastic contacts
of rough surfaces, in f64 or to proven digits.

A :class:`Case` is one load cycle P = P0 + P1 cos θ, Q = Q0 + Q1 cos(θ − φ) on a contact
of friction coefficient f, compliance ratio λ (or Poisson's ratio ν) and normal compliance
SPEC. Numbers are exact decimals: give strings (``"0.4pi"``, ``"1e-300"``) to say exactly
what you mean; a float is read as the shortest decimal that reads back to it (its
``repr``). :func:`dissipation` gives W as ``microslip dissipation`` prints it,
:func:`dissipation_many` a numpy array of W over broadcast parameter arrays on all cores,
:func:`aft` the friction force of a displacement-driven contact in harmonic-balance form with
its exact Jacobian.
"""

from ._microslip import (
    Answer,
    Case,
    PathResult,
    Series,
    Simulation,
    __version__,
    aft,
    dissipation,
    series,
    simulate,
    small_amplitude,
)
from ._path import path
from ._sweep import Dissipations, dissipation_many

__all__ = [
    "Answer",
    "Case",
    "Dissipations",
    "PathResult",
    "Series",
    "Simulation",
    "__version__",
    "aft",
    "dissipation",
    "dissipation_many",
    "path",
    "series",
    "simulate",
    "small_amplitude",
]
