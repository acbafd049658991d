//! `microslip verify`: the theorem gate as a table or JSON.

use std::time::Instant;

use clap::Args;

use microslip::verify::{self, GateOptions};

use super::case::Jobs;
use super::durations::VERIFY_QUICK;
use super::json::{ClaimRow, GateReport};
use super::parse;
use super::progress::Progress;
use super::report::Failure;

#[derive(Args)]
pub struct VerifyArgs {
    #[arg(long, help = format!("A smaller sample ({VERIFY_QUICK})"))]
    pub quick: bool,
    /// The seed of the random draws.
    #[arg(long, allow_hyphen_values = true, value_parser = parse::seed, default_value = "2026")]
    pub seed: u64,
    /// Print one JSON object.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub jobs: Jobs,
}

/// The working precision of a gate row (`f64` or `N bits`) in bits.
fn precision_bits(precision: &str) -> u32 {
    if precision == "f64" {
        return 53;
    }
    precision
        .split_whitespace()
        .next()
        .and_then(|bits| bits.parse().ok())
        .unwrap_or(0)
}

pub fn run(args: &VerifyArgs) -> Result<(String, bool), Failure> {
    let options = GateOptions {
        seed: args.seed,
        quick: args.quick,
    };
    let started = Instant::now();
    let progress = Progress::new(0);
    let reports = verify::run(options, |done, total, name| {
        progress.at_of(done, total, &format!("{name} done"));
    });
    progress.finish();
    let passed = reports.iter().all(|r| r.passed);
    let seconds = started.elapsed().as_secs_f64();
    if args.json {
        let report = GateReport {
            passed,
            seed: args.seed,
            quick: args.quick,
            seconds,
            claims: reports
                .iter()
                .map(|r| ClaimRow {
                    claim: &r.claim,
                    precision_bits: precision_bits(&r.precision),
                    cases: r.cases,
                    worst_error: r.worst_error,
                    tolerance: r.tolerance,
                    passed: r.passed,
                    proved: r.proved(),
                    proof: r.proof.filter(|_| r.proved()),
                    note: &r.note,
                })
                .collect(),
        };
        return Ok((serde_json::to_string(&report)?, passed));
    }
    let mut out = format!(
        "{:<62} {:<9} {:>6} {:>11} {:>9}  result\n",
        "claim", "precision", "cases", "worst", "tolerance"
    );
    for r in &reports {
        out.push_str(&format!(
            "{:<62} {:<9} {:>6} {:>11.3e} {:>9.0e}  {}\n",
            r.claim,
            r.precision,
            r.cases,
            r.worst_error,
            r.tolerance,
            if r.proved() {
                "proved"
            } else if r.passed {
                "sampled"
            } else {
                "FAIL"
            }
        ));
        if !r.note.is_empty() {
            out.push_str(&format!("    {}\n", r.note));
        }
    }
    out.push_str(&format!(
        "{} in {seconds:.1} s (seed {})",
        if passed { "all claims hold" } else { "SOME CLAIMS FAIL" },
        args.seed
    ));
    Ok((out, passed))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gate_precisions_read_as_bits() {
        assert_eq!(precision_bits("f64"), 53);
        assert_eq!(precision_bits("256 bits"), 256);
    }
}
