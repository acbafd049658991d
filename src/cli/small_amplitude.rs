//! `microslip small-amplitude`: the coefficient I(ρ, φ).

use clap::Args;
use serde::Serialize;

use microslip::exact::printing::coefficient_answer;

use super::case::Answer;
use super::report::Failure;
use super::series::{failure, shown, ValueReport};

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

/// ρ and φ as given.
#[derive(Serialize)]
struct ShapeInputs<'a> {
    rho: &'a str,
    phi: &'a str,
}

/// `microslip small-amplitude --json`.
#[derive(Serialize)]
struct CoefficientReport<'a> {
    #[serde(rename = "I")]
    i: String,
    /// I in binary64 where it is representable there (null otherwise).
    #[serde(rename = "I_f64")]
    i_f64: Option<f64>,
    digits: u32,
    /// The digits printed, each vouched for (proven unless `provenance` says `agreement`).
    digits_verified: u32,
    digits_certified: u32,
    enclosure: Option<(String, String)>,
    provenance: &'static str,
    /// The working precision of the enclosure (null for an exact value).
    precision_bits: Option<u32>,
    /// Why I is exactly the 0 printed, where it is.
    #[serde(skip_serializing_if = "Option::is_none")]
    exact: Option<&'static str>,
    inputs: ShapeInputs<'a>,
}

pub fn run(args: &SmallAmplitudeArgs) -> Result<String, Failure> {
    let answer =
        coefficient_answer(&args.rho, &args.phi, args.answer.digits, args.answer.max_seconds).map_err(failure)?;
    if args.answer.json {
        let value = ValueReport::of(&answer);
        let report = CoefficientReport {
            i: value.value,
            i_f64: value.f64,
            digits: value.digits,
            digits_verified: value.digits,
            digits_certified: value.digits_certified,
            enclosure: value.enclosure,
            provenance: value.provenance,
            precision_bits: answer.provenance.precision_bits(),
            exact: value.exact,
            inputs: ShapeInputs {
                rho: &args.rho,
                phi: &args.phi,
            },
        };
        return Ok(serde_json::to_string(&report)?);
    }
    Ok(format!("I(ρ = {}, φ = {}) = {}", args.rho, args.phi, shown(&answer)))
}
