//! Reference values: W to a requested number of verified significant digits.
//!
//! The case is computed twice — at a working precision and rule chosen for the
//! target, then again at a higher precision with at least twice the quadrature
//! points — with the decimal inputs re-read exactly at each precision. Digits are
//! only reported when the two agree to the target plus guard digits; otherwise both
//! precision and rule are raised, until a time budget runs out.

use std::time::{Duration, Instant};

use rug::Float;

use crate::dissipation::{dissipation, Dissipation, DissipationError, Method, Options};
use crate::inputs::{Case, CaseText, InputError};
use crate::real::{Precision, Real};

/// Digits agreed beyond the target before a value counts as verified.
pub const GUARD_DIGITS: u32 = 4;

/// The most digits that may be asked for.
pub const MAX_DIGITS: u32 = 1000;

/// W with its segments, rounded to the verified digits.
#[derive(Clone, Debug)]
pub struct VerifiedDissipation {
    /// W, rounded to `digits_verified` significant digits.
    pub total: String,
    /// The segments (EB, BC, CH, HE), rounded to the same number of significant digits.
    /// They carry the same absolute accuracy as W (they are not verified one by one).
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

/// Why a verified value could not be produced.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ReferenceError {
    /// The case's text is wrong.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The case is outside the theory, or would not converge.
    #[error(transparent)]
    Dissipation(#[from] DissipationError),
    /// The digits asked for are out of range.
    #[error("--digits must be between 1 and {MAX_DIGITS}, got {0}")]
    DigitsOutOfRange(u32),
    /// The budget ran out first.
    #[error("only {digits_reached} of {digits_requested} digits could be verified within {seconds:.1} s (last attempt at {precision_bits} bits); raise --max-seconds or ask for fewer digits")]
    Budget {
        digits_requested: u32,
        digits_reached: u32,
        seconds: f64,
        precision_bits: u32,
    },
}

fn attempt(
    case: &CaseText,
    precision: Precision,
    options: &Options<Float>,
) -> Result<Dissipation<Float>, ReferenceError> {
    let Case { cycle, compliance } = case.read::<Float>(precision)?;
    Ok(dissipation(&cycle, compliance.as_ref(), options)?)
}

/// The number of leading significant digits on which `a` and `b` agree (1000+ when equal).
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

/// W for `case` to `digits` verified significant digits, within `budget`.
pub fn verified_dissipation(
    case: &CaseText,
    digits: u32,
    budget: Duration,
) -> Result<VerifiedDissipation, ReferenceError> {
    if digits == 0 || digits > MAX_DIGITS {
        return Err(ReferenceError::DigitsOutOfRange(digits));
    }
    let started = Instant::now();
    let target = digits + GUARD_DIGITS;
    let mut precision = Precision::decimal_digits(target + 12);
    let mut max_points = 512;
    let mut best_digits = 0;
    loop {
        let tolerance = |p: Precision, extra: i32| {
            let ten = Float::with_val(p.in_bits(), 10);
            ten.powi(-(target as i32 + extra))
        };
        let deadline = Some(started + budget);
        let first_options = Options {
            relative_tolerance: Some(tolerance(precision, 2)),
            max_points,
            deadline,
            ..Options::default()
        };
        let higher = Precision::bits(precision.in_bits() + 32 + precision.in_bits() / 8);
        let outcome = attempt(case, precision, &first_options).and_then(|first| {
            // First a single rule of twice the points at the higher precision; if that does
            // not agree (a piece that needed tanh–sinh, say), a full converged run there.
            let check_options = Options {
                fixed_points: Some((2 * first.points).max(32)),
                deadline,
                ..Options::default()
            };
            let check = attempt(case, higher, &check_options)?;
            if agreeing_digits(&first.total, &check.total) >= target {
                return Ok((first, check));
            }
            let second_options = Options {
                relative_tolerance: Some(tolerance(higher, 4)),
                min_points: (2 * first.points).max(16),
                max_points: max_points.max(4 * first.points),
                deadline,
                ..Options::default()
            };
            let second = attempt(case, higher, &second_options)?;
            Ok((first, second))
        });
        match outcome {
            Ok((first, second)) => {
                let agreed = agreeing_digits(&first.total, &second.total);
                if agreed >= target {
                    let round = |x: &Float| x.to_scientific(digits as usize);
                    let s = &second.segments;
                    return Ok(VerifiedDissipation {
                        total: round(&second.total),
                        segments: [
                            ("EB", round(&s.eb)),
                            ("BC", round(&s.bc)),
                            ("CH", round(&s.ch)),
                            ("HE", round(&s.he)),
                        ],
                        digits_requested: digits,
                        digits_verified: digits,
                        precision_bits: higher.in_bits(),
                        method: second.method,
                        value: second,
                    });
                }
                best_digits = best_digits.max(agreed.min(digits));
            }
            Err(ReferenceError::Dissipation(DissipationError::NotConverged { .. } | DissipationError::OutOfTime)) => {}
            Err(other) => return Err(other),
        }
        if started.elapsed() >= budget {
            return Err(ReferenceError::Budget {
                digits_requested: digits,
                digits_reached: best_digits,
                seconds: started.elapsed().as_secs_f64(),
                precision_bits: higher.in_bits(),
            });
        }
        precision = Precision::bits(precision.in_bits() * 3 / 2);
        max_points *= 2;
    }
}
