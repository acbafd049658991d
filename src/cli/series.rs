//! `microslip series`: the coefficients Iₙ, or a case's partial sums beside W.

use clap::{ArgGroup, Args};

use serde::Serialize;

use microslip::answer::{Answer, Provenance};
use microslip::case::CaseText;
use microslip::compliance::{spec_help, spec_summary};
use microslip::exact::printing::{coefficient_answers, partial_sum_answers, ExactAnswerError};

use super::case::Answer as AnswerArgs;
use super::json::{printed, ShapeInputs, ValueEnvelope, ValueReport};
use super::report::Failure;

/// `--rho` for the coefficients Iₙ alone, or a case (`--p0 … --compliance`) for its partial sums.
#[derive(Args)]
#[command(mut_arg("digits", |digits| digits.help(
    "Significant digits (1–1000), proven by rigorous enclosures; without it, 15 proven digits (and \
     the f64 values of Iₙ beside them in JSON)"
)))]
#[command(group(ArgGroup::new("source").args(["rho", "p0"]).required(true)))]
#[command(group(ArgGroup::new("ratio").args(["lambda", "nu"])))]
pub struct SeriesArgs {
    /// ρ = Q1/(f P1) (> 0): print I₀ … I_N.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["p0", "compliance"])]
    pub rho: Option<String>,
    /// The phase φ: radians (`1.2`), a multiple of π (`pi/2`, `3pi/4`, `0.4pi`, `π/2`), plus or minus
    /// radians (`pi-1e-6`), or degrees (`72deg`, `72°`); read exactly
    #[arg(long, allow_hyphen_values = true)]
    pub phi: String,
    /// The highest order N.
    #[arg(long)]
    pub order: usize,
    /// Mean normal load P0 (with a case).
    #[arg(long, allow_hyphen_values = true, requires_all = ["p1", "q1", "friction", "ratio", "compliance"])]
    pub p0: Option<String>,
    /// Normal load amplitude P1.
    #[arg(long, allow_hyphen_values = true)]
    pub p1: Option<String>,
    /// Mean tangential load Q0.
    #[arg(long, allow_hyphen_values = true, default_value = "0")]
    pub q0: String,
    /// Tangential load amplitude Q1.
    #[arg(long, allow_hyphen_values = true)]
    pub q1: Option<String>,
    /// Coulomb friction coefficient f.
    #[arg(long, allow_hyphen_values = true)]
    pub friction: Option<String>,
    /// Tangential/normal compliance ratio λ, in [1, 2].
    #[arg(long, allow_hyphen_values = true, conflicts_with = "nu")]
    pub lambda: Option<String>,
    /// Poisson's ratio ν.
    #[arg(long, allow_hyphen_values = true)]
    pub nu: Option<String>,
    #[arg(long, allow_hyphen_values = true, requires = "p0", help = spec_summary(), long_help = spec_help())]
    pub compliance: Option<String>,
    #[command(flatten)]
    pub answer: AnswerArgs,
}

/// Why an answer is exact, where it is.
pub fn exact_reason(answer: &Answer) -> Option<&'static str> {
    match &answer.provenance {
        Provenance::Exact(reason) => Some(reason.reason()),
        _ => None,
    }
}

/// `value   (provenance)`, as a line of text shows an answer.
pub fn shown(answer: &Answer) -> String {
    format!("{}   ({})", answer.value.decimal, answer.provenance)
}

/// A failure of an answer: refused input (exit 2), or a result that could not be
/// vouched for (exit 1).
pub fn failure(error: ExactAnswerError) -> Failure {
    if error.is_failure() {
        Failure::failed(error.to_string())
    } else {
        Failure::refused(error.to_string())
    }
}

/// `microslip series --rho … --json`.
#[derive(Serialize)]
struct SeriesReport<'a> {
    /// The fewest digits printed of any coefficient.
    digits: u32,
    /// I₀ … I_N as printed.
    coefficients: Vec<Option<String>>,
    /// I₀ … I_N in binary64 (runs without --digits).
    coefficients_f64: Option<Vec<f64>>,
    /// I₀ … I_N, each with what vouches for it.
    values: Vec<ValueReport>,
    inputs: ShapeInputs<'a>,
}

/// `microslip series` with a case `--json`: W as `dissipation --json` prints it, and the
/// partial sums W_N beside it.
#[derive(Serialize)]
struct PartialSumsReport<'a> {
    #[serde(rename = "W")]
    w: Option<String>,
    #[serde(rename = "W_f64")]
    w_f64: Option<f64>,
    #[serde(flatten)]
    envelope: ValueEnvelope,
    partial_sums: Vec<ValueReport>,
    /// W_N − W for N = 1 … order.
    differences: Vec<ValueReport>,
    inputs: &'a CaseText,
}

pub fn run(args: &SeriesArgs) -> Result<String, Failure> {
    let budget = args.answer.max_seconds;
    let Some(p0) = &args.p0 else {
        let rho = args
            .rho
            .as_deref()
            .ok_or_else(|| Failure::refused("give --rho, or a case with --p0 … --compliance"))?;
        let answers = coefficient_answers(rho, &args.phi, args.order, args.answer.digits, budget).map_err(failure)?;
        if args.answer.json {
            let in_f64: Option<Vec<f64>> = answers
                .iter()
                .map(|answer| match answer.provenance {
                    Provenance::Exact(_) => Some(0.0),
                    _ => answer.value.binary64,
                })
                .collect();
            let report = SeriesReport {
                digits: answers.iter().map(Answer::digits).min().unwrap_or(0),
                coefficients: answers.iter().map(|a| printed(&a.value)).collect(),
                coefficients_f64: in_f64.filter(|_| args.answer.digits.is_none()),
                values: answers.iter().map(ValueReport::of).collect(),
                inputs: ShapeInputs { rho, phi: &args.phi },
            };
            return Ok(serde_json::to_string(&report)?);
        }
        let rows: Vec<String> = answers
            .iter()
            .enumerate()
            .map(|(n, answer)| format!("I_{n:<3} = {}", shown(answer)))
            .collect();
        return Ok(format!(
            "Iₙ(ρ = {rho}, φ = {}), n = 0 … {}:\n{}",
            args.phi,
            args.order,
            rows.join("\n")
        ));
    };
    let missing = || Failure::refused("a case needs --p0, --p1, --q1, --friction, --lambda or --nu, and --compliance");
    let case = CaseText {
        p0: p0.clone(),
        p1: args.p1.clone().ok_or_else(missing)?,
        q0: args.q0.clone(),
        q1: args.q1.clone().ok_or_else(missing)?,
        phi: args.phi.clone(),
        friction: args.friction.clone().ok_or_else(missing)?,
        lambda: args.lambda.clone(),
        nu: args.nu.clone(),
        compliance: args.compliance.clone().ok_or_else(missing)?,
    };
    let sums = partial_sum_answers(&case, args.order, args.answer.digits, budget).map_err(failure)?;
    let all_exact = exact_reason(&sums.dissipation);
    if args.answer.json {
        let report = PartialSumsReport {
            w: printed(&sums.dissipation.value),
            w_f64: sums.dissipation.value.binary64,
            envelope: ValueEnvelope::of(&sums.dissipation),
            partial_sums: sums.sums.iter().map(ValueReport::of).collect(),
            differences: sums.differences.iter().map(ValueReport::of).collect(),
            inputs: &case,
        };
        return Ok(serde_json::to_string(&report)?);
    }
    if let Some(reason) = all_exact {
        return Ok(format!(
            "W = 0 and W_N = 0 for N = 1 … {} (exact: {reason})",
            args.order
        ));
    }
    let width = sums
        .sums
        .iter()
        .map(|sum| sum.value.decimal.to_string().chars().count())
        .max()
        .unwrap_or(0)
        .max(24);
    let mut out = format!(
        "W (four-segment) = {}\n   N  {:<width$}  W_N − W",
        shown(&sums.dissipation),
        "W_N (series to order N)"
    );
    for (n, (sum, difference)) in sums.sums.iter().zip(&sums.differences).enumerate() {
        out.push_str(&format!(
            "\n{:>4}  {:<width$}  {}",
            n + 1,
            sum.value.decimal.to_string(),
            shown(difference)
        ));
    }
    let provenance = sums
        .sums
        .first()
        .map(|sum| sum.provenance.to_string())
        .unwrap_or_default();
    out.push_str(&format!("\nW_N: {provenance}"));
    Ok(out)
}
