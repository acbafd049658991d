//! The series as printed: Iₙ(ρ, φ) and the partial sums of a case, each digit verified.

use std::time::{Duration, Instant};

use rug::Float;

use super::series::{partial_sums, series_coefficients, SeriesError};
use crate::compliance::slope_polynomial_degree;
use crate::inputs::{parse_phase, Case, CaseText, InputError};
use crate::phase::{decimal, ExactPhase, PhaseError};
use crate::real::{ParseRealError, Precision, Real};
use crate::reference::{printable_dissipation, ReferenceError};
use crate::verified::{f64_digits_against, verified_values, OutOfBudget, VerifyError, F64_MOST_DIGITS, MAX_DIGITS};

/// The highest order the series is computed to.
pub const MAX_ORDER: usize = 200;

/// Why the series could not be printed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PrintedSeriesError {
    /// ρ is not a number.
    #[error("{quantity} is not a number: {source}")]
    Number {
        quantity: &'static str,
        #[source]
        source: ParseRealError,
    },
    /// φ is not a phase.
    #[error(transparent)]
    Phase(#[from] PhaseError),
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
    /// The time budget ran out.
    #[error("only {} of the {} digits needed agreed between two precisions within the time budget; ask for fewer digits or a lower order", .0.digits_agreed, .0.digits_required())]
    OutOfTime(OutOfBudget),
}

impl From<VerifyError<PrintedSeriesError>> for PrintedSeriesError {
    fn from(error: VerifyError<PrintedSeriesError>) -> Self {
        error.into_error(PrintedSeriesError::OutOfTime)
    }
}

/// Why I₀ is exactly 0: v' = 1 is a constant slope (proofs/constant-term.md).
pub const CONSTANT_TERM: &str = "I₀ ≡ 0, the constant-term theorem";

/// Why every Iₙ is exactly 0 in phase with ρ ≤ 1.
pub const NOTHING_SLIPS: &str = "in phase, φ = kπ exactly, with ρ ≤ 1: nothing slips";

/// I₀ … I_N as decimal strings.
#[derive(Clone, Debug, PartialEq)]
pub struct PrintedCoefficients {
    /// Iₙ at index n; I₀ is printed as 0 (the constant-term theorem).
    pub values: Vec<String>,
    /// Why Iₙ is exactly the 0 printed, where it is (I₀ always).
    pub exact: Vec<Option<&'static str>>,
    /// The verified significant digits of each (I₀: those asked for).
    pub digits: Vec<u32>,
    /// Iₙ in binary64 where f64 was used (no `digits`), else empty.
    pub binary64: Vec<f64>,
}

/// ρ and φ's offset from the nearest multiple of π (the series has period π in φ).
fn read_shape<R: Real>(rho: &str, phase: &str, precision: Precision) -> Result<(R, R), PrintedSeriesError> {
    let number = |quantity, source| PrintedSeriesError::Number { quantity, source };
    let rho = R::parse_decimal(rho, precision).map_err(|source| number("ρ", source))?;
    let (offset, _) = parse_phase(phase, precision)?;
    Ok((rho, offset))
}

/// I₁ … I_N at a precision. I₀ is not computed: it is 0 exactly (the constant-term
/// theorem), and what the integration gives for it is only its rounding.
fn coefficients_at<R: Real>(rho: &R, phase: &R, order: usize) -> Result<Vec<R>, PrintedSeriesError> {
    let values = series_coefficients(rho, phase, order)?;
    Ok(values.into_iter().skip(1).map(|(value, _)| value).collect())
}

/// In phase (φ = kπ exactly, as written) with 0 < ρ ≤ 1 (exactly) nothing slips: every Iₙ is 0.
pub fn vanishes_in_phase(rho: &str, phase: &str) -> bool {
    let rho = decimal(rho);
    ExactPhase::parse(phase).is_ok_and(|phase| phase.is_in_phase()) && rho.is_some_and(|rho| rho > 0 && rho <= 1)
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
    // Refusals first: ρ and φ must read.
    read_shape::<Float>(rho, phase, Precision::bits(64))?;
    let zero = "0".to_string();
    if vanishes_in_phase(rho, phase) {
        return Ok(PrintedCoefficients {
            values: vec![zero; order + 1],
            exact: vec![Some(NOTHING_SLIPS); order + 1],
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
        exact: vec![Some(CONSTANT_TERM)],
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
        printed.exact.push(None);
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

/// W_N − W as printed.
#[derive(Clone, Debug, PartialEq)]
pub enum SumDifference {
    /// Exactly 0, and why.
    Exact(&'static str),
    /// Below what the digits of W resolve: |W_N − W| < the bound given (3 digits).
    Unresolved(String),
    /// The difference (3 digits).
    Value(String),
}

/// Why W_N − W is exactly 0 for a polynomial v' of degree d ≤ N.
pub const SERIES_ENDS: &str = "v' is a polynomial of degree ≤ N, so the series ends at order N";

/// The partial sums W_N (N = 1 … order) of a case beside its W by quadrature.
#[derive(Clone, Debug, PartialEq)]
pub struct PrintedPartialSums {
    /// W (four-segment quadrature), verified digits.
    pub dissipation: String,
    /// The verified significant digits of W.
    pub dissipation_digits: u32,
    /// Why W (and with it every W_N) is exactly 0, where it is.
    pub exact: Option<&'static str>,
    /// W_N at index N − 1.
    pub sums: Vec<String>,
    /// W_N − W at index N − 1.
    pub differences: Vec<SumDifference>,
    /// The verified significant digits of every W_N.
    pub digits: u32,
}

/// The series of a case summed to orders 1 … `order`, each partial sum to `digits`
/// verified digits (15 without), beside W from the four-segment quadrature. Where W is
/// exactly 0 (v'' ≡ 0, Q1 = 0, in phase with nothing slipping) every W_N is too, and
/// where v' is a polynomial of degree d, W_N = W exactly from N = d on.
pub fn printed_partial_sums(
    case: &CaseText,
    order: usize,
    digits: Option<u32>,
    budget: Duration,
) -> Result<PrintedPartialSums, PrintedSeriesError> {
    let asked = digits_asked(order, digits)?;
    let started = Instant::now();
    let w = printable_dissipation(case, Some(asked), budget)?;
    if let crate::dissipation::Method::Exact(reason) = w.method {
        return Ok(PrintedPartialSums {
            dissipation: w.total,
            dissipation_digits: w.digits,
            exact: Some(reason.reason()),
            sums: vec!["0".to_string(); order],
            differences: vec![SumDifference::Exact(reason.reason()); order],
            digits: asked,
        });
    }
    let remaining = budget.saturating_sub(started.elapsed());
    // The sums get what W left of the budget; running out, they report the whole run's time.
    let sums = verified_values(asked, started + remaining, |precision| {
        let Case { cycle, compliance } = case.read::<Float>(precision)?;
        Ok(partial_sums(&cycle, compliance.as_ref(), order)?)
    })
    .map_err(|error| match error {
        VerifyError::OutOfBudget(out) => VerifyError::OutOfBudget(OutOfBudget {
            seconds: started.elapsed().as_secs_f64(),
            ..out
        }),
        other => other,
    })?;
    let bits = sums.precision.in_bits();
    let w_value = Float::parse_decimal(&w.total, sums.precision).unwrap_or_else(|_| Float::with_val(bits, 0));
    let resolved = w_value.clone().abs() * Float::with_val(bits, 10).powi(-(w.digits as i32));
    let degree = slope_polynomial_degree(&case.compliance);
    let differences = sums
        .output
        .iter()
        .enumerate()
        .map(|(index, sum)| {
            let difference = sum.clone() - &w_value;
            if degree.is_some_and(|degree| degree <= index + 1) {
                SumDifference::Exact(SERIES_ENDS)
            } else if difference.clone().abs() > resolved {
                SumDifference::Value(difference.to_scientific(3))
            } else {
                SumDifference::Unresolved(resolved.to_scientific(3))
            }
        })
        .collect();
    Ok(PrintedPartialSums {
        dissipation: w.total,
        dissipation_digits: w.digits,
        exact: None,
        sums: sums.output.iter().map(|s| s.to_scientific(asked as usize)).collect(),
        differences,
        digits: asked,
    })
}
