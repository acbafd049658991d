//! The theorem gate: the claims of the paper (Sections 5.1–5.2) and the
//! invariants of the construction, checked over seeded random draws of compliance
//! functions and cycles, in f64 and at 256 bits. `microslip verify` runs it and
//! fails when any claim fails; the property tests in `tests/theorems.rs` run the
//! same checks with fixed seeds.

pub mod claims;
pub mod generators;
pub mod small_amplitude;

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;

use rug::Float;
use serde::Serialize;

use crate::real::Precision;
use claims::{Claim, FourSegment, Simulation};

/// The outcome of one claim at one precision.
#[derive(Clone, Debug, Serialize)]
pub struct ClaimReport {
    /// The claim, numbered as in proofs/README.md.
    pub claim: String,
    /// `f64` or `N bits`.
    pub precision: String,
    /// Cases checked.
    pub cases: usize,
    /// The worst error against the claim (relative, or |order − 1| for the cubic law).
    pub worst_error: f64,
    /// The largest error allowed.
    pub tolerance: f64,
    /// Whether every case passed.
    pub passed: bool,
    /// What was found: the first failure, or a measured figure.
    pub note: String,
}

/// How much of the gate to run.
#[derive(Clone, Copy, Debug)]
pub struct GateOptions {
    /// The seed every draw derives from.
    pub seed: u64,
    /// A smaller sample (under 10 s on 2 cores).
    pub quick: bool,
}

/// One step of the gate: a name for progress, and the check that produces its reports.
pub type GateStep = (&'static str, Box<dyn Fn() -> Vec<ClaimReport> + Send + Sync>);

/// The steps in claim order (independent of each other, so they may run in parallel).
pub fn gate(options: GateOptions) -> Vec<GateStep> {
    let GateOptions { seed, quick } = options;
    let n = move |quick_cases: usize, full_cases: usize| if quick { quick_cases } else { full_cases };
    let wide = Precision::bits(256);
    vec![
        ("cubic law", Box::new(move || vec![claims::cubic_law(seed, n(3, 60))])),
        (
            "small-amplitude coefficient",
            Box::new(move || {
                let (homogeneous, in_phase) = claims::small_amplitude_coefficient(seed + 1, n(4, 100));
                vec![homogeneous, in_phase]
            }),
        ),
        (
            "coefficient against the simulation",
            Box::new(move || vec![claims::coefficient_against_simulation(seed + 9, n(4, 30))]),
        ),
        (
            "constant term",
            Box::new(move || {
                twins(
                    &claims::ConstantTerm,
                    [seed + 2, seed + 3, seed + 13],
                    [n(40, 1000), n(3, 40), n(2, 10)],
                )
            }),
        ),
        (
            "linearity",
            Box::new(move || {
                twins(
                    &claims::Linearity,
                    [seed + 4, seed + 5, seed + 14],
                    [n(40, 1000), n(3, 40), n(2, 10)],
                )
            }),
        ),
        (
            "roughness",
            Box::new(move || {
                twins(
                    &claims::Roughness,
                    [seed + 6, seed + 7, seed + 15],
                    [n(40, 1000), n(2, 30), n(2, 10)],
                )
            }),
        ),
        (
            "invariants",
            Box::new(move || {
                vec![
                    claims::check_claim(
                        &claims::Invariants,
                        &FourSegment::<f64>::new(Precision::DOUBLE),
                        seed + 8,
                        n(40, 1000),
                    ),
                    claims::check_claim(
                        &claims::Invariants,
                        &FourSegment::<Float>::new(wide),
                        seed + 10,
                        n(2, 30),
                    ),
                ]
            }),
        ),
        (
            "in-phase limit",
            Box::new(move || vec![claims::in_phase_limit(seed + 11, n(40, 1000))]),
        ),
        (
            "simulation",
            Box::new(move || vec![claims::simulation_agrees(seed + 12, n(6, 60))]),
        ),
        (
            "exact methods",
            Box::new(move || {
                vec![
                    claims::closed_form_coefficient_claim(seed + 16, n(6, 60)),
                    claims::polynomial_dissipation_claim(seed + 17, n(3, 30)),
                    claims::series_claim(seed + 18, n(4, 20)),
                ]
            }),
        ),
    ]
}

/// A claim checked with each evaluator, `cases[i]` draws from `seeds[i]`: the segment
/// formulas in f64 and at 256 bits, and the history simulation.
fn twins<C: Claim>(claim: &C, seeds: [u64; 3], cases: [usize; 3]) -> Vec<ClaimReport> {
    vec![
        claims::check_claim(claim, &FourSegment::<f64>::new(Precision::DOUBLE), seeds[0], cases[0]),
        claims::check_claim(
            claim,
            &FourSegment::<Float>::new(Precision::bits(256)),
            seeds[1],
            cases[1],
        ),
        claims::check_claim(claim, &Simulation, seeds[2], cases[2]),
    ]
}

/// Runs the whole gate on every core, and returns the reports in claim order;
/// `progress(done, total, name)` is told each step's name as it finishes.
pub fn run(options: GateOptions, mut progress: impl FnMut(usize, usize, &str)) -> Vec<ClaimReport> {
    let steps = gate(options);
    let total = steps.len();
    let workers = std::thread::available_parallelism().map_or(1, usize::from).min(total);
    let next = AtomicUsize::new(0);
    let (sender, receiver) = mpsc::channel();
    let mut results: Vec<Option<Vec<ClaimReport>>> = vec![None; total];
    std::thread::scope(|scope| {
        for _ in 0..workers {
            let (sender, steps, next) = (sender.clone(), &steps, &next);
            scope.spawn(move || loop {
                let index = next.fetch_add(1, Ordering::Relaxed);
                let Some((_, check)) = steps.get(index) else {
                    break;
                };
                if sender.send((index, check())).is_err() {
                    break;
                }
            });
        }
        drop(sender);
        for (done, (index, reports)) in receiver.iter().enumerate() {
            progress(done + 1, total, steps[index].0);
            results[index] = Some(reports);
        }
    });
    results.into_iter().flatten().flatten().collect()
}
