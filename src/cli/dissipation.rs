//! `microslip dissipation`: W and its four segments, in f64 or to proven digits.

use clap::Args;

use microslip::answer::dissipation::{dissipation_report, DissipationAnswer};
use microslip::answer::Provenance;
use microslip::decimal::printing::Decimal;
use microslip::dissipation::Method;

use super::case::{Answer, CaseArgs};
use super::json::DissipationReport;
use super::report::Failure;

#[derive(Args)]
#[command(
    mut_arg("digits", |digits| digits.help(
        "Significant digits to compute and prove by a rigorous enclosure (1–1000); without it, the 12 \
         to 15 that an enclosure in f64 intervals proves, or 15 from Arb's balls where it proves fewer"
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
fewer digits than W; the output says whether the digits are proven (a rigorous enclosure, or \
exact) or estimated (a table's error, or agreement of two precisions where no enclosure can be \
had). For a table compliance, --digits proves the digits of \
its interpolant's W and states the table's own error beside them.";

pub fn run(args: &DissipationArgs) -> Result<String, Failure> {
    let case = args.case.text();
    let report = dissipation_report(&case, args.answer.digits, args.answer.max_seconds)
        .map_err(|error| Failure::of(&error, args.answer.digits.is_some()))?;
    if args.answer.json {
        return Ok(serde_json::to_string(&DissipationReport::new(&report, &case))?);
    }
    Ok(text(&report))
}

/// The text of W's line and its segments.
fn text(report: &DissipationAnswer) -> String {
    let answer = &report.answer;
    let segments = answer.segments.as_ref().expect("W has segments");
    if let Provenance::Exact(reason) = &answer.provenance {
        let mut out = format!("W = {}   (exact: {})", answer.value.decimal, reason.reason());
        for (name, value) in segments.named() {
            out.push_str(&format!("\n  {name}  {}", value.decimal));
        }
        return out;
    }
    let method = answer.method.unwrap_or(Method::FourSegment).description();
    let mut out = match &report.table {
        Some(table) if answer.value.digits() == 0 => format!(
            "W: no digit determined ({method}; its error, table {:.1e} + quadrature {:.1e}, is as large as W itself: |W| ≤ {:.1e}; a denser table resolves it)\n",
            table.error,
            table.quadrature_error,
            table.unrounded.abs() + table.error + table.quadrature_error,
        ),
        _ => format!("W = {}   ({method}; {})\n", answer.value.decimal, provenance(report)),
    };
    if segments.iter().any(|(_, value)| value.decimal != Decimal::Zero) {
        out.push_str("  segments, each printed to the digits its own bound determines:\n");
    }
    for (name, value) in segments.named() {
        match value.digits() {
            0 if report.table.is_some() => out.push_str(&format!("  {name}  no digit determined\n")),
            _ => out.push_str(&format!("  {name}  {}\n", value.decimal)),
        }
    }
    if let Some(table) = &report.table {
        let smoothing = match table.smoothing_residual {
            r if r > 0.0 => format!("; smoothing moved the data by up to {r:.1e} relative"),
            _ => String::new(),
        };
        out.push_str(&match answer.provenance.is_proven() {
            true => format!(
                "  model error: the table itself is accurate to about {:.1e} in W (from the table without its odd rows and without its even rows, on its own spacing, and with its values moved by their rounding; an estimate, not proven){smoothing}\n",
                table.error,
            ),
            false => format!(
                "  error estimates: table {:.1e} (from the table without its odd rows and without its even rows, on its own spacing, and with its values moved by their rounding), quadrature {:.1e}{smoothing}\n",
                table.error, table.quadrature_error,
            ),
        });
    }
    out.trim_end().to_string()
}

/// What a table's W is, and what it is not.
const TABLE_W: &str =
    "the W of the interpolated table, not a statement about the surface or the solver that produced it";

/// How many digits W has and what vouches for them (proven or estimated, and by what),
/// and why the policy left f64 or found no enclosure, as W's line says it.
fn provenance(report: &DissipationAnswer) -> String {
    let answer = &report.answer;
    // An exact zero has as many digits as are asked for (`Answer::digits`), not the unbounded
    // digits of its value.
    let digits = match answer.digits() {
        0 => "no significant digit determined".to_string(),
        1 => "1 significant digit".to_string(),
        n => format!("{n} significant digits"),
    };
    let mut out = format!("{digits}, {}", answer.provenance);
    match (&report.table, answer.provenance.is_proven()) {
        (Some(table), true) => out.push_str(&format!(
            ", for the table's interpolant; the table error, about {:.1e}, estimates only the interpolation of the given points, not the discretisation of the solver that produced them nor the surface",
            table.error
        )),
        (Some(_), false) => out.push_str(&format!(", from the data: {TABLE_W}")),
        (None, _) => {}
    }
    if let Some(why) = &report.no_enclosure {
        out.push_str(&format!("; no enclosure: {why}"));
    }
    out
}
