//! Claim 5: how W scales with the roughness (errata item 7).

use super::simulation::{refinement_note, simulate_within_tolerance, SIMULATED_IDENTITY_TOLERANCE};
use super::{describe, identity_tolerance, random_case, read, relative, relative_estimate, unresolvable, Tally};
use crate::compliance::{LoadScaled, Persson, PowerLaw};
use crate::cycle::LoadCycle;
use crate::dissipation::{dissipation, Options};
use crate::real::{Precision, Real};
use crate::verify::generators::Draw;
use crate::verify::ClaimReport;

fn scaled_cycle<R: Real>(cycle: &LoadCycle<R>, divisor: &R) -> LoadCycle<R> {
    LoadCycle {
        mean_normal_load: cycle.mean_normal_load.clone() / divisor,
        normal_amplitude: cycle.normal_amplitude.clone() / divisor,
        mean_tangential_load: cycle.mean_tangential_load.clone() / divisor,
        tangential_amplitude: cycle.tangential_amplitude.clone() / divisor,
        ..cycle.clone()
    }
}

/// Claim 5, roughness: scaling the roughness heights by k (v_k'(P) = v'(P/k)) gives
/// W_k(P0, P1, Q1) = k² W(P0/k, P1/k, Q1/k) for any compliance; for Persson's
/// v' = γσ/P that makes W ∝ σ exactly, and for v' = C P^β, W_k = k^(−β) W — linear
/// in the roughness only for β = −1. The note reports how far from linear.
pub fn roughness<R: Real>(seed: u64, cases: usize, precision: Precision) -> ClaimReport {
    let tolerance = identity_tolerance(precision);
    let mut tally = Tally::new(
        "5 roughness: W_k = k²W(·/k); Persson W ∝ σ; power law ∝ k^-β",
        precision,
        tolerance,
    );
    let mut draw = Draw::new(seed);
    let mut worst_departure: (f64, f64) = (0.0, 0.0);
    for _ in 0..cases {
        let case = random_case(&mut draw);
        let k = draw.uniform(0.2, 5.0);
        let beta = draw.uniform(-2.0, -0.05);
        let label = format!("{} k={k} β={beta}", describe(&case));
        let Some((cycle, compliance)) = read::<R>(&case, precision) else {
            tally.fail(&label, "case did not read");
            continue;
        };
        let number = |x: f64| R::parse_decimal(&x.to_string(), precision).unwrap_or_else(|_| R::from_i64(1, precision));
        let k_r = number(k);
        let options = Options {
            check_compliance: false,
            ..Options::default()
        };
        // The general identity, on the drawn compliance.
        let scaled = LoadScaled {
            factor: k_r.clone(),
            inner: compliance,
        };
        let general = (
            dissipation(&cycle, &scaled, &options),
            dissipation(&scaled_cycle(&cycle, &k_r), scaled.inner.as_ref(), &options),
        );
        // Persson at σ and kσ, and a power law with loads scaled by k.
        let persson = |sigma: R| Persson {
            gamma: number(1.0),
            sigma,
        };
        let sigma = number(draw.uniform(0.01, 1.0));
        let persson_pair = (
            dissipation(&cycle, &persson(sigma.clone()), &options),
            dissipation(&cycle, &persson(sigma * &k_r), &options),
        );
        let power = PowerLaw {
            coefficient: number(1.0),
            exponent: number(beta),
        };
        let power_scaled = LoadScaled {
            factor: k_r.clone(),
            inner: Box::new(power.clone()),
        };
        let power_pair = (
            dissipation(&cycle, &power, &options),
            dissipation(&cycle, &power_scaled, &options),
        );
        match (general, persson_pair, power_pair) {
            ((Ok(wk), Ok(w)), (Ok(p1), Ok(pk)), (Ok(q1), Ok(qk))) => {
                // The identities' errors against the sums of their sides' own estimates.
                let pairs = [(&wk, &w), (&p1, &pk), (&q1, &qk)];
                let estimates = pairs.map(|(x, y)| relative_estimate(x) + relative_estimate(y));
                let largest = estimates.iter().fold(0.0f64, |acc, &e| acc.max(e));
                let identity = relative(&wk.total, &(w.total * &k_r * &k_r));
                let linear_sigma = relative(&pk.total, &(p1.total * &k_r));
                let power_law = relative(&qk.total, &(q1.total.clone() * &k_r.powr(&(-number(beta)))));
                tally.record_resolved(identity.max(linear_sigma).max(power_law), &[largest], &label);
                let departure = (qk.total / q1.total / &k_r).to_f64_lossy() - 1.0;
                if departure.abs() > worst_departure.1.abs() {
                    worst_departure = (beta, departure);
                }
            }
            ((Err(e), _), _, _)
            | ((_, Err(e)), _, _)
            | (_, (Err(e), _), _)
            | (_, (_, Err(e)), _)
            | (_, _, (Err(e), _))
            | (_, _, (_, Err(e)))
                if unresolvable(&e) =>
            {
                tally.unresolved()
            }
            _ => tally.fail(&label, "a computation failed"),
        }
    }
    tally.note(format!(
        "linearity in roughness fails for β ≠ −1: at β = {:.3}, W(kσ)/(k W(σ)) − 1 = {:.3e}",
        worst_departure.0, worst_departure.1
    ))
}

/// Claim 5 by the history simulation: W_k = k² W(·/k) on the drawn compliance (as
/// W_k(k·loads) = k² W(loads), so that both beds see their compliance where it is
/// physical), and Persson's W ∝ σ, each side simulated.
pub fn roughness_simulated(seed: u64, cases: usize) -> ClaimReport {
    let mut tally = Tally::new(
        "5 roughness, simulated: W_k = k²W(·/k); Persson W ∝ σ",
        Precision::DOUBLE,
        SIMULATED_IDENTITY_TOLERANCE,
    );
    let mut draw = Draw::new(seed);
    for _ in 0..cases {
        let case = random_case(&mut draw);
        let k = draw.uniform(0.2, 5.0);
        let sigma = draw.uniform(0.01, 1.0);
        let label = format!("{} k={k} σ={sigma}", describe(&case));
        let Some((cycle, compliance)) = read::<f64>(&case, Precision::DOUBLE) else {
            tally.fail(&label, "case did not read");
            continue;
        };
        // The loads scaled up with the heights, so that each simulated bed sees its
        // compliance where that is physical: W[v'(·/k)](k·loads) = k² W[v'](loads).
        let scaled = LoadScaled {
            factor: k,
            inner: compliance,
        };
        let general = (
            simulate_within_tolerance(&scaled_cycle(&cycle, &(1.0 / k)), &scaled),
            simulate_within_tolerance(&cycle, scaled.inner.as_ref()),
        );
        let persson = |sigma: f64| Persson { gamma: 1.0, sigma };
        let persson_pair = (
            simulate_within_tolerance(&cycle, &persson(sigma)),
            simulate_within_tolerance(&cycle, &persson(k * sigma)),
        );
        match (general, persson_pair) {
            ((Ok(wk), Ok(w)), (Ok(p1), Ok(pk))) => {
                let identity = relative(&wk.w_work, &(k * k * w.w_work));
                let linear_sigma = relative(&pk.w_work, &(k * p1.w_work));
                tally.record(identity.max(linear_sigma), &label);
            }
            _ => tally.fail(&label, "a simulation failed"),
        }
    }
    // The bed is dimensionless: scaling loads or stiffnesses maps it onto itself, element
    // for element, so these hold to rounding even at the coarse resolution.
    tally.note(refinement_note() + "; the bed scales exactly")
}
