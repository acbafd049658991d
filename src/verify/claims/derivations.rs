//! Claims 3, 4 and 5 proved by their derivations (proofs/constant-term.md,
//! proofs/linearity.md, proofs/roughness-scaling.md): each is an exact argument about the
//! construction, valid for every cycle and compliance. Each row checks on Arb balls the
//! step of its derivation that can be computed, where a violation would be proven, not
//! sampled within a tolerance: the measure's mass I₀ = ∫ dm encloses 0 over the whole
//! (ρ, φ) domain; the enclosures of W[a v₁' + b v₂'] and a W[v₁'] + b W[v₂'] meet; those of
//! W_k and k² W(·/k) meet. The sampled and simulated rows stay as independent evidence.

use super::{Draw, Tally};
use crate::ball::Ball;
use crate::compliance::{Compliance, ComplianceSpec, LoadScaled, Scaled, Sum};
use crate::cycle::LoadCycle;
use crate::digits::enclosure::certified_dissipation;
use crate::exact::series_coefficients;
use crate::real::{Precision, Real};
use crate::verify::generators::compliance_spec;
use crate::verify::ClaimReport;

/// The working precision of the checks.
const BITS: u32 = 128;

/// The certified digits of each W compared.
const DIGITS: u32 = 30;

/// The row of a claim proved by the derivation in `document`, once its checks passed.
fn proved_by(tally: Tally, document: &'static str, note: String) -> ClaimReport {
    tally.proved_by(document, format!("derived in {document}; {note}"))
}

/// The lower end of |x| over the upper end of |scale|: 0 where x may be 0, positive only
/// where x ≠ 0 is proven.
fn proven_gap(x: &Ball, scale: &Ball) -> f64 {
    let low = x.abs().real_span().map_or(f64::NAN, |span| span.0);
    let high = scale.abs().real_span().map_or(f64::NAN, |span| span.1);
    if low > 0.0 {
        low / high
    } else {
        0.0
    }
}

/// Claim 3: a constant in v' dissipates nothing, because with v' ≡ c every segment's
/// integrand is c·Q'(θ) and ∮(Q − Q0) dQ = 0; equivalently m has mass I₀ = 0. Checked: at
/// (ρ, φ) drawn over the whole domain, I₀ from the exact trigonometric integrals encloses 0
/// (error: |I₀| over the magnitude of the terms it sums).
pub fn constant_term_proved(seed: u64, cases: usize) -> ClaimReport {
    let precision = Precision::bits(BITS);
    let mut tally = Tally::new("3 constant term: ∫dm = I₀ = 0, so W[c] = 0", precision, 1e-30);
    let mut draw = Draw::new(seed);
    let mut widest = 0.0f64;
    for _ in 0..cases {
        let rho = 10f64.powf(draw.uniform(-4.0, 4.0));
        let phase = draw.uniform(0.0, 1.0) * std::f64::consts::PI;
        let case = format!("ρ={rho:e} φ={phase:e}");
        match series_coefficients(&Ball::from_f64(rho, precision), &Ball::from_f64(phase, precision), 0) {
            Ok(coefficients) => {
                let (mass, scale) = &coefficients[0];
                let encloses_zero = mass.contains_zero();
                let relative = mass.abs().real_span().map_or(f64::NAN, |span| span.1)
                    / scale.real_span().map_or(f64::NAN, |span| span.0);
                widest = widest.max(relative);
                tally.record(if encloses_zero { relative } else { f64::INFINITY }, &case);
            }
            Err(error) => tally.record(f64::NAN, &format!("{case}: {error}")),
        }
    }
    proved_by(
        tally,
        "proofs/constant-term.md",
        format!("I₀ encloses 0 at {cases} (ρ, φ), ρ from 1e-4 to 1e4, |I₀| ≤ {widest:.1e} of its terms"),
    )
}

/// A cycle inside the theory for compliances admissible on [0.1, 2]: P0 = 1,
/// ρ ∈ (0.1, 3), P1(1 + ρ) < 0.9, so that P_T > 0.1.
fn drawn_cycle(draw: &mut Draw) -> LoadCycle<f64> {
    let rho = draw.uniform(0.1, 3.0);
    let normal_amplitude = draw.uniform(0.02, 0.9 / (1.0 + rho));
    let friction = draw.uniform(0.2, 1.0);
    LoadCycle {
        mean_normal_load: 1.0,
        normal_amplitude,
        mean_tangential_load: draw.uniform(-0.05, 0.05) * friction,
        tangential_amplitude: rho * friction * normal_amplitude,
        phase: draw.uniform(0.05, 0.95) * std::f64::consts::PI,
        friction,
        compliance_ratio: draw.uniform(1.0, 2.0),
    }
}

/// The certified W of `cycle` (its loads divided by `divisor`) on the compliance `build`
/// gives at each precision.
fn certified_w(
    cycle: &LoadCycle<f64>,
    divisor: f64,
    build: &dyn Fn(Precision) -> Result<Box<dyn Compliance<Ball>>, String>,
) -> Result<Ball, String> {
    let read = |precision: Precision| {
        let k = Ball::from_f64(divisor, precision);
        let load = |x: f64| Ball::from_f64(x, precision) / &k;
        let cycle = LoadCycle {
            mean_normal_load: load(cycle.mean_normal_load),
            normal_amplitude: load(cycle.normal_amplitude),
            mean_tangential_load: load(cycle.mean_tangential_load),
            tangential_amplitude: load(cycle.tangential_amplitude),
            phase: Ball::from_f64(cycle.phase, precision),
            friction: Ball::from_f64(cycle.friction, precision),
            compliance_ratio: Ball::from_f64(cycle.compliance_ratio, precision),
        };
        Ok((cycle, build(precision)?))
    };
    certified_dissipation(read, DIGITS)
        .map(|certified| certified.enclosure.total)
        .map_err(|error| error.to_string())
}

/// A SPEC at a precision, as a compliance on balls.
fn spec_at(spec: &str, precision: Precision) -> Result<Box<dyn Compliance<Ball>>, String> {
    ComplianceSpec::parse(spec)
        .and_then(|spec| spec.build::<Ball>(precision))
        .map_err(|error| error.to_string())
}

/// Claim 4: W = ∫ v' dm with m set by the cycle alone, so W is linear in v'. Checked: on
/// drawn cycles and pairs of compliances of every family, the certified enclosures of
/// W[a v₁' + b v₂'] (built with the `Sum` and `Scaled` combinators) and a W[v₁'] + b W[v₂']
/// meet (error: their proven gap over |W|, 0 where they meet).
pub fn linearity_proved(seed: u64, cases: usize) -> ClaimReport {
    let mut tally = Tally::new("4 linearity: W = ∫v'dm, m free of v'", Precision::bits(BITS), 0.0);
    let mut draw = Draw::new(seed);
    for _ in 0..cases {
        let cycle = drawn_cycle(&mut draw);
        let (first, second) = (
            compliance_spec(&mut draw, 0.1, 2.0, 1.0),
            compliance_spec(&mut draw, 0.1, 2.0, 1.0),
        );
        let (a, b) = (draw.uniform(0.1, 3.0), draw.uniform(0.1, 3.0));
        let case = format!("{cycle:?} v'={a}·({first}) + {b}·({second})");
        let factor = |x: f64, precision: Precision| Ball::from_f64(x, precision);
        let combined = certified_w(&cycle, 1.0, &|precision| {
            let scaled = |x: f64, spec: &str| -> Result<Box<dyn Compliance<Ball>>, String> {
                Ok(Box::new(Scaled {
                    factor: factor(x, precision),
                    inner: spec_at(spec, precision)?,
                }))
            };
            Ok(Box::new(Sum {
                terms: vec![scaled(a, &first)?, scaled(b, &second)?],
            }) as Box<dyn Compliance<Ball>>)
        });
        let w = |spec: &str| certified_w(&cycle, 1.0, &|precision| spec_at(spec, precision));
        match (combined, w(&first), w(&second)) {
            (Ok(together), Ok(w1), Ok(w2)) => {
                let precision = Precision::bits(BITS);
                let apart = w1 * &factor(a, precision) + &(w2 * &factor(b, precision));
                tally.record(proven_gap(&(together.clone() - &apart), &together), &case);
            }
            (Err(error), _, _) | (_, Err(error), _) | (_, _, Err(error)) => {
                tally.record(f64::NAN, &format!("{case}: {error}"))
            }
        }
    }
    proved_by(
        tally,
        "proofs/linearity.md",
        format!("the enclosures of W[av₁' + bv₂'] and aW[v₁'] + bW[v₂'] meet on {cases} cases ({DIGITS} digits)"),
    )
}

/// Claim 5: heights scaled by k give v_k(P) = k·v(P/k), and substituting P = kP̃, Q = kQ̃
/// in the construction gives W_k(P0, P1, Q1) = k² W(P0/k, P1/k, Q1/k). Checked: on drawn
/// cycles, compliances and k, the certified enclosures of both sides meet.
pub fn roughness_proved(seed: u64, cases: usize) -> ClaimReport {
    let mut tally = Tally::new(
        "5 roughness: W_k = k²W(·/k) by change of variables",
        Precision::bits(BITS),
        0.0,
    );
    let mut draw = Draw::new(seed);
    for _ in 0..cases {
        let cycle = drawn_cycle(&mut draw);
        let k = draw.uniform(0.2, 5.0);
        let spec = compliance_spec(&mut draw, 0.1 / k, 2.0 / k, 1.0 / k);
        let case = format!("{cycle:?} k={k} v'={spec}");
        let scaled = certified_w(&cycle, 1.0, &|precision| {
            Ok(Box::new(LoadScaled {
                factor: Ball::from_f64(k, precision),
                inner: spec_at(&spec, precision)?,
            }) as Box<dyn Compliance<Ball>>)
        });
        let original = certified_w(&cycle, k, &|precision| spec_at(&spec, precision));
        match (scaled, original) {
            (Ok(scaled), Ok(original)) => {
                let k = Ball::from_f64(k, Precision::bits(BITS));
                let changed = original * &k.square();
                tally.record(proven_gap(&(scaled.clone() - &changed), &scaled), &case);
            }
            (Err(error), _) | (_, Err(error)) => tally.record(f64::NAN, &format!("{case}: {error}")),
        }
    }
    proved_by(
        tally,
        "proofs/roughness-scaling.md",
        format!("the enclosures of W_k and k²W(·/k) meet on {cases} cases ({DIGITS} digits)"),
    )
}
