//! `microslip series` (case form): the proven remainder bound beside each partial sum, the
//! enclosure of W they give, and `--within R`, the largest P1 at which the cubic law is
//! proven within R of W (proofs/cubic-law-remainder.md).

use serde::Serialize;

use microslip::answer::{Answer, Arithmetic, Provenance, Value};
use microslip::case::{Case, CaseText};
use microslip::exact::enclosure::case_balls;
use microslip::exact::remainder::{largest_amplitude, WithinLimit};
use microslip::exact::{partial_sums, remainders as enclosed_remainders, Remainder, RemainderError, SeriesShape};
use microslip::real::{Precision, Real};

use super::report::Failure;
use super::series::failure;

/// The working precision of the remainders: they are bounds, read to 3 digits.
const BITS: u32 = 128;
/// Significant digits of W from the series.
const SERIES_DIGITS: u32 = 15;

/// The remainders of a case's partial sums and what they prove.
pub struct Remainders {
    /// An upper bound on |W − W_N|, index N − 1, rounded up to 3 digits.
    pub bounds: Vec<String>,
    /// Index N − 1: whether W ≥ W_N is proven (as for a completely monotone v' at even N).
    pub from_below: Vec<bool>,
    /// W enclosed by the narrowest W_N + [least, greatest] of its remainder: the series
    /// alone proves it.
    pub series_w: Answer,
    /// With `--within`.
    pub within: Option<WithinAnswer>,
}

/// `--within R` answered.
#[derive(Clone, Debug, Serialize)]
pub struct WithinAnswer {
    /// The largest P1 found at which |W − W₁| ≤ R·|W| is proven (rounded down, 3 digits).
    pub p1_max: Option<String>,
    /// What stops a larger P1: `remainder`, `separation` or `gross slip`.
    pub limited_by: &'static str,
    /// Where the cycle leaves the theory, with ρ and the rest kept (3 digits).
    pub theory_end: String,
}

/// Reads `--within`: a positive finite ratio.
pub fn read_ratio(text: &str) -> Result<f64, Failure> {
    match text.trim().parse::<f64>() {
        Ok(ratio) if ratio.is_finite() && ratio > 0.0 => Ok(ratio),
        _ => Err(Failure::refused(format!(
            "--within must be a positive number, the relative error allowed (e.g. 0.01), got {text:?}"
        ))),
    }
}

fn refused(error: RemainderError) -> Failure {
    match error {
        RemainderError::Kernel { .. } => Failure::failed(error.to_string()),
        other => Failure::refused(other.to_string()),
    }
}

/// The remainders of the case's partial sums to `order`, and `--within` where asked.
pub fn remainders(case: &CaseText, order: usize, within: Option<f64>) -> Result<Remainders, Failure> {
    let spec = case.spec().map_err(|error| failure(error.into()))?;
    let Case { cycle, compliance } = case_balls(&spec, Precision::bits(BITS)).map_err(failure)?;
    let remainders = enclosed_remainders(&cycle, compliance.as_ref(), order).map_err(refused)?;
    let bounds: Vec<_> = remainders.iter().map(Remainder::bound).collect();
    let sums = partial_sums(&cycle, compliance.as_ref(), order).map_err(|error| failure(error.into()))?;
    // W lies in every W_N + [least, greatest]: the narrowest.
    let from_below: Vec<bool> = remainders
        .iter()
        .map(|remainder| remainder.least.real_span().is_some_and(|span| span.0 >= 0.0))
        .collect();
    let mut narrowest = f64::INFINITY;
    let (mut lower, mut upper) = (sums[0].clone(), sums[0].clone());
    for (sum, remainder) in sums.iter().zip(&remainders) {
        let low = sum.clone() + &remainder.least;
        let high = sum.clone() + &remainder.greatest;
        let width = high.to_f64_lossy() - low.to_f64_lossy();
        if width < narrowest {
            narrowest = width;
            (lower, upper) = (low, high);
        }
    }
    let bits = BITS + 64;
    let (low, _) = lower.bounds(bits);
    let (_, high) = upper.bounds(bits);
    let series_w = Answer {
        value: Value::within(&low, &high, SERIES_DIGITS),
        segments: None,
        digits_requested: None,
        provenance: Provenance::Certified {
            bits: BITS,
            arithmetic: Arithmetic::ArbBalls,
        },
        method: None,
    };
    let within = match within {
        None => None,
        Some(ratio) => {
            let rho = cycle.tangential_amplitude.clone() / &(cycle.friction.clone() * &cycle.normal_amplitude);
            let shape = SeriesShape::new(&rho, &cycle.phase, 3).map_err(refused)?;
            let found = largest_amplitude(&shape, &cycle, compliance.as_ref(), ratio);
            Some(WithinAnswer {
                p1_max: found.p1_max.map(|p1| three_digits(p1, false)),
                limited_by: match found.limit {
                    WithinLimit::Remainder => "remainder",
                    WithinLimit::Separation => "separation",
                    WithinLimit::GrossSlip => "gross slip",
                },
                theory_end: three_digits(found.theory_end, true),
            })
        }
    };
    Ok(Remainders {
        bounds: bounds
            .iter()
            .map(|bound| three_digits(bound.real_span().map_or(f64::INFINITY, |span| span.1), true))
            .collect(),
        from_below,
        series_w,
        within,
    })
}

/// `x` to 3 significant digits, rounded up (`up`) or down, so that a bound stays one.
fn three_digits(x: f64, up: bool) -> String {
    if !x.is_finite() || x == 0.0 {
        return format!("{x:e}");
    }
    let text = format!("{x:.2e}");
    let nearest: f64 = text.parse().unwrap_or(x);
    if (up && nearest >= x) || (!up && nearest <= x) {
        return text;
    }
    let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
    let exponent: i32 = exponent.parse().unwrap_or(0);
    let hundredths = (mantissa.parse::<f64>().unwrap_or(0.0) * 100.0).round() as i64 + if up { 1 } else { -1 };
    let (hundredths, exponent) = match hundredths.abs() {
        1000 => (hundredths / 10, exponent + 1),
        99 => (hundredths * 10 + hundredths.signum() * 9, exponent - 1),
        _ => (hundredths, exponent),
    };
    format!("{:.2}e{exponent}", hundredths as f64 / 100.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn three_digits_round_outwards() {
        for x in [1.234567e-7, 9.996e3, 1.0e5, 2.5, 0.0999999, 1.005] {
            let (up, down) = (three_digits(x, true), three_digits(x, false));
            let (up_value, down_value): (f64, f64) = (up.parse().unwrap(), down.parse().unwrap());
            assert!(up_value >= x && down_value <= x, "{x}: {down} {up}");
            assert!(up_value <= x * 1.011 && down_value >= x * 0.989, "{x}: {down} {up}");
        }
    }
}
