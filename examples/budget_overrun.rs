//! How far the library itself overruns a verified-digits budget (the command line's
//! watchdogs cut a run at its budget regardless): `dissipation_answer::dissipation_report` at 1000
//! digits with budgets of 1 and 2 s, timed to its own answer. Figures in proofs/stability.md.

use std::time::{Duration, Instant};

use microslip::answer::dissipation::dissipation_report;
use microslip::case::CaseText;

fn main() {
    for (phase, compliance) in [("0.4pi", "persson:gamma=1,sigma=1"), ("0.3pi", "hertz:r=1,estar=1")] {
        let case = CaseText {
            p0: "1".into(),
            p1: "0.4".into(),
            q0: "0".into(),
            q1: "0.5".into(),
            phi: phase.into(),
            friction: "1".into(),
            lambda: Some("1".into()),
            nu: None,
            compliance: compliance.into(),
        };
        for budget in [1, 2] {
            let started = Instant::now();
            let outcome = dissipation_report(&case, Some(1000), Duration::from_secs(budget));
            let answer = match outcome {
                Ok(result) => format!("W = {}…", &result.total()[..12]),
                Err(error) => error.to_string(),
            };
            println!(
                "{compliance}, budget {budget} s: answered after {:.2} s: {answer}",
                started.elapsed().as_secs_f64()
            );
        }
    }
}
