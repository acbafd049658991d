//! `microslip series`: the coefficients Iₙ, or a case's partial sums beside W.

use clap::{ArgGroup, Args};

use microslip::exact::printing::{printed_coefficients, printed_partial_sums, SumDifference};
use microslip::inputs::CaseText;

use super::case::Answer;
use super::json::{PartialSumsReport, SeriesReport};
use super::report::Failure;

/// `--rho` for the coefficients Iₙ alone, or a case (`--p0 … --compliance`) for its partial sums.
#[derive(Args)]
#[command(mut_arg("digits", |digits| digits.help(
    "Verified significant digits (1–1000); without it, f64 (Iₙ) or 15 verified digits (a case)"
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
    /// Normal compliance SPEC (as for `dissipation`).
    #[arg(long, allow_hyphen_values = true, requires = "p0")]
    pub compliance: Option<String>,
    #[command(flatten)]
    pub answer: Answer,
}

pub fn run(args: &SeriesArgs) -> Result<String, Failure> {
    let budget = args.answer.max_seconds;
    let Some(p0) = &args.p0 else {
        let rho = args
            .rho
            .as_deref()
            .ok_or_else(|| Failure::refused("give --rho, or a case with --p0 … --compliance"))?;
        let printed = printed_coefficients(rho, &args.phi, args.order, args.answer.digits, budget)?;
        let digits = printed.digits.iter().copied().min().unwrap_or(0);
        if args.answer.json {
            let report = SeriesReport {
                rho,
                phi: &args.phi,
                digits,
                coefficients: &printed.values,
                digits_verified: &printed.digits,
                coefficients_f64: (!printed.binary64.is_empty()).then_some(&printed.binary64),
                exact: &printed.exact,
            };
            return Ok(serde_json::to_string(&report)?);
        }
        let rows: Vec<String> = printed
            .values
            .iter()
            .enumerate()
            .zip(&printed.exact)
            .map(|((n, v), exact)| match exact {
                Some(reason) => format!("I_{n:<3} = {v}   (exact: {reason})"),
                None => format!("I_{n:<3} = {v}"),
            })
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
    let printed = printed_partial_sums(&case, args.order, args.answer.digits, budget)?;
    let differences: Vec<String> = printed
        .differences
        .iter()
        .map(|difference| match difference {
            SumDifference::Exact(_) => "0".to_string(),
            SumDifference::Unresolved(bound) => format!("<{bound}"),
            SumDifference::Value(value) => value.clone(),
        })
        .collect();
    let differences_exact: Vec<Option<&'static str>> = printed
        .differences
        .iter()
        .map(|difference| match difference {
            SumDifference::Exact(reason) => Some(*reason),
            _ => None,
        })
        .collect();
    if args.answer.json {
        let report = PartialSumsReport {
            w: &printed.dissipation,
            w_digits_verified: printed.dissipation_digits,
            partial_sums: &printed.sums,
            differences: &differences,
            differences_exact: &differences_exact,
            exact: printed.exact,
            digits_verified: printed.digits,
            inputs: &case,
        };
        return Ok(serde_json::to_string(&report)?);
    }
    if let Some(reason) = printed.exact {
        return Ok(format!(
            "W = 0 and W_N = 0 for N = 1 … {} (exact: {reason})",
            args.order
        ));
    }
    let width = printed.digits as usize + 8;
    let mut out = format!(
        "W (four-segment) = {}\n   N  {:<width$}  W_N − W",
        printed.dissipation, "W_N (series to order N)"
    );
    for (n, ((sum, difference), exact)) in printed
        .sums
        .iter()
        .zip(&differences)
        .zip(&differences_exact)
        .enumerate()
    {
        out.push_str(&format!("\n{:>4}  {sum:<width$}  {difference}", n + 1));
        if let Some(reason) = exact {
            out.push_str(&format!(" (exact: {reason})"));
        }
    }
    Ok(out)
}
