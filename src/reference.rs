//! Reference values: W to a requested number of verified significant digits.
//!
//! The case is computed twice by [`crate::verified::verify`] — at a working precision
//! and rule chosen for the target, then again at a higher precision with twice the
//! quadrature points — with the decimal inputs re-read exactly at each precision. Digits
//! are only reported when the two agree to the target plus guard digits; otherwise both
//! precision and rule are raised, until a time budget runs out. Without a digit count,
//! f64 is printed where it suffices ([`crate::verified::f64_printed_digits`]).

use std::time::{Duration, Instant};

use rug::Float;

use crate::compliance::{check_admissible, Compliance};
use crate::cycle::{LoadCycle, ValidCycle};
use crate::dissipation::{dissipation, Dissipation, DissipationError, ExactZero, Method, Options, Rules};
use crate::inputs::{Case, CaseText, InputError};
use crate::quad::{FixedRule, RuleError};
use crate::real::{Precision, Real};
use crate::verified::{
    agreeing_digits, agreement_radius, decimal_ball, decimal_f64, f64_printed_digits, resolved_digits, verify, Bound,
    Decimal, OutOfBudget, TwoPrecisions, Verified, F64_DIGITS_FLOOR, F64_MOST_DIGITS, GUARD_DIGITS,
};

pub use crate::verified::MAX_DIGITS;

/// W with its segments, rounded to the verified digits.
#[derive(Clone, Debug)]
pub struct VerifiedDissipation {
    /// W, rounded to `digits_verified` significant digits (`0` for a closed form's zero).
    pub total: String,
    /// The segments (EB, BC, CH, HE), each printed by the same rule as W to the digits
    /// its own agreement between the two precisions determines (at most W's).
    pub segments: [(&'static str, String); 4],
    /// The digits asked for.
    pub digits_requested: u32,
    /// The significant digits on which the two estimates agreed, capped at the request.
    pub digits_verified: u32,
    /// The higher of the two working precisions.
    pub precision_bits: u32,
    /// How W was computed.
    pub method: Method,
    /// The full higher-precision result.
    pub value: Dissipation<Float>,
}

/// W and its segments as decimal strings, with how far they can be trusted.
#[derive(Clone, Debug)]
pub struct PrintedDissipation {
    /// W in scientific notation.
    pub total: String,
    /// EB, BC, CH, HE.
    pub segments: Vec<(&'static str, String)>,
    /// The significant digits of `total`.
    pub digits: u32,
    /// How W was computed.
    pub method: Method,
    /// The working precision of the value printed (53 for f64).
    pub precision_bits: u32,
    /// The absolute error estimate of an f64 result (verified digits need none).
    pub error_estimate: Option<f64>,
    /// What vouches for the digits printed.
    pub bound: Bound,
    /// Why a run without a digit count computed verified digits in MPFR instead of f64.
    pub fallback: Option<String>,
    /// The f64 values W, EB, BC, CH, HE as computed, where the printed ones come from f64.
    pub binary64: Option<[f64; 5]>,
}

impl PrintedDissipation {
    /// An f64 result printed: W to `digits` (as [`resolved_digits`] gives them for its
    /// bound; 0, where none is determined, prints the interval of its error estimate), each
    /// segment by the same rule to the digits its absolute error in `segment_errors` (EB,
    /// BC, CH, HE) determines. [`PrintedDissipation::within`] takes W's bound instead.
    pub fn from_f64(result: &Dissipation<f64>, digits: u32, segment_errors: [f64; 4]) -> Self {
        let total = match digits {
            0 => decimal_f64(result.total, result.error_estimate).to_string(),
            _ if result.total == 0.0 => Decimal::Zero.to_string(),
            _ => result.total.to_scientific(digits as usize),
        };
        Self::printed(result, total, digits, segment_errors)
    }

    /// An f64 result printed by the one rule: W for the absolute `bound` on its error, each
    /// segment for its own in `segment_errors` (EB, BC, CH, HE).
    pub fn within(result: &Dissipation<f64>, bound: f64, segment_errors: [f64; 4]) -> Self {
        let total = decimal_f64(result.total, bound);
        let digits = total.digits().min(F64_MOST_DIGITS);
        Self::printed(result, total.to_string(), digits, segment_errors)
    }

    fn printed(result: &Dissipation<f64>, total: String, digits: u32, segment_errors: [f64; 4]) -> Self {
        let s = &result.segments;
        PrintedDissipation {
            bound: zero_bound(&total, result.method).unwrap_or(Bound::Estimate),
            total,
            segments: s
                .named()
                .iter()
                .zip(segment_errors)
                .map(|((name, value), error)| (*name, decimal_f64(**value, error).to_string()))
                .collect(),
            digits,
            method: result.method,
            precision_bits: 53,
            error_estimate: Some(result.error_estimate),
            fallback: None,
            binary64: Some([result.total, s.eb, s.bc, s.ch, s.he]),
        }
    }
}

/// [`Bound::Exact`] for a zero W of a closed form (no tangential oscillation, or in phase
/// with nothing slipping), which is zero by theory, not by rounding.
fn zero_bound(total: &str, method: Method) -> Option<Bound> {
    (total == Decimal::Zero.to_string() && method != Method::FourSegment).then_some(Bound::Exact)
}

/// W for printing: with `digits` = Some(N), N verified digits; without, f64 with the
/// digits its error estimate vouches for (segments to the same absolute accuracy), or
/// [`F64_MOST_DIGITS`] verified digits where f64 does not suffice
/// ([`f64_printed_digits`]: too few digits, or a failure of f64 itself) — and why.
pub fn printable_dissipation(
    case: &CaseText,
    digits: Option<u32>,
    budget: Duration,
) -> Result<PrintedDissipation, ReferenceError> {
    let verified = |digits: u32, fallback: Option<String>| -> Result<PrintedDissipation, ReferenceError> {
        let verified = verified_dissipation(case, digits, budget)?;
        let bound = zero_bound(&verified.total, verified.method).unwrap_or(Bound::Agreement);
        Ok(PrintedDissipation {
            total: verified.total,
            segments: verified.segments.to_vec(),
            digits: verified.digits_verified,
            method: verified.method,
            precision_bits: verified.precision_bits,
            error_estimate: None,
            bound,
            fallback,
            binary64: None,
        })
    };
    if let Some(digits) = digits {
        return verified(digits, None);
    }
    if exact_zero(case)?.is_some() {
        return verified(F64_MOST_DIGITS, None);
    }
    let Case { cycle, compliance } = match case.read::<f64>(Precision::DOUBLE) {
        Ok(case) => case,
        // A number f64 cannot hold (1e-400, c=1e400): MPFR reads the text exactly.
        Err(error) if case.read::<Float>(Precision::bits(64)).is_ok() => {
            return verified(F64_MOST_DIGITS, Some(format!("f64 cannot read the case: {error}")))
        }
        Err(error) => return Err(error.into()),
    };
    if let Some(reason) = slope_change_differs_from_mpfr(case, &cycle, compliance.as_ref()) {
        return verified(F64_MOST_DIGITS, Some(reason));
    }
    let within_budget = Options {
        deadline: Some(Instant::now() + budget),
        ..Options::default()
    };
    let result = match dissipation(&cycle, compliance.as_ref(), &within_budget) {
        Ok(result) => result,
        Err(DissipationError::OutsideRange {
            quantity,
            value,
            low,
            high,
            ..
        }) => {
            return verified(
                F64_MOST_DIGITS,
                Some(format!(
                    "{quantity} = {value:.1e} is outside the magnitudes f64 carries through the integrals without overflow or underflow ({low:.0e} to {high:.0e})"
                )),
            )
        }
        // Out of f64's range in the result, not finite, or a compliance f64 sees as
        // non-physical (v' underflowing to 0, say): MPFR either computes it or says why not.
        Err(
            error @ (DissipationError::OutOfRange { .. }
            | DissipationError::NotFinite { .. }
            | DissipationError::Compliance(_)),
        ) => return verified(F64_MOST_DIGITS, Some(format!("f64 fails here: {error}"))),
        Err(DissipationError::IllConditioned { cause, expected, .. }) => {
            return verified(
                F64_MOST_DIGITS,
                Some(format!(
                    "f64 is ill-conditioned here ({cause}): rounding alone would move W by ~{expected:.0e}"
                )),
            )
        }
        Err(DissipationError::NotConverged { .. }) => {
            return verified(F64_MOST_DIGITS, Some("the f64 integrals did not converge here".to_string()))
        }
        Err(other) => return Err(other.into()),
    };
    let resolved = resolved_digits(result.total, result.error_estimate);
    let Some(digits) = f64_printed_digits(resolved) else {
        let largest = result.segments.named().iter().map(|(_, v)| v.abs()).fold(0.0, f64::max);
        // The digits the estimate's width alone would leave.
        let width = (result.total.abs() / result.error_estimate).log10();
        let reason = if width >= f64::from(F64_DIGITS_FLOOR) {
            format!(
                "f64 resolves {resolved} digits here: W ± its error estimate {:.1e} straddles a rounding boundary of digit {}",
                result.error_estimate,
                resolved + 1
            )
        } else {
            format!("f64 resolves {resolved} digits here: its segments, up to {largest:.1e}, cancel to W")
        };
        return verified(F64_MOST_DIGITS, Some(reason));
    };
    Ok(PrintedDissipation::from_f64(
        &result,
        digits,
        [result.error_estimate; 4],
    ))
}

/// Interior loads of the cycle at which [`slope_change_differs_from_mpfr`] compares.
const COMPARED_LOADS: i64 = 16;

/// Why the f64 compliance is not to be trusted, if it is not: its change of v' about P0,
/// the only function of it the integrals see, differs from the same change in MPFR at
/// loads across the cycle by more than 1e-6 of the largest. That is what an overflow or
/// underflow inside a compliance formula does (v' = a + b/(P + c) with c = 1e300 makes
/// every change 0 in f64), and within f64 it may look like a legitimate linear v.
fn slope_change_differs_from_mpfr(
    case: &CaseText,
    cycle: &LoadCycle<f64>,
    compliance: &dyn Compliance<f64>,
) -> Option<String> {
    let precise = case.read::<Float>(Precision::bits(64)).ok()?;
    let p0 = cycle.mean_normal_load;
    let low = (p0 - cycle.normal_amplitude).min(cycle.permanent_stick_load());
    let high = p0 + cycle.normal_amplitude;
    if !(low.is_finite() && high.is_finite() && low < high) {
        return None;
    }
    let change = compliance.slope_change_about(&p0);
    let precise_change = precise.compliance.slope_change_about(&precise.cycle.mean_normal_load);
    // Compared in MPFR: an exact change below f64's range must not round to the f64 zero.
    let pairs: Vec<(f64, f64, Float)> = (1..COMPARED_LOADS)
        .map(|k| {
            let offset = (low - p0) + (high - low) * (k as f64 / COMPARED_LOADS as f64);
            let exact = precise_change(&Float::with_val(64, offset));
            (p0 + offset, change(&offset), exact)
        })
        .collect();
    let zero = Float::with_val(64, 0);
    let largest = pairs
        .iter()
        .fold(zero, |acc, (_, _, exact)| acc.max(&exact.clone().abs()));
    let tolerance = largest / 1_000_000u32;
    let (load, value, exact) = pairs.into_iter().find(|(_, value, exact)| {
        // NaN on either side counts as a difference.
        let difference = (Float::with_val(64, *value) - exact).abs();
        difference.is_nan() || difference > tolerance
    })?;
    Some(format!(
        "in f64 the compliance gives v'(P) − v'(P0) = {value:.3e} at P = {load:.3e}, in MPFR {}: an intermediate of its formula leaves the range of f64",
        exact.to_scientific(4)
    ))
}

/// Why a verified value could not be produced.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ReferenceError {
    /// The case's text is wrong.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The case is outside the theory, or would not converge.
    #[error(transparent)]
    Dissipation(#[from] DissipationError),
    /// The digits asked for are out of range.
    #[error("the significant digits asked for must be between 1 and {MAX_DIGITS}, got {0}")]
    DigitsOutOfRange(u32),
    /// The budget ran out first.
    #[error("only {} of {} digits could be verified within {:.1} s (two precisions must agree to {GUARD_DIGITS} digits more; last attempt at {} bits)", .0.digits_reached(), .0.digits_requested, .0.seconds, .0.precision_bits)]
    Budget(OutOfBudget),
}

fn attempt(
    case: &CaseText,
    precision: Precision,
    options: &Options<Float>,
) -> Result<Dissipation<Float>, ReferenceError> {
    let Case { cycle, compliance } = case.read::<Float>(precision)?;
    Ok(dissipation(&cycle, compliance.as_ref(), options)?)
}

/// The digits that rounding inside the four-segment integrands costs on `case`: log10 of
/// the product of its load rounding and slip-term cancellation amplifications (0 for a
/// case that does not read).
fn conditioning_digits(case: &CaseText) -> u32 {
    // In MPFR, whose range holds the amplification of a phase within 1e-300 of 0 or π.
    let Ok(Case { cycle, .. }) = case.read::<Float>(Precision::bits(64)) else {
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
    case: &'a CaseText,
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
    type Error = ReferenceError;

    /// Twelve digits beyond those required, and those the case's conditioning costs.
    fn starting_precision(&self, required: u32) -> Precision {
        Precision::decimal_digits(required + 12 + conditioning_digits(self.case))
    }

    fn first(&mut self, precision: Precision, attempt_number: u32) -> Result<Self::Output, ReferenceError> {
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
    ) -> Result<Self::Output, ReferenceError> {
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

    /// A closed form's W = 0 (no tangential oscillation, in phase with nothing slipping).
    fn zeros_are_exact(&self, output: &Self::Output) -> bool {
        output.method != Method::FourSegment
    }

    /// An integral that did not converge within the attempt's points or time.
    fn retries(&self, error: &ReferenceError) -> bool {
        matches!(
            error,
            ReferenceError::Dissipation(DissipationError::NotConverged { .. } | DissipationError::OutOfTime)
        )
    }
}

/// Why W is exactly 0 for a case the theory covers, if it is ([`CaseText::exact_zero`]);
/// the cycle is validated and the compliance checked over its loads as for a computation.
fn exact_zero(case: &CaseText) -> Result<Option<ExactZero>, ReferenceError> {
    let Some(reason) = case.exact_zero()? else {
        return Ok(None);
    };
    let Case { cycle, compliance } = case.read::<Float>(Precision::bits(128))?;
    let cycle = ValidCycle::new(cycle).map_err(DissipationError::from)?;
    let low = (cycle.mean_normal_load.clone() - &cycle.normal_amplitude).min_of(&cycle.permanent_stick_load());
    let high = cycle.mean_normal_load.clone() + &cycle.normal_amplitude;
    check_admissible(compliance.as_ref(), &low, &high).map_err(DissipationError::from)?;
    Ok(Some(reason))
}

/// W for `case` to `digits` verified significant digits, within `budget`, by [`verify`];
/// an exact zero ([`CaseText::exact_zero`]) at once, as `0`.
pub fn verified_dissipation(
    case: &CaseText,
    digits: u32,
    budget: Duration,
) -> Result<VerifiedDissipation, ReferenceError> {
    if digits == 0 || digits > MAX_DIGITS {
        return Err(ReferenceError::DigitsOutOfRange(digits));
    }
    if let Some(reason) = exact_zero(case)? {
        let zero = Float::with_val(Precision::decimal_digits(digits).in_bits(), 0);
        let segments = crate::dissipation::Segments {
            eb: zero.clone(),
            bc: zero.clone(),
            ch: zero.clone(),
            he: zero.clone(),
        };
        return Ok(VerifiedDissipation {
            total: "0".to_string(),
            segments: segments.named().map(|(name, _)| (name, "0".to_string())),
            digits_requested: digits,
            digits_verified: digits,
            precision_bits: zero.prec(),
            method: Method::Exact(reason),
            value: Dissipation {
                total: zero.clone(),
                segments,
                error_estimate: zero,
                evaluations: 0,
                points: 0,
                piece_points: Vec::new(),
                method: Method::Exact(reason),
            },
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
    } = verify(digits, w.deadline, &mut w).map_err(|error| error.into_error(ReferenceError::Budget))?;
    // Each value by the one rule, bounded by its agreement with the first run: W has the
    // digits asked for (verify holds out for them), a segment as many as its own allows.
    let round = |value: &Float, first: &Float| decimal_ball(value, &agreement_radius(first, value), digits).to_string();
    let firsts = first.segments.named().map(|(_, value)| value.clone());
    let mut firsts = firsts.iter();
    Ok(VerifiedDissipation {
        total: round(&output.total, &first.total),
        segments: output.segments.named().map(|(name, value)| {
            let first = firsts.next().expect("four segments in both runs");
            (name, round(value, first))
        }),
        digits_requested: digits,
        digits_verified: digits,
        precision_bits: precision.in_bits(),
        method: output.method,
        value: output,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_budget_error_reads_as_before() {
        let budget = OutOfBudget {
            digits_requested: 1000,
            digits_agreed: 1002,
            seconds: 0.01,
            precision_bits: 3834,
        };
        assert_eq!(
            ReferenceError::Budget(budget).to_string(),
            "only 1000 of 1000 digits could be verified within 0.0 s (two precisions must agree to 4 digits more; last attempt at 3834 bits)"
        );
    }

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
        assert_eq!(zero.method, Method::Exact(ExactZero::NoTangentialOscillation));
        assert_eq!(zero.total, "0");
        let w = verified_dissipation(&case("0.5"), 20, Duration::from_secs(30)).unwrap();
        assert_eq!(w.total, "4.0624757924582385709e-1");
    }
}
