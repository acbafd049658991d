//! Claim 4: W is linear in v'.

use super::{describe, identity_tolerance, random_case, read, relative, Tally};
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
                let expected = w1.total * &weight(a) + &(w2.total * &weight(b));
                tally.record(relative(&sum.total, &expected), &label);
            }
            (Err(e), _, _) | (_, Err(e), _) | (_, _, Err(e)) => tally.fail(&label, e),
        }
    }
    tally.note("")
}
