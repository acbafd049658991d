//! `microslip series` (case form): the proven remainder bound beside each partial sum, the
//! enclosure of W they give, and `--within R`, the largest P1 at which the cubic law is
//! proven within R of W (proofs/cubic-law-remainder.md).

use serde::Serialize;

use microslip::answer::remainders::case_remainders;
use microslip::answer::Answer;
use microslip::case::CaseText;
use microslip::exact::remainder::WithinLimit;

use super::report::Failure;

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

/// The remainders of the case's partial sums to `order`, and `--within` where asked,
/// formatted as the command prints them.
pub fn remainders(case: &CaseText, order: usize, within: Option<f64>) -> Result<Remainders, Failure> {
    let found = case_remainders(case, order, within).map_err(|error| Failure::of(&error, false))?;
    Ok(Remainders {
        bounds: found.bounds.iter().map(|&bound| three_digits(bound, true)).collect(),
        from_below: found.from_below,
        series_w: found.series_w,
        within: found.within.map(|within| WithinAnswer {
            p1_max: within.p1_max.map(|p1| three_digits(p1, false)),
            limited_by: match within.limit {
                WithinLimit::Remainder => "remainder",
                WithinLimit::Separation => "separation",
                WithinLimit::GrossSlip => "gross slip",
            },
            theory_end: three_digits(within.theory_end, true),
        }),
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
