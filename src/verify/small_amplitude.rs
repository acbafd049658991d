//! The small-amplitude coefficient I(ρ, φ) of the cubic law
//! W ≈ λ f² P1³ v''(P0) · I(Q1/(fP1), φ) (paper Section 5.1, errata item 3).
//!
//! W is linear in v', and for v' = P − P0 (v'' = 1, v''' = 0) every load scales
//! with P1, so W = λ f² P1³ I exactly at any amplitude: I is that W divided by
//! λ f² P1³. That v' is not a physical compliance (it is negative below P0), so
//! the admissibility check is off here.
//!
//! The functions here compute I by the four-segment quadrature (the gate checks the
//! closed form against them); [`evaluate`], what `microslip small-amplitude` prints,
//! uses the closed form of [`crate::exact::coefficient`] and no quadrature.

use std::time::{Duration, Instant};

use rug::Float;

use crate::compliance::Polynomial;
use crate::cycle::LoadCycle;
use crate::dissipation::{dissipation, Dissipation, DissipationError, Options};
use crate::exact::closed_form_coefficient;
use crate::exact::printing::{vanishes_in_phase, NOTHING_SLIPS};
use crate::inputs::parse_phase;
use crate::phase::PhaseError;
use crate::real::{ParseRealError, Precision, Real};
use crate::verified::{f64_digits_against, verified_values, OutOfBudget, F64_MOST_DIGITS, GUARD_DIGITS, MAX_DIGITS};

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
    /// Significant digits printed, each verified.
    pub digits: u32,
    /// The working precision of the value printed (53 for f64).
    pub precision_bits: u32,
    /// I in binary64 when it is representable there (finite, not below the normal range).
    pub binary64: Option<f64>,
    /// Why I is exactly the 0 printed, where it is.
    pub exact: Option<&'static str>,
}

/// Why I(ρ, φ) could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CoefficientError {
    /// ρ or φ is not a number.
    #[error("{quantity}: {source}")]
    Number {
        /// Which input (`ρ` or `φ`).
        quantity: &'static str,
        /// Why it does not read as a number.
        #[source]
        source: ParseRealError,
    },
    /// φ is not a phase.
    #[error(transparent)]
    Phase(#[from] PhaseError),
    /// ρ ≤ 0, or not finite at the working precision.
    #[error("ρ must be a positive number (and below MPFR's range, about 1e323228496), got {0}")]
    NonPositiveRatio(String),
    /// The digits asked for are out of range.
    #[error("the digits asked for must be between 1 and {MAX_DIGITS}, got {0}")]
    DigitsOutOfRange(u32),
    /// The integrals failed (e.g. a phase too large to reduce).
    #[error(transparent)]
    Dissipation(#[from] DissipationError),
    /// The time budget ran out before two precisions agreed.
    #[error("only {} of the {} digits of I needed ({} asked for and {GUARD_DIGITS} guard digits) agreed between two precisions within {:.1} s; ask for fewer digits", .0.digits_agreed, .0.digits_required(), .0.digits_requested, .0.seconds)]
    Budget(OutOfBudget),
}

/// ρ and φ read from text at a precision (φ in radians or as `0.4pi`), ρ checked positive
/// and finite at that precision.
fn read_shape<R: Real>(rho: &str, phase: &str, precision: Precision) -> Result<(R, R), CoefficientError> {
    let rho_value =
        R::parse_decimal(rho, precision).map_err(|source| CoefficientError::Number { quantity: "ρ", source })?;
    let (phase, _): (R, bool) = parse_phase(phase, precision)?;
    if !(rho_value.is_finite() && rho_value > rho_value.int(0)) {
        return Err(CoefficientError::NonPositiveRatio(rho.to_string()));
    }
    if !phase.is_finite() {
        return Err(CoefficientError::Number {
            quantity: "φ",
            source: ParseRealError {
                text: phase_text(phase),
            },
        });
    }
    Ok((rho_value, phase))
}

fn phase_text<R: Real>(phase: R) -> String {
    phase.to_scientific(6)
}

/// I(ρ, φ) for printing, from the closed form (no quadrature): with `digits` = None,
/// f64 with the digits on which it agrees with verified MPFR digits where that suffices
/// ([`f64_digits_against`]), the verified [`F64_MOST_DIGITS`] MPFR digits otherwise — also
/// where I or ρ is beyond the range of f64; with `digits` = Some(N), N verified digits.
pub fn evaluate(
    rho: &str,
    phase: &str,
    digits: Option<u32>,
    budget: Duration,
) -> Result<PrintedCoefficient, CoefficientError> {
    let Some(digits) = digits else {
        let (verified, reference) = verified_closed_form(rho, phase, F64_MOST_DIGITS, budget)?;
        let binary64 = read_shape::<f64>(rho, phase, Precision::DOUBLE)
            .ok()
            // + 0.0 turns a −0 from the formula into 0.
            .map(|(rho, phase)| closed_form_coefficient(&rho, &phase) + 0.0)
            .filter(|value| value.is_finite() && (*value == 0.0 || value.abs() >= f64::MIN_POSITIVE));
        if let Some((value, kept)) = binary64.and_then(|value| Some((value, f64_digits_against(value, &reference)?))) {
            return Ok(PrintedCoefficient {
                value: value.to_scientific(kept as usize),
                digits: kept,
                precision_bits: 53,
                binary64: Some(value),
                exact: None,
            });
        }
        return Ok(PrintedCoefficient { binary64, ..verified });
    };
    Ok(verified_closed_form(rho, phase, digits, budget)?.0)
}

/// I(ρ, φ) to `digits` verified significant digits from the closed form, computed at
/// two precisions (the inputs re-read exactly at each) by [`verified_values`].
pub fn verified_coefficient(
    rho: &str,
    phase: &str,
    digits: u32,
    budget: Duration,
) -> Result<PrintedCoefficient, CoefficientError> {
    Ok(verified_closed_form(rho, phase, digits, budget)?.0)
}

/// [`verified_coefficient`] with the verified value itself.
fn verified_closed_form(
    rho: &str,
    phase: &str,
    digits: u32,
    budget: Duration,
) -> Result<(PrintedCoefficient, Float), CoefficientError> {
    if digits == 0 || digits > MAX_DIGITS {
        return Err(CoefficientError::DigitsOutOfRange(digits));
    }
    // In phase with ρ ≤ 1 nothing slips; at ρ = 1 this is also the closed form's limit.
    if vanishes_in_phase(rho, phase) {
        let zero = Float::with_val(Precision::decimal_digits(digits).in_bits(), 0);
        let printed = PrintedCoefficient {
            value: "0".to_string(),
            digits,
            precision_bits: zero.prec(),
            binary64: Some(0.0),
            exact: Some(NOTHING_SLIPS),
        };
        return Ok((printed, zero));
    }
    let mut verified = verified_values(digits, Instant::now() + budget, |precision| {
        let (rho, phase) = read_shape::<Float>(rho, phase, precision)?;
        Ok(vec![closed_form_coefficient(&rho, &phase)])
    })
    .map_err(|error| error.into_error(CoefficientError::Budget))?;
    let value = verified.output.swap_remove(0);
    let printed = PrintedCoefficient {
        value: value.to_scientific(digits as usize),
        digits,
        precision_bits: verified.precision.in_bits(),
        binary64: None,
        exact: None,
    };
    Ok((printed, value))
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
        // Near in phase with ρ < 1, I ≈ −(4/3)φ² is 1e−18 of the segments the quadrature sums;
        // the closed form has no such cancellation and f64 keeps its digits.
        let thin = evaluate("0.5", "1e-9", None, budget).unwrap();
        assert_eq!(thin.precision_bits, 53, "{thin:?}");
        let value: f64 = thin.value.parse().unwrap();
        assert!((value / (-4.0 / 3.0 * 1e-18) - 1.0).abs() < 1e-8, "{thin:?}");
        // Beyond the range of f64 (I ≈ −⅔ρ³ = −6.7e308): the verified MPFR digits.
        let huge = evaluate("1e103", "0.4pi", None, budget).unwrap();
        assert!(huge.precision_bits > 53 && huge.binary64.is_none(), "{huge:?}");
        assert_eq!(huge.value, "-6.66666666666667e308");
        let tiny = evaluate("1e-300", "0.5pi", None, budget).unwrap();
        assert!(
            tiny.precision_bits > 53 && tiny.value.starts_with("-2.6666666666666"),
            "{tiny:?}"
        );
    }

    #[test]
    fn every_printed_f64_digit_is_a_verified_digit() {
        // f64 −7.621618987768808 agrees with I = −7.6216189877688040355… to 15 digits, but its
        // 15th digit rounds to 1 where I's rounds to 0: 14 digits are printed.
        let printed = evaluate("2", "0.7", None, Duration::from_secs(30)).unwrap();
        assert_eq!(
            (printed.value.as_str(), printed.precision_bits),
            ("-7.6216189877688e0", 53)
        );
        let verified = verified_coefficient("2", "0.7", 20, Duration::from_secs(30)).unwrap();
        assert_eq!(verified.value, "-7.6216189877688040355e0");
    }

    #[test]
    fn the_budget_error_reads_as_before() {
        let budget = OutOfBudget {
            digits_requested: 1000,
            digits_agreed: 998,
            seconds: 0.04,
            precision_bits: 3834,
        };
        assert_eq!(
            CoefficientError::Budget(budget).to_string(),
            "only 998 of the 1004 digits of I needed (1000 asked for and 4 guard digits) agreed between two precisions within 0.0 s; ask for fewer digits"
        );
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
