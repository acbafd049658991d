//! Claim 5: how W scales with the roughness (errata item 7).

use std::fmt;

use super::evaluator::{all_of, Claim, ConstantSlope, Evaluator, Measured, Outcome, Value};
use super::{describe, random_case, read_case, relative};
use crate::case::CaseText;
use crate::compliance::{LoadScaled, Persson, PowerLaw};
use crate::cycle::LoadCycle;
use crate::real::Real;
use crate::verify::generators::Draw;

/// Claim 5, roughness: scaling the roughness heights by k (v_k'(P) = v'(P/k)) gives
/// W_k(P0, P1, Q1) = k² W(P0/k, P1/k, Q1/k) for any compliance; for Persson's
/// v' = γσ/P that makes W ∝ σ exactly, and for v' = C P^β, W_k = k^(−β) W — linear
/// in the roughness only for β = −1 (checked through the segment formulas, whose note
/// reports how far from linear).
#[derive(Clone, Copy, Debug, Default)]
pub struct Roughness;

/// A cycle and compliance, the height scale k, Persson's σ, and the exponent β of the
/// power law (drawn for the segment formulas only).
#[derive(Clone, PartialEq)]
pub struct RoughnessCase {
    /// The cycle and v'.
    pub case: CaseText,
    /// k.
    pub k: f64,
    /// β, if the power law is checked.
    pub beta: Option<f64>,
    /// σ.
    pub sigma: f64,
}

impl fmt::Display for RoughnessCase {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} k={} σ={}", describe(&self.case), self.k, self.sigma)?;
        match self.beta {
            Some(beta) => write!(f, " β={beta}"),
            None => Ok(()),
        }
    }
}

/// The cycle with every load divided by `divisor`.
fn scaled_cycle<R: Real>(cycle: &LoadCycle<R>, divisor: &R) -> LoadCycle<R> {
    LoadCycle {
        mean_normal_load: cycle.mean_normal_load.clone() / divisor,
        normal_amplitude: cycle.normal_amplitude.clone() / divisor,
        mean_tangential_load: cycle.mean_tangential_load.clone() / divisor,
        tangential_amplitude: cycle.tangential_amplitude.clone() / divisor,
        ..cycle.clone()
    }
}

impl Claim for Roughness {
    type Case = RoughnessCase;

    const NAME: &'static str = "5 roughness: W_k = k²W(·/k); Persson W ∝ σ; power law ∝ k^-β";
    const SIMULATED_NAME: &'static str = "5 roughness, simulated: W_k = k²W(·/k); Persson W ∝ σ";

    fn draw<E: Evaluator>(&self, draw: &mut Draw, evaluator: &E) -> RoughnessCase {
        let case = random_case(draw);
        let k = draw.uniform(0.2, 5.0);
        let beta = (!evaluator.simulated()).then(|| draw.uniform(-2.0, -0.05));
        let sigma = draw.uniform(0.01, 1.0);
        RoughnessCase { case, k, beta, sigma }
    }

    fn check<E: Evaluator>(&self, evaluator: &E, case: &RoughnessCase) -> Outcome {
        let (cycle, compliance) = read_case::<E::Number>(&case.case, evaluator.precision())?;
        let number = |x: f64| evaluator.number(x);
        let k = number(case.k);
        let w = |cycle: &LoadCycle<E::Number>, compliance: &dyn crate::compliance::Compliance<E::Number>| {
            evaluator.w(cycle, compliance, ConstantSlope::Removed)
        };
        // The general identity W[v'(·/k)](L) = k² W[v'](L/k), on the drawn compliance. The
        // integrals, which do not need v' admissible, take L = the drawn loads; the simulated
        // bed, which does, takes L = k × the drawn loads, so that L/k is where v' was drawn.
        let scaled = LoadScaled {
            factor: k.clone(),
            inner: compliance,
        };
        let (loads, reduced) = if evaluator.simulated() {
            (scaled_cycle(&cycle, &(k.int(1) / &k)), cycle.clone())
        } else {
            (cycle.clone(), scaled_cycle(&cycle, &k))
        };
        let general = [w(&loads, &scaled), w(&reduced, scaled.inner.as_ref())];
        // Persson at σ and kσ, and a power law with loads scaled by k.
        let persson = |sigma: E::Number| Persson {
            gamma: number(1.0),
            sigma,
        };
        let sigma = number(case.sigma);
        let persson_pair = [w(&cycle, &persson(sigma.clone())), w(&cycle, &persson(sigma * &k))];
        let power_pair = match case.beta {
            Some(beta) => {
                let power = PowerLaw {
                    coefficient: number(1.0),
                    exponent: number(beta),
                };
                let power_scaled = LoadScaled {
                    factor: k.clone(),
                    inner: Box::new(power.clone()),
                };
                [w(&cycle, &power), w(&cycle, &power_scaled)]
            }
            None => [(); 2].map(|_| {
                Ok(Value {
                    w: k.int(1),
                    rounding: 0.0,
                })
            }),
        };
        let [general_k, general_1] = general;
        let [persson_1, persson_k] = persson_pair;
        let [power_1, power_k] = power_pair;
        let [wk, w1, p1, pk, q1, qk] = all_of([general_k, general_1, persson_1, persson_k, power_1, power_k])?;
        // The identities' errors against the sums of their sides' own rounding estimates.
        let pairs = [(&wk, &w1), (&p1, &pk), (&q1, &qk)];
        let rounding = pairs
            .iter()
            .map(|(x, y)| x.rounding + y.rounding)
            .fold(0.0f64, f64::max);
        let identity = relative(&wk.w, &(w1.w.clone() * &k * &k));
        let linear_sigma = relative(&pk.w, &(p1.w.clone() * &k));
        let (power_law, figure) = match case.beta {
            Some(beta) => {
                let power_law = relative(&qk.w, &(q1.w.clone() * &k.powr(&(-number(beta)))));
                let departure = (qk.w / q1.w / &k).to_f64_lossy() - 1.0;
                (power_law, Some((beta, departure)))
            }
            None => (0.0, None),
        };
        Ok(Measured {
            error: identity.max(linear_sigma).max(power_law),
            rounding,
            figure,
        })
    }

    fn note<E: Evaluator>(&self, evaluator: &E, figure: Option<(f64, f64)>) -> String {
        if evaluator.simulated() {
            // The bed is dimensionless: scaling loads or stiffnesses maps it onto itself,
            // element for element, so these hold to rounding even at the coarse resolution.
            return "the bed scales exactly".into();
        }
        let (beta, departure) = figure.unwrap_or((0.0, 0.0));
        format!("linearity in roughness fails for β ≠ −1: at β = {beta:.3}, W(kσ)/(k W(σ)) − 1 = {departure:.3e}")
    }
}
