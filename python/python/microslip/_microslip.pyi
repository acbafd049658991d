# Type stubs of the native module: the classes and functions ``microslip`` re-exports.

from collections.abc import Sequence
from decimal import Decimal
from typing import Any, SupportsFloat, SupportsIndex, TypeAlias, final

import numpy as np
import numpy.typing as npt

__version__: str

#: A number as microslip reads it: a decimal string exactly as written (``"0.4pi"``,
#: ``"1e-300"``), an integer or ``Decimal`` exactly, a float as its shortest decimal (repr).
Number: TypeAlias = str | SupportsIndex | SupportsFloat | Decimal

@final
class Case:
    # One load cycle P = P0 + P1 cos θ, Q = Q0 + Q1 cos(θ − φ) on a contact; validated on
    # construction (``ValueError`` with the command line's message).

    def __new__(
        cls,
        p0: Number,
        p1: Number,
        q1: Number,
        phi: Number,
        friction: Number,
        compliance: str,
        lam: Number | None = None,
        nu: Number | None = None,
        q0: Number | None = 0,
    ) -> Case: ...
    @property
    def p0(self) -> str: ...
    @property
    def p1(self) -> str: ...
    @property
    def q0(self) -> str: ...
    @property
    def q1(self) -> str: ...
    @property
    def phi(self) -> str: ...
    @property
    def friction(self) -> str: ...
    @property
    def lam(self) -> str | None: ...
    @property
    def nu(self) -> str | None: ...
    @property
    def compliance(self) -> str: ...
    def __eq__(self, other: object) -> bool: ...

@final
class Answer:
    # A value as printed, with its digits, enclosure and provenance.

    @property
    def value(self) -> float: ...
    @property
    def digits(self) -> int: ...
    @property
    def digits_certified(self) -> int: ...
    @property
    def text(self) -> str | None: ...
    @property
    def enclosure(self) -> tuple[str, str] | None: ...
    @property
    def provenance(self) -> str: ...
    @property
    def provenance_text(self) -> str: ...
    @property
    def proven(self) -> bool: ...
    @property
    def precision_bits(self) -> int | None: ...
    @property
    def value_f64(self) -> float | None: ...
    @property
    def segments(self) -> dict[str, str | None] | None: ...
    @property
    def method(self) -> str | None: ...
    @property
    def no_enclosure(self) -> str | None: ...
    @property
    def error_estimate(self) -> float | None: ...
    @property
    def table_error(self) -> float | None: ...
    def to_mpmath(self, interval: bool = False) -> Any: ...
    def to_arb(self) -> Any: ...
    def __float__(self) -> float: ...

@final
class Series:
    # A case's partial sums W_N of the small-amplitude series beside W.

    @property
    def dissipation(self) -> Answer: ...
    @property
    def partial_sums(self) -> list[Answer]: ...
    @property
    def differences(self) -> list[Answer]: ...
    @property
    def remainder_bounds(self) -> list[float]: ...
    @property
    def lower_bound_of_w(self) -> list[bool]: ...
    @property
    def series_w(self) -> Answer: ...

@final
class Simulation:
    # W by the history simulation, with its steady loop.

    @property
    def W(self) -> Answer: ...  # noqa: N802
    @property
    def w_friction(self) -> Answer: ...
    @property
    def estimated_rel_error(self) -> float: ...
    @property
    def elements(self) -> int: ...
    @property
    def steps(self) -> int: ...
    @property
    def loop(self) -> dict[str, npt.NDArray[np.float64]]: ...

@final
class PathResult:
    # W of a periodic load path (digits two precisions agree on) and its f64 outputs.

    @property
    def W(self) -> float: ...  # noqa: N802
    @property
    def text(self) -> str: ...
    @property
    def digits(self) -> int: ...
    @property
    def digits_agreed(self) -> int: ...
    @property
    def provenance(self) -> str: ...
    @property
    def drive(self) -> str: ...
    @property
    def q_amplitude(self) -> float: ...
    @property
    def u_amplitude(self) -> float: ...
    @property
    def secant_stiffness(self) -> float: ...
    @property
    def loss_factor(self) -> float: ...
    @property
    def damping_ratio(self) -> float: ...
    @property
    def harmonics(self) -> dict[str, npt.NDArray[Any]]: ...
    @property
    def loop(self) -> dict[str, npt.NDArray[np.float64]]: ...

def dissipation(case: Case, digits: int | None = None, max_seconds: float = 60.0) -> Answer: ...
def series(
    case: Case, order: int, digits: int | None = None, max_seconds: float = 60.0
) -> Series: ...
def small_amplitude(
    rho: Number, phi: Number, digits: int | None = None, max_seconds: float = 60.0
) -> Answer: ...
def simulate(
    case: Case,
    elements: int | None = None,
    steps: int | None = None,
    tolerance: float = 1e-6,
    max_seconds: float = 60.0,
) -> Simulation: ...
def aft(
    U: npt.ArrayLike,
    h: Sequence[SupportsIndex] | npt.NDArray[np.integer[Any]],
    p0: float,
    friction: float,
    compliance: str,
    lam: float | None = None,
    nu: float | None = None,
    time_points: int = 128,
    p_harmonics: npt.ArrayLike | None = None,
    elements: int = 256,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    # The friction force's harmonics F (ordered as U: [U_0 if h holds 0, cos h1, sin h1, …])
    # and their exact Jacobian dF/dU (n × n), at normal load p0 (constant: Masing's element),
    # plus p_harmonics in U's order where given (the spring bed of `elements` elements).
    ...

def sweep(
    columns: dict[str, Any], rows: int, digits: int | None, max_seconds: float, jobs: int | None
) -> tuple[npt.NDArray[np.float64], list[tuple[int, str]]]: ...
def _decimal_text(value: Any, field: str) -> str: ...
def _path_of_text(
    contents: str,
    drive: str,
    friction: str,
    compliance: str,
    lam: str | None = None,
    nu: str | None = None,
    digits: int | None = None,
    max_seconds: float = 60.0,
    harmonics_out: int = 3,
) -> PathResult: ...
