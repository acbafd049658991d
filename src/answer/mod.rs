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
//! else agreement, else the reason), [`agreed`] for W by agreement and the errors of
//! every path to W, [`simulation`] for the simulation's W.

pub mod agreed;
pub mod dissipation;
pub mod simulation;

use rug::Float;

use crate::decimal::printing::{decimal_f64, decimal_interval, rounded_alike_expanded, F64_MOST_DIGITS};
use crate::decimal::rounding::{scientific, DecimalEnd, ENCLOSURE_DIGITS};
use crate::dissipation::{ExactZero, Method, Segments};

pub use crate::decimal::printing::Decimal;

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

/// One value as printed, with the interval its digits were read from.
#[derive(Clone, Debug, PartialEq)]
pub struct Value {
    /// The value by the one printing rule.
    pub decimal: Decimal,
    /// Decimal strings, rounded outwards, of an interval that contains the value (for a
    /// proven provenance, proven to): `None` for an exact value.
    pub enclosure: Option<(String, String)>,
    /// The binary64 number nearest the middle of the enclosure (the value an f64 program
    /// reads), where it is finite and the value is not exact.
    pub binary64: Option<f64>,
}

/// Bits at which [`Value::to_at_most`] reads an enclosure's decimal ends (outwards): far
/// more than their [`ENCLOSURE_DIGITS`] or more digits need.
const ENCLOSURE_BITS: u32 = 256;

impl Value {
    /// Exactly zero.
    pub fn zero() -> Self {
        Value {
            decimal: Decimal::Zero,
            enclosure: None,
            binary64: None,
        }
    }

    /// The value in [`lower`, `upper`], with at most `most` significant digits.
    pub fn within(lower: &Float, upper: &Float, most: u32) -> Self {
        Value::between(lower, upper, most)
    }

    /// [`Value::within`] for ends of either kind.
    fn between<T: DecimalEnd>(lower: &T, upper: &T, most: u32) -> Self {
        let digits = T::enclosure_digits(most);
        let (decimal, expansions) = rounded_alike_expanded(lower, upper, most, digits);
        let enclosure = match expansions {
            Some((low, high)) => (
                scientific(&low.directed(digits, rug::float::Round::Down)),
                scientific(&high.directed(digits, rug::float::Round::Up)),
            ),
            None => (
                lower.directed(digits, rug::float::Round::Down),
                upper.directed(digits, rug::float::Round::Up),
            ),
        };
        let (lower_exact, upper_exact) = (lower.exact(), upper.exact());
        Value {
            decimal,
            enclosure: Some(enclosure),
            binary64: Some(
                Float::with_val(
                    lower_exact.prec().max(upper_exact.prec()) + 1,
                    &lower_exact + &upper_exact,
                )
                .to_f64()
                    / 2.0,
            )
            // Not where f64's range loses the value: infinite, or zero for a value that is not.
            .filter(|middle| middle.is_finite() && (*middle != 0.0 || (lower.is_zero() && upper.is_zero()))),
        }
    }

    /// The value in the ball's real interval (read at `bits`), with at most `most`
    /// significant digits, however far its size lies beyond the range of MPFR.
    #[cfg(feature = "certified")]
    pub fn of_ball(ball: &crate::ball::Ball, bits: u32, most: u32) -> Self {
        let Some((scaled, shift)) = ball.decimal_scaled() else {
            let (lower, upper) = ball.bounds(bits);
            return Value::within(&lower, &upper, most);
        };
        let (lower, upper) = scaled.bounds(bits);
        let value = Value::within(&lower, &upper, most);
        let shift_text = |text: String| crate::decimal::printing::shift_exponent(&text, shift);
        // Beyond MPFR's exponents the value is far beyond f64's too.
        Value {
            decimal: value.decimal.shifted(shift),
            enclosure: value
                .enclosure
                .map(|(lower, upper)| (shift_text(lower), shift_text(upper))),
            binary64: None,
        }
    }

    /// The value in the interval's real part, with at most `most` significant digits:
    /// its two doubles are exact rationals, read as they are.
    pub fn of_interval(interval: &crate::interval::Interval, most: u32) -> Self {
        let (lower, upper) = interval.real_bounds();
        Value::between(&lower, &upper, most)
    }

    /// The value in [`value` − `radius`, `value` + `radius`], with at most `most`
    /// significant digits.
    pub fn about(value: &Float, radius: &Float, most: u32) -> Self {
        let (lower, upper) = crate::decimal::printing::ends(value, &radius.clone().abs());
        Value::within(&lower, &upper, most)
    }

    /// An f64 `value` with an absolute `bound` on its error.
    pub fn from_f64(value: f64, bound: f64) -> Self {
        let (lower, upper) = (Float::with_val(64, value) - bound, Float::with_val(64, value) + bound);
        Value {
            decimal: decimal_f64(value, bound),
            enclosure: Some((
                lower.directed(ENCLOSURE_DIGITS, rug::float::Round::Down),
                upper.directed(ENCLOSURE_DIGITS, rug::float::Round::Up),
            )),
            binary64: Some(value),
        }
    }

    /// The significant digits printed (`u32::MAX` for an exact zero, 0 where none is
    /// determined).
    pub fn digits(&self) -> u32 {
        self.decimal.digits()
    }

    /// The value printed by the one rule to at most `most` significant digits (fewer
    /// where its enclosure does not settle them): rounding the printed digits again would
    /// round twice.
    pub fn to_at_most(&self, most: u32) -> Decimal {
        match (&self.decimal, &self.enclosure) {
            (Decimal::Zero, _) | (_, None) => self.decimal.clone(),
            (_, Some((lower, upper))) => {
                // Read outwards, so that the interval still holds the value.
                let read = |text: &str, round| {
                    Float::parse(text).map(|parsed| Float::with_val_round(ENCLOSURE_BITS, parsed, round).0)
                };
                match (read(lower, rug::float::Round::Down), read(upper, rug::float::Round::Up)) {
                    (Ok(lower), Ok(upper)) => decimal_interval(&lower, &upper, most),
                    _ => self.decimal.clone(),
                }
            }
        }
    }

    /// The enclosure as binary64 numbers rounded outwards, so that every number it holds
    /// lies between them (`(0, 0)` for an exact zero; `None` for an exact value other than
    /// zero, which has no enclosure to round).
    ///
    /// ```
    /// use microslip::answer::Value;
    ///
    /// let value = Value::from_f64(0.1, 1e-17);
    /// let (lower, upper) = value.enclosure_f64().unwrap();
    /// assert!(lower < 0.1 && 0.1 < upper && upper - lower < 1e-16);
    /// assert_eq!(Value::zero().enclosure_f64(), Some((0.0, 0.0)));
    /// ```
    pub fn enclosure_f64(&self) -> Option<(f64, f64)> {
        if self.decimal == Decimal::Zero {
            return Some((0.0, 0.0));
        }
        let (lower, upper) = self.enclosure.as_ref()?;
        let outward = |text: &str, round: rug::float::Round| {
            let (rounded, _) = Float::with_val_round(53, Float::parse(text).ok()?, round);
            Some(rounded.to_f64())
        };
        Some((
            outward(lower, rug::float::Round::Down)?,
            outward(upper, rug::float::Round::Up)?,
        ))
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
