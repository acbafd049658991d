//! Claim 3: the constant term of v' contributes nothing.

use super::evaluator::{all_of, Claim, ConstantSlope, Evaluator, Measured, Outcome, Value};
use super::{random_case, read_case, CaseWith};
use crate::compliance::{Compliance, Polynomial, Shifted};
use crate::cycle::LoadCycle;
use crate::real::{Precision, Real};
use crate::verify::generators::Draw;

/// Claim 3, the constant term: W[v' + c] = W[v'] for any c, and W\[c\] = 0, through the
/// raw segment formulas (v' itself integrated, not v' − v'(P0)). In f64 the identity holds
/// to 1e−13 of the terms that cancel; at 256 bits to 1e−70 of W. In the simulated spring
/// bed a constant added to v' changes every element's stiffness (K = 1/v' is not linear
/// in v'), so there W_sim[v' + c] = W_sim[v'] is a consequence of the physics, not of the
/// segment formulas.
#[derive(Clone, Copy, Debug, Default)]
pub struct ConstantTerm;

/// The largest constant drawn: the coarse spring bed resolves W[v' + c] to its tolerance
/// for c up to 3 (v' itself is at most a few).
fn largest_constant<E: Evaluator>(evaluator: &E) -> f64 {
    if evaluator.simulated() {
        3.0
    } else {
        10.0
    }
}

/// 2πλ Q1 (Q1 + f P1) (max v' + c): a bound on ∫|(Q − Q0) du/dθ| dθ, the size of the terms
/// the raw segment formulas cancel — what "to working precision" means in f64.
fn cancelling_terms<R: Real>(cycle: &LoadCycle<R>, shifted: &dyn Compliance<R>, shift: &R, precision: Precision) -> R {
    let top = cycle.mean_normal_load.clone() - &cycle.normal_amplitude;
    let low = top.min_of(&cycle.permanent_stick_load());
    let steepest = shifted
        .slope(&low)
        .max_of(&shifted.slope(&(cycle.mean_normal_load.clone() * &top.int(2))));
    cycle.compliance_ratio.clone()
        * &cycle.tangential_amplitude
        * &(cycle.tangential_amplitude.clone() + &(cycle.friction.clone() * &cycle.normal_amplitude))
        * &steepest
        * &(R::pi(precision) * &shift.int(2))
}

impl Claim for ConstantTerm {
    type Case = CaseWith;

    const NAME: &'static str = "3 constant term: W[v' + c] = W[v'], W[c] = 0";
    const SIMULATED_NAME: &'static str = "3 constant term, simulated: W_sim[v' + c] = W_sim[v']";

    fn tolerance<E: Evaluator>(&self, evaluator: &E) -> f64 {
        match evaluator.precision() {
            _ if evaluator.simulated() => evaluator.identity_tolerance(),
            precision if precision <= Precision::DOUBLE => 1e-13,
            _ => 1e-70,
        }
    }

    fn draw<E: Evaluator>(&self, draw: &mut Draw, evaluator: &E) -> CaseWith {
        let case = random_case(draw);
        let constant = draw.uniform(0.1, largest_constant(evaluator));
        CaseWith {
            case,
            symbol: "c",
            value: constant,
        }
    }

    fn check<E: Evaluator>(&self, evaluator: &E, case: &CaseWith) -> Outcome {
        let precision = evaluator.precision();
        let (cycle, compliance) = read_case::<E::Number>(&case.case, precision)?;
        let shift = evaluator.number(case.value);
        let shifted = Shifted {
            extra_slope: shift.clone(),
            inner: compliance,
        };
        // W[c] = 0 is asked of the segment formulas only (the simulated row claims the shift).
        let constant = Polynomial {
            reference: shift.int(0),
            coefficients: vec![shift.clone()],
        };
        let only_constant = if evaluator.simulated() {
            Ok(Value {
                w: shift.int(0),
                rounding: 0.0,
            })
        } else {
            evaluator.w(&cycle, &constant, ConstantSlope::Kept)
        };
        // Raw values of either sign, without the non-negativity guard: a W that vanishes
        // in exact arithmetic is rounding noise here, which is what is measured.
        let [base, with_constant, only_constant] = all_of([
            evaluator.w(&cycle, shifted.inner.as_ref(), ConstantSlope::Kept),
            evaluator.w(&cycle, &shifted, ConstantSlope::Kept),
            only_constant,
        ])?;
        // In f64 the segment formulas are held to the size of the terms that cancel;
        // otherwise the difference is relative to W itself.
        let magnitude = if precision <= Precision::DOUBLE && !evaluator.simulated() {
            cancelling_terms(&cycle, &shifted, &shift, precision)
        } else {
            base.w.abs()
        };
        let magnitude = magnitude.max_of(&E::Number::smallest_full_precision(precision));
        let vanishing = (only_constant.w.abs() / &magnitude).to_f64_lossy();
        let difference = (with_constant.w - &base.w).abs() / &magnitude;
        Ok(Measured {
            error: difference.to_f64_lossy().max(vanishing),
            ..Measured::default()
        })
    }

    fn note<E: Evaluator>(&self, evaluator: &E, _: Option<(f64, f64)>) -> String {
        match evaluator.precision() {
            _ if evaluator.simulated() => String::new(),
            precision if precision <= Precision::DOUBLE => {
                "v' itself integrated (remove_constant_slope off); f64 error relative to the cancelling terms".into()
            }
            _ => "v' itself integrated (remove_constant_slope off); error relative to W".into(),
        }
    }
}
