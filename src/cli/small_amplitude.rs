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
    /// The phase φ, in radians or as a multiple of π (`0.4pi`).
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
            inputs: ShapeInputs {
                rho: &args.rho,
                phi: &args.phi,
            },
        };
        return Ok(serde_json::to_string(&report)?);
    }
    Ok(format!("I(ρ = {}, φ = {}) = {}", args.rho, args.phi, printed.value))
}
