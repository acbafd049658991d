//! Claim 1, the cubic law (paper Section 5.1).

use rug::Float;

use super::evaluator::{tally_cases, Failure, Measured, Outcome};
use super::{number, Tally};
use crate::compliance::ComplianceSpec;
use crate::cycle::LoadCycle;
use crate::dissipation::{dissipation, Options};
use crate::real::{Precision, Real};
use crate::verify::generators::compliance_spec;
use crate::verify::small_amplitude::coefficient;
use crate::verify::ClaimReport;

/// The exponents k of the amplitudes P1 = P0·2^(−k) the order is fitted over.
const EXPONENTS: std::ops::RangeInclusive<i32> = 8..=15;

/// A case of claim 1: the shape ρ = Q1/(fP1) and φ/π, f, λ and the compliance.
#[derive(Clone, PartialEq)]
pub struct CubicLawCase {
    /// ρ = Q1/(fP1).
    pub rho: f64,
    /// φ/π.
    pub phase_fraction: f64,
    /// f.
    pub friction: f64,
    /// λ.
    pub lambda: f64,
    /// v' as a SPEC, admissible on [0.5, 1.5].
    pub compliance: String,
}

impl std::fmt::Display for CubicLawCase {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "ρ={} φ={}π f={} λ={} v'={}",
            self.rho, self.phase_fraction, self.friction, self.lambda, self.compliance
        )
    }
}

/// Claim 1 for one case: the order of W/(λf²P1³v''(P0)) → I(ρ, φ) fitted over
/// P1 = P0·2^(−k), k = 8 … 15, at 160 bits; the error is |order − 1| and the figure
/// (order, relative error of the ratio at k = 15).
pub fn cubic_law_order(case: &CubicLawCase) -> Outcome {
    let precision = Precision::bits(160);
    let compliance = ComplianceSpec::parse(&case.compliance)
        .and_then(|spec| spec.build::<Float>(precision))
        .map_err(|_| Failure::Failed("spec did not parse".into()))?;
    let phase = Float::pi(precision) * number::<Float>(case.phase_fraction, precision);
    let rho: Float = number(case.rho, precision);
    let limit = coefficient(&rho, &phase).map_err(|_| Failure::Failed("I(ρ, φ) failed".into()))?;
    let one = Float::from_i64(1, precision);
    let curvature = compliance.curvature(&one);
    let (f, lambda): (Float, Float) = (number(case.friction, precision), number(case.lambda, precision));
    let mut points = Vec::new();
    for k in EXPONENTS {
        let p1 = Float::from_i64(2, precision).powi(-k);
        let cycle = LoadCycle {
            mean_normal_load: one.clone(),
            normal_amplitude: p1.clone(),
            mean_tangential_load: one.int(0),
            tangential_amplitude: rho.clone() * &f * &p1,
            phase: phase.clone(),
            friction: f.clone(),
            compliance_ratio: lambda.clone(),
        };
        let result = dissipation(&cycle, compliance.as_ref(), &Options::default())
            .map_err(|error| Failure::Failed(error.to_string()))?;
        let scale = lambda.clone() * &f * &f * &p1.clone().powi(3) * &curvature;
        let ratio = result.total / scale;
        let error = ((ratio - &limit) / &limit).abs().to_f64();
        points.push((-f64::from(k), error.log2()));
    }
    let order = least_squares_slope(&points);
    Ok(Measured {
        error: (order - 1.0).abs(),
        rounding: 0.0,
        figure: Some((order, points[points.len() - 1].1.exp2())),
    })
}

/// Claim 1: W/(λf²P1³v''(P0)) → I(ρ, φ) as P1 = P0·2^(−k) → 0 with error O(P1), for
/// every compliance: the order fitted over k = 8 … 15 must be 1 ± 0.1. Random
/// compliances, ρ ∈ (0.2, 3), φ ∈ (0.1π, 0.9π) (near 0 and π, I itself vanishes for
/// ρ < 1 and the O(P1) term dominates longer), random f and λ. At 160 bits: the ratio's
/// error at k = 15 is ~1e−5 of a W that f64 would hold only to ~1e−11 after the
/// cancellation between segments.
pub fn cubic_law(seed: u64, cases: usize) -> ClaimReport {
    let mut tally = Tally::new(
        "1 cubic law: fitted order of W/(λf²P1³v'') → I",
        Precision::bits(160),
        0.1,
    );
    let figures = tally_cases(
        &mut tally,
        seed,
        cases,
        |draw| {
            let (rho, phase_fraction) = (draw.uniform(0.2, 3.0), draw.uniform(0.1, 0.9));
            let friction = draw.uniform(0.3, 1.0);
            let lambda = draw.uniform(1.0, 1.5);
            let compliance = compliance_spec(draw, 0.5, 1.5, 1.0);
            CubicLawCase {
                rho,
                phase_fraction,
                friction,
                lambda,
                compliance,
            }
        },
        cubic_law_order,
    );
    let range = |values: &mut dyn Iterator<Item = f64>| {
        values.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), o| (l.min(o), h.max(o)))
    };
    let (low, high) = range(&mut figures.iter().map(|figure| figure.0));
    let (smallest, largest) = range(&mut figures.iter().map(|figure| figure.1));
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
