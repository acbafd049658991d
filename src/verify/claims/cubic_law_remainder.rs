//! Claim 1 with its proven remainder (proofs/cubic-law-remainder.md): the certified W of
//! each drawn case inside W_N ± the Peano bound, and the sign of K₃ that a two-sided
//! bracket for completely monotone compliances would need.

use super::{Draw, Tally};
use crate::ball::Ball;
use crate::certified::certified_dissipation;
use crate::compliance::{Compliance, ComplianceSpec};
use crate::cycle::LoadCycle;
use crate::exact::{cubic_kernel_majorant, partial_sums, remainder_bounds, SeriesShape};
use crate::real::{Precision, Real};
use crate::verify::generators::compliance_spec;
use crate::verify::{ClaimReport, Proof};

/// A cycle and its compliance on balls, as the certified W reads them.
type BallCase = (LoadCycle<Ball>, Box<dyn Compliance<Ball>>);

/// The working precision of the bounds and partial sums.
const BITS: u32 = 128;

/// A drawn case: P0 = 1, P1 ∈ (0.01, 0.1), ρ ∈ (0.2, 3), φ ∈ (0.1π, 0.9π), f, λ and a
/// compliance admissible on [0.5, 1.5] (P_T ≥ 1 − (1 + ρ)P1 > 0.5).
struct RemainderCase {
    cycle: LoadCycle<f64>,
    compliance: String,
}

impl RemainderCase {
    fn draw(draw: &mut Draw) -> Self {
        let (rho, phase) = (draw.uniform(0.2, 3.0), draw.uniform(0.1, 0.9) * std::f64::consts::PI);
        let (friction, lambda, p1) = (draw.uniform(0.3, 1.0), draw.uniform(1.0, 1.5), draw.uniform(0.01, 0.1));
        let compliance = compliance_spec(draw, 0.5, 1.5, 1.0);
        let cycle = LoadCycle {
            mean_normal_load: 1.0,
            normal_amplitude: p1,
            mean_tangential_load: 0.0,
            tangential_amplitude: rho * friction * p1,
            phase,
            friction,
            compliance_ratio: lambda,
        };
        RemainderCase { cycle, compliance }
    }

    fn at(&self, precision: Precision) -> Result<BallCase, String> {
        let compliance = ComplianceSpec::parse(&self.compliance)
            .and_then(|spec| spec.build::<Ball>(precision))
            .map_err(|error| error.to_string())?;
        // f64 values, which every precision reads exactly.
        Ok((self.cycle.clone().map(|x| Ball::from_f64(x, precision)), compliance))
    }

    /// max over N = 1 … 3 of |W − W_N|'s lower end over the bound's upper end (≤ 1: W
    /// lies in every W_N ± bound_N), and |W − W_N|'s upper end over the same for the figure.
    fn worst_ratio(&self) -> Result<(f64, f64), String> {
        let (cycle, compliance) = self.at(Precision::bits(BITS))?;
        let bounds = remainder_bounds(&cycle, compliance.as_ref(), 3).map_err(|e| e.to_string())?;
        let sums = partial_sums(&cycle, compliance.as_ref(), 3).map_err(|e| e.to_string())?;
        let w = certified_dissipation(|precision| self.at(precision), 20)
            .map_err(|e| e.to_string())?
            .enclosure
            .total;
        let span = |x: &Ball| x.real_span().unwrap_or((f64::NAN, f64::NAN));
        let mut worst = (0.0f64, 0.0f64);
        for (sum, bound) in sums.iter().zip(&bounds) {
            let (error_low, error_high) = span(&(w.clone() - sum).abs());
            let bound_high = span(bound).1;
            // A bound of exactly 0 (a polynomial v' of degree ≤ N) needs W = W_N.
            let (proven, figure) = if bound_high > 0.0 {
                (error_low / bound_high, error_high / bound_high)
            } else if error_low > 0.0 {
                (f64::INFINITY, f64::INFINITY)
            } else {
                (0.0, 0.0)
            };
            worst = (worst.0.max(proven), worst.1.max(figure));
        }
        Ok(worst)
    }
}

/// Claim 1's remainder: on drawn cases the certified W lies inside W_N ± the proven bound
/// for N = 1, 2, 3 (error: |W − W_N|/bound, which must be ≤ 1).
pub fn cubic_law_remainder(seed: u64, cases: usize) -> ClaimReport {
    let mut tally = Tally::new(
        "1 cubic law remainder: W inside W_N ± Peano bound",
        Precision::bits(BITS),
        1.0,
    );
    let mut draw = Draw::new(seed);
    let mut tightest = 0.0f64;
    for _ in 0..cases {
        let case = RemainderCase::draw(&mut draw);
        match case.worst_ratio() {
            Ok((ratio, figure)) => {
                tightest = tightest.max(figure);
                tally.record(ratio, &format!("{:?} v'={}", case.cycle, case.compliance));
            }
            Err(error) => tally.record(f64::NAN, &format!("{:?} v'={}: {error}", case.cycle, case.compliance)),
        }
    }
    tally.note(format!(
        "the remainder is derived (Peano kernel, proofs/cubic-law-remainder.md) and its bound enclosed in balls; W inside every W_N ± bound (largest |W − W_N|/bound {tightest:.3}); the sharp bound of each drawn (ρ, φ); over the whole domain, the closed-form row above"
    ))
}

/// The sign of K₃ behind the completely monotone bracket W₂ ≤ W ≤ W₂ + λf²P1⁵(|I₃|/6) max|v''''|:
/// at drawn (ρ, φ), K₃ ≤ 0 at every box end of its norm's boxes (balls, decided), and
/// ‖K₃‖₁ within 3% of |∫K₃| = |I₃|/6, so that K₃'s positive part is at most 1.5% of it.
/// Checked at sampled points, not proved over τ or the (ρ, φ) domain.
pub fn completely_monotone_bracket(seed: u64, cases: usize) -> ClaimReport {
    let mut tally = Tally::new(
        "1 completely monotone bracket: K₃ ≤ 0 sampled",
        Precision::bits(BITS),
        0.03,
    );
    let mut draw = Draw::new(seed);
    let precision = Precision::bits(BITS);
    let mut points = 0;
    for _ in 0..cases {
        let (rho, phase) = (
            draw.uniform(0.01, 10.0),
            draw.uniform(0.01, 0.99) * std::f64::consts::PI,
        );
        let case = format!("ρ={rho} φ={phase}");
        let Ok(shape) = SeriesShape::new(&Ball::from_f64(rho, precision), &Ball::from_f64(phase, precision), 2) else {
            tally.record(f64::NAN, &case);
            continue;
        };
        points += shape.kernels.evaluations;
        let largest = shape.kernels.largest[1].real_span().map_or(f64::NAN, |span| span.1);
        let integral = shape.coefficients[3].real_span().map_or(f64::NAN, |span| -span.1) / 6.0;
        let norm = shape.kernels.norms[1].real_span().map_or(f64::NAN, |span| span.1);
        // Positive somewhere is a failure; else the excess of the norm over |∫K₃|.
        let error = if largest > 0.0 || integral <= 0.0 {
            f64::INFINITY
        } else {
            norm / integral - 1.0
        };
        tally.record(error, &case);
    }
    tally.note(format!(
        "K₃ ≤ 0 decided on balls at all {points} box ends and ‖K₃‖₁ ≤ (1 + worst)·|I₃|/6: checked at {cases} sampled (ρ, φ), not proved"
    ))
}

/// Claim 1 proved over the whole domain: |W − W₁| ≤ λ f² P1⁴ C̄(ρ, φ) max |v⁽³⁾| with the
/// closed-form majorant C̄ of ‖K₂‖₁ ([`cubic_kernel_majorant`]), a derivation
/// (proofs/cubic-law-remainder.md). Its cases check the derivation's computable steps:
/// at (ρ, φ) drawn over the whole domain (ρ from 10⁻⁴ to 10⁴, φ up to 10⁻⁸ from 0 and π)
/// the trapezoid estimate of ‖K₂‖₁ from the exact kernels lies below C̄, and on drawn
/// cases the certified W lies inside W₁ ± the bound (error: estimate/C̄ and |W − W₁|/bound,
/// which must be ≤ 1).
pub fn cubic_law_proved(seed: u64, cases: usize) -> ClaimReport {
    let mut tally = Tally::new(
        "1 cubic law: |W − W₁| ≤ λf²P1⁴·C̄(ρ,φ)·max|v'''|",
        Precision::bits(BITS),
        1.0,
    );
    let mut draw = Draw::new(seed);
    let precision = Precision::bits(BITS);
    let ball = |x: f64| Ball::from_f64(x, precision);
    let upper = |x: &Ball| x.real_span().map_or(f64::NAN, |span| span.1);
    let lower = |x: &Ball| x.real_span().map_or(f64::NAN, |span| span.0);
    // How far C̄ lies above the kernel's norm, for the note.
    let (mut loosest, mut tightest) = (0.0f64, f64::INFINITY);
    for _ in 0..cases {
        let rho = 10f64.powf(draw.uniform(-4.0, 4.0));
        let phase = match draw.below(3) {
            0 => draw.uniform(0.0, 1.0) * std::f64::consts::PI,
            1 => 10f64.powf(-draw.uniform(1.0, 8.0)) * std::f64::consts::PI,
            _ => (1.0 - 10f64.powf(-draw.uniform(1.0, 8.0))) * std::f64::consts::PI,
        };
        let case = format!("ρ={rho:e} φ={phase:e}");
        let shape = SeriesShape::new(&ball(rho), &ball(phase), 1);
        let majorant = cubic_kernel_majorant(&ball(rho), &ball(phase));
        let (Ok(shape), Ok(majorant)) = (shape, majorant) else {
            tally.record(f64::NAN, &case);
            continue;
        };
        let estimate = upper(&shape.kernels.estimates[0]);
        let ratio = lower(&majorant) / upper(&shape.kernels.norms[0]);
        (loosest, tightest) = (loosest.max(ratio), tightest.min(ratio));
        tally.record(estimate / lower(&majorant), &case);
    }
    for _ in 0..cases {
        let case = RemainderCase::draw(&mut draw);
        let described = format!("{:?} v'={}", case.cycle, case.compliance);
        match case.within_majorant_bound() {
            Ok(ratio) => tally.record(ratio, &described),
            Err(error) => tally.record(f64::NAN, &format!("{described}: {error}")),
        }
    }
    let mut report = tally.note(format!(
        "derived (Peano kernel and ‖K₂‖₁ ≤ ½∫σ²d|m| ≤ C̄, proofs/cubic-law-remainder.md); the exact ‖K₂‖₁ below C̄ at {cases} (ρ, φ) over the whole domain (C̄ is {tightest:.1}–{loosest:.1}× it) and W inside W₁ ± the bound on {cases} cases"
    ));
    if report.passed {
        report.proof = Some(Proof::Derivation {
            document: "proofs/cubic-law-remainder.md",
        });
    }
    report
}

impl RemainderCase {
    /// |W − W₁|'s lower end over the upper end of λ f² P1⁴ C̄ max |v⁽³⁾| on [P_T, P0 + P1].
    fn within_majorant_bound(&self) -> Result<f64, String> {
        let (cycle, compliance) = self.at(Precision::bits(BITS))?;
        let rho = cycle.tangential_amplitude.clone() / &(cycle.friction.clone() * &cycle.normal_amplitude);
        let majorant = cubic_kernel_majorant(&rho, &cycle.phase).map_err(|e| e.to_string())?;
        let shape = SeriesShape::new(&rho, &cycle.phase, 1).map_err(|e| e.to_string())?;
        let p1 = &cycle.normal_amplitude;
        let low = cycle.mean_normal_load.clone() - &(shape.kernels.reach.clone() * p1);
        let high = cycle.mean_normal_load.clone() + p1;
        let largest = compliance.derivative_bound(3, &low, &high).ok_or_else(|| {
            format!(
                "no bound on v''' over [{}, {}]",
                low.to_f64_lossy(),
                high.to_f64_lossy()
            )
        })?;
        let bound =
            cycle.compliance_ratio.clone() * &cycle.friction.square() * &p1.square().square() * &majorant * &largest;
        let sums = partial_sums(&cycle, compliance.as_ref(), 1).map_err(|e| e.to_string())?;
        let w = certified_dissipation(|precision| self.at(precision), 20)
            .map_err(|e| e.to_string())?
            .enclosure
            .total;
        let error = (w - &sums[0]).abs();
        let span = |x: &Ball| x.real_span().unwrap_or((f64::NAN, f64::NAN));
        Ok(span(&error).0 / span(&bound).1)
    }
}
