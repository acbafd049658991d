//! The small-amplitude coefficient I(ρ, φ) of the cubic law
//! W ≈ λ f² P1³ v''(P0) · I(Q1/(fP1), φ) (paper Section 5.1, errata item 3).
//!
//! W is linear in v', and for v' = P − P0 (v'' = 1, v''' = 0) every load scales
//! with P1, so W = λ f² P1³ I exactly at any amplitude: I is that W divided by
//! λ f² P1³. That v' is not a physical compliance (it is negative below P0), so
//! the admissibility check is off here.
//!
//! Near in-phase loading with ρ < 1, I is O(φ²) while the segments it is summed from
//! are O(1): f64 then keeps few digits, and [`evaluate`] switches to verified MPFR.

use std::time::{Duration, Instant};

use rug::Float;

use crate::compliance::Polynomial;
use crate::cycle::LoadCycle;
use crate::dissipation::{dissipation, Dissipation, DissipationError, Options};
use crate::inputs::parse_phase;
use crate::real::{ParseRealError, Precision, Real};
use crate::reference::{agreeing_digits, GUARD_DIGITS, MAX_DIGITS};

/// W[v' = P − P0] on the cycle P0 = 1, P1 = `amplitude`, Q1 = ρP1, f = λ = 1, so that
/// I = W / P1³. `amplitude` must keep the cycle inside the theory: P1 (1 + ρ) < 1 does.
fn linear_dissipation<R: Real>(
    rho: &R,
    phase: &R,
    amplitude: &R,
    options: Options<R>,
) -> Result<Dissipation<R>, DissipationError> {
    let one = rho.int(1);
    let cycle = LoadCycle {
        mean_normal_load: one.clone(),
        normal_amplitude: amplitude.clone(),
        mean_tangential_load: one.int(0),
        tangential_amplitude: rho.clone() * amplitude,
        phase: phase.clone(),
        friction: one.clone(),
        compliance_ratio: one.clone(),
    };
    let linear = Polynomial {
        reference: one.clone(),
        coefficients: vec![one.int(0), one.clone()],
    };
    let options = Options {
        check_compliance: false,
        ..options
    };
    dissipation(&cycle, &linear, &options)
}

/// I(ρ, φ) from the cycle P0 = 1, P1 = `amplitude`, Q1 = ρP1, f = λ = 1.
/// `amplitude` must keep the cycle inside the theory: P1 (1 + ρ) < 1 does.
pub fn coefficient_at<R: Real>(rho: &R, phase: &R, amplitude: &R) -> Result<R, DissipationError> {
    let w = linear_dissipation(rho, phase, amplitude, Options::default())?.total;
    Ok(w / (amplitude.clone() * amplitude * amplitude))
}

/// The amplitude every coefficient is computed at: P1 = 1/(2(1 + ρ)), half-way to gross slip.
fn standard_amplitude<R: Real>(rho: &R) -> R {
    rho.int(1) / ((rho.clone() + &rho.int(1)) * &rho.int(2))
}

/// I(ρ, φ) (≤ 0), computed at the amplitude P1 = 1/(2(1 + ρ)).
pub fn coefficient<R: Real>(rho: &R, phase: &R) -> Result<R, DissipationError> {
    coefficient_at(rho, phase, &standard_amplitude(rho))
}

/// I(ρ, φ) with an estimate of its absolute error (quadrature and rounding), and the
/// options to compute it with.
pub fn coefficient_with_error<R: Real>(rho: &R, phase: &R, options: Options<R>) -> Result<(R, R), DissipationError> {
    let amplitude = standard_amplitude(rho);
    let cube = amplitude.clone() * &amplitude * &amplitude;
    let result = linear_dissipation(rho, phase, &amplitude, options)?;
    Ok((result.total / &cube, result.error_estimate / &cube))
}

/// I(ρ, φ) as printed: a decimal string of `digits` significant digits.
#[derive(Clone, Debug, PartialEq)]
pub struct PrintedCoefficient {
    /// I in scientific notation, e.g. `-3.47923485744058e0`.
    pub value: String,
    /// Significant digits printed.
    pub digits: u32,
    /// The working precision of the value printed (53 for f64).
    pub precision_bits: u32,
}

/// Why I(ρ, φ) could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CoefficientError {
    /// `--rho` or `--phi` is not a number.
    #[error("--{flag}: {source}")]
    Number {
        flag: &'static str,
        #[source]
        source: ParseRealError,
    },
    /// ρ ≤ 0 or not finite.
    #[error("--rho must be a positive number, got {0}")]
    NonPositiveRatio(String),
    /// The digits asked for are out of range.
    #[error("--digits must be between 1 and {MAX_DIGITS}, got {0}")]
    DigitsOutOfRange(u32),
    /// The integrals failed (e.g. a phase too large to reduce).
    #[error(transparent)]
    Dissipation(#[from] DissipationError),
    /// The time budget ran out before two precisions agreed.
    #[error("only {reached} of the {required} digits of I needed ({digits} asked for and {GUARD_DIGITS} guard digits) agreed between two precisions within {seconds:.1} s; ask for fewer digits")]
    Budget {
        digits: u32,
        required: u32,
        reached: u32,
        seconds: f64,
    },
}

/// ρ and φ read from text at a precision (φ in radians or as `0.4pi`), ρ checked positive.
fn read_shape<R: Real>(rho: &str, phase: &str, precision: Precision) -> Result<(R, R), CoefficientError> {
    let rho_value =
        R::parse_decimal(rho, precision).map_err(|source| CoefficientError::Number { flag: "rho", source })?;
    let phase = parse_phase(phase, precision).map_err(|source| CoefficientError::Number { flag: "phi", source })?;
    if !(rho_value.is_finite() && rho_value > rho_value.int(0)) {
        return Err(CoefficientError::NonPositiveRatio(rho.to_string()));
    }
    Ok((rho_value, phase))
}

/// The relative error f64 may carry for its 15 printed digits to be trusted to 13.
const F64_RELATIVE_LIMIT: f64 = 1e-13;

/// I(ρ, φ) for printing: with `digits` = None, f64 (15 digits) when its error estimate
/// is within 1e−13 of I, otherwise 15 verified digits in MPFR; with `digits` = Some(N),
/// N verified digits (see [`verified_coefficient`]).
pub fn evaluate(
    rho: &str,
    phase: &str,
    digits: Option<u32>,
    budget: Duration,
) -> Result<PrintedCoefficient, CoefficientError> {
    if let Some(digits) = digits {
        return verified_coefficient(rho, phase, digits, budget);
    }
    let (rho_value, phase_value) = read_shape::<f64>(rho, phase, Precision::DOUBLE)?;
    let (value, error) = coefficient_with_error(&rho_value, &phase_value, Options::default())?;
    if error <= value.abs() * F64_RELATIVE_LIMIT {
        return Ok(PrintedCoefficient {
            value: value.to_scientific(15),
            digits: 15,
            precision_bits: 53,
        });
    }
    verified_coefficient(rho, phase, 15, budget)
}

/// I(ρ, φ) to `digits` verified significant digits: computed at two precisions (the
/// inputs re-read exactly at each) with tolerances beyond the target, and printed only
/// when the two agree to `digits` + 4 digits. Where they do not (I much smaller than
/// the segments it is summed from, as near in-phase loading with ρ < 1), the precision
/// is raised by the digits that were missing, until `budget` runs out.
pub fn verified_coefficient(
    rho: &str,
    phase: &str,
    digits: u32,
    budget: Duration,
) -> Result<PrintedCoefficient, CoefficientError> {
    if digits == 0 || digits > MAX_DIGITS {
        return Err(CoefficientError::DigitsOutOfRange(digits));
    }
    let started = Instant::now();
    let required = digits + GUARD_DIGITS;
    let mut precision = Precision::decimal_digits(required + 12);
    let mut reached = 0;
    loop {
        let at = |precision: Precision, extra: i32| -> Result<Float, CoefficientError> {
            let (rho_value, phase_value) = read_shape::<Float>(rho, phase, precision)?;
            let tolerance = Float::with_val(precision.in_bits(), 10).powi(-(required as i32 + extra));
            let options = Options {
                relative_tolerance: Some(tolerance),
                deadline: Some(started + budget),
                ..Options::default()
            };
            Ok(coefficient_with_error(&rho_value, &phase_value, options)?.0)
        };
        let higher = Precision::bits(precision.in_bits() * 5 / 4 + 32);
        let outcome = at(precision, 2).and_then(|first| Ok((first, at(higher, 4)?)));
        match outcome {
            Ok((first, second)) => {
                let agreed = agreeing_digits(&Float::with_val(higher.in_bits(), &first), &second);
                if agreed >= required {
                    return Ok(PrintedCoefficient {
                        value: second.to_scientific(digits as usize),
                        digits,
                        precision_bits: higher.in_bits(),
                    });
                }
                reached = reached.max(agreed);
                // Raise the precision by the digits that were missing, and a margin.
                let missing = (required - agreed.min(required)) + 8;
                precision = Precision::bits(
                    (precision.in_bits() * 5 / 4)
                        .max(precision.in_bits() + Precision::decimal_digits(missing).in_bits()),
                );
            }
            Err(CoefficientError::Dissipation(DissipationError::OutOfTime | DissipationError::NotConverged { .. })) => {
                precision = Precision::bits(precision.in_bits() * 3 / 2);
            }
            Err(other) => return Err(other),
        }
        if started.elapsed() >= budget {
            return Err(CoefficientError::Budget {
                digits,
                required,
                reached,
                seconds: started.elapsed().as_secs_f64(),
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn f64_is_used_where_it_resolves_i_and_mpfr_where_it_does_not() {
        let budget = Duration::from_secs(30);
        let ordinary = evaluate("1.25", "0.4pi", None, budget).unwrap();
        assert_eq!(ordinary.precision_bits, 53);
        assert!(ordinary.value.starts_with("-3.479234857440"), "{ordinary:?}");
        // Near in phase with ρ < 1, I ≈ −(4/3)φ² is 1e−18 of the segments: f64 cannot hold it.
        let thin = evaluate("0.5", "1e-9", None, budget).unwrap();
        assert!(thin.precision_bits > 53, "{thin:?}");
        let value: f64 = thin.value.parse().unwrap();
        assert!((value / (-4.0 / 3.0 * 1e-18) - 1.0).abs() < 1e-6, "{thin:?}");
    }

    #[test]
    fn verified_digits_survive_cancellation() {
        let thin = verified_coefficient("0.5", "1e-6", 30, Duration::from_secs(30)).unwrap();
        assert!(thin.value.starts_with("-1.33333333333155555555555"), "{thin:?}");
        assert!(matches!(
            verified_coefficient("-1", "1", 10, Duration::from_secs(1)),
            Err(CoefficientError::NonPositiveRatio(_))
        ));
        assert!(matches!(
            verified_coefficient("1", "0.3", 0, Duration::from_secs(1)),
            Err(CoefficientError::DigitsOutOfRange(0))
        ));
    }
}
