//! Digits by agreement: a computation run at two working precisions, its results
//! printed only as far as the two agree (with guard digits), the precision raised
//! until they do or the deadline passes. Evidence, not proof: the rung of the ladder for
//! quantities no enclosure reaches.
//!
//! [`verify`] is the one loop; what a run at one precision is, and how it is checked at
//! the higher one, is the caller's [`TwoPrecisions`] strategy (the four-segment W checks
//! with a fixed rule first, a closed form just recomputes). [`verified_values`] is the
//! strategy of a computation that only needs re-running.

use std::time::Instant;

use rug::float::Round;
use rug::Float;

use crate::decimal::printing::decimal_ball;
use crate::digits::{Ladder, Rung, Stop};
use crate::real::{Precision, Real};

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
}
