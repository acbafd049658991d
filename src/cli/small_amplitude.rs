//! `microslip small-amplitude`: the coefficient I(ρ, φ).

use clap::Args;

use microslip::verify::small_amplitude;

use super::case::Answer;
use super::json::{CoefficientReport, ShapeInputs};
use super::report::Failure;

#[derive(Args)]
#[command(mut_arg("digits", |digits| digits.help(
    "Significant digits, verified by a second run at higher precision (1–1000); without it, f64 with \
     the digits it shares with 15 verified MPFR digits (those MPFR digits where f64 keeps fewer than \
     12 or I lies outside its range)"
)))]
pub struct SmallAmplitudeArgs {
    /// ρ = Q1/(f P1) (> 0).
    #[arg(long, allow_hyphen_values = true)]
    pub rho: String,
    /// The phase φ: radians (`1.2`), a multiple of π (`pi/2`, `3pi/4`, `0.4pi`, `π/2`), plus or minus
    /// radians (`pi-1e-6`), or degrees (`72deg`, `72°`); read exactly
    #[arg(long, allow_hyphen_values = true)]
    pub phi: String,
    #[command(flatten)]
    pub answer: Answer,
}

pub fn run(args: &SmallAmplitudeArgs) -> Result<String, Failure> {
    let printed = small_amplitude::evaluate(&args.rho, &args.phi, args.answer.digits, args.answer.max_seconds)?;
    if args.answer.json {
        let report = CoefficientReport {
            i: printed.value.clone(),
            i_f64: printed.binary64,
            digits: printed.digits,
            digits_verified: Some(printed.digits),
            precision_bits: printed.precision_bits,
            exact: printed.exact,
            inputs: ShapeInputs {
                rho: &args.rho,
                phi: &args.phi,
            },
        };
        return Ok(serde_json::to_string(&report)?);
    }
    let exact = printed
        .exact
        .map(|reason| format!("   (exact: {reason})"))
        .unwrap_or_default();
    Ok(format!(
        "I(ρ = {}, φ = {}) = {}{exact}",
        args.rho, args.phi, printed.value
    ))
}
