//! Claim 4: W is linear in v'.

use std::fmt;

use super::evaluator::{all_of, Claim, ConstantSlope, Evaluator, Measured, Outcome, Source};
use super::{describe, random_case, read_case, relative};
use crate::case::CaseText;
use crate::compliance::{Compliance, Scaled, Sum};
use crate::real::Precision;
use crate::verify::generators::{compliance_spec, Draw, Loads};

/// Claim 4, linearity: W[a v1' + b v2'] = a W[v1'] + b W[v2']. In the simulated spring bed
/// the stiffnesses 1/v' do not add, so there linearity in v' is a property of the physics,
/// not of the segment formulas.
#[derive(Clone, Copy, Debug, Default)]
pub struct Linearity;

/// A cycle and v1', a second compliance v2' and the weights a, b.
#[derive(Clone, PartialEq)]
pub struct LinearityCase {
    /// The cycle and v1'.
    pub case: CaseText,
    /// v2' as a SPEC.
    pub second: String,
    /// a.
    pub a: f64,
    /// b.
    pub b: f64,
}

impl fmt::Display for LinearityCase {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} + v2'={} a={} b={}",
            describe(&self.case),
            self.second,
            self.a,
            self.b
        )
    }
}

/// The loads v2' is drawn admissible over: the simulated bed reaches down to 0.9 P_T, so
/// there from 0.8 P_T to P0 + P1; the integrals do not check v2', drawn over a fixed range.
pub fn second_compliance_loads(case: &CaseText, source: Source) -> Loads {
    let bed = match source {
        Source::Simulation => read_case::<f64>(case, Precision::DOUBLE).ok(),
        Source::Segments => None,
    };
    let (low, high) = match bed {
        Some((cycle, _)) => (0.8 * cycle.permanent_stick_load(), 1.0 + cycle.normal_amplitude),
        None => (0.05, 1.9),
    };
    Loads { low, high, mean: 1.0 }
}

impl Claim for Linearity {
    type Case = LinearityCase;

    const NAME: &'static str = "4 linearity: W[a v1' + b v2'] = a W[v1'] + b W[v2']";
    const SIMULATED_NAME: &'static str = "4 linearity, simulated: W_sim is linear in v'";

    fn draw<E: Evaluator>(&self, draw: &mut Draw, evaluator: &E) -> LinearityCase {
        let case = random_case(draw);
        let loads = second_compliance_loads(&case, evaluator.source());
        let second = compliance_spec(draw, loads.low, loads.high, loads.mean);
        let (a, b) = (draw.uniform(0.1, 3.0), draw.uniform(0.1, 3.0));
        LinearityCase { case, second, a, b }
    }

    fn check<E: Evaluator>(&self, evaluator: &E, case: &LinearityCase) -> Outcome {
        let precision = evaluator.precision();
        let (cycle, first) = read_case::<E::Number>(&case.case, precision)?;
        let other = CaseText {
            compliance: case.second.clone(),
            ..case.case.clone()
        };
        let (_, second) = read_case::<E::Number>(&other, precision)?;
        let (a, b) = (evaluator.number(case.a), evaluator.number(case.b));
        let (w1, w2) = (
            evaluator.w(&cycle, first.as_ref(), ConstantSlope::Removed),
            evaluator.w(&cycle, second.as_ref(), ConstantSlope::Removed),
        );
        let combined = Sum {
            terms: vec![
                Box::new(Scaled {
                    factor: a.clone(),
                    inner: first,
                }) as Box<dyn Compliance<E::Number>>,
                Box::new(Scaled {
                    factor: b.clone(),
                    inner: second,
                }),
            ],
        };
        let [w1, w2, sum] = all_of([w1, w2, evaluator.w(&cycle, &combined, ConstantSlope::Removed)])?;
        let expected = w1.w * &a + &(w2.w * &b);
        Ok(Measured {
            error: relative(&sum.w, &expected),
            rounding: w1.rounding + w2.rounding + sum.rounding,
            figure: None,
        })
    }

    fn note<E: Evaluator>(&self, _: &E, _: Option<(f64, f64)>) -> String {
        String::new()
    }
}
