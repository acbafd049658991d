//! The proven default near separation, timed in process: `cargo run --release --example
//! near_separation_timing [ROUNDS]` prints, per case, the best of ROUNDS runs (default 20)
//! of W without a digit count (f64 intervals where they prove 12 digits, else the Arb
//! ladder) beside `--digits 15` (the Arb ladder alone, the default's fallback), with the
//! arithmetic and digits of each. Cases: P0 = 1, P0 − P1 = δ = 1e-3, 1e-6, 1e-9 with
//! Q1 = 0.1·√(2δ) at φ = π/2, and δ = 1e-6 with Q1 = 5e-7 at φ = 0.4π, for Persson,
//! the power law −1.5 and Hertz.

use std::time::{Duration, Instant};

use microslip::answer::dissipation::dissipation_of;
use microslip::case::{CaseSpec, CaseText};

const FAMILIES: [&str; 3] = ["persson:gamma=1,sigma=1", "power:c=1,beta=-1.5", "hertz:r=1,estar=1"];

/// P0 = 1, Q0 = 0, f = λ = 1, with the rest given.
fn case(p1: &str, q1: &str, phi: &str, compliance: &str) -> CaseSpec {
    let unit_loads = CaseText::builder().p0(1).friction(1).lambda(1);
    let cycle = unit_loads.p1(p1).q1(q1).phi(phi);
    cycle.compliance(compliance).build().expect("a case inside the theory")
}

/// The best time of `rounds` runs, with the arithmetic and digits of the last.
fn best_of(rounds: usize, case: &CaseSpec, digits: Option<u32>) -> (Duration, String) {
    let budget = Duration::from_secs(60);
    let mut best = Duration::MAX;
    let mut last = String::new();
    for _ in 0..rounds {
        let start = Instant::now();
        let answer = dissipation_of(case, digits, budget).expect("W").answer;
        best = best.min(start.elapsed());
        last = format!("{} digits, {}", answer.value.digits(), answer.provenance);
    }
    (best, last)
}

fn main() {
    let rounds = std::env::args().nth(1).and_then(|n| n.parse().ok()).unwrap_or(20);
    let mut cases = vec![];
    for (gap, p1) in [("1e-3", "0.999"), ("1e-6", "0.999999"), ("1e-9", "0.999999999")] {
        let q1 = format!("{:.3e}", 0.1 * (2.0 * gap.parse::<f64>().unwrap()).sqrt());
        cases.push((gap, p1, q1, "0.5pi"));
    }
    cases.push(("1e-6", "0.999999", "5e-7".to_string(), "0.4pi"));
    for (gap, p1, q1, phi) in &cases {
        for family in FAMILIES {
            let spec = case(p1, q1, phi, family);
            let (default, how) = best_of(rounds, &spec, None);
            let (arb, _) = best_of(rounds, &spec, Some(15));
            println!(
                "δ = {gap:5}  Q1 = {q1:9}  φ = {phi:5}  {family:24}  default {:8.3} ms ({how})  --digits 15 {:8.3} ms",
                default.as_secs_f64() * 1e3,
                arb.as_secs_f64() * 1e3,
            );
        }
    }
}
