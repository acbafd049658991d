//! The series as printed: Iₙ(ρ, φ) and the partial sums of a case, each digit verified.

use std::time::{Duration, Instant};

use rug::Float;

use super::series::{partial_sums, series_coefficients, SeriesError};
use crate::inputs::{parse_phase, Case, CaseText, InputError};
use crate::real::{ParseRealError, Precision, Real};
use crate::reference::{printable_dissipation, ReferenceError};
use crate::verified::{f64_digits_against, verified_values, OutOfBudget, VerifyError, F64_MOST_DIGITS, MAX_DIGITS};

/// The highest order the series is computed to.
pub const MAX_ORDER: usize = 200;

/// Why the series could not be printed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PrintedSeriesError {
    /// ρ or φ is not a number.
    #[error("{quantity} is not a number: {source}")]
    Number {
        quantity: &'static str,
        #[source]
        source: ParseRealError,
    },
    /// The digits asked for are out of range.
    #[error("the digits asked for must be between 1 and {MAX_DIGITS}, got {0}")]
    DigitsOutOfRange(u32),
    /// The order asked for is out of range.
    #[error("the order of the series must be between 1 and {MAX_ORDER}, got {0}")]
    OrderOutOfRange(usize),
    /// The series itself failed.
    #[error(transparent)]
    Series(#[from] SeriesError),
    /// The case does not read.
    #[error(transparent)]
    Input(#[from] InputError),
    /// W by quadrature failed.
    #[error(transparent)]
    Reference(#[from] ReferenceError),
    /// I₀ came out beyond its rounding bound (the constant-term theorem says it is 0).
    #[error("I₀ = {value:e} exceeds its rounding bound {bound:e}: the exact integration is inconsistent here")]
    ConstantTerm { value: f64, bound: f64 },
    /// The time budget ran out.
    #[error("only {} of the {} digits needed agreed between two precisions within the time budget; ask for fewer digits or a lower order", .0.digits_agreed, .0.digits_required())]
    OutOfTime(OutOfBudget),
}

impl From<VerifyError<PrintedSeriesError>> for PrintedSeriesError {
    fn from(error: VerifyError<PrintedSeriesError>) -> Self {
        error.into_error(PrintedSeriesError::OutOfTime)
    }
}

/// I₀ … I_N as decimal strings.
#[derive(Clone, Debug, PartialEq)]
pub struct PrintedCoefficients {
    /// Iₙ at index n; I₀ is printed as 0 (the constant-term theorem, checked to rounding).
    pub values: Vec<String>,
    /// The verified significant digits of each (I₀: those asked for).
    pub digits: Vec<u32>,
    /// Iₙ in binary64 where f64 was used (no `digits`), else empty.
    pub binary64: Vec<f64>,
}

fn read_shape<R: Real>(rho: &str, phase: &str, precision: Precision) -> Result<(R, R), PrintedSeriesError> {
    let number = |quantity, source| PrintedSeriesError::Number { quantity, source };
    let rho = R::parse_decimal(rho, precision).map_err(|source| number("ρ", source))?;
    let phase = parse_phase(phase, precision).map_err(|source| number("φ", source))?;
    Ok((rho, phase))
}

/// I₁ … I_N at a precision, after checking that I₀ vanishes to its rounding bound.
fn coefficients_at<R: Real>(rho: &R, phase: &R, order: usize) -> Result<Vec<R>, PrintedSeriesError> {
    let mut values = series_coefficients(rho, phase, order)?;
    let (constant, scale) = values.remove(0);
    let bound = scale * &rho.epsilon_like() * &rho.int(1024);
    if constant.abs() > bound {
        return Err(PrintedSeriesError::ConstantTerm {
            value: constant.to_f64_lossy(),
            bound: bound.to_f64_lossy(),
        });
    }
    Ok(values.into_iter().map(|(value, _)| value).collect())
}

/// In phase (φ ≡ 0 mod π, exactly at two precisions) with ρ ≤ 1 nothing slips: every Iₙ is 0.
pub fn vanishes_in_phase(rho: &str, phase: &str) -> bool {
    [64, 256].into_iter().all(|bits| {
        read_shape::<Float>(rho, phase, Precision::bits(bits)).is_ok_and(|(rho, phase)| {
            let pi = phase.pi_like();
            let reduced = phase.clone() - &((phase / &pi).floor() * &pi);
            reduced.is_zero() && rho <= rho.int(1) && rho > rho.int(0)
        })
    })
}

/// The verified digits to compute for `order` and `digits` (without, [`F64_MOST_DIGITS`]),
/// each checked in range.
fn digits_asked(order: usize, digits: Option<u32>) -> Result<u32, PrintedSeriesError> {
    if order == 0 || order > MAX_ORDER {
        return Err(PrintedSeriesError::OrderOutOfRange(order));
    }
    let asked = digits.unwrap_or(F64_MOST_DIGITS);
    if asked == 0 || asked > MAX_DIGITS {
        return Err(PrintedSeriesError::DigitsOutOfRange(asked));
    }
    Ok(asked)
}

/// I₀ … I_`order` at (ρ, φ) given as text: with `digits` = Some(D), each to D verified
/// digits; without, f64 with the digits on which it agrees with 15 verified digits
/// where that suffices ([`f64_digits_against`]), the verified digits themselves otherwise.
pub fn printed_coefficients(
    rho: &str,
    phase: &str,
    order: usize,
    digits: Option<u32>,
    budget: Duration,
) -> Result<PrintedCoefficients, PrintedSeriesError> {
    let asked = digits_asked(order, digits)?;
    let zero = Float::with_val(Precision::decimal_digits(asked).in_bits(), 0).to_scientific(asked as usize);
    if vanishes_in_phase(rho, phase) {
        return Ok(PrintedCoefficients {
            values: vec![zero; order + 1],
            digits: vec![asked; order + 1],
            binary64: if digits.is_none() { vec![0.0; order + 1] } else { vec![] },
        });
    }
    let verified = verified_values(asked, Instant::now() + budget, |precision| {
        let (rho, phase) = read_shape::<Float>(rho, phase, precision)?;
        coefficients_at(&rho, &phase, order)
    })?;
    let mut printed = PrintedCoefficients {
        values: vec![zero],
        digits: vec![asked],
        binary64: vec![],
    };
    let in_f64 = match digits {
        Some(_) => None,
        None => read_shape::<f64>(rho, phase, Precision::DOUBLE)
            .ok()
            .and_then(|(rho, phase)| coefficients_at(&rho, &phase, order).ok()),
    };
    if let Some(values) = &in_f64 {
        printed.binary64 = std::iter::once(0.0).chain(values.iter().copied()).collect();
    }
    for (n, reference) in verified.output.iter().enumerate() {
        let kept = in_f64
            .as_ref()
            .and_then(|values| Some((values[n], f64_digits_against(values[n], reference)?)));
        match kept {
            Some((value, kept)) => {
                printed.values.push(value.to_scientific(kept as usize));
                printed.digits.push(kept);
            }
            None => {
                printed.values.push(reference.to_scientific(asked as usize));
                printed.digits.push(asked);
            }
        }
    }
    Ok(printed)
}

/// The partial sums W_N (N = 1 … order) of a case beside its W by quadrature.
#[derive(Clone, Debug, PartialEq)]
pub struct PrintedPartialSums {
    /// W (four-segment quadrature), verified digits.
    pub dissipation: String,
    /// The verified significant digits of W.
    pub dissipation_digits: u32,
    /// W_N at index N − 1.
    pub sums: Vec<String>,
    /// W_N − W at index N − 1 (3 digits), or `None` where it is below what the digits
    /// of W resolve.
    pub differences: Vec<Option<String>>,
    /// The verified significant digits of every W_N.
    pub digits: u32,
}

/// The series of a case summed to orders 1 … `order`, each partial sum to `digits`
/// verified digits (15 without), beside W from the four-segment quadrature.
pub fn printed_partial_sums(
    case: &CaseText,
    order: usize,
    digits: Option<u32>,
    budget: Duration,
) -> Result<PrintedPartialSums, PrintedSeriesError> {
    let asked = digits_asked(order, digits)?;
    let started = Instant::now();
    let sums = verified_values(asked, started + budget, |precision| {
        let Case { cycle, compliance } = case.read::<Float>(precision)?;
        Ok(partial_sums(&cycle, compliance.as_ref(), order)?)
    })?;
    let remaining = budget.saturating_sub(started.elapsed());
    // W gets what the sums left of the budget; running out, it reports the whole run's time.
    let w = printable_dissipation(case, Some(asked), remaining).map_err(|error| match error {
        ReferenceError::Budget(out) => ReferenceError::Budget(OutOfBudget {
            seconds: started.elapsed().as_secs_f64(),
            ..out
        }),
        other => other,
    })?;
    let bits = sums.precision.in_bits();
    let w_value = Float::parse_decimal(&w.total, sums.precision).unwrap_or_else(|_| Float::with_val(bits, 0));
    let resolved = w_value.clone().abs() * Float::with_val(bits, 10).powi(-(w.digits as i32));
    let differences = sums
        .output
        .iter()
        .map(|sum| {
            let difference = sum.clone() - &w_value;
            (difference.clone().abs() > resolved).then(|| difference.to_scientific(3))
        })
        .collect();
    Ok(PrintedPartialSums {
        dissipation: w.total,
        dissipation_digits: w.digits,
        sums: sums.output.iter().map(|s| s.to_scientific(asked as usize)).collect(),
        differences,
        digits: asked,
    })
}
