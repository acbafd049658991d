//! Claim 2, the coefficient I(ρ, φ) of the cubic law.

use rug::Float;

use super::{least_squares_slope, number, relative, Tally};
use crate::real::{Precision, Real};
use crate::verify::generators::{shape, Draw};
use crate::verify::small_amplitude::{coefficient, coefficient_at};
use crate::verify::ClaimReport;

/// The phases at which the approach to the in-phase value is measured (ρ < 1).
const NEAR_IN_PHASE: [f64; 5] = [1e-4, 3e-5, 1e-5, 3e-6, 1e-6];

/// Claim 2, as two reports at 128 bits:
/// (a) I(ρ, φ) does not depend on the amplitude it is computed at (P1 and P1/7 agree to
///     1e−30 relative) and is negative for 0 < φ < π;
/// (b) in phase (φ = 0) I = 0 exactly for ρ ≤ 1 (no slip), and the ellipse tends to it
///     as φ²: the order fitted over φ = 1e−4 … 1e−6 must be 2 ± 0.1 (ρ ∈ (0.1, 0.95)),
///     and at φ = 1e−6, I must match the measured asymptote −(8/3)ρ²φ²/(1 − ρ) (found
///     numerically to 10 digits, proofs/small-amplitude.md) to 0.1 relative.
pub fn small_amplitude_coefficient(seed: u64, cases: usize) -> (ClaimReport, ClaimReport) {
    let precision = Precision::bits(128);
    let mut homogeneous = Tally::new("2a I(ρ,φ): the same at every amplitude, and < 0", precision, 1e-30);
    let mut in_phase = Tally::new("2b I(ρ,0) = 0 for ρ ≤ 1, approached as −8ρ²φ²/(3(1−ρ))", precision, 0.1);
    let mut draw = Draw::new(seed);
    let mut largest = f64::NEG_INFINITY;
    let mut orders = Vec::new();
    let mut worst_asymptote: f64 = 0.0;
    for _ in 0..cases {
        let (rho, phase_fraction) = shape(&mut draw);
        let label = format!("ρ={rho} φ={phase_fraction}π");
        let rho_r: Float = number(rho, precision);
        let phase = Float::pi(precision) * number::<Float>(phase_fraction, precision);
        let amplitude = Float::from_i64(1, precision) / (rho_r.clone() + 1i32) / 4i32;
        let smaller = amplitude.clone() / 7i32;
        match (
            coefficient_at(&rho_r, &phase, &amplitude),
            coefficient_at(&rho_r, &phase, &smaller),
        ) {
            (Ok(a), Ok(b)) => {
                largest = largest.max(a.to_f64());
                let sign_error = if a < 0 { 0.0 } else { f64::INFINITY };
                homogeneous.record(relative(&a, &b).max(sign_error), &label);
            }
            (Err(e), _) | (_, Err(e)) => homogeneous.fail(&label, e),
        }
        let below_one: Float = number(draw.uniform(0.1, 0.95), precision);
        let label = format!("ρ={} in phase", below_one.to_f64());
        let exact = match coefficient(&below_one, &Float::from_i64(0, precision)) {
            Ok(exact) => exact,
            Err(e) => {
                in_phase.fail(&label, e);
                continue;
            }
        };
        let mut points = Vec::new();
        let mut smallest_phase = None;
        for phi in NEAR_IN_PHASE {
            match coefficient(&below_one, &number(phi, precision)) {
                Ok(value) => {
                    points.push((phi.ln(), value.clone().abs().to_f64().ln()));
                    smallest_phase = Some((phi, value));
                }
                Err(e) => in_phase.fail(&label, e),
            }
        }
        if points.len() == NEAR_IN_PHASE.len() {
            let order = least_squares_slope(&points);
            orders.push(order);
            let not_zero = if exact == 0 { 0.0 } else { f64::INFINITY };
            let asymptote_error = smallest_phase.map_or(f64::INFINITY, |(phi, value)| {
                let rho = below_one.clone();
                let phi: Float = number(phi, precision);
                let asymptote = -(rho.clone() * &rho * &phi * &phi * 8i32) / ((rho.int(1) - &rho) * 3i32);
                relative(&value, &asymptote)
            });
            worst_asymptote = worst_asymptote.max(asymptote_error);
            in_phase.record((order - 2.0).abs().max(not_zero).max(asymptote_error), &label);
        }
    }
    let (low, high) = orders
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &o| (l.min(o), h.max(o)));
    (
        homogeneous.note(format!("largest I drawn: {largest:.6e} (all negative)")),
        in_phase.note(format!(
            "I(ρ,0) = 0 exactly; fitted orders of I(ρ,φ) → 0 in [{low:.4}, {high:.4}]; at φ = 1e-6 within {worst_asymptote:.1e} of −8ρ²φ²/(3(1 − ρ))"
        )),
    )
}
