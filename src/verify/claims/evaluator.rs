//! How a claim computes W: by the four-segment integrals at a precision, or by the
//! independent history simulation (which uses none of the segment formulas; its
//! evaluator lives with it, in `simulation.rs`). A claim is written once, as a check of
//! one case through an [`Evaluator`], and the gate runs it with each evaluator;
//! [`check_claim`] is the one loop over drawn cases.

use std::fmt;
use std::marker::PhantomData;

use super::{identity_tolerance, number, relative_estimate, unresolvable, Tally};
use crate::compliance::Compliance;
use crate::cycle::LoadCycle;
use crate::dissipation::{dissipation, Options};
use crate::real::{Precision, Real};
use crate::verify::generators::Draw;
use crate::verify::ClaimReport;

/// A W and how far rounding alone may have moved it.
#[derive(Clone, Debug)]
pub struct Value<R> {
    /// W.
    pub w: R,
    /// The relative error rounding may leave in `w`: an identity whose tolerance this
    /// exceeds cannot be told apart at the precision (0 for the simulation, whose
    /// tolerance already allows for its discretisation).
    pub rounding: f64,
}

/// Why a case has no result.
#[derive(Clone, Debug, PartialEq)]
pub enum Failure {
    /// The precision cannot resolve the case (the computation says it is ill-conditioned):
    /// left out, not failed.
    Unresolvable,
    /// The computation failed: the claim fails.
    Failed(String),
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Failure::Unresolvable => f.write_str("not resolvable at this precision"),
            Failure::Failed(why) => f.write_str(why),
        }
    }
}

/// One case checked: its error against the claim and the rounding its computations allow.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Measured {
    /// The error against the claim (relative unless the claim says otherwise).
    pub error: f64,
    /// The sum of the relative rounding errors of the values the error compares.
    pub rounding: f64,
    /// A figure the claim's note reports (the one of largest magnitude over the cases is
    /// kept): a parameter and what was measured at it.
    pub figure: Option<(f64, f64)>,
}

/// A case's outcome.
pub type Outcome = Result<Measured, Failure>;

/// Where an evaluator's W comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    /// The four-segment integrals.
    Segments,
    /// The history simulation, which uses none of the segment formulas.
    Simulation,
}

/// Whether W is computed of v' as given or of v' less its constant slope (a constant in v'
/// contributes nothing to W, claim 3, and removing it first spares the integrals from
/// cancelling it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConstantSlope {
    /// v' integrated as given: the segment formulas must cancel a constant themselves.
    Kept,
    /// The constant slope removed before integrating.
    Removed,
}

/// A way of computing W for a cycle and a compliance.
pub trait Evaluator {
    /// The number type it computes in.
    type Number: Real;

    /// Its working precision.
    fn precision(&self) -> Precision;

    /// Where its W comes from.
    fn source(&self) -> Source;

    /// Whether W comes from the history simulation rather than the segment formulas.
    fn simulated(&self) -> bool {
        self.source() == Source::Simulation
    }

    /// The largest relative error allowed in an identity between its W values.
    fn identity_tolerance(&self) -> f64;

    /// W of `compliance` over `cycle`, its constant slope kept or removed first.
    fn w(
        &self,
        cycle: &LoadCycle<Self::Number>,
        compliance: &dyn Compliance<Self::Number>,
        constant: ConstantSlope,
    ) -> Result<Value<Self::Number>, Failure>;

    /// A drawn number at the working precision.
    fn number(&self, value: f64) -> Self::Number {
        number(value, self.precision())
    }

    /// What the report says about the evaluator, after the claim's own `note`.
    fn note(&self, note: String) -> String;
}

/// W by the four-segment integrals in `R` at a precision.
#[derive(Clone, Copy, Debug)]
pub struct FourSegment<R> {
    precision: Precision,
    number: PhantomData<fn() -> R>,
}

impl<R: Real> FourSegment<R> {
    /// The integrals at `precision`.
    pub fn new(precision: Precision) -> Self {
        FourSegment {
            precision,
            number: PhantomData,
        }
    }
}

impl<R: Real> Evaluator for FourSegment<R> {
    type Number = R;

    fn precision(&self) -> Precision {
        self.precision
    }

    fn source(&self) -> Source {
        Source::Segments
    }

    fn identity_tolerance(&self) -> f64 {
        identity_tolerance(self.precision)
    }

    fn w(
        &self,
        cycle: &LoadCycle<R>,
        compliance: &dyn Compliance<R>,
        constant: ConstantSlope,
    ) -> Result<Value<R>, Failure> {
        // The drawn compliances are admissible by construction; some identities evaluate
        // them a little beyond the loads they were drawn for.
        let options = Options {
            check_compliance: false,
            remove_constant_slope: constant == ConstantSlope::Removed,
            ..Options::default()
        };
        match dissipation(cycle, compliance, &options) {
            Ok(result) => Ok(Value {
                rounding: relative_estimate(&result),
                w: result.total,
            }),
            Err(error) if unresolvable(&error) => Err(Failure::Unresolvable),
            Err(error) => Err(Failure::Failed(error.to_string())),
        }
    }

    fn note(&self, note: String) -> String {
        note
    }
}

/// Several W of one case, or why not: the first failure, unless some computation only
/// says the precision cannot resolve the case.
pub fn all_of<R, const N: usize>(values: [Result<Value<R>, Failure>; N]) -> Result<[Value<R>; N], Failure> {
    if values.iter().any(|value| matches!(value, Err(Failure::Unresolvable))) {
        return Err(Failure::Unresolvable);
    }
    let mut found = Vec::with_capacity(N);
    for value in values {
        found.push(value?);
    }
    Ok(found
        .try_into()
        .unwrap_or_else(|_| unreachable!("N values were pushed")))
}

/// A claim about W checked one case at a time through any evaluator.
pub trait Claim {
    /// What one case draws: printed readably, for reports and shrunk property tests.
    type Case: fmt::Display;

    /// The claim as the gate's row names it.
    const NAME: &'static str;

    /// The row's name when W comes from the history simulation.
    const SIMULATED_NAME: &'static str = Self::NAME;

    /// The largest error allowed with `evaluator`.
    fn tolerance<E: Evaluator>(&self, evaluator: &E) -> f64 {
        evaluator.identity_tolerance()
    }

    /// A random case for `evaluator` from the gate's seeded draw.
    fn draw<E: Evaluator>(&self, draw: &mut Draw, evaluator: &E) -> Self::Case;

    /// The case computed with `evaluator` and measured against the claim.
    fn check<E: Evaluator>(&self, evaluator: &E, case: &Self::Case) -> Outcome;

    /// The row's note (a measured figure), given the figure of largest magnitude.
    fn note<E: Evaluator>(&self, evaluator: &E, figure: Option<(f64, f64)>) -> String;
}

/// `claim` over `cases` draws from `seed`, computed with `evaluator`.
pub fn check_claim<C: Claim, E: Evaluator>(claim: &C, evaluator: &E, seed: u64, cases: usize) -> ClaimReport {
    let mut tally = Tally::new(
        if evaluator.simulated() {
            C::SIMULATED_NAME
        } else {
            C::NAME
        },
        evaluator.precision(),
        claim.tolerance(evaluator),
    );
    let figures = tally_cases(
        &mut tally,
        seed,
        cases,
        |draw| claim.draw(draw, evaluator),
        |case| claim.check(evaluator, case),
    );
    let largest = figures
        .into_iter()
        .fold(None, |worst: Option<(f64, f64)>, figure| match worst {
            Some(worst) if figure.1.abs() <= worst.1.abs() => Some(worst),
            _ => Some(figure),
        });
    tally.note(evaluator.note(claim.note(evaluator, largest)))
}

/// The one loop over random cases: `cases` cases drawn from `seed`, each checked and
/// tallied (a failure fails the claim, an unresolvable case is left out). Returns the
/// figures the checks measured, in order.
pub(super) fn tally_cases<C: fmt::Display>(
    tally: &mut Tally,
    seed: u64,
    cases: usize,
    mut draw_case: impl FnMut(&mut Draw) -> C,
    mut check: impl FnMut(&C) -> Outcome,
) -> Vec<(f64, f64)> {
    let mut draw = Draw::new(seed);
    let mut figures = Vec::new();
    for _ in 0..cases {
        let case = draw_case(&mut draw);
        match check(&case) {
            Ok(measured) => {
                figures.extend(measured.figure);
                tally.record_resolved(measured.error, &[measured.rounding], &case.to_string());
            }
            Err(Failure::Unresolvable) => tally.unresolved(),
            Err(Failure::Failed(why)) => tally.fail(&case.to_string(), why),
        }
    }
    figures
}
