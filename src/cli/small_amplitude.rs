//! `microslip small-amplitude`: the coefficient I(ρ, φ).

use clap::Args;
use serde::Serialize;

use microslip::answer::series::coefficient_answer;

use super::case::Answer;
use super::json::{printed, ShapeInputs, ValueEnvelope};
use super::report::Failure;
use super::series::shown;

#[derive(Args)]
#[command(mut_arg("digits", |digits| digits.help(
    "Significant digits (1–1000), proven by a rigorous enclosure of the closed form; without it, \
     15 proven digits (and I's f64 value beside them in JSON)"
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

/// `microslip small-amplitude --json`.
#[derive(Serialize)]
struct CoefficientReport<'a> {
    #[serde(rename = "I")]
    i: Option<String>,
    /// I in binary64 where it is computed there (null otherwise).
    #[serde(rename = "I_f64")]
    i_f64: Option<f64>,
    #[serde(flatten)]
    envelope: ValueEnvelope,
    inputs: ShapeInputs<'a>,
}

pub fn run(args: &SmallAmplitudeArgs) -> Result<String, Failure> {
    let answer = coefficient_answer(&args.rho, &args.phi, args.answer.digits, args.answer.max_seconds)
        .map_err(|error| Failure::of(&error, false))?;
    if args.answer.json {
        let report = CoefficientReport {
            i: printed(&answer.value),
            i_f64: answer.value.binary64,
            envelope: ValueEnvelope::of(&answer),
            inputs: ShapeInputs {
                rho: &args.rho,
                phi: &args.phi,
            },
        };
        return Ok(serde_json::to_string(&report)?);
    }
    Ok(format!("I(ρ = {}, φ = {}) = {}", args.rho, args.phi, shown(&answer)))
}
