//! Verified digits: a computation run at two working precisions, its results
//! printed only as far as the two agree (with guard digits), the precision raised
//! until they do or the deadline passes — and the rule for when f64 suffices instead.
//!
//! [`verify`] is the one loop; what a run at one precision is, and how it is checked at
//! the higher one, is the caller's [`TwoPrecisions`] strategy (the four-segment W checks
//! with a fixed rule first, a closed form just recomputes). [`verified_values`] is the
//! strategy of a computation that only needs re-running.

use std::time::Instant;

use rug::float::Round;
use rug::Float;

use crate::ladder::{Ladder, Rung, Stop};
use crate::real::{Precision, Real};
use crate::rounding::{scientific, DecimalEnd, Expansion};

/// Digits agreed beyond the target before a value counts as verified.
pub const GUARD_DIGITS: u32 = 4;

/// The most digits that may be asked for.
pub const MAX_DIGITS: u32 = 1000;

/// The number of leading significant digits on which `a` and `b` agree (`u32::MAX`
/// when they are equal).
pub fn agreeing_digits(a: &Float, b: &Float) -> u32 {
    if a == b {
        return u32::MAX;
    }
    let difference = (a.clone() - b).abs();
    let scale = a.clone().abs().max_of(&b.clone().abs());
    let relative = difference / scale;
    let digits = -relative.log10().to_f64();
    if digits.is_finite() && digits > 0.0 {
        digits.floor() as u32
    } else {
        0
    }
}

/// The digits on which every pair of values agrees (`u32::MAX` for no values). Two
/// exact zeros count as agreeing on none unless `zeros_exact`: that is what a complete
/// cancellation looks like at both precisions, and only the computation knows when a
/// zero is exact (a closed form's W = 0).
pub fn agreement(first: &[Float], second: &[Float], zeros_exact: bool) -> u32 {
    first
        .iter()
        .zip(second)
        .map(|(a, b)| {
            if a.is_zero() && b.is_zero() {
                if zeros_exact {
                    u32::MAX
                } else {
                    0
                }
            } else {
                agreeing_digits(&Float::with_val(a.prec().max(b.prec()), a), b)
            }
        })
        .min()
        .unwrap_or(u32::MAX)
}

/// The higher of the two precisions: 32 bits (about 10 digits) more, so that the first
/// run's rounding errors are a billion times the check's and disagreement measures them,
/// plus an eighth, for rounding errors that grow with the length of the computation.
pub fn check_precision(precision: Precision) -> Precision {
    Precision::bits(precision.in_bits() + 32 + precision.in_bits() / 8)
}

/// The precision of the next attempt after one at `precision` agreed on `agreed` of the
/// `required` digits (0 after a run that gave nothing to compare): the digits still
/// missing plus 8, since rounding is what two precisions disagree about, and at least
/// ×5/4, so that a disagreement that is not rounding (an integral that did not converge)
/// still meets a schedule that grows geometrically; at most [`MAX_PRECISION_BITS`].
pub fn next_precision(precision: Precision, required: u32, agreed: u32) -> Precision {
    let missing = Precision::decimal_digits(required.saturating_sub(agreed) + 8).in_bits();
    let raised = (precision.in_bits() * 5 / 4).max(precision.in_bits() + missing);
    Precision::bits(raised.min(MAX_PRECISION_BITS))
}

/// The highest working precision tried (about five million digits): far beyond any
/// case's needs, well inside MPFR's limits, so that a computation that never agrees
/// (complete cancellation) runs into its deadline, not an overflow.
pub const MAX_PRECISION_BITS: u32 = 1 << 24;

/// A computation to verify: a run at one precision, its check at a higher one, and the
/// values in which the two must agree.
pub trait TwoPrecisions {
    /// One run's result.
    type Output;
    /// Why a run failed.
    type Error;
    /// The first precision to try for `required` significant digits.
    fn starting_precision(&self, required: u32) -> Precision {
        Precision::decimal_digits(required + 8)
    }
    /// The run at `precision`; `attempt` counts from 0 (a strategy may widen its own
    /// limits with it).
    fn first(&mut self, precision: Precision, attempt: u32) -> Result<Self::Output, Self::Error>;
    /// The run at the higher `precision` that checks `first`.
    fn check(&mut self, first: &Self::Output, precision: Precision, attempt: u32) -> Result<Self::Output, Self::Error>;
    /// The values that must agree.
    fn values<'a>(&self, output: &'a Self::Output) -> &'a [Float];
    /// Whether the exact zeros among `output`'s values are zeros by theory (a closed
    /// form's), not complete cancellation; by default they are not.
    fn zeros_are_exact(&self, _output: &Self::Output) -> bool {
        false
    }
    /// Whether a failed run may succeed at a higher precision in a later attempt (a
    /// quadrature that did not converge); otherwise the failure is final.
    fn retries(&self, _error: &Self::Error) -> bool {
        false
    }
}

/// A result on which two precisions agreed.
#[derive(Clone, Debug)]
pub struct Verified<T> {
    /// The check run's result (the higher precision).
    pub output: T,
    /// The first run's result (the lower precision): its distance from `output` is the
    /// bound with which `output`'s values are printed ([`agreement_radius`]).
    pub first: T,
    /// The significant digits on which every value agreed (at least those asked for
    /// plus [`GUARD_DIGITS`]).
    pub agreed: u32,
    /// The higher working precision.
    pub precision: Precision,
}

/// The time budget ran out before two precisions agreed to the digits asked for plus
/// [`GUARD_DIGITS`].
#[derive(Debug, Clone, PartialEq)]
pub struct OutOfBudget {
    /// The significant digits asked for.
    pub digits_requested: u32,
    /// The most significant digits on which two precisions agreed.
    pub digits_agreed: u32,
    /// The time spent.
    pub seconds: f64,
    /// The higher precision of the last attempt.
    pub precision_bits: u32,
}

impl OutOfBudget {
    /// The digits two precisions must agree on: those asked for and the guard digits.
    pub fn digits_required(&self) -> u32 {
        self.digits_requested + GUARD_DIGITS
    }

    /// The agreed digits that would have been printed, at most those asked for.
    pub fn digits_reached(&self) -> u32 {
        self.digits_agreed.min(self.digits_requested)
    }
}

/// Why verified digits were not obtained.
#[derive(Debug, Clone, PartialEq)]
pub enum VerifyError<E> {
    /// A run failed, and a higher precision would not help.
    Failed(E),
    /// The deadline passed first.
    OutOfBudget(OutOfBudget),
}

impl<E> VerifyError<E> {
    /// The caller's error: a failed run's own, or `budget` made of the budget error.
    pub fn into_error(self, budget: impl FnOnce(OutOfBudget) -> E) -> E {
        match self {
            VerifyError::Failed(error) => error,
            VerifyError::OutOfBudget(out) => budget(out),
        }
    }
}

/// Runs `computation` at a precision p and checks it at [`check_precision`] (p), and
/// accepts the check's result when every value agrees to `digits` + [`GUARD_DIGITS`]
/// significant digits ([`agreement`]); otherwise tries again at [`next_precision`],
/// until `deadline`. The deadline is looked at before every attempt (none is made past
/// it), and a run that can stop early should be handed it too.
pub fn verify<C: TwoPrecisions>(
    digits: u32,
    deadline: Instant,
    computation: &mut C,
) -> Result<Verified<C::Output>, VerifyError<C::Error>> {
    let started = Instant::now();
    let required = digits + GUARD_DIGITS;
    let start = computation.starting_precision(required);
    let ladder = Ladder::new(start, Precision::bits(MAX_PRECISION_BITS)).until(Some(deadline));
    // The most digits any attempt agreed on, the attempts made, and the last one's precision.
    let (mut best, mut attempt, mut last) = (0, 0, start);
    let rung = |precision: Precision| {
        last = precision;
        let higher = check_precision(precision);
        let outcome = computation
            .first(precision, attempt)
            .and_then(|first| Ok((computation.check(&first, higher, attempt)?, first)));
        attempt += 1;
        let agreed = match outcome {
            Ok((second, first)) => {
                let exact = computation.zeros_are_exact(&first) && computation.zeros_are_exact(&second);
                let agreed = agreement(computation.values(&first), computation.values(&second), exact);
                let determined = || {
                    computation
                        .values(&first)
                        .iter()
                        .zip(computation.values(&second))
                        .all(|(a, b)| decimal_ball(b, &agreement_radius(a, b), digits).digits() >= digits)
                };
                if agreed >= required && determined() {
                    return Rung::Reached(Verified {
                        output: second,
                        first,
                        agreed,
                        precision: higher,
                    });
                }
                // Agreement that still straddles a rounding boundary of the last digit
                // asked for: one more attempt at a higher precision settles it.
                agreed.min(required - 1)
            }
            Err(error) if computation.retries(&error) => 0,
            Err(error) => return Rung::Final(Attempt::Failed(error)),
        };
        best = best.max(agreed);
        Rung::Short(Attempt::Agreed(agreed))
    };
    let next = |precision: Precision, short: &Attempt<C::Error>| match short {
        Attempt::Agreed(agreed) => next_precision(precision, required, *agreed),
        // A failure is final, never short.
        Attempt::Failed(_) => precision,
    };
    match ladder.climb(rung, next) {
        Ok((verified, _)) => return Ok(verified),
        Err(Stop::Final(Attempt::Failed(error))) => return Err(VerifyError::Failed(error)),
        // Out of time, or short at the highest precision (complete cancellation): out of
        // budget either way.
        Err(Stop::OutOfTime { .. } | Stop::Exhausted(_) | Stop::Final(Attempt::Agreed(_))) => {}
    }
    Err(VerifyError::OutOfBudget(OutOfBudget {
        digits_requested: digits,
        digits_agreed: best,
        seconds: started.elapsed().as_secs_f64(),
        // The higher precision of the last attempt (of the first, where none was made).
        precision_bits: check_precision(last).in_bits(),
    }))
}

/// What one attempt of [`verify`] gave: the digits two precisions agreed on, or a failure
/// no precision changes.
enum Attempt<E> {
    Agreed(u32),
    Failed(E),
}

/// The bound with which agreement vouches for the check's `second`: its distance from
/// the `first` run, and at least one unit in the first run's last bit (two runs that
/// agree exactly have not measured their error below that).
pub fn agreement_radius(first: &Float, second: &Float) -> Float {
    let (distance, _) = Float::with_val_round(second.prec(), first - second, Round::AwayZero);
    let distance = distance.abs();
    let resolution = Float::with_val(second.prec(), second.abs_ref()) >> (first.prec().max(2) - 1);
    distance.max(&resolution)
}

/// A computation whose check is the same computation at the higher precision; it must
/// re-read its inputs at the precision it is given.
struct Recompute<F>(F);

impl<E, F: FnMut(Precision) -> Result<Vec<Float>, E>> TwoPrecisions for Recompute<F> {
    type Output = Vec<Float>;
    type Error = E;

    fn first(&mut self, precision: Precision, _attempt: u32) -> Result<Vec<Float>, E> {
        (self.0)(precision)
    }

    fn check(&mut self, _first: &Vec<Float>, precision: Precision, _attempt: u32) -> Result<Vec<Float>, E> {
        (self.0)(precision)
    }

    fn values<'a>(&self, output: &'a Vec<Float>) -> &'a [Float] {
        output
    }
}

/// [`verify`] for values that are checked by computing them again at the higher
/// precision (`compute` re-reads its inputs at the precision it is given).
pub fn verified_values<E>(
    digits: u32,
    deadline: Instant,
    compute: impl FnMut(Precision) -> Result<Vec<Float>, E>,
) -> Result<Verified<Vec<Float>>, VerifyError<E>> {
    verify(digits, deadline, &mut Recompute(compute))
}

/// The most significant digits an f64 result is printed with: binary64 carries 15.95
/// decimal digits, and 15 always survive a round trip through decimal text.
pub const F64_MOST_DIGITS: u32 = 15;

/// A value as printed by the one rule: an N-digit decimal is printed only if every point
/// of the value's interval [value − bound, value + bound] rounds to it (to nearest);
/// otherwise fewer digits, and where not even one is determined, the interval itself.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Decimal {
    /// Exactly zero: the interval is the point 0.
    Zero,
    /// The decimal in scientific notation (`5.25214879245e-1`) with its significant digits.
    Digits {
        /// The decimal as printed.
        text: String,
        /// Its significant digits.
        digits: u32,
    },
    /// Not one significant digit is determined: the interval, rounded outwards to two
    /// digits.
    Undetermined {
        /// The interval's lower end, rounded down.
        lower: String,
        /// The interval's upper end, rounded up.
        upper: String,
    },
}

/// A decimal in scientific notation (`8.26e-5`) times 10^`shift` (`8.26e-872038342` for a
/// shift of −872038337); text without an exponent (`0`, `inf`) as it is.
#[cfg(feature = "certified")]
pub(crate) fn shift_exponent(text: &str, shift: i64) -> String {
    match text
        .split_once('e')
        .map(|(mantissa, exponent)| (mantissa, exponent.parse::<i64>()))
    {
        Some((mantissa, Ok(exponent))) if shift != 0 => format!("{mantissa}e{}", exponent + shift),
        _ => text.to_string(),
    }
}

impl Decimal {
    /// The same decimal times 10^`shift`.
    #[cfg(feature = "certified")]
    pub(crate) fn shifted(self, shift: i64) -> Decimal {
        match self {
            Decimal::Zero => Decimal::Zero,
            Decimal::Digits { text, digits } => Decimal::Digits {
                text: shift_exponent(&text, shift),
                digits,
            },
            Decimal::Undetermined { lower, upper } => Decimal::Undetermined {
                lower: shift_exponent(&lower, shift),
                upper: shift_exponent(&upper, shift),
            },
        }
    }

    /// The significant digits determined: `u32::MAX` for an exact zero, 0 where none is.
    pub fn digits(&self) -> u32 {
        match self {
            Decimal::Zero => u32::MAX,
            Decimal::Digits { digits, .. } => *digits,
            Decimal::Undetermined { .. } => 0,
        }
    }
}

impl std::fmt::Display for Decimal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Decimal::Zero => f.write_str("0"),
            Decimal::Digits { text, .. } => f.write_str(text),
            Decimal::Undetermined { lower, upper } => write!(f, "no digit determined: in [{lower}, {upper}]"),
        }
    }
}

/// The f64 `value` printed with at most [`F64_MOST_DIGITS`] digits by the one rule, for an
/// absolute `bound` on its error ([`decimal_ball`], which it agrees with). Most digit counts
/// are settled in f64 alone (a few hundred nanoseconds); only an end within a few units
/// in the last place of a rounding boundary is settled in exact arithmetic.
pub fn decimal_f64(value: f64, bound: f64) -> Decimal {
    if !value.is_finite() || bound.is_nan() || bound.is_infinite() {
        let text = |x: f64| {
            if x.is_nan() {
                "NaN".to_string()
            } else {
                format!("{x:e}")
            }
        };
        return Decimal::Undetermined {
            lower: text(if bound.is_nan() { f64::NAN } else { value - bound.abs() }),
            upper: text(if bound.is_nan() { f64::NAN } else { value + bound.abs() }),
        };
    }
    let bound = bound.max(0.0);
    let exact = || (Float::with_val(53, value), Float::with_val(53, bound));
    if value.abs() <= bound {
        let (value, bound) = exact();
        return decimal_ball(&value, &bound, F64_MOST_DIGITS);
    }
    // A cell of N digits about a value of exponent e is 10^(e − N + 1) wide (one exponent
    // more where the value may round up to a power of ten), and must be wider than 2·bound.
    let most = match bound {
        0.0 => F64_MOST_DIGITS,
        _ => {
            let exponent = value.abs().log10().floor();
            let carry = if value.abs() >= 9.0 * 10f64.powf(exponent) {
                1.0
            } else {
                0.0
            };
            let width = exponent + 1.0 + carry - (2.0 * bound).log10() + 1e-6;
            (width.floor().max(0.0) as u32).min(F64_MOST_DIGITS)
        }
    };
    (1..=most)
        .rev()
        .find_map(|digits| {
            let text = match rounds_alike_in_f64(value - bound, value + bound, digits) {
                Ok(text) => text,
                Err(Undecided) => {
                    let (value, bound) = exact();
                    let (lower, upper) = ends(&value, &bound);
                    alike(
                        &lower.expansion(digits as usize + 1),
                        &upper.expansion(digits as usize + 1),
                        digits,
                    )
                }
            };
            text.map(|text| Decimal::Digits { text, digits })
        })
        .unwrap_or_else(|| {
            let (value, bound) = exact();
            decimal_ball(&value, &bound, F64_MOST_DIGITS)
        })
}

/// f64 arithmetic cannot tell: an end lies within a few ulps of a rounding boundary.
struct Undecided;

/// The `digits`-digit decimal to which every point of [`lower`, `upper`] rounds, where f64
/// can tell: `lower` and `upper` are the interval's ends rounded to nearest, so the true
/// ends lie within half an ulp of them, and two ulps further out on each side still
/// rounding alike (Rust's decimal formatting is correctly rounded) leaves no rounding
/// boundary inside. `Ok(None)` where each end's own rounding is certain and they differ.
fn rounds_alike_in_f64(lower: f64, upper: f64, digits: u32) -> Result<Option<String>, Undecided> {
    if !lower.is_finite() || !upper.is_finite() {
        return Err(Undecided);
    }
    let text = |y: f64| format!("{:.*e}", digits as usize - 1, y);
    let (outer_low, outer_high) = (text(lower.next_down().next_down()), text(upper.next_up().next_up()));
    if outer_low == outer_high {
        return Ok(Some(outer_low));
    }
    let (inner_low, inner_high) = (text(lower.next_up().next_up()), text(upper.next_down().next_down()));
    if inner_low == outer_low && inner_high == outer_high {
        Ok(None)
    } else {
        Err(Undecided)
    }
}

/// `value` printed with at most `most` significant digits by the one rule, for an absolute
/// `radius` about it: the most digits N for which every point of [`value` − `radius`,
/// `value` + `radius`] rounds to nearest to the same N-digit decimal, with neither end
/// on a rounding boundary (where ties would decide). The ends are rounded outwards, so
/// the interval tested contains the one given.
pub fn decimal_ball(value: &Float, radius: &Float, most: u32) -> Decimal {
    let radius = radius.clone().abs();
    if value.is_zero() && radius.is_zero() {
        return Decimal::Zero;
    }
    let (lower, upper) = ends(value, &radius);
    decimal_interval(&lower, &upper, most)
}

/// The interval [`lower`, `upper`] printed with at most `most` significant digits by the
/// one rule: the most digits N for which every point of it rounds to nearest to the same
/// N-digit decimal, with neither end on a rounding boundary.
pub fn decimal_interval(lower: &Float, upper: &Float, most: u32) -> Decimal {
    rounded_alike_expanded(lower, upper, most, 0).0
}

/// [`decimal_interval`] over ends of either kind (MPFR floats, or doubles: the same digits
/// without MPFR's conversions), and the ends' expansions it read, to at least `at_least`
/// digits (for the caller's other roundings of them; `None` for a zero or an infinite end).
pub(crate) fn rounded_alike_expanded<T: DecimalEnd>(
    lower: &T,
    upper: &T,
    most: u32,
    at_least: usize,
) -> (Decimal, Option<(Expansion, Expansion)>) {
    if lower.is_zero() && upper.is_zero() {
        return (Decimal::Zero, None);
    }
    let undetermined = || Decimal::Undetermined {
        lower: lower.directed(2, Round::Down),
        upper: upper.directed(2, Round::Up),
    };
    if !lower.is_finite() || !upper.is_finite() || lower.is_zero() || upper.is_zero() {
        return (undetermined(), None);
    }
    // Each end expanded once, to one digit more than the most that may be printed.
    let expand = at_least.max(most as usize + 1);
    let expansions = (lower.expansion(expand), upper.expansion(expand));
    if lower.is_sign_negative() != upper.is_sign_negative() {
        return (undetermined(), Some(expansions));
    }
    // A cell of N digits is wider than the interval only for N ≤ log10(|value|/width) + 2.
    let (lower_exact, upper_exact) = (lower.exact(), upper.exact());
    let width = Float::with_val(64, &upper_exact - &lower_exact);
    let magnitude = lower_exact.get_exp().max(upper_exact.get_exp());
    let most = match (magnitude, width.get_exp()) {
        (Some(v), Some(r)) => {
            let ratio_digits = (f64::from(v) - f64::from(r) + 1.0) * std::f64::consts::LOG10_2;
            (ratio_digits.floor().max(-1.0) as u32 + 2).min(most)
        }
        _ => most,
    };
    let decimal = (1..=most.max(1))
        .rev()
        .find_map(|digits| alike(&expansions.0, &expansions.1, digits).map(|text| Decimal::Digits { text, digits }))
        .unwrap_or_else(undetermined);
    (decimal, Some(expansions))
}

/// The `digits`-digit decimal to which every point between two expanded ends rounds, if
/// there is one and neither end is a tie.
fn alike(lower: &Expansion, upper: &Expansion, digits: u32) -> Option<String> {
    let low = lower.nearest(digits as usize)?;
    (upper.nearest(digits as usize)? == low).then(|| scientific(&low))
}

/// The ends of [`value` − `radius`, `value` + `radius`], rounded outwards (exact for f64
/// operands: 64 bits more than either holds).
pub(crate) fn ends(value: &Float, radius: &Float) -> (Float, Float) {
    let bits = value.prec().max(radius.prec()) + 64;
    let (lower, _) = Float::with_val_round(bits, value - radius, Round::Down);
    let (upper, _) = Float::with_val_round(bits, value + radius, Round::Up);
    (lower, upper)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::real::Real;
    use std::cell::Cell;
    use std::time::Duration;

    fn soon() -> Instant {
        Instant::now() + Duration::from_secs(30)
    }

    fn at(p: Precision, text: &str) -> Float {
        Float::parse_decimal(text, p).unwrap()
    }

    #[test]
    fn agreeing_digits_counts_the_leading_digits_two_values_share() {
        let p = Precision::bits(200);
        assert_eq!(agreeing_digits(&at(p, "1.23456"), &at(p, "1.23457")), 5);
        assert_eq!(agreeing_digits(&at(p, "-2"), &at(p, "2")), 0);
        assert_eq!(agreeing_digits(&at(p, "3.5"), &at(p, "3.5")), u32::MAX);
        let zero = Float::with_val(64, 0);
        let zeros = [zero.clone()];
        assert_eq!(agreement(&zeros, &zeros, false), 0);
        assert_eq!(agreement(&zeros, &zeros, true), u32::MAX);
        let (first, second) = ([at(p, "1"), at(p, "5")], [at(p, "1.002"), at(p, "5")]);
        assert_eq!(agreement(&first, &second, false), 2);
    }

    #[test]
    fn values_that_agree_at_two_precisions_are_accepted_at_the_first_attempt() {
        let runs = Cell::new(0);
        let third = |p: Precision| -> Result<Vec<Float>, ()> {
            runs.set(runs.get() + 1);
            Ok(vec![Float::with_val(p.in_bits(), 1) / 3u32])
        };
        let verified = verified_values(30, soon(), third).unwrap();
        assert_eq!(runs.get(), 2);
        assert!(verified.agreed >= 34, "{}", verified.agreed);
        let first = Precision::decimal_digits(30 + GUARD_DIGITS + 8);
        assert_eq!(verified.precision, check_precision(first));
        assert_eq!(verified.output[0].to_scientific(30), format!("3.{}e-1", "3".repeat(29)));
    }

    #[test]
    fn two_exact_zeros_are_not_agreement() {
        // Complete cancellation at every precision: never verified, and the budget error
        // says no digit agreed.
        let cancelled = |p: Precision| -> Result<Vec<Float>, ()> {
            let one = Float::with_val(p.in_bits(), 1);
            Ok(vec![one.clone() - &one])
        };
        let deadline = Instant::now() + Duration::from_millis(50);
        match verified_values(10, deadline, cancelled) {
            Err(VerifyError::OutOfBudget(budget)) => {
                assert_eq!((budget.digits_agreed, budget.digits_requested), (0, 10));
                assert_eq!(budget.digits_required(), 10 + GUARD_DIGITS);
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn the_schedule_raises_the_precision_through_a_cancellation() {
        // (1 + 10⁻⁶⁰) − 1 needs more than 200 bits to keep any digit.
        let tiny = |p: Precision| -> Result<Vec<Float>, ()> {
            let one = Float::with_val(p.in_bits(), 1);
            Ok(vec![(one.clone() + &at(p, "1e-60")) - &one])
        };
        let verified = verified_values(20, soon(), tiny).unwrap();
        assert!(verified.precision.in_bits() > 260, "{:?}", verified.precision);
        assert_eq!(verified.output[0].to_scientific(20), "1.0000000000000000000e-60");
        // The schedule adds the missing digits, and grows by at least a quarter.
        let p = Precision::bits(400);
        assert_eq!(next_precision(p, 24, 24 - 10).in_bits(), 500);
        let missing = Precision::decimal_digits(100 + 8).in_bits();
        assert_eq!(next_precision(p, 100, 0).in_bits(), 400 + missing);
    }

    #[test]
    fn a_deadline_gives_a_budget_error_naming_the_digits_reached() {
        // Every other run is off by 3e-12: 11 digits agree at any precision.
        let calls = Cell::new(0);
        let stuck = |p: Precision| -> Result<Vec<Float>, ()> {
            calls.set(calls.get() + 1);
            let offset = if calls.get() % 2 == 0 { "3e-12" } else { "0" };
            Ok(vec![Float::with_val(p.in_bits(), 1) + &at(p, offset)])
        };
        let deadline = Instant::now() + Duration::from_millis(100);
        let error = verified_values(20, deadline, stuck).unwrap_err();
        let VerifyError::OutOfBudget(budget) = error else {
            panic!("{error:?}")
        };
        assert_eq!(budget.digits_agreed, 11, "{budget:?}");
        assert_eq!(budget.digits_reached(), 11);
        assert!(budget.seconds >= 0.1 && budget.precision_bits > 100, "{budget:?}");
        // Past the deadline already: no attempt, and the precision it would have checked at.
        calls.set(0);
        let start = Precision::decimal_digits(15 + GUARD_DIGITS + 8);
        match verified_values(15, Instant::now(), stuck) {
            Err(VerifyError::OutOfBudget(budget)) => {
                assert_eq!(
                    (budget.digits_agreed, budget.precision_bits),
                    (0, check_precision(start).in_bits())
                )
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(calls.get(), 0);
    }

    #[test]
    fn failures_end_the_loop_unless_the_strategy_retries_them() {
        struct Flaky(u32);
        impl TwoPrecisions for Flaky {
            type Output = Vec<Float>;
            type Error = &'static str;
            fn first(&mut self, p: Precision, attempt: u32) -> Result<Vec<Float>, &'static str> {
                self.0 += 1;
                match attempt {
                    0 => Err("not converged"),
                    _ => Ok(vec![Float::with_val(p.in_bits(), 2).sqrt()]),
                }
            }
            fn check(&mut self, _: &Vec<Float>, p: Precision, a: u32) -> Result<Vec<Float>, &'static str> {
                self.first(p, a)
            }
            fn values<'a>(&self, output: &'a Vec<Float>) -> &'a [Float] {
                output
            }
            fn retries(&self, error: &&'static str) -> bool {
                *error == "not converged"
            }
        }
        let verified = verify(25, soon(), &mut Flaky(0)).unwrap();
        assert!(verified.agreed >= 29);
        let broken = |_: Precision| -> Result<Vec<Float>, &'static str> { Err("broken") };
        assert!(matches!(
            verified_values(25, soon(), broken),
            Err(VerifyError::Failed("broken"))
        ));
    }

    fn digits(text: &str, digits: u32) -> Decimal {
        Decimal::Digits {
            text: text.to_string(),
            digits,
        }
    }

    #[test]
    fn a_decimal_is_printed_only_where_the_whole_interval_rounds_to_it() {
        // 0.12345 ± 1e-9 rounds to 1.2345000e-1 at 8 digits and to nothing finer: at 9 its
        // ends are 1.23449999e-1 and 1.23450001e-1.
        assert_eq!(decimal_f64(0.12345, 1e-9), digits("1.2345000e-1", 8));
        // Straddling a rounding boundary costs the digit it straddles: [0.123454, 0.123458]
        // holds the boundary 0.123455 of 5 digits, so it has 4, though its width allows 5.
        assert_eq!(decimal_f64(0.123456, 2e-6), digits("1.235e-1", 4));
        // The most digits, not the fewest: [0.123549, 0.123551] straddles 4 digits' boundary
        // 0.12355 but lies inside a cell of 5.
        assert_eq!(decimal_f64(0.12355, 1e-6), digits("1.2355e-1", 5));
        // A carry into the next power of ten: [9.9996, 9.9998] rounds to 1.000e1 at 4 digits.
        assert_eq!(decimal_f64(9.9997, 1e-4), digits("1.000e1", 4));
        // An exact value has all of f64's digits; an end exactly on a rounding boundary is a
        // tie, which decides nothing: [0.375, 0.3828125] is not 3.8e-1 (0.375 ties between
        // 3.7e-1 and 3.8e-1), only 4e-1.
        assert_eq!(decimal_f64(0.25, 0.0), digits("2.50000000000000e-1", 15));
        assert_eq!(decimal_f64(0.37890625, 0.00390625), digits("4e-1", 1));
        assert!(matches!(decimal_f64(0.25, 0.05), Decimal::Undetermined { .. }));
        // Zero exactly is "0"; an interval about zero determines no digit, and says where W is.
        assert_eq!(decimal_f64(0.0, 0.0), Decimal::Zero);
        assert_eq!(decimal_f64(0.0, 0.0).to_string(), "0");
        let about_zero = decimal_f64(1e-17, 1.234e-16);
        assert_eq!(about_zero.digits(), 0);
        assert_eq!(about_zero.to_string(), "no digit determined: in [-1.2e-16, 1.4e-16]");
        // An interval not about zero but across a first-digit boundary: no digit either.
        assert_eq!(decimal_f64(0.95, 0.01).digits(), 0);
        // Negative values round by magnitude; f64's 15 digits are the most.
        assert_eq!(decimal_f64(-0.12345, 1e-9), digits("-1.2345000e-1", 8));
        assert_eq!(
            decimal_f64(1.0 / 3.0, 0.0),
            digits("3.33333333333333e-1", F64_MOST_DIGITS)
        );
        // MPFR values: 1/3 ± 10⁻⁴⁰ at up to 50 digits has 39 (its 40th is within a unit).
        let p = Precision::bits(300);
        let third = Float::with_val(p.in_bits(), 1) / 3u32;
        let ball = decimal_ball(&third, &at(p, "1e-40"), 50);
        assert_eq!(ball, digits(&format!("3.{}e-1", "3".repeat(38)), 39));
    }

    #[test]
    fn the_f64_shortcut_prints_what_exact_arithmetic_prints() {
        // Random values over 40 decades, both signs, bounds from 1e-17 to 1 of the value
        // and exact values: the f64 path equals the exact MPFR one on every draw
        // (300,000 draws in proofs/printing.md).
        let mut state: u64 = 88172645463325252;
        for _ in 0..20_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let sign = if state & 1 == 0 { 1.0 } else { -1.0 };
            let mantissa = f64::from_bits((state >> 12) | 0x3FE0_0000_0000_0000);
            let value = sign * mantissa * 10f64.powi((state % 40) as i32 - 20);
            let bound = match state % 97 {
                0 => 0.0,
                _ => value.abs() * 10f64.powf(-(((state >> 20) % 1700) as f64) / 100.0),
            };
            let exact = decimal_ball(
                &Float::with_val(53, value),
                &Float::with_val(53, bound),
                F64_MOST_DIGITS,
            );
            assert_eq!(decimal_f64(value, bound), exact, "{value:e} ± {bound:e}");
        }
    }

    #[test]
    fn the_two_misrounded_reproducers_lose_the_digit_their_bound_straddles() {
        // Persson (P1 = 0.82575): f64 W = 0.5252148792448502 with error estimate 2.6e-14;
        // W = 5.2521487924484932684e-1 (Arb), whose 13th digit is 8, not 9.
        let w = decimal_f64(0.5252148792448502, 2.6218303737392632e-14);
        assert_eq!(w, digits("5.25214879245e-1", 12));
        // v' = P⁻³: f64 W = 14018.010208534673, estimate 7.7e-10; W = 14018.01020853501…
        assert_eq!(
            decimal_f64(14018.010208534673, 7.72750012239026e-10),
            digits("1.40180102085e4", 12)
        );
    }
}
