//! Claim 1, the cubic law (paper Section 5.1).

use rug::Float;

use super::{number, Tally};
use crate::compliance::parse_spec;
use crate::cycle::LoadCycle;
use crate::dissipation::{dissipation, Options};
use crate::real::{Precision, Real};
use crate::verify::generators::{compliance_spec, Draw};
use crate::verify::small_amplitude::coefficient;
use crate::verify::ClaimReport;

/// The exponents k of the amplitudes P1 = P0·2^(−k) the order is fitted over.
const EXPONENTS: std::ops::RangeInclusive<i32> = 8..=15;

/// Claim 1: W/(λf²P1³v''(P0)) → I(ρ, φ) as P1 = P0·2^(−k) → 0 with error O(P1), for
/// every compliance: the order fitted over k = 8 … 15 must be 1 ± 0.1. Random
/// compliances, ρ ∈ (0.2, 3), φ ∈ (0.1π, 0.9π) (near 0 and π, I itself vanishes for
/// ρ < 1 and the O(P1) term dominates longer), random f and λ. At 160 bits: the ratio's
/// error at k = 15 is ~1e−5 of a W that f64 would hold only to ~1e−11 after the
/// cancellation between segments.
pub fn cubic_law(seed: u64, cases: usize) -> ClaimReport {
    let precision = Precision::bits(160);
    let mut tally = Tally::new("1 cubic law: fitted order of W/(λf²P1³v'') → I", precision, 0.1);
    let mut draw = Draw::new(seed);
    let mut orders = Vec::new();
    let mut last_errors = Vec::new();
    for _ in 0..cases {
        let (rho, phase_fraction) = (draw.uniform(0.2, 3.0), draw.uniform(0.1, 0.9));
        let f = draw.uniform(0.3, 1.0);
        let lambda = draw.uniform(1.0, 1.5);
        let spec = compliance_spec(&mut draw, 0.5, 1.5, 1.0);
        let label = format!("ρ={rho} φ={phase_fraction}π f={f} v'={spec}");
        let Ok(compliance) = parse_spec::<Float>(&spec, precision) else {
            tally.fail(&label, "spec did not parse");
            continue;
        };
        let phase = Float::pi(precision) * number::<Float>(phase_fraction, precision);
        let rho_r: Float = number(rho, precision);
        let Ok(limit) = coefficient(&rho_r, &phase) else {
            tally.fail(&label, "I(ρ, φ) failed");
            continue;
        };
        let one = Float::from_i64(1, precision);
        let curvature = compliance.curvature(&one);
        let (f_r, lambda_r): (Float, Float) = (number(f, precision), number(lambda, precision));
        let mut points = Vec::new();
        for k in EXPONENTS {
            let p1 = Float::from_i64(2, precision).powi(-k);
            let cycle = LoadCycle {
                mean_normal_load: one.clone(),
                normal_amplitude: p1.clone(),
                mean_tangential_load: one.int(0),
                tangential_amplitude: rho_r.clone() * &f_r * &p1,
                phase: phase.clone(),
                friction: f_r.clone(),
                compliance_ratio: lambda_r.clone(),
            };
            match dissipation(&cycle, compliance.as_ref(), &Options::default()) {
                Ok(result) => {
                    let scale = lambda_r.clone() * &f_r * &f_r * &p1.clone().powi(3) * &curvature;
                    let ratio = result.total / scale;
                    let error = ((ratio - &limit) / &limit).abs().to_f64();
                    points.push((-f64::from(k), error.log2()));
                }
                Err(error) => {
                    tally.fail(&label, error);
                    break;
                }
            }
        }
        if points.len() == EXPONENTS.count() {
            let order = least_squares_slope(&points);
            orders.push(order);
            last_errors.push(points[points.len() - 1].1.exp2());
            tally.record((order - 1.0).abs(), &label);
        }
    }
    let range = |values: &[f64]| {
        values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &o| (l.min(o), h.max(o)))
    };
    let (low, high) = range(&orders);
    let (smallest, largest) = range(&last_errors);
    tally.note(format!(
        "fitted orders in [{low:.4}, {high:.4}] over P1 = 2^-8 … 2^-15; relative error of the ratio at 2^-15 in [{smallest:.1e}, {largest:.1e}]"
    ))
}

/// The slope of the least-squares line through (x, y) points.
pub fn least_squares_slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (sx, sy) = points.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x, b + y));
    let (mx, my) = (sx / n, sy / n);
    let (num, den) = points.iter().fold((0.0, 0.0), |(a, b), (x, y)| {
        (a + (x - mx) * (y - my), b + (x - mx) * (x - mx))
    });
    num / den
}
