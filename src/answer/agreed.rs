//! W to a requested number of digits by agreement of two precisions — the path
//! [`crate::answer::dissipation`] takes where no rigorous enclosure can be had.
//!
//! The case is computed twice by [`crate::digits::agreement::verify`] — at a working precision
//! and rule chosen for the target, then again at a higher precision with twice the
//! quadrature points — with the decimal inputs re-read exactly at each precision. Digits
//! are only reported when the two agree to the target plus guard digits; otherwise both
//! precision and rule are raised, until a time budget runs out. Agreement is evidence,
//! not proof.

use std::time::{Duration, Instant};

use rug::Float;

use crate::admissibility::prove_admissible;
use crate::answer::{Answer, DissipationAnswerError, Provenance, Value};
use crate::case::{Case, CaseSpec, CaseText};
use crate::digits::agreement::{agreeing_digits, agreement_radius, verify, TwoPrecisions, Verified, GUARD_DIGITS};
use crate::dissipation::{dissipation, Dissipation, DissipationError, ExactZero, Options, Rules, Segments};
use crate::quad::{FixedRule, RuleError};
use crate::real::{Precision, Real};

pub use crate::digits::agreement::MAX_DIGITS;

/// W with its segments to the digits two precisions agree on: the answer as printed, and
/// the higher precision's whole result.
#[derive(Clone, Debug)]
pub struct VerifiedDissipation {
    /// W and its segments as printed, each bounded by its agreement with the first run
    /// (W to the digits asked for; `Provenance::Agreement` names the higher precision).
    pub answer: Answer,
    /// The full higher-precision result.
    pub value: Dissipation<Float>,
}

fn attempt(
    case: &CaseSpec,
    precision: Precision,
    options: &Options<Float>,
) -> Result<Dissipation<Float>, DissipationAnswerError> {
    let Case { cycle, compliance } = case.at::<Float>(precision)?;
    Ok(dissipation(&cycle, compliance.as_ref(), options)?)
}

/// The digits that rounding inside the four-segment integrands costs on `case`: log10 of
/// the product of its load rounding and slip-term cancellation amplifications (0 for a
/// case that does not read).
fn conditioning_digits(case: &CaseSpec) -> u32 {
    // In MPFR, whose range holds the amplification of a phase within 1e-300 of 0 or π.
    let Ok(Case { cycle, .. }) = case.at::<Float>(Precision::bits(64)) else {
        return 0;
    };
    let one = Float::with_val(64, 1);
    let amplification = cycle.rounding_amplification() * cycle.cancellation_amplification().max(&one);
    if amplification.is_finite() && amplification > 1 {
        amplification.log10().floor().to_f64() as u32
    } else {
        0
    }
}

/// W by the four-segment integrals as a [`TwoPrecisions`] computation: the first run is
/// held to the target itself (the agreement with the check, not this tolerance, vouches
/// for the digits), with a quadrature limit that doubles with every attempt. The check is
/// first a single rule of twice each piece's points at the higher precision; if that does
/// not agree (a piece that needed tanh–sinh, say), a full converged run there.
struct FourSegmentW<'a> {
    case: &'a CaseSpec,
    /// The significant digits that must agree.
    required: u32,
    deadline: Instant,
}

impl FourSegmentW<'_> {
    fn tolerance(&self, precision: Precision, extra: i32) -> Option<Float> {
        Some(Float::with_val(precision.in_bits(), 10).powi(-(self.required as i32 + extra)))
    }

    fn max_points(attempt: u32) -> usize {
        512usize << attempt.min(20)
    }
}

impl TwoPrecisions for FourSegmentW<'_> {
    type Output = Dissipation<Float>;
    type Error = DissipationAnswerError;

    /// Twelve digits beyond those required, and those the case's conditioning costs.
    fn starting_precision(&self, required: u32) -> Precision {
        Precision::decimal_digits(required + 12 + conditioning_digits(self.case))
    }

    fn first(&mut self, precision: Precision, attempt_number: u32) -> Result<Self::Output, DissipationAnswerError> {
        let options = Options {
            relative_tolerance: self.tolerance(precision, 0),
            rules: Rules::Adaptive {
                first_points: None,
                max_points: Self::max_points(attempt_number),
            },
            deadline: Some(self.deadline),
            ..Options::default()
        };
        attempt(self.case, precision, &options)
    }

    fn check(
        &mut self,
        first: &Self::Output,
        higher: Precision,
        attempt_number: u32,
    ) -> Result<Self::Output, DissipationAnswerError> {
        // The check's own error estimate goes unused and its compliance was checked by the
        // first run: it only has to agree (a check that missed something disagrees, and the
        // full run below decides).
        let fixed = Options {
            rules: Rules::Fixed(FixedRule {
                points: (2 * first.points).max(32),
                per_piece: Some(first.piece_points.iter().map(|&n| (2 * n).max(32)).collect()),
                error: RuleError::RoundingFloor,
            }),
            check_compliance: false,
            deadline: Some(self.deadline),
            ..Options::default()
        };
        let check = attempt(self.case, higher, &fixed)?;
        if agreeing_digits(&first.total, &check.total) >= self.required {
            return Ok(check);
        }
        let converged = Options {
            relative_tolerance: self.tolerance(higher, 4),
            rules: Rules::Adaptive {
                first_points: Some((2 * first.points).max(16)),
                max_points: Self::max_points(attempt_number).max(4 * first.points),
            },
            deadline: Some(self.deadline),
            ..Options::default()
        };
        attempt(self.case, higher, &converged)
    }

    fn values<'a>(&self, output: &'a Self::Output) -> &'a [Float] {
        std::slice::from_ref(&output.total)
    }

    /// Never: the exact zeros (no tangential oscillation, in phase with nothing slipping,
    /// a constant v') are answered by their reason before any run, so a zero here is a W
    /// that underflowed or cancelled at both precisions, on whose digits they do not agree.
    fn zeros_are_exact(&self, _output: &Self::Output) -> bool {
        false
    }

    /// An integral that did not converge within the attempt's points or time.
    fn retries(&self, error: &DissipationAnswerError) -> bool {
        matches!(
            error,
            DissipationAnswerError::Dissipation(DissipationError::NotConverged { .. } | DissipationError::OutOfTime)
        )
    }
}

/// Why W is exactly 0 for a case the theory covers, if it is ([`CaseSpec::exact_zero`]);
/// the cycle is validated and the compliance checked over its loads as for a computation.
pub(crate) fn checked_exact_zero(case: &CaseSpec) -> Result<Option<ExactZero>, DissipationAnswerError> {
    let Some(reason) = case.exact_zero() else {
        return Ok(None);
    };
    check_case(case)?;
    Ok(Some(reason))
}

/// Refuses a case whose compliance is not admissible over the cycle's loads
/// ([`prove_admissible`]; the cycle itself was decided exactly when the case was read).
pub(crate) fn check_case(case: &CaseSpec) -> Result<(), DissipationAnswerError> {
    prove_admissible(case).map_err(DissipationError::from)?;
    Ok(())
}

/// W for `case` to `digits` verified significant digits, within `budget`, by [`verify`];
/// an exact zero ([`CaseSpec::exact_zero`]) at once, as `0`.
pub fn verified_dissipation(
    case: &CaseText,
    digits: u32,
    budget: Duration,
) -> Result<VerifiedDissipation, DissipationAnswerError> {
    verified_dissipation_of(&case.spec()?, digits, budget)
}

/// [`verified_dissipation`] of a case already read.
pub fn verified_dissipation_of(
    case: &CaseSpec,
    digits: u32,
    budget: Duration,
) -> Result<VerifiedDissipation, DissipationAnswerError> {
    if digits == 0 || digits > MAX_DIGITS {
        return Err(DissipationAnswerError::DigitsOutOfRange(digits));
    }
    if let Some(reason) = checked_exact_zero(case)? {
        let zero = Float::with_val(Precision::decimal_digits(digits).in_bits(), 0);
        return Ok(VerifiedDissipation {
            answer: Answer::exact_zero(reason, Some(digits)),
            value: Dissipation::exact_zero(reason, &zero),
        });
    }
    let mut w = FourSegmentW {
        case,
        required: digits + GUARD_DIGITS,
        deadline: Instant::now() + budget,
    };
    let Verified {
        output,
        first,
        precision,
        ..
    } = verify(digits, w.deadline, &mut w).map_err(|error| error.into_error(DissipationAnswerError::Budget))?;
    // Each value by the one rule, bounded by its agreement with the first run: W has the
    // digits asked for (verify holds out for them), a segment as many as its own allows.
    let value = |value: &Float, first: &Float| Value::about(value, &agreement_radius(first, value), digits);
    let answer = Answer {
        value: value(&output.total, &first.total),
        segments: Some(Segments::from_fn(|segment| {
            value(output.segments.get(segment), first.segments.get(segment))
        })),
        digits_requested: Some(digits),
        provenance: Provenance::Agreement {
            bits: precision.in_bits(),
        },
        method: Some(output.method),
    };
    Ok(VerifiedDissipation { answer, value: output })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dissipation::Method;

    #[test]
    fn a_closed_form_zero_is_verified_as_exact() {
        let case = |q1: &str| CaseText {
            p0: "1".into(),
            p1: "0.4".into(),
            q0: "0".into(),
            q1: q1.into(),
            phi: "0.4pi".into(),
            friction: "1".into(),
            lambda: Some("1".into()),
            nu: None,
            compliance: "persson:gamma=1,sigma=1".into(),
        };
        let zero = verified_dissipation(&case("0"), 20, Duration::from_secs(30)).unwrap();
        assert_eq!(
            zero.answer.method,
            Some(Method::Exact(ExactZero::NoTangentialOscillation))
        );
        assert_eq!(zero.answer.value.decimal.to_string(), "0");
        let w = verified_dissipation(&case("0.5"), 20, Duration::from_secs(30)).unwrap();
        assert_eq!(w.answer.value.decimal.to_string(), "4.0624757924582385709e-1");
        assert_eq!(w.answer.provenance.key(), "agreement");
    }
}
