//! `microslip dissipation`: W and its four segments, in f64 or to verified digits.

use clap::Args;

use microslip::batch::{case_dissipation, CaseError};
use microslip::dissipation::{DissipationError, Method};
use microslip::reference::ReferenceError;

use super::case::{Answer, CaseArgs};
use super::json::{DissipationReport, Segments};
use super::report::Failure;

#[derive(Args)]
#[command(mut_arg("digits", |digits| digits.help(
    "Significant digits to compute and verify (1–1000); without it, f64 and the digits its error \
     estimate vouches for"
)))]
pub struct DissipationArgs {
    #[command(flatten)]
    pub case: CaseArgs,
    #[command(flatten)]
    pub answer: Answer,
}

fn method_name(method: Method) -> &'static str {
    match method {
        Method::FourSegment => "four-segment integrals in the cycle angle",
        Method::InPhase => "in-phase closed form (paper appendix)",
        Method::ConstantNormalLoad => "constant-normal-load closed form",
        Method::NoTangentialOscillation => "no tangential oscillation (W = 0)",
        Method::Exact(_) => "exact zero",
    }
}

/// Why W is exactly what is printed, where it is.
fn exact_reason(method: Method) -> Option<&'static str> {
    match method {
        Method::Exact(reason) => Some(reason.reason()),
        _ => None,
    }
}

/// A library error on a verified-digits path, with the flag that may help where it applies.
fn reference_failure(error: ReferenceError, digits_given: bool) -> Failure {
    let hint = match &error {
        ReferenceError::Dissipation(
            DissipationError::NotConverged { .. }
            | DissipationError::IllConditioned { .. }
            | DissipationError::OutOfRange { .. },
        ) if !digits_given => "; try --digits N (verified digits in MPFR)",
        ReferenceError::Budget { .. } if digits_given => "; raise --max-seconds or ask for fewer --digits",
        ReferenceError::Budget { .. } => "; raise --max-seconds",
        _ => "",
    };
    Failure::refused(format!("{error}{hint}"))
}

pub fn run(args: &DissipationArgs) -> Result<String, Failure> {
    let case = args.case.text();
    let result = case_dissipation(&case, args.answer.digits, args.answer.max_seconds).map_err(|error| match error {
        CaseError::Reference(error) => reference_failure(error, args.answer.digits.is_some()),
        CaseError::DigitsForTable => Failure::refused(format!("{error}; drop --digits")),
        other => Failure::refused(other.to_string()),
    })?;
    let (printed, table) = (result.printed, result.table);
    if args.answer.json {
        let segments: Vec<String> = printed.segments.iter().map(|(_, value)| value.clone()).collect();
        let report = DissipationReport {
            w: printed.total.clone(),
            w_f64: printed.binary64.map(|values| values[0]),
            digits: printed.digits,
            digits_verified: printed.error_estimate.is_none().then_some(printed.digits),
            precision_bits: printed.precision_bits,
            error_estimate: printed.error_estimate,
            f64_fallback: printed.fallback.clone(),
            method: method_name(printed.method),
            exact: exact_reason(printed.method),
            segments: Segments::from_slice(&segments),
            segments_f64: printed.binary64.and_then(|values| Segments::from_slice(&values[1..])),
            inputs: &case,
            table_error: table.as_ref().map(|t| t.error),
            smoothing_residual: table.as_ref().map(|t| t.smoothing_residual),
        };
        return Ok(serde_json::to_string(&report)?);
    }
    if let Some(reason) = exact_reason(printed.method) {
        let mut out = format!("W = {}   (exact: {reason})", printed.total);
        for (name, value) in &printed.segments {
            out.push_str(&format!("\n  {name}  {value}"));
        }
        return Ok(out);
    }
    let mut out = format!(
        "W = {}   ({}; {} significant digits{})\n",
        printed.total,
        method_name(printed.method),
        printed.digits,
        match (&printed.fallback, printed.error_estimate) {
            (Some(reason), _) => format!(", verified in MPFR: {reason}"),
            (None, Some(_)) if table.is_some() => ", f64, as far as the table and the quadrature vouch".to_string(),
            (None, Some(error)) if printed.digits < 15 => {
                format!(", f64, error estimate {error:.1e}; --digits N gives more")
            }
            (None, Some(_)) => ", f64".to_string(),
            (None, None) => ", verified".to_string(),
        }
    );
    for (name, value) in &printed.segments {
        out.push_str(&format!("  {name}  {value}\n"));
    }
    if let Some(table) = table {
        out.push_str(&format!(
            "  error estimates: table {:.1e} (from the table and its every other row), quadrature {:.1e}{}\n",
            table.error,
            printed.error_estimate.unwrap_or(0.0),
            match table.smoothing_residual {
                r if r > 0.0 => format!("; smoothing moved the data by up to {r:.1e} relative"),
                _ => String::new(),
            }
        ));
    }
    Ok(out.trim_end().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_digits_hint_is_given_only_where_digits_were_not() {
        let out_of_range = || ReferenceError::Dissipation(DissipationError::OutOfRange { scale: 1e-310 });
        assert!(reference_failure(out_of_range(), false)
            .message
            .ends_with("try --digits N (verified digits in MPFR)"));
        assert!(!reference_failure(out_of_range(), true).message.contains("--digits"));
        let budget = || {
            ReferenceError::Budget(microslip::verified::OutOfBudget {
                digits_requested: 30,
                digits_agreed: 3,
                seconds: 1.0,
                precision_bits: 256,
            })
        };
        assert!(reference_failure(budget(), true).message.contains("fewer --digits"));
        assert!(!reference_failure(budget(), false).message.contains("--digits"));
    }
}
