//! Claim 1 with its proven remainder (proofs/cubic-law-remainder.md): the certified W of
//! each drawn case inside W_N ± the Peano bound, the closed-form majorant over the whole
//! domain, and the two-sided bracket of completely monotone compliances.

use super::{Draw, Tally};
use crate::ball::Ball;
use crate::compliance::{Compliance, ComplianceSpec};
use crate::cycle::LoadCycle;
use crate::digits::enclosure::certified_dissipation;
use crate::exact::{cubic_kernel_majorant, partial_sums, remainders, PeanoKernels, SeriesShape};
use crate::real::{Precision, Real};
use crate::verify::generators::{compliance_spec, Family, Loads};
use crate::verify::ClaimReport;

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
        RemainderCase::draw_with(draw, |draw| compliance_spec(draw, 0.5, 1.5, 1.0))
    }

    /// A drawn case whose compliance is completely monotone: a family other than the
    /// polynomial, plus Hertz's v' ∝ P^(−1/3) every other time.
    fn draw_completely_monotone(draw: &mut Draw) -> Self {
        RemainderCase::draw_with(draw, |draw| {
            let monotone: Vec<Family> = Family::ALL.into_iter().filter(|f| *f != Family::Polynomial).collect();
            let family = monotone[draw.below(monotone.len())];
            let values = draw.parameters(family.parameters());
            let loads = Loads {
                low: 0.5,
                high: 1.5,
                mean: 1.0,
            };
            let mut compliance = family.spec(&values, loads);
            if draw.below(2) == 1 {
                compliance += &format!(" + hertz:r={},estar=1", draw.uniform(0.5, 2.0));
            }
            compliance
        })
    }

    /// The cycle drawn first, then its compliance by `compliance`.
    fn draw_with(draw: &mut Draw, compliance: impl FnOnce(&mut Draw) -> String) -> Self {
        let (rho, phase) = (draw.uniform(0.2, 3.0), draw.uniform(0.1, 0.9) * std::f64::consts::PI);
        let (friction, lambda, p1) = (draw.uniform(0.3, 1.0), draw.uniform(1.0, 1.5), draw.uniform(0.01, 0.1));
        let compliance = compliance(draw);
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
    /// lies in every W_N ± bound_N; infinite where W − W_N is proven outside its enclosure
    /// W_N + [least, greatest]), and |W − W_N|'s upper end over the same for the note.
    fn worst_ratio(&self) -> Result<(f64, f64), String> {
        let (cycle, compliance) = self.at(Precision::bits(BITS))?;
        let enclosures = remainders(&cycle, compliance.as_ref(), 3).map_err(|e| e.to_string())?;
        let sums = partial_sums(&cycle, compliance.as_ref(), 3).map_err(|e| e.to_string())?;
        let w = certified_dissipation(|precision| self.at(precision), 20)
            .map_err(|e| e.to_string())?
            .enclosure
            .total;
        let span = |x: &Ball| x.real_span().unwrap_or((f64::NAN, f64::NAN));
        let mut worst = (0.0f64, 0.0f64);
        for (sum, enclosure) in sums.iter().zip(&enclosures) {
            let difference = span(&(w.clone() - sum));
            if difference.1 < span(&enclosure.least).0 || difference.0 > span(&enclosure.greatest).1 {
                return Ok((f64::INFINITY, f64::INFINITY));
            }
            let (error_low, error_high) = span(&(w.clone() - sum).abs());
            let bound_high = span(&enclosure.bound()).1;
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
        "1 cubic law remainder: W inside W_N + Peano enclosure",
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
        "the remainder is derived (Peano kernel, one-signed on each side of P0, proofs/cubic-law-remainder.md) and enclosed in balls; W inside every W_N + [least, greatest] (largest |W − W_N|/bound {tightest:.3}); the sharp enclosure of each drawn (ρ, φ); over the whole domain, the closed-form row above"
    ))
}

/// The completely monotone bracket W₂ ≤ W ≤ W₂ + λf²P1⁵(|I₃|/6) max|v''''|, proved by a
/// derivation (proofs/cubic-law-remainder.md, "The sign of the kernels"): W ≥ 0 for every
/// admissible compliance makes K₁ ≤ 0, hence K₃ ≤ 0 over the whole (ρ, φ, τ) domain. Its
/// cases check the computable steps: at (ρ, φ) drawn over the whole domain, K₁ and K₃ are
/// nowhere proven positive at points across the support, and the exact ‖K₃‖₁ =
/// |K₄(0+)| + |K₄(0−)| lies below the box bound (error: exact/boxes, ≤ 1); on drawn
/// completely monotone compliances the certified W lies in the bracket (error: 0 inside,
/// infinite where it is proven outside).
pub fn completely_monotone_bracket(seed: u64, cases: usize) -> ClaimReport {
    let mut tally = Tally::new(
        "1 completely monotone bracket: W₂ ≤ W ≤ W₂ + λf²P1⁵(|I₃|/6)·max|v''''|",
        Precision::bits(BITS),
        1.0,
    );
    let mut draw = Draw::new(seed);
    let (mut decided, mut points) = (0, 0);
    for _ in 0..cases {
        let (rho, phase) = whole_domain_shape(&mut draw);
        let case = format!("ρ={rho:e} φ={phase:e}");
        match kernel_signs(rho, phase) {
            Ok(signs) => {
                decided += signs.decided;
                points += signs.points;
                let error = if signs.positive {
                    f64::INFINITY
                } else {
                    signs.exact_over_boxes
                };
                tally.record(error, &case);
            }
            Err(why) => tally.fail(&case, why),
        }
    }
    let (mut lowest, mut highest) = (f64::INFINITY, f64::NEG_INFINITY);
    for _ in 0..cases {
        let case = RemainderCase::draw_completely_monotone(&mut draw);
        let described = format!("{:?} v'={}", case.cycle, case.compliance);
        match case.bracket_position() {
            Ok((low, high)) => {
                (lowest, highest) = (lowest.min(low), highest.max(high));
                // Proven outside [0, 1] fails; inside, or undecided at its ends, passes.
                let outside = high < 0.0 || low > 1.0;
                tally.record(if outside { f64::INFINITY } else { 0.0 }, &described);
            }
            Err(error) => tally.fail(&described, error),
        }
    }
    tally.proved_by(
        "proofs/cubic-law-remainder.md",
        format!(
            "derived (W ≥ 0 for admissible v' ⇒ K₁ ≤ 0 ⇒ K₃ ≤ 0, proofs/cubic-law-remainder.md); K₁, K₃ ≤ 0 decided at {decided} of {points} points over {cases} (ρ, φ) of the whole domain, none positive, the exact ‖K₃‖₁ below the boxes' bound; on {cases} completely monotone cases (W − W₂)/bound in [{lowest:.3}, {highest:.3}] ⊂ [0, 1]"
        ),
    )
}

/// A (ρ, φ) over the whole domain: ρ = 10^U(−4, 4), φ uniform or within 10^U(−8, −1)·π of
/// 0 or of π.
fn whole_domain_shape(draw: &mut Draw) -> (f64, f64) {
    let rho = 10f64.powf(draw.uniform(-4.0, 4.0));
    let phase = match draw.below(3) {
        0 => draw.uniform(0.0, 1.0) * std::f64::consts::PI,
        1 => 10f64.powf(-draw.uniform(1.0, 8.0)) * std::f64::consts::PI,
        _ => (1.0 - 10f64.powf(-draw.uniform(1.0, 8.0))) * std::f64::consts::PI,
    };
    (rho, phase)
}

/// What the balls decide of the signs of K₁ and K₃ at one (ρ, φ).
struct KernelSigns {
    /// Points where both signs were decided ≤ 0.
    decided: usize,
    /// Points evaluated.
    points: usize,
    /// Whether K₁ or K₃ was proven positive anywhere.
    positive: bool,
    /// The exact ‖K₃‖₁ (upper end) over the box bound's lower end.
    exact_over_boxes: f64,
}

/// Points across the support [−L, 1] per side of τ = 0.
const SIGN_POINTS: usize = 32;

/// K₁ and K₃ at points across [−L, 1] on balls, and ‖K₃‖₁ exactly and by boxes.
fn kernel_signs(rho: f64, phase: f64) -> Result<KernelSigns, String> {
    let precision = Precision::bits(BITS);
    let ball = |x: f64| Ball::from_f64(x, precision);
    let kernels = PeanoKernels::new(&ball(rho), &ball(phase), 3).map_err(|e| e.to_string())?;
    let reach = kernels.reach().to_f64_lossy();
    let (mut decided, mut points, mut positive) = (0, 0, false);
    for (from, to, upper) in [(-reach, 0.0, false), (0.0, 1.0, true)] {
        for i in 0..SIGN_POINTS {
            let tau = from + (to - from) * (i as f64 + 0.5) / SIGN_POINTS as f64;
            let Some(values) = kernels.at(&ball(tau), upper) else {
                continue;
            };
            points += 1;
            let spans = [&values[0], &values[2]].map(|k| k.real_span().unwrap_or((f64::NAN, f64::NAN)));
            positive |= spans.iter().any(|span| span.0 > 0.0);
            if spans.iter().all(|span| span.1 <= 0.0) {
                decided += 1;
            }
        }
    }
    let (below, above) = kernels
        .at_origin()
        .ok_or("the kernels at τ = 0 could not be enclosed")?
        .sides
        .swap_remove(1);
    let boxes = kernels.norms().ok_or("the kernels' boxes could not be enclosed")?;
    let upper = |x: &Ball| x.real_span().map_or(f64::NAN, |span| span.1);
    let lower = |x: &Ball| x.real_span().map_or(f64::NAN, |span| span.0);
    Ok(KernelSigns {
        decided,
        points,
        positive,
        exact_over_boxes: upper(&(below.abs() + &above.abs())) / lower(&boxes.norms[1]),
    })
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
        let (rho, phase) = whole_domain_shape(&mut draw);
        let case = format!("ρ={rho:e} φ={phase:e}");
        let boxes = PeanoKernels::new(&ball(rho), &ball(phase), 1)
            .ok()
            .and_then(|kernels| kernels.norms());
        let majorant = cubic_kernel_majorant(&ball(rho), &ball(phase));
        let (Some(boxes), Ok(majorant)) = (boxes, majorant) else {
            tally.record(f64::NAN, &case);
            continue;
        };
        let estimate = upper(&boxes.estimates[0]);
        let ratio = lower(&majorant) / upper(&boxes.norms[0]);
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
    tally.proved_by(
        "proofs/cubic-law-remainder.md",
        format!(
            "derived (Peano kernel and ‖K₂‖₁ ≤ ½∫σ²d|m| ≤ C̄, proofs/cubic-law-remainder.md); the exact ‖K₂‖₁ below C̄ at {cases} (ρ, φ) over the whole domain (C̄ is {tightest:.1}–{loosest:.1}× it) and W inside W₁ ± the bound on {cases} cases"
        ),
    )
}

impl RemainderCase {
    /// (W − W₂)/(λ f² P1⁵ (|I₃|/6) max|v''''|) enclosed (its lower and upper ends), for a
    /// completely monotone compliance: the bracket holds where it lies in [0, 1].
    fn bracket_position(&self) -> Result<(f64, f64), String> {
        let (cycle, compliance) = self.at(Precision::bits(BITS))?;
        let p1 = &cycle.normal_amplitude;
        let rho = cycle.tangential_amplitude.clone() / &(cycle.friction.clone() * p1);
        let shape = SeriesShape::new(&rho, &cycle.phase, 2).map_err(|e| e.to_string())?;
        let low = cycle.mean_normal_load.clone() - &(shape.reach.clone() * p1);
        let high = cycle.mean_normal_load.clone() + p1;
        let largest = compliance
            .derivative_bound(4, &low, &high)
            .ok_or_else(|| format!("no bound on v'''' for {}", compliance.describe()))?;
        let width =
            cycle.compliance_ratio.clone() * &cycle.friction.square() * &p1.powi(5) * &shape.coefficients[3].abs()
                / &p1.int(6)
                * &largest;
        let sums = partial_sums(&cycle, compliance.as_ref(), 2).map_err(|e| e.to_string())?;
        let w = certified_dissipation(|precision| self.at(precision), 20)
            .map_err(|e| e.to_string())?
            .enclosure
            .total;
        let position = (w - &sums[1]) / &width;
        position
            .real_span()
            .ok_or_else(|| "the bracket's position is not finite".to_string())
    }

    /// |W − W₁|'s lower end over the upper end of λ f² P1⁴ C̄ max |v⁽³⁾| on [P_T, P0 + P1].
    fn within_majorant_bound(&self) -> Result<f64, String> {
        let (cycle, compliance) = self.at(Precision::bits(BITS))?;
        let rho = cycle.tangential_amplitude.clone() / &(cycle.friction.clone() * &cycle.normal_amplitude);
        let majorant = cubic_kernel_majorant(&rho, &cycle.phase).map_err(|e| e.to_string())?;
        let shape = SeriesShape::new(&rho, &cycle.phase, 1).map_err(|e| e.to_string())?;
        let p1 = &cycle.normal_amplitude;
        let low = cycle.mean_normal_load.clone() - &(shape.reach.clone() * p1);
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
