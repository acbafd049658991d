//! The checks against the independent history simulation (`crate::simulate`): the
//! four-segment W (claim 6c) and the coefficient I(ρ, φ) (claim 2c), computed by a
//! method that uses none of the segment formulas; and the [`Simulation`] evaluator, which
//! runs claims 3–5 with W from the simulation.

use std::fmt;

use super::evaluator::{tally_cases, ConstantSlope, Evaluator, Failure, Measured, Outcome, Source, Value};
use super::{describe, gross_slip_amplitude, random_case, read_case, Tally};
use crate::case::CaseText;
use crate::compliance::Compliance;
use crate::compliance::Polynomial;
use crate::cycle::LoadCycle;
use crate::dissipation::{dissipation, DissipationError, Options};
use crate::real::Precision;
use crate::simulate::{simulate, SimulationError, SimulationOptions, SimulationResult};
use crate::verify::generators::{shape, Draw};
use crate::verify::small_amplitude::coefficient;
use crate::verify::ClaimReport;

/// The agreement asked of the simulation at the gate's resolution (an identity between
/// two simulated values is held to `SIMULATED_IDENTITY_TOLERANCE`).
///
/// Above the simulation's error at the gate's resolution (100 elements and 300 steps per
/// cycle, extrapolated; measured in proofs/independent-simulation.md), and far below
/// what a wrong segment formula does to W (percents).
pub const SIMULATION_TOLERANCE: f64 = 1e-4;

/// An identity between simulated values, each within [`SIMULATION_TOLERANCE`] of its own.
pub const SIMULATED_IDENTITY_TOLERANCE: f64 = 3.0 * SIMULATION_TOLERANCE;

/// The largest P1/P0 simulated in claim 2c: the range of the simulation's own tests (and
/// of [`random_case`], which claim 6c draws).
pub const LARGEST_SIMULATED_AMPLITUDE: f64 = 0.9;

/// The note of a row whose every W comes from [`simulate_within_tolerance`].
fn refinement_note() -> String {
    format!("each simulation refined until its own estimate is within {SIMULATION_TOLERANCE:e}")
}

/// The simulation at 100 elements and 300 steps, refined (twice the elements and steps,
/// at most twice) while its own error estimate exceeds the tolerance: near in phase or
/// anti-phase with a small Q1/(fP1), W is small against the energies stored in the bed
/// and the coarse bed resolves it to only a few percent — and says so.
fn simulate_within_tolerance(
    cycle: &LoadCycle<f64>,
    compliance: &dyn Compliance<f64>,
) -> Result<SimulationResult, SimulationError> {
    let mut result = None;
    for scale in [1, 2, 4] {
        let options = SimulationOptions {
            elements: Some(100 * scale),
            steps: Some(300 * scale),
            ..SimulationOptions::default()
        };
        let simulated = simulate(cycle, compliance, &options)?;
        let settled = simulated.estimated_rel_error <= SIMULATION_TOLERANCE;
        result = Some(simulated);
        if settled {
            break;
        }
    }
    result.ok_or(SimulationError::Resolution { elements: 0, steps: 0 })
}

/// W by the history simulation (`simulate_within_tolerance`), in f64.
#[derive(Clone, Copy, Debug, Default)]
pub struct Simulation;

impl Evaluator for Simulation {
    type Number = f64;

    fn precision(&self) -> Precision {
        Precision::DOUBLE
    }

    fn source(&self) -> Source {
        Source::Simulation
    }

    fn identity_tolerance(&self) -> f64 {
        SIMULATED_IDENTITY_TOLERANCE
    }

    fn w(
        &self,
        cycle: &LoadCycle<f64>,
        compliance: &dyn Compliance<f64>,
        _: ConstantSlope,
    ) -> Result<Value<f64>, Failure> {
        match simulate_within_tolerance(cycle, compliance) {
            Ok(result) => Ok(Value {
                w: result.w_work,
                rounding: 0.0,
            }),
            Err(error) => Err(Failure::Failed(error.to_string())),
        }
    }

    fn note(&self, note: String) -> String {
        if note.is_empty() {
            refinement_note()
        } else {
            format!("{}; {note}", refinement_note())
        }
    }
}

/// A cycle and compliance for claim 6c, and how the simulated cycle departs from it: Q0
/// as a fraction of its margin (negative towards −fP0), and whether Q is reversed (φ + π).
#[derive(Clone, PartialEq)]
pub struct SimulatedHistoryCase {
    /// The cycle (Q0 = 0) and v' the four-segment W is computed for.
    pub case: CaseText,
    /// Q0 of the simulated cycle as a fraction of the gross-slip margin, in (−1, 1).
    pub q0_fraction: f64,
    /// Whether the simulated cycle has the phase φ + π.
    pub reverse: bool,
}

impl fmt::Display for SimulatedHistoryCase {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} simulated with Q0 at {} of its margin{}",
            describe(&self.case),
            self.q0_fraction,
            if self.reverse { ", φ+π" } else { "" }
        )
    }
}

/// Claim 6c for one case: the simulated W against the four-segment W. The figure is
/// (1 if the simulation had to be refined else 0, its own error estimate).
pub fn simulated_history_error(case: &SimulatedHistoryCase) -> Outcome {
    let (cycle, compliance) = read_case::<f64>(&case.case, Precision::DOUBLE)?;
    // Q0 inside the margins of the simulated cycle: −(fP0 − σ₊) < Q0 < fP0 − σ₋, with
    // σ₊ and σ₋ trading places when Q is reversed (φ + π).
    let (plus, minus) = cycle.slip_line_amplitudes();
    let (plus, minus) = if case.reverse { (minus, plus) } else { (plus, minus) };
    let room = cycle.friction * cycle.mean_normal_load;
    let fraction = case.q0_fraction;
    let q0 = if fraction >= 0.0 {
        fraction * (room - minus)
    } else {
        fraction * (room - plus)
    };
    let simulated_cycle = LoadCycle {
        mean_tangential_load: q0,
        phase: cycle.phase + if case.reverse { std::f64::consts::PI } else { 0.0 },
        ..cycle.clone()
    };
    let exact = match dissipation(&cycle, compliance.as_ref(), &Options::default()) {
        Ok(exact) => exact,
        Err(DissipationError::IllConditioned { .. }) => return Err(Failure::Unresolvable),
        Err(error) => return Err(Failure::Failed(error.to_string())),
    };
    let simulated = simulate_within_tolerance(&simulated_cycle, compliance.as_ref())
        .map_err(|error| Failure::Failed(format!("Q0={q0:.4e}: {error}")))?;
    Ok(Measured {
        error: (simulated.w_work - exact.total).abs() / exact.total.abs(),
        rounding: 0.0,
        figure: Some((
            f64::from(u8::from(simulated.elements > 400)),
            simulated.estimated_rel_error,
        )),
    })
}

/// Claim 6c: the simulation of the loading history agrees with the four-segment W, with
/// the simulated cycle given a random Q0 inside the gross-slip margin and, half of the
/// time, the phase φ + π — so that it also checks, independently of the segment code,
/// that W depends on neither.
pub fn simulation_agrees(seed: u64, cases: usize) -> ClaimReport {
    let mut tally = Tally::new(
        "6c simulated history (any Q0, φ or φ+π) gives the same W",
        Precision::DOUBLE,
        SIMULATION_TOLERANCE,
    );
    let figures = tally_cases(
        &mut tally,
        seed,
        cases,
        |draw| {
            let case = random_case(draw);
            let (q0_fraction, reverse) = (draw.uniform(-0.9, 0.9), draw.below(2) == 1);
            SimulatedHistoryCase {
                case,
                q0_fraction,
                reverse,
            }
        },
        simulated_history_error,
    );
    let refined = figures.iter().filter(|figure| figure.0 > 0.0).count();
    let mut estimates: Vec<f64> = figures.iter().map(|figure| figure.1).collect();
    let median = median(&mut estimates);
    tally.note(format!(
        "100 elements, 300 steps, extrapolated ({refined} refined to meet the tolerance); P1 ≤ {LARGEST_SIMULATED_AMPLITUDE} P0; median self-estimate of the simulation's error {median:.1e}"
    ))
}

/// Claim 2c: I(ρ, φ) agrees with the simulation. v' = 2 − (P − P0) is admissible
/// (v'' = −1) and W is linear in v' with the constant dissipating nothing, so its W is
/// exactly −λf²P1³ I(ρ, φ) at any amplitude: the simulated W gives I independently of the
/// segment formulas. Random ρ, φ, f, λ and P1 up to 0.9 of the gross-slip limit.
pub fn coefficient_against_simulation(seed: u64, cases: usize) -> ClaimReport {
    let precision = Precision::DOUBLE;
    let mut tally = Tally::new(
        "2c I(ρ,φ) = −W_sim[v' = 2 − (P − P0)]/(λf²P1³)",
        precision,
        SIMULATION_TOLERANCE,
    );
    let mut draw = Draw::new(seed);
    let linear = Polynomial {
        reference: 1.0,
        coefficients: vec![2.0, -1.0],
    };
    let mut refined = 0;
    for _ in 0..cases {
        let (rho, phase_fraction) = shape(&mut draw);
        let (f, lambda) = (draw.uniform(0.3, 2.0), draw.uniform(1.0, 1.5));
        let phi = phase_fraction * std::f64::consts::PI;
        // Q1 = ρfP1 < gross_slip_amplitude(P0, P1, φ, f) for P1 below the root of the
        // equality; bisection finds it.
        let inside = |p1: f64| rho * f * p1 < gross_slip_amplitude(1.0, p1, phi, f);
        let (mut low, mut high) = (0.0, LARGEST_SIMULATED_AMPLITUDE);
        if inside(high) {
            low = high;
        } else {
            for _ in 0..60 {
                let middle = 0.5 * (low + high);
                if inside(middle) {
                    low = middle;
                } else {
                    high = middle;
                }
            }
        }
        let p1 = draw.uniform(0.2, 0.9) * low;
        let label = format!("ρ={rho} φ={phase_fraction}π f={f} λ={lambda} P1={p1}");
        let cycle = LoadCycle {
            mean_normal_load: 1.0,
            normal_amplitude: p1,
            mean_tangential_load: 0.0,
            tangential_amplitude: rho * f * p1,
            phase: phi,
            friction: f,
            compliance_ratio: lambda,
        };
        match (coefficient(&rho, &phi), simulate_within_tolerance(&cycle, &linear)) {
            (Ok(expected), Ok(simulated)) => {
                refined += usize::from(simulated.elements > 400);
                let from_simulation = -simulated.w_work / (lambda * f * f * p1.powi(3));
                tally.record(((from_simulation - expected) / expected).abs(), &label);
            }
            (Err(e), _) => tally.fail(&label, e),
            (_, Err(e)) => tally.fail(&label, e),
        }
    }
    tally.note(format!(
        "100 elements, 300 steps, extrapolated ({refined} refined to meet the tolerance)"
    ))
}

fn median(values: &mut [f64]) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}
