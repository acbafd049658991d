//! Claim 3: the constant term of v' contributes nothing.

use super::simulation::{refinement_note, simulate_within_tolerance, SIMULATED_IDENTITY_TOLERANCE};
use super::{describe, random_case, read, relative, Tally};
use crate::compliance::{Compliance, Polynomial, Shifted};
use crate::dissipation::{dissipation, four_segment, Options};
use crate::real::{Precision, Real};
use crate::verify::generators::Draw;
use crate::verify::ClaimReport;

/// Options that integrate v' itself, so the segment formulas must cancel a constant.
fn raw_options<R: Real>() -> Options<R> {
    Options {
        remove_constant_slope: false,
        check_compliance: false,
        ..Options::default()
    }
}

/// Claim 3, the constant term: W[v' + c] = W[v'] for any c, and W[c] = 0, through the
/// raw segment formulas (v' itself integrated, not v' − v'(P0)). In f64 the identity holds
/// to 1e−13 of the terms that cancel; at 256 bits to 1e−70 of W.
pub fn constant_term<R: Real>(seed: u64, cases: usize, precision: Precision) -> ClaimReport {
    let tolerance = if precision <= Precision::DOUBLE { 1e-13 } else { 1e-70 };
    let mut tally = Tally::new("3 constant term: W[v' + c] = W[v'], W[c] = 0", precision, tolerance);
    let mut draw = Draw::new(seed);
    for _ in 0..cases {
        let case = random_case(&mut draw);
        let c = draw.uniform(0.1, 10.0);
        let label = format!("{} c={c}", describe(&case));
        let Some((cycle, compliance)) = read::<R>(&case, precision) else {
            tally.fail(&label, "case did not read");
            continue;
        };
        let shift = R::parse_decimal(&c.to_string(), precision).unwrap_or_else(|_| R::from_i64(1, precision));
        let shifted = Shifted {
            extra_slope: shift.clone(),
            inner: compliance,
        };
        let constant = Polynomial {
            reference: shift.int(0),
            coefficients: vec![shift.clone()],
        };
        // Raw values of either sign, without the non-negativity guard: a W that vanishes
        // in exact arithmetic is rounding noise here, which is what is measured.
        let options = raw_options::<R>();
        match (
            dissipation(&cycle, shifted.inner.as_ref(), &options),
            dissipation(&cycle, &shifted, &options),
            four_segment(&cycle, &constant, &options),
        ) {
            (Ok(base), Ok(with_constant), Ok(only_constant)) => {
                // In f64, "to working precision" is relative to the size of the terms that
                // cancel: 2πλ Q1 (Q1 + f P1) (max v' + c) bounds ∫|(Q − Q0) du/dθ| dθ. At
                // 256 bits the difference is held to 1e−70 of W itself.
                let magnitude = if precision <= Precision::DOUBLE {
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
                } else {
                    base.total.abs()
                };
                let magnitude = magnitude.max_of(&R::smallest_full_precision(precision));
                let vanishing = (only_constant.total.abs() / &magnitude).to_f64_lossy();
                let difference = (with_constant.total - &base.total).abs() / &magnitude;
                tally.record(difference.to_f64_lossy().max(vanishing), &label);
            }
            (Err(e), _, _) | (_, Err(e), _) | (_, _, Err(e)) => tally.fail_unless_unresolvable(&label, e),
        }
    }
    tally.note(if precision <= Precision::DOUBLE {
        "v' itself integrated (remove_constant_slope off); f64 error relative to the cancelling terms"
    } else {
        "v' itself integrated (remove_constant_slope off); error relative to W"
    })
}

/// Claim 3 by the history simulation: W_sim[v' + c] = W_sim[v']. In the spring bed a
/// constant added to v' changes every element's stiffness (K = 1/v' is not linear in v'),
/// so the identity is a consequence of the physics there, not of the segment formulas.
pub fn constant_term_simulated(seed: u64, cases: usize) -> ClaimReport {
    let mut tally = Tally::new(
        "3 constant term, simulated: W_sim[v' + c] = W_sim[v']",
        Precision::DOUBLE,
        SIMULATED_IDENTITY_TOLERANCE,
    );
    let mut draw = Draw::new(seed);
    for _ in 0..cases {
        let case = random_case(&mut draw);
        let c = draw.uniform(0.1, 3.0);
        let label = format!("{} c={c}", describe(&case));
        let Some((cycle, compliance)) = read::<f64>(&case, Precision::DOUBLE) else {
            tally.fail(&label, "case did not read");
            continue;
        };
        let plain = simulate_within_tolerance(&cycle, compliance.as_ref());
        let shifted = Shifted {
            extra_slope: c,
            inner: compliance,
        };
        match (plain, simulate_within_tolerance(&cycle, &shifted)) {
            (Ok(plain), Ok(shifted)) => tally.record(relative(&shifted.w_work, &plain.w_work), &label),
            (Err(e), _) | (_, Err(e)) => tally.fail(&label, e),
        }
    }
    tally.note(refinement_note())
}
