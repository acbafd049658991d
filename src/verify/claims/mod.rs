//! The claims of the theorem gate, each checked over random draws.
//!
//! Every row draws its cases from a seed, computes, and returns a
//! [`ClaimReport`]: how many cases, the worst error against the claim, the
//! tolerance, and whether all passed. A computation that fails counts as a failure.
//! Claims 1 and 3–6 check one case at a time (a [`Claim`], or a function of the case), so the
//! property tests can run the same check on shrinking cases; claims 3–5 compute W through
//! an [`Evaluator`], the segment formulas or the history simulation. One file per claim;
//! what they share (the tally, the random cycle) is here, the evaluators and the loop over
//! cases in `evaluator.rs` (the simulated one beside the simulation, in `simulation.rs`).

mod coefficient;
#[cfg(feature = "certified")]
pub mod coefficient_proof;
mod constant_term;
mod cubic_law;
#[cfg(feature = "certified")]
mod cubic_law_remainder;
#[cfg(feature = "certified")]
mod derivations;
mod evaluator;
mod exact;
mod invariants;
mod linearity;
mod roughness;
mod simulation;

pub use coefficient::small_amplitude_coefficient;
#[cfg(feature = "certified")]
pub use coefficient_proof::coefficient_is_negative;
pub use constant_term::ConstantTerm;
pub use cubic_law::{cubic_law, cubic_law_order, least_squares_slope, CubicLawCase};
#[cfg(feature = "certified")]
pub use cubic_law_remainder::{completely_monotone_bracket, cubic_law_proved, cubic_law_remainder};
#[cfg(feature = "certified")]
pub use derivations::{constant_term_proved, linearity_proved, roughness_proved};
pub use evaluator::{
    check_claim, Claim, ConstantSlope, Evaluator, Failure, FourSegment, Measured, Outcome, Source, Value,
};
pub use exact::{closed_form_coefficient_claim, polynomial_dissipation_claim, series_claim};
pub use invariants::{in_phase_limit, in_phase_limit_error, mean_tangential_margin, Invariants};
pub use linearity::{second_compliance_loads, Linearity, LinearityCase};
pub use roughness::{Roughness, RoughnessCase};
pub use simulation::{
    coefficient_against_simulation, simulated_history_error, simulation_agrees, SimulatedHistoryCase, Simulation,
    SIMULATION_TOLERANCE,
};

pub use super::generators::gross_slip_amplitude;
use super::generators::{compliance_spec, cycle_case, Draw, CYCLE};
use super::ClaimReport;
#[cfg(feature = "certified")]
use super::Proof;
use crate::case::CaseText;
use crate::compliance::Compliance;
use crate::cycle::LoadCycle;
use crate::dissipation::{Dissipation, DissipationError};
use crate::real::{Precision, Real};

/// Debug as Display: proptest prints a failing case as the gate reports it.
macro_rules! debug_as_display {
    ($($case:ty),+) => {$(
        impl std::fmt::Debug for $case {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                std::fmt::Display::fmt(self, f)
            }
        }
    )+};
}

debug_as_display!(
    CubicLawCase,
    CaseWith,
    LinearityCase,
    RoughnessCase,
    SimulatedHistoryCase,
    Drawn
);

/// The tolerance on a relative identity at a precision: 1e−12 in f64, 1e−70 at 256 bits.
fn identity_tolerance(precision: Precision) -> f64 {
    if precision <= Precision::DOUBLE {
        1e-12
    } else {
        1e-70
    }
}

fn precision_name(precision: Precision) -> String {
    if precision == Precision::DOUBLE {
        "f64".to_string()
    } else {
        format!("{} bits", precision.in_bits())
    }
}

/// Accumulates the worst error over cases and remembers the first failure.
struct Tally {
    report: ClaimReport,
    /// Draws left out because the computations' own error estimates exceed what the
    /// tolerance could tell apart (W a small difference of large terms in f64, say).
    unresolved: usize,
}

impl Tally {
    fn new(claim: &str, precision: Precision, tolerance: f64) -> Self {
        Tally {
            report: ClaimReport {
                claim: claim.to_string(),
                precision: precision_name(precision),
                cases: 0,
                worst_error: 0.0,
                tolerance,
                passed: true,
                note: String::new(),
                proof: None,
            },
            unresolved: 0,
        }
    }

    /// Records a case whose computations carry relative error estimates `estimates`:
    /// when they add up to more than the tolerance, the identity cannot be told apart from
    /// rounding at this precision, and the draw is counted as unresolved instead (the
    /// 256-bit row checks such draws). The estimates bound the errors (proofs/stability.md).
    fn record_resolved(&mut self, error: f64, estimates: &[f64], case: &str) {
        let estimated: f64 = estimates.iter().sum();
        if estimated > self.report.tolerance {
            self.unresolved += 1;
        } else {
            self.record(error, case);
        }
    }

    /// One case with its error against the claim (NaN counts as a failure).
    fn record(&mut self, error: f64, case: &str) {
        let report = &mut self.report;
        report.cases += 1;
        let error = if error.is_nan() { f64::INFINITY } else { error };
        if error > report.worst_error {
            report.worst_error = error;
        }
        if error > report.tolerance && report.passed {
            report.passed = false;
            report.note = format!("first failure: {case} (error {error:.3e})");
        }
    }

    /// A draw the precision cannot resolve (see [`Tally::record_resolved`]).
    fn unresolved(&mut self) {
        self.unresolved += 1;
    }

    /// One case whose computation failed.
    fn fail(&mut self, case: &str, why: impl std::fmt::Display) {
        self.report.cases += 1;
        self.report.worst_error = f64::INFINITY;
        if self.report.passed {
            self.report.passed = false;
            self.report.note = format!("{case}: {why}");
        }
    }

    /// The report of a claim proved by the derivation in `document`, marked proved once its
    /// checks passed, with `note` as its measured figure.
    #[cfg(feature = "certified")]
    fn proved_by(self, document: &'static str, note: impl Into<String>) -> ClaimReport {
        let mut report = self.note(note);
        if report.passed {
            report.proof = Some(Proof::Derivation { document });
        }
        report
    }

    /// The report, with `note` as its measured figure unless a failure is noted.
    fn note(mut self, note: impl Into<String>) -> ClaimReport {
        if self.report.passed {
            self.report.note = note.into();
            if self.unresolved > 0 {
                let joint = if self.report.note.is_empty() { "" } else { "; " };
                self.report.note += &format!(
                    "{joint}{} draws left out: their own error estimates exceed the tolerance",
                    self.unresolved
                );
            }
        }
        self.report
    }
}

/// A result's error estimate relative to its value (infinite for an estimate on a zero W).
fn relative_estimate<R: Real>(result: &Dissipation<R>) -> f64 {
    let (value, estimate) = (result.total.abs().to_f64_lossy(), result.error_estimate.to_f64_lossy());
    if estimate == 0.0 {
        0.0
    } else {
        estimate / value
    }
}

/// Whether a failed computation only says the precision cannot resolve the case.
fn unresolvable(error: &DissipationError) -> bool {
    matches!(error, DissipationError::IllConditioned { .. })
}

/// |a − b| / |b| in f64 terms (|a − b| when b is 0).
fn relative<R: Real>(a: &R, b: &R) -> f64 {
    let difference = (a.clone() - b).abs();
    if b.abs() > b.int(0) {
        (difference / b.abs()).to_f64_lossy()
    } else {
        difference.to_f64_lossy()
    }
}

/// A drawn number at a precision (drawn numbers print exactly as decimals).
fn number<R: Real>(value: f64, precision: Precision) -> R {
    R::parse_decimal(&value.to_string(), precision).unwrap_or_else(|_| R::from_f64(value, precision))
}

/// A random cycle inside the theory: P0 = 1, P1/P0 ∈ (0.05, 0.9), φ ∈ (0, π), Q1 a
/// random fraction of the largest amplitude the friction cone allows, and a
/// compliance admissible over the loads the cycle reaches.
pub fn random_case(draw: &mut Draw) -> CaseText {
    let values = draw.parameters(&CYCLE);
    cycle_case(&values, |loads| {
        compliance_spec(draw, loads.low, loads.high, loads.mean)
    })
}

/// The case at the precision its claim is evaluated in (each draw is evaluated at one).
fn read<R: Real>(case: &CaseText, precision: Precision) -> Option<(LoadCycle<R>, Box<dyn Compliance<R>>)> {
    let case = case.spec().ok()?.at::<R>(precision).ok()?;
    Some((case.cycle, case.compliance))
}

/// A case read at a precision: its cycle and compliance.
type ReadCase<R> = (LoadCycle<R>, Box<dyn Compliance<R>>);

/// The case read at a precision, or a failure saying it did not read.
fn read_case<R: Real>(case: &CaseText, precision: Precision) -> Result<ReadCase<R>, Failure> {
    read(case, precision).ok_or_else(|| Failure::Failed("case did not read".into()))
}

/// A drawn cycle and compliance, printed as a report prints them ([`describe`]).
#[derive(Clone, PartialEq)]
pub struct Drawn(pub CaseText);

/// A drawn case and one more drawn number its claim needs (the constant c added to v' in
/// claim 3, another Q0 in claim 6a).
#[derive(Clone, PartialEq)]
pub struct CaseWith {
    /// The cycle and v'.
    pub case: CaseText,
    /// The number's symbol, as the report prints it.
    pub symbol: &'static str,
    /// The number.
    pub value: f64,
}

impl std::fmt::Display for CaseWith {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} {}={}", describe(&self.case), self.symbol, self.value)
    }
}

impl std::fmt::Display for Drawn {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&describe(&self.0))
    }
}

/// A case as a report prints it: the loads, f, λ and the compliance SPEC.
pub fn describe(case: &CaseText) -> String {
    format!(
        "P1={} Q0={} Q1={} φ={} f={} λ={} v'={}",
        case.p1,
        case.q0,
        case.q1,
        case.phi,
        case.friction,
        case.lambda.as_deref().unwrap_or("?"),
        case.compliance
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_claim_fails_on_an_error_beyond_its_tolerance_a_nan_or_a_failed_computation() {
        let mut tally = Tally::new("x", Precision::DOUBLE, 1e-12);
        tally.record(1e-13, "fine");
        assert!(tally.report.passed);
        tally.record(2e-12, "too far");
        let report = tally.note("measured");
        assert!(!report.passed && report.note.contains("too far"), "{report:?}");
        let mut tally = Tally::new("x", Precision::bits(256), 1e-70);
        tally.record(f64::NAN, "nan");
        assert!(!tally.report.passed && tally.report.worst_error == f64::INFINITY);
        let mut tally = Tally::new("x", Precision::DOUBLE, 1.0);
        tally.fail("case", "did not converge");
        assert!(!tally.report.passed && tally.report.cases == 1);
        assert_eq!(tally.note("ignored").note, "case: did not converge");
    }

    #[test]
    fn draws_beyond_the_precisions_resolution_are_left_out_and_counted_not_passed_or_failed() {
        let mut tally = Tally::new("x", Precision::DOUBLE, 1e-12);
        // An identity error of 5e-12 whose computations say they may be off by 6e-12: unresolved.
        tally.record_resolved(5e-12, &[3e-12, 3e-12], "rounding-bound");
        tally.record_resolved(1e-13, &[1e-14], "resolved");
        let ill = DissipationError::IllConditioned {
            bits: 53,
            cause: "Q1 = fP1/1e4".to_string(),
            expected: 3e-11,
            limit: 1e-12,
        };
        assert!(unresolvable(&ill));
        tally.unresolved();
        let report = tally.note("measured");
        assert!(
            report.passed && report.cases == 1 && report.worst_error == 1e-13,
            "{report:?}"
        );
        assert!(report.note.contains("2 draws left out"), "{report:?}");
        // An unresolved draw does not hide a real failure.
        let mut tally = Tally::new("x", Precision::DOUBLE, 1e-12);
        tally.record_resolved(1e-9, &[1e-14], "wrong");
        let stalled = DissipationError::NotConverged {
            points: 512,
            relative_error: 1e-9,
            requested: 1e-14,
        };
        assert!(!unresolvable(&stalled));
        tally.fail("stalled", stalled);
        assert!(!tally.report.passed && tally.report.note.contains("wrong"));
    }
}
