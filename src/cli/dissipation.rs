//! `microslip dissipation`: W and its four segments, in f64 or to verified digits.

use clap::Args;

use microslip::batch::{case_dissipation, CaseError};
use microslip::dissipation::{DissipationError, Method};
use microslip::reference::{PrintedDissipation, ReferenceError};
use microslip::verified::{Bound, F64_MOST_DIGITS};

use super::case::{Answer, CaseArgs};
use super::json::{DissipationReport, Segments};
use super::report::Failure;

#[derive(Args)]
#[command(
    mut_arg("digits", |digits| digits.help(
        "Significant digits to compute and verify (1–1000); without it, f64 and the digits its error \
         estimate vouches for"
    )),
    after_help = UNITS_AND_DIGITS
)]
pub struct DissipationArgs {
    #[command(flatten)]
    pub case: CaseArgs,
    #[command(flatten)]
    pub answer: Answer,
}

/// What the printed numbers mean, for --help.
const UNITS_AND_DIGITS: &str = "W is energy per cycle in the units of load × approach of the inputs \
(N·m for loads in N and a compliance in m/N). The segments are the four integrals of v'(P) − v'(P0) \
(v'(P0) contributes nothing over the closed cycle, so they sum to W). Every number is printed \
only with the digits on which its whole error interval rounds alike, so a segment may carry \
fewer digits than W; the output names the bound: an f64 error estimate (not proven), agreement \
of two precisions with --digits (not a proof), a table's error, or exact.";

fn method_name(method: Method) -> &'static str {
    method.description()
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
    let bound = match printed.bound {
        Bound::Estimate if table.is_some() => Bound::TableError,
        bound => bound,
    };
    if args.answer.json {
        // A segment with no known digit is printed empty (a coarse table): null here.
        let segments: Vec<Option<String>> = printed
            .segments
            .iter()
            .map(|(_, value)| (!value.is_empty()).then(|| value.clone()))
            .collect();
        let report = DissipationReport {
            w: (printed.digits > 0).then(|| printed.total.clone()),
            w_f64: printed.binary64.map(|values| values[0]),
            digits: printed.digits,
            digits_verified: matches!(bound, Bound::Agreement | Bound::Exact).then_some(printed.digits),
            bound: bound.key(),
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
    let mut out = match &table {
        Some(table) if printed.digits == 0 => format!(
            "W: no digit determined ({}; its error, table {:.1e} + quadrature {:.1e}, is as large as W itself: |W| ≤ {:.1e}; a denser table resolves it)\n",
            method_name(printed.method),
            table.error,
            printed.error_estimate.unwrap_or(0.0),
            table.unrounded.abs() + table.error + printed.error_estimate.unwrap_or(0.0),
        ),
        _ => format!(
            "W = {}   ({}; {})\n",
            printed.total,
            method_name(printed.method),
            provenance(&printed, bound)
        ),
    };
    if printed.segments.iter().any(|(_, value)| value != "0") {
        out.push_str("  segments, each printed to the digits its own bound determines:\n");
    }
    for (name, value) in &printed.segments {
        let value = if value.is_empty() { "no digit determined" } else { value };
        out.push_str(&format!("  {name}  {value}\n"));
    }
    if let Some(table) = table {
        out.push_str(&format!(
            "  error estimates: table {:.1e} (from the table without its odd rows, and without its even rows), quadrature {:.1e}{}\n",
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

/// How many digits W has and what vouches for them, as the W line says it.
fn provenance(printed: &PrintedDissipation, bound: Bound) -> String {
    let digits = match printed.digits {
        0 => "no significant digit determined".to_string(),
        1 => "1 significant digit".to_string(),
        n => format!("{n} significant digits"),
    };
    let agreement = "verified by agreement of two precisions (not a proof)";
    match (bound, &printed.fallback, printed.error_estimate) {
        (Bound::Exact, _, _) => "exact".to_string(),
        (_, None, Some(error)) if printed.total == "0" => {
            format!("zero in f64, error estimate {error:.1e} (not proven)")
        }
        (_, Some(reason), _) => format!("{digits}, in MPFR, {agreement}: {reason}"),
        (Bound::TableError, _, _) => {
            format!("{digits}, f64, as far as the table error and the quadrature's error estimate vouch")
        }
        (Bound::Agreement, None, _) => format!("{digits}, {agreement}"),
        (_, None, Some(error)) if printed.digits < F64_MOST_DIGITS => {
            format!("{digits}, f64, error estimate {error:.1e} (not proven); --digits N gives more")
        }
        (_, None, _) => format!("{digits}, f64, error estimate (not proven)"),
    }
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
