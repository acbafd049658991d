//! Claim 4: W is linear in v'.

use super::simulation::{refinement_note, simulate_within_tolerance, SIMULATED_IDENTITY_TOLERANCE};
use super::{describe, identity_tolerance, random_case, read, relative, relative_estimate, unresolvable, Tally};
use crate::compliance::{Compliance, Scaled, Sum};
use crate::dissipation::{dissipation, Options};
use crate::real::{Precision, Real};
use crate::verify::generators::{compliance_spec, Draw};
use crate::verify::ClaimReport;

/// Claim 4, linearity: W[a v1' + b v2'] = a W[v1'] + b W[v2'].
pub fn linearity<R: Real>(seed: u64, cases: usize, precision: Precision) -> ClaimReport {
    let tolerance = identity_tolerance(precision);
    let mut tally = Tally::new(
        "4 linearity: W[a v1' + b v2'] = a W[v1'] + b W[v2']",
        precision,
        tolerance,
    );
    let mut draw = Draw::new(seed);
    for _ in 0..cases {
        let case = random_case(&mut draw);
        let mut other = case.clone();
        other.compliance = compliance_spec(&mut draw, 0.05, 1.9, 1.0);
        let (a, b) = (draw.uniform(0.1, 3.0), draw.uniform(0.1, 3.0));
        let label = format!("{} + v2'={} a={a} b={b}", describe(&case), other.compliance);
        let (Some((cycle, first)), Some((_, second))) = (read::<R>(&case, precision), read::<R>(&other, precision))
        else {
            tally.fail(&label, "case did not read");
            continue;
        };
        let weight = |x: f64| R::parse_decimal(&x.to_string(), precision).unwrap_or_else(|_| R::from_i64(1, precision));
        let options = Options {
            check_compliance: false,
            ..Options::default()
        };
        let (w1, w2) = (
            dissipation(&cycle, first.as_ref(), &options),
            dissipation(&cycle, second.as_ref(), &options),
        );
        let combined = Sum {
            terms: vec![
                Box::new(Scaled {
                    factor: weight(a),
                    inner: first,
                }) as Box<dyn Compliance<R>>,
                Box::new(Scaled {
                    factor: weight(b),
                    inner: second,
                }),
            ],
        };
        match (w1, w2, dissipation(&cycle, &combined, &options)) {
            (Ok(w1), Ok(w2), Ok(sum)) => {
                let estimates = [&w1, &w2, &sum].map(relative_estimate);
                let expected = w1.total * &weight(a) + &(w2.total * &weight(b));
                tally.record_resolved(relative(&sum.total, &expected), &estimates, &label);
            }
            (Err(e), _, _) | (_, Err(e), _) | (_, _, Err(e)) if unresolvable(&e) => tally.unresolved(),
            (Err(e), _, _) | (_, Err(e), _) | (_, _, Err(e)) => tally.fail(&label, e),
        }
    }
    tally.note("")
}

/// Claim 4 by the history simulation: W_sim[a v1' + b v2'] = a W_sim[v1'] + b W_sim[v2'] —
/// in the spring bed the stiffnesses 1/v' do not add, so linearity in v' is a property
/// of the physics there, not of the segment formulas.
pub fn linearity_simulated(seed: u64, cases: usize) -> ClaimReport {
    let mut tally = Tally::new(
        "4 linearity, simulated: W_sim is linear in v'",
        Precision::DOUBLE,
        SIMULATED_IDENTITY_TOLERANCE,
    );
    let mut draw = Draw::new(seed);
    for _ in 0..cases {
        let case = random_case(&mut draw);
        let Some((cycle, first)) = read::<f64>(&case, Precision::DOUBLE) else {
            tally.fail(&describe(&case), "case did not read");
            continue;
        };
        // The second compliance is admissible wherever the bed reaches (down to 0.9 P_T).
        let mut other = case.clone();
        let low = 0.8 * cycle.permanent_stick_load();
        other.compliance = compliance_spec(&mut draw, low, 1.0 + cycle.normal_amplitude, 1.0);
        let (a, b) = (draw.uniform(0.1, 3.0), draw.uniform(0.1, 3.0));
        let label = format!("{} + v2'={} a={a} b={b}", describe(&case), other.compliance);
        let Some((_, second)) = read::<f64>(&other, Precision::DOUBLE) else {
            tally.fail(&label, "case did not read");
            continue;
        };
        let (w1, w2) = (
            simulate_within_tolerance(&cycle, first.as_ref()),
            simulate_within_tolerance(&cycle, second.as_ref()),
        );
        let combined = Sum {
            terms: vec![
                Box::new(Scaled {
                    factor: a,
                    inner: first,
                }) as Box<dyn Compliance<f64>>,
                Box::new(Scaled {
                    factor: b,
                    inner: second,
                }),
            ],
        };
        match (w1, w2, simulate_within_tolerance(&cycle, &combined)) {
            (Ok(w1), Ok(w2), Ok(sum)) => tally.record(relative(&sum.w_work, &(a * w1.w_work + b * w2.w_work)), &label),
            (Err(e), _, _) | (_, Err(e), _) | (_, _, Err(e)) => tally.fail(&label, e),
        }
    }
    tally.note(refinement_note())
}
