//! One answer for every quantity microslip prints — W with its segments, the
//! small-amplitude coefficient I(ρ, φ), the series coefficients Iₙ, a partial sum W_N
//! and its difference from W — so that the command line, JSON, batch rows and the
//! catalogue only format it.
//!
//! An [`Answer`] is a value printed by the one rule ([`crate::decimal::printing::decimal_ball`]:
//! a digit is printed only if every point of the value's interval rounds to it), the
//! interval itself, and its [`Provenance`]: what vouches for the interval — a proof
//! (exact by reason, a rigorous enclosure) or an estimate (f64's error estimate, two
//! precisions agreeing, a table's error, the simulation).
//!
//! One policy per quantity builds it: [`dissipation`](mod@dissipation) for W (enclosure,
//! else agreement, else the reason), [`agreed`] for W by agreement, [`series`] for I, Iₙ
//! and W_N, `remainders` (feature `certified`) for the series' proven remainders,
//! [`path`] for a path's W, [`simulation`] for the simulation's W. Every error of these
//! entry points says how a command ends on it ([`ExitStatus`]: exit code and hint).

pub mod agreed;
pub mod dissipation;
mod dissipation_error;
mod exit_status;
pub mod path;
#[cfg(feature = "certified")]
pub mod remainders;
pub mod series;
mod series_error;
pub mod simulation;

use crate::decimal::printing::F64_MOST_DIGITS;
use crate::dissipation::{ExactZero, Method, Segments};

pub use crate::decimal::printing::Decimal;
pub use crate::decimal::value::Value;
pub use dissipation_error::DissipationAnswerError;
pub use exit_status::{ExitStatus, FAILED, REFUSED};

/// What vouches for a printed value.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Provenance {
    /// The value is exactly the one printed, for a reason read from the exact input.
    Exact(ExactReason),
    /// A rigorous enclosure, in f64 interval arithmetic or in Arb's balls at a working
    /// precision: every printed digit is proven.
    Certified {
        /// The working precision of the enclosure, in bits (53 for f64 intervals).
        bits: u32,
        /// The arithmetic that computed the enclosure.
        arithmetic: Arithmetic,
    },
    /// Two computations at different working precisions agree: evidence, not proof.
    Agreement {
        /// The higher of the two working precisions, in bits.
        bits: u32,
    },
    /// A table compliance: the quadrature's estimate plus the table's estimated error of
    /// interpolating its points (an estimate from the data, not a proof).
    Table {
        /// The estimated absolute error due to the table.
        table_error: f64,
        /// The largest relative change the smoothing fit made to the data.
        smoothing_residual: f64,
    },
    /// The history simulation: an independent estimate, not a proof.
    Simulated {
        /// Its estimated absolute error.
        error_estimate: f64,
    },
}

impl Provenance {
    /// Whether the interval printed is proven to contain the value.
    pub fn is_proven(&self) -> bool {
        matches!(self, Provenance::Exact(_) | Provenance::Certified { .. })
    }

    /// The machine-readable name: `exact`, `certified`, `agreement`, `estimate`,
    /// `table_error` or `simulated`.
    pub fn key(&self) -> &'static str {
        match self {
            Provenance::Exact(_) => "exact",
            Provenance::Certified { .. } => "certified",
            Provenance::Agreement { .. } => "agreement",
            Provenance::Table { .. } => "table_error",
            Provenance::Simulated { .. } => "simulated",
        }
    }

    /// The arithmetic of a rigorous enclosure (`None` for every other provenance).
    pub fn arithmetic(&self) -> Option<Arithmetic> {
        match self {
            Provenance::Certified { arithmetic, .. } => Some(*arithmetic),
            _ => None,
        }
    }

    /// The working precision in bits of the value printed (53 for f64).
    pub fn precision_bits(&self) -> Option<u32> {
        match self {
            Provenance::Certified { bits, .. } | Provenance::Agreement { bits } => Some(*bits),
            Provenance::Table { .. } | Provenance::Simulated { .. } => Some(53),
            Provenance::Exact(_) => None,
        }
    }
}

impl std::fmt::Display for Provenance {
    /// How the output names the bound: proven or estimated, and by what.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Provenance::Exact(reason) => write!(f, "exact: {}", reason.reason()),
            Provenance::Certified {
                arithmetic: Arithmetic::F64Intervals,
                ..
            } => f.write_str("proven (rigorous enclosure in f64 interval arithmetic)"),
            Provenance::Certified { bits, .. } => write!(f, "proven (rigorous enclosure at {bits} bits)"),
            Provenance::Agreement { bits } => {
                write!(f, "agreement, not proof (two precisions agree, up to {bits} bits)")
            }
            Provenance::Table { table_error, .. } => {
                write!(
                    f,
                    "estimated (table error {table_error:.1e} with the quadrature's; not proven)"
                )
            }
            Provenance::Simulated { error_estimate } => {
                write!(
                    f,
                    "estimated (simulation, error estimate {error_estimate:.1e}; not proven)"
                )
            }
        }
    }
}

/// The arithmetic of a rigorous enclosure.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arithmetic {
    /// f64 intervals rounded outward (`crate::interval`), 53 bits.
    F64Intervals,
    /// Arb's balls at a working precision of 64 bits or more.
    ArbBalls,
}

impl Arithmetic {
    /// The machine-readable name: `f64 intervals` or `arb balls`.
    pub fn key(self) -> &'static str {
        match self {
            Arithmetic::F64Intervals => "f64 intervals",
            Arithmetic::ArbBalls => "arb balls",
        }
    }
}

/// Why a value is exact.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum ExactReason {
    /// W = 0 (and every W_N, and every segment): see [`ExactZero`].
    Zero(ExactZero),
    /// I₀ ≡ 0: the constant term of v' dissipates nothing (the constant-term theorem).
    ConstantTerm,
    /// In phase (φ = kπ exactly) with ρ ≤ 1: nothing slips, so every Iₙ is 0.
    NothingSlips,
    /// v' is a polynomial of degree ≤ N, so the series ends at order N and W_N − W = 0.
    SeriesEnds,
}

impl ExactReason {
    /// The reason, as printed after `exact:`.
    pub fn reason(self) -> &'static str {
        match self {
            ExactReason::Zero(zero) => zero.reason(),
            ExactReason::ConstantTerm => "the constant term of v' dissipates nothing",
            ExactReason::NothingSlips => "in phase, φ = kπ exactly, with ρ ≤ 1: nothing slips",
            ExactReason::SeriesEnds => "v' is a polynomial of degree ≤ N, so the series ends at order N",
        }
    }

    /// A short machine-readable name.
    pub fn key(self) -> &'static str {
        match self {
            ExactReason::Zero(zero) => zero.key(),
            ExactReason::ConstantTerm => "constant-term",
            ExactReason::NothingSlips => "nothing-slips",
            ExactReason::SeriesEnds => "series-ends",
        }
    }
}

/// One printed quantity: its value, its segments where it has them (W), and what
/// vouches for them.
///
/// ```
/// use microslip::answer::{Answer, Decimal, Provenance, Value};
///
/// // A simulated W with an estimated error of 1.4e-14: its interval
/// // [0.40624757924580…, 0.40624757924583…] rounds alike to 13 digits, not to 14.
/// let value = Value::from_f64(0.406247579245824, 1.4e-14);
/// assert_eq!(value.decimal.to_string(), "4.062475792458e-1");
/// let answer = Answer {
///     value,
///     segments: None,
///     digits_requested: None,
///     provenance: Provenance::Simulated { error_estimate: 1.4e-14 },
///     method: None,
/// };
/// assert_eq!(answer.digits(), 13);
/// assert_eq!(answer.digits_certified(), 0); // an estimate proves nothing
/// assert!(!matches!(answer.value.decimal, Decimal::Zero));
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Answer {
    /// The value.
    pub value: Value,
    /// W's four segments (EB, BC, CH, HE), each by the same rule; `None` for I, Iₙ, W_N.
    pub segments: Option<Segments<Value>>,
    /// The significant digits asked for (`--digits`), if any.
    pub digits_requested: Option<u32>,
    /// What vouches for the value and its segments.
    pub provenance: Provenance,
    /// How W was computed, where the answer is a W.
    pub method: Option<Method>,
}

impl Answer {
    /// W = 0 exactly, and every segment, for `reason`.
    pub fn exact_zero(reason: ExactZero, digits: Option<u32>) -> Answer {
        Answer {
            value: Value::zero(),
            segments: Some(Segments::from_fn(|_| Value::zero())),
            digits_requested: digits,
            provenance: Provenance::Exact(ExactReason::Zero(reason)),
            method: Some(Method::Exact(reason)),
        }
    }

    /// The significant digits printed (at most the request; [`F64_MOST_DIGITS`] or the
    /// request for an exact value).
    pub fn digits(&self) -> u32 {
        match self.value.decimal {
            Decimal::Zero => self.digits_requested.unwrap_or(F64_MOST_DIGITS),
            _ => self.value.digits(),
        }
    }

    /// The digits that are proven (all printed ones for a proven provenance, else 0).
    pub fn digits_certified(&self) -> u32 {
        if self.provenance.is_proven() {
            self.digits()
        } else {
            0
        }
    }
}
