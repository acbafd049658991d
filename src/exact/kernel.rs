//! The Peano kernels K_{N+1}(τ; ρ, φ) of the small-amplitude series and rigorous upper
//! bounds on their L¹ norms (proofs/cubic-law-remainder.md).
//!
//! W is a linear functional of g = v' that kills constants: on the scaled cycle
//! (P1 = f = λ = 1, Q1 = ρ) it is ∫ g(P0 + σ) dm(σ) for a signed measure m on [−L, 1],
//! the image of the segment weights under the loads they evaluate v' at. Taylor's formula
//! with integral remainder then gives W − W_N = λ f² P1^(N+3) ∫ v⁽ᴺ⁺²⁾(P0 + P1τ) K_{N+1}(τ) dτ
//! with
//!
//! ```text
//! K_{N+1}(τ) =  ∫_{σ>τ} (σ − τ)ᴺ/N! dm(σ)   (τ > 0)
//! K_{N+1}(τ) = −∫_{σ<τ} (σ − τ)ᴺ/N! dm(σ)   (τ < 0).
//! ```
//!
//! Every load along a segment is c + r cos(θ − γ), so {σ > τ} is an arc of the cycle angle
//! with closed-form ends, and each K_j(τ) is a sum of exact trigonometric integrals
//! ([`super::trig`]): the kernels are computed exactly, not by quadrature, and on Arb
//! balls they are enclosed. Which copy of the arc meets a segment is not decided on
//! balls: every nearby copy is integrated with its length clamped at 0 by `max`. The
//! one decision, whether u lies beyond ±1, reads the ball's whole interval, and where
//! it may not (τ at a load's extreme) the arc's half-width is enclosed by its hull.
//!
//! The norms are exact: W ≥ 0 for every admissible compliance makes K_1 ≤ 0, so every
//! K_{N+1} is one-signed on each side of τ = 0 (≤ 0 above; (−1)^(N+1) below), and
//! ‖K_{N+1}‖₁ = |K_{N+2}(0+)| + |K_{N+2}(0−)|, two evaluations ([`PeanoKernels::at_origin`];
//! the derivation is proofs/cubic-law-remainder.md, "The sign of the kernels").
//!
//! Independently of that derivation, ‖K_{N+1}‖₁ is bounded by boxes in τ
//! ([`PeanoKernels::norms`], the gate's check): K_{N+1}' = −K_N on each
//! side of τ = 0 (where K_{N+1} jumps by I_N/N!), so on a box [a, b] of width h,
//! |K_{N+1}| ≤ min(|K_{N+1}(a)| + (τ − a)S, |K_{N+1}(b)| + (b − τ)S) with S ≥ sup |K_N|,
//! whose integral is at most h(|K_{N+1}(a)| + |K_{N+1}(b)|)/2 + h²S/4. S comes down the
//! same ladder to K_1(τ) = ±m(tail), which moves across a box by at most |m|(box), bounded
//! by the weights' sup times the arc lengths the box sweeps. The boxes are refined where
//! this slack is largest; where they are not refined the bound is still an upper bound.

use super::polynomial_w::{segment_terms, Term};
use super::series::scaled_geometry;
use super::series::SeriesError;
use super::trig::{Interval, TrigPolynomial};
use crate::real::Real;

/// One weight·g(load) term of a segment, with its load as c + r cos(θ − γ).
struct Piece<R> {
    weight: TrigPolynomial<R>,
    weight_bound: R,
    load: TrigPolynomial<R>,
    centre: R,
    radius: R,
    angle: R,
    start: R,
    length: R,
}

/// The kernels K_1 … K_{N+1} at one τ, from one side of 0, and the weighted arc length
/// of the tail region (for the total variation of m over a box).
#[derive(Clone, Debug)]
struct KernelPoint<R> {
    tau: R,
    kernels: Vec<R>,
    tail_arc: R,
}

/// The measure m of a (ρ, φ), prepared for evaluating its Peano kernels.
pub struct PeanoKernels<R> {
    pieces: Vec<Piece<R>>,
    reach: R,
    highest: usize,
}

/// The kernels' integrals over each side of τ = 0 and the series' coefficients, from the
/// kernels at 0± ([`PeanoKernels::at_origin`]).
#[derive(Clone, Debug)]
pub struct AtOrigin<R> {
    /// Index n − 1: (∫_{τ<0} K_{n+1}, ∫_{τ>0} K_{n+1}).
    pub sides: Vec<(R, R)>,
    /// I₀ … I_N.
    pub coefficients: Vec<R>,
}

/// Upper bounds on ‖K_{n+1}‖₁ for n = 1 … N, and how they were reached.
#[derive(Clone, Debug)]
pub struct KernelNorms<R> {
    /// Index n − 1: an upper bound on ‖K_{n+1}‖₁ (a ball whose upper end bounds it).
    pub norms: Vec<R>,
    /// Index n − 1: the trapezoid sum h(|K(a)| + |K(b)|)/2 over the same boxes, an
    /// estimate of ‖K_{n+1}‖₁ from below the bound, for judging its slack.
    pub estimates: Vec<R>,
    /// Index n − 1: the largest K_{n+1}(τ) at the boxes' ends (a sample of its sign, not a
    /// bound over the boxes).
    pub largest: Vec<R>,
    /// L = (P0 − P_T)/P1, how far below P0 the measure reaches in units of P1.
    pub reach: R,
    /// The kernel evaluations the boxes used.
    pub evaluations: usize,
}

/// The relative slack at which the boxes stop being refined.
const SLACK: f64 = 0.02;
/// The most kernel evaluations spent on one (ρ, φ).
const MAX_EVALUATIONS: usize = 1200;
/// Boxes per side of τ = 0 to start from.
const START_BOXES: usize = 24;

impl<R: Real> PeanoKernels<R> {
    /// The kernels of (ρ, φ) up to K_{`highest` + 1}.
    pub fn new(rho: &R, phase: &R, highest: usize) -> Result<Self, SeriesError> {
        let geometry = scaled_geometry(rho, phase)?;
        let reach = -geometry.permanent_stick_offset.clone();
        let mut pieces = Vec::new();
        for (terms, start, length) in segment_terms(&geometry) {
            for Term { weight, load } in terms {
                let (a, b) = (load.cos_coefficient(1), load.sin_coefficient(1));
                pieces.push(Piece {
                    weight_bound: weight.magnitude(),
                    weight,
                    centre: load.cos_coefficient(0),
                    radius: a.hypot(&b),
                    angle: b.atan2(&a),
                    load,
                    start: start.clone(),
                    length: length.clone(),
                });
            }
        }
        Ok(PeanoKernels { pieces, reach, highest })
    }

    /// L = (P0 − P_T)/P1.
    pub fn reach(&self) -> &R {
        &self.reach
    }

    /// K_1(τ) … K_{N+1}(τ) (index j − 1), τ taken on the side of 0 that `upper` names
    /// (τ = 0 itself from either side).
    /// `None` where τ is a load's extreme to within a ball's width.
    pub fn at(&self, tau: &R, upper: bool) -> Option<Vec<R>> {
        self.point(tau, upper).map(|point| point.kernels)
    }

    /// The kernels at τ. Where u may be ±1 (τ at a load's extreme to within a ball's width)
    /// the arc's half-width is enclosed by the hull of its possible values; `None` only
    /// where u may be both (a load of near-zero amplitude).
    fn point(&self, tau: &R, upper: bool) -> Option<KernelPoint<R>> {
        let zero = tau.int(0);
        let turn = zero.pi_like() * &zero.int(2);
        let mut kernels = vec![zero.clone(); self.highest + 1];
        let mut tail_arc = zero.clone();
        for piece in &self.pieces {
            // The tail {load > τ} (upper) or {load < τ}: cos(θ − centre) > u.
            let (u, centre) = if upper {
                ((tau.clone() - &piece.centre) / &piece.radius, piece.angle.clone())
            } else {
                (
                    (piece.centre.clone() - tau) / &piece.radius,
                    piece.angle.clone() + &zero.pi_like(),
                )
            };
            let one = zero.int(1);
            let (low, high) = span(&u);
            let half_width = if low >= 1.0 {
                continue;
            } else if high <= -1.0 {
                zero.pi_like()
            } else if low > -1.0 && high < 1.0 {
                (one - &u.square()).sqrt().atan2(&u)
            } else if low > -1.0 {
                // u may be 1 (τ at the load's largest value, as at φ = π/2 where a slip
                // load's top is P0): the half-width lies in [0, acos(low)].
                zero.union(&arc_half_width(low, &zero))
            } else if high < 1.0 {
                zero.pi_like().union(&arc_half_width(high, &zero))
            } else {
                return None;
            };
            let first = centre - &half_width;
            // Which copy of the arc lies first past the segment's start: chosen in f64, the
            // copies k − 2 … k + 2 cover every overlap whatever the choice.
            let k = ((first.clone() - &piece.start) / &turn).to_f64_lossy().floor();
            let end = piece.start.clone() + &piece.length;
            let shifted = piece.load.plus(&TrigPolynomial::constant(-tau.clone()));
            let sign = if upper { tau.int(1) } else { -tau.int(1) };
            for copy in -2..=2 {
                let from = first.clone() + &(turn.clone() * &zero.int(copy - k as i64));
                let to = from.clone() + &half_width + &half_width;
                let lo = from.max_of(&piece.start);
                let length = (to.min_of(&end) - &lo).max_of(&zero);
                if surely_zero(&length) {
                    continue;
                }
                tail_arc += &(piece.weight_bound.clone() * &length);
                let interval = Interval::new(&lo, &length, self.highest + 2);
                let mut integrand = piece.weight.clone();
                let mut factorial = tau.int(1);
                for (j, kernel) in kernels.iter_mut().enumerate() {
                    if j > 0 {
                        integrand = integrand.times(&shifted);
                        factorial *= &zero.int(j as i64);
                    }
                    *kernel += &(integrand.integral_over(&interval) / &factorial * &sign);
                }
            }
        }
        Some(KernelPoint {
            tau: tau.clone(),
            kernels,
            tail_arc,
        })
    }

    /// The kernels at `tau` or, where a load's extreme lies there, at the nearest of a few
    /// points moved towards `towards` by a millionth of the distance (a box's end may be
    /// anywhere; it only has to be where the kernels were evaluated).
    fn point_near(&self, tau: f64, towards: f64, upper: bool) -> Option<KernelPoint<R>> {
        let precision = self.reach.precision();
        (0..4).find_map(|attempt| {
            let moved = tau + (towards - tau) * 1e-6 * f64::from(attempt);
            self.point(&R::from_f64(moved, precision), upper)
        })
    }

    /// What the kernels just above and below τ = 0 give, with N = `highest`: the integrals of
    /// K_{n+1} over τ < 0 and over τ > 0 for n = 1 … N − 1 (index n − 1), −K_{n+2}(0−) and
    /// K_{n+2}(0+), since K_{n+2}' = −K_{n+1} on each side and K_{n+2} vanishes past the
    /// support; and the coefficients I₀ … I_N from the jumps K_{n+1}(0+) − K_{n+1}(0−) = Iₙ/n!.
    /// K_{n+1} is one-signed on each side (proofs/cubic-law-remainder.md, "The sign of the
    /// kernels"), so ‖K_{n+1}‖₁ is the sum of its sides' magnitudes. `None` where the kernels
    /// at τ = 0 cannot be enclosed (a load's extreme there to within the working precision,
    /// or a load of zero amplitude).
    pub fn at_origin(&self) -> Option<AtOrigin<R>> {
        let zero = self.reach.int(0);
        let (above, below) = (self.at(&zero, true)?, self.at(&zero, false)?);
        let sides: Vec<(R, R)> = (2..=self.highest)
            .map(|j| (-below[j].clone(), above[j].clone()))
            .collect();
        let mut factorial = zero.int(1);
        let coefficients: Vec<R> = (0..=self.highest)
            .map(|n| {
                if n > 0 {
                    factorial *= &zero.int(n as i64);
                }
                (above[n].clone() - &below[n]) * &factorial
            })
            .collect();
        let finite = sides
            .iter()
            .all(|(below, above)| below.is_finite() && above.is_finite())
            && coefficients.iter().all(R::is_finite);
        finite.then_some(AtOrigin { sides, coefficients })
    }

    /// Upper bounds on ‖K_{n+1}‖₁, n = 1 … N, by boxes in τ over [−L, 1].
    /// `None` where the kernels cannot be enclosed at a box's end: a load's extreme
    /// there stays undecided (τ = 0, where K_{N+1} jumps, is not moved), or the measure
    /// is degenerate (a load of zero amplitude, a non-finite geometry). One loop: the
    /// boxes on both sides of τ = 0 are refined together, where the slack is largest.
    pub fn norms(&self) -> Option<KernelNorms<R>> {
        // Past the support [−L, 1] every tail is surely empty and the kernels vanish.
        let low = -upper_f64(&self.reach) * (1.0 + 1e-9) - f64::MIN_POSITIVE;
        let high = 1.0 + 1e-9;
        let mut evaluations = 0;
        let mut sides = Vec::with_capacity(2);
        for (from, to, upper) in [(low, 0.0, false), (0.0, high, true)] {
            let mut points = Vec::with_capacity(START_BOXES + 1);
            for i in 0..=START_BOXES {
                let t = match i {
                    0 => from,
                    START_BOXES => to,
                    _ => from + (to - from) * i as f64 / START_BOXES as f64,
                };
                evaluations += 1;
                let point = if i == 0 || i == START_BOXES {
                    self.point(&R::from_f64(t, self.reach.precision()), upper)
                } else {
                    self.point_near(t, to, upper)
                };
                points.push(point?);
            }
            sides.push(points);
        }
        loop {
            let boxes: Vec<Vec<BoxBound<R>>> = sides
                .iter()
                .map(|points| points.windows(2).map(|w| self.box_bound(&w[0], &w[1])).collect())
                .collect();
            let all = || boxes.iter().flatten();
            let (bounds, estimates) = self.totals(all());
            let scales: Vec<f64> = bounds.iter().map(|b| b.to_f64_lossy().max(f64::MIN_POSITIVE)).collect();
            let slack_of = |b: &BoxBound<R>| -> f64 {
                b.bounds
                    .iter()
                    .zip(&b.estimates)
                    .zip(&scales)
                    .map(|((bound, estimate), scale)| (bound.to_f64_lossy() - estimate.to_f64_lossy()) / scale)
                    .fold(0.0, f64::max)
            };
            let worst = bounds
                .iter()
                .zip(&estimates)
                .map(|(b, e)| b.to_f64_lossy() / e.to_f64_lossy().max(f64::MIN_POSITIVE) - 1.0)
                .fold(0.0, f64::max);
            if !bounds.iter().all(R::is_finite) {
                return None;
            }
            let count = all().count();
            if worst <= SLACK || evaluations + count / 2 > MAX_EVALUATIONS || !worst.is_finite() {
                let largest = (1..=self.highest)
                    .map(|j| {
                        let mut values = sides.iter().flatten().map(|point| point.kernels[j].clone());
                        let first = values.next().unwrap_or_else(|| self.reach.int(0));
                        values.fold(first, |acc, value| acc.max_of(&value))
                    })
                    .collect();
                return Some(KernelNorms {
                    norms: bounds,
                    estimates,
                    largest,
                    reach: self.reach.clone(),
                    evaluations,
                });
            }
            let slacks: Vec<Vec<f64>> = boxes.iter().map(|side| side.iter().map(slack_of).collect()).collect();
            let mean = slacks.iter().flatten().sum::<f64>() / count as f64;
            for (points, (slack, upper)) in sides.iter_mut().zip(slacks.iter().zip([false, true])) {
                let mut refined = Vec::with_capacity(points.len() * 2);
                for (i, pair) in points.windows(2).enumerate() {
                    refined.push(pair[0].clone());
                    if slack[i] >= mean {
                        let (a, b) = (pair[0].tau.to_f64_lossy(), pair[1].tau.to_f64_lossy());
                        evaluations += 1;
                        refined.push(self.point_near((a + b) / 2.0, b, upper)?);
                    }
                }
                refined.push(points[points.len() - 1].clone());
                *points = refined;
            }
        }
    }

    /// The sums of the boxes' bounds and trapezoid estimates, per order.
    fn totals<'a>(&self, boxes: impl Iterator<Item = &'a BoxBound<R>>) -> (Vec<R>, Vec<R>)
    where
        R: 'a,
    {
        let zero = self.reach.int(0);
        let mut bounds = vec![zero.clone(); self.highest];
        let mut estimates = vec![zero; self.highest];
        for b in boxes {
            for n in 0..self.highest {
                bounds[n] += &b.bounds[n];
                estimates[n] += &b.estimates[n];
            }
        }
        (bounds, estimates)
    }

    /// ∫ over [a, b] of |K_{n+1}| bounded for n = 1 … N (the module doc's ladder).
    fn box_bound(&self, a: &KernelPoint<R>, b: &KernelPoint<R>) -> BoxBound<R> {
        let width = (b.tau.clone() - &a.tau).abs();
        let half = width.clone() / &width.int(2);
        let ends = |j: usize| (a.kernels[j].abs(), b.kernels[j].abs());
        let (k1a, k1b) = ends(0);
        // sup |K_1| over the box: an end value moved by at most |m|(box).
        let mut sup = k1a.min_of(&k1b) + &(a.tail_arc.clone() - &b.tail_arc).abs();
        let (mut bounds, mut estimates) = (Vec::with_capacity(self.highest), Vec::with_capacity(self.highest));
        for j in 1..=self.highest {
            let (ka, kb) = ends(j);
            let mean = (ka + &kb) / &width.int(2);
            let trapezoid = mean.clone() * &width;
            bounds.push(trapezoid.clone() + &(sup.clone() * &width * &half / &width.int(2)));
            estimates.push(trapezoid);
            // sup |K_{j+1}| ≤ (|K(a)| + |K(b)|)/2 + h·sup |K_j|/2.
            sup = mean + &(sup * &half);
        }
        BoxBound { bounds, estimates }
    }
}

/// One box's bounds and trapezoid estimates, per order.
struct BoxBound<R> {
    bounds: Vec<R>,
    estimates: Vec<R>,
}

/// acos(u) for an f64 u in [−1, 1], at the precision of `like`.
fn arc_half_width<R: Real>(u: f64, like: &R) -> R {
    let u = R::from_f64(u.clamp(-1.0, 1.0), like.precision());
    (like.int(1) - &u.square()).max_of(like).sqrt().atan2(&u)
}

/// The real interval of a value, outward in f64 (a number: itself).
fn span<R: Real>(x: &R) -> (f64, f64) {
    x.real_span().unwrap_or_else(|| (x.to_f64_lossy(), x.to_f64_lossy()))
}

/// Whether a value is certainly 0 or below (for a ball: its whole interval), so that a
/// piece of that length can be left out; asks no comparison of a ball.
fn surely_zero<R: Real>(length: &R) -> bool {
    span(length).1 <= 0.0
}

/// C̄(ρ, φ), a closed-form majorant of ‖K₂‖₁, the cubic law's kernel, over the whole
/// (ρ, φ) domain: |W − W₁| ≤ λ f² P1⁴ C̄(ρ, φ) max over [P_T, P0 + P1] of |v⁽³⁾|
/// (proofs/cubic-law-remainder.md, "A majorant over the whole domain").
///
/// ‖K₂‖₁ ≤ ½ ∫ σ² d|m|, and |m| is at most the image of |weight| dθ, so each term of a
/// segment contributes at most its weight's bound times the largest σ² of its load times
/// the segment's length. With the slip and stick angles α and β (α + β = π), the slip
/// amplitudes σ± and the reach L = (σ₊ + σ₋)/2 of the slip loads below P0:
///
/// ```text
/// C̄ = (ρ/2)·[α(2 + (σ₊ + σ₋)L²) + β(1 + ρ/2 + σ₋)].
/// ```
pub fn cubic_kernel_majorant<R: Real>(rho: &R, phase: &R) -> Result<R, SeriesError> {
    let geometry = scaled_geometry(rho, phase)?;
    let (plus, minus) = (&geometry.sum_amplitude, &geometry.difference_amplitude);
    let reach = -geometry.permanent_stick_offset.clone();
    let one = rho.int(1);
    let slipping = geometry.slip_angle.clone() * &(one.int(2) + &((plus.clone() + minus) * &reach.square()));
    let sticking = geometry.stick_angle.clone() * &(one + &(rho.clone() / &rho.int(2)) + minus);
    Ok((slipping + &sticking) * rho / &rho.int(2))
}

/// An f64 at or above the value (for a ball: above its whole interval).
fn upper_f64<R: Real>(x: &R) -> f64 {
    let high = span(x).1;
    if x.real_span().is_some() {
        high
    } else {
        high + high.abs() * 4.0 * f64::EPSILON
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exact::series_coefficients;

    /// K_1 ≤ 0 and K_3 ≤ 0 everywhere, K_2 ≥ 0 below τ = 0 and ≤ 0 above (the signs W ≥ 0
    /// forces), across ρ from 10⁻³ to 10³ and φ over (0, π); and the exact norms agree with
    /// the boxes' bound: below it, and within the 20% that a budget-capped refinement leaves.
    #[test]
    fn the_odd_kernels_are_never_positive_and_the_norms_are_exact() {
        let pi = std::f64::consts::PI;
        for i in 0..13 {
            let rho = 10f64.powf(-3.0 + 0.5 * i as f64);
            for j in 1..12 {
                let phase = pi * j as f64 / 12.0;
                let kernels = PeanoKernels::new(&rho, &phase, 3).unwrap();
                let reach = *kernels.reach();
                // The largest |K_j| seen, for a rounding tolerance.
                let mut scale = [0.0f64; 3];
                let mut worst = [f64::NEG_INFINITY; 3];
                for t in 0..200 {
                    let tau = -reach + (1.0 + reach) * (t as f64 + 0.5) / 200.0;
                    let values = kernels.at(&tau, tau > 0.0).unwrap();
                    let side = if tau > 0.0 { 1.0 } else { -1.0 };
                    for (n, signed) in [values[0], side * values[1], values[2]].into_iter().enumerate() {
                        scale[n] = scale[n].max(signed.abs());
                        worst[n] = worst[n].max(signed);
                    }
                }
                for n in 0..3 {
                    assert!(
                        worst[n] <= 1e-12 * scale[n],
                        "ρ = {rho}, φ = {phase}: K{} reaches {:e} (scale {:e})",
                        n + 1,
                        worst[n],
                        scale[n]
                    );
                }
                let exact: Vec<f64> = kernels
                    .at_origin()
                    .unwrap()
                    .sides
                    .iter()
                    .map(|(below, above)| below.abs() + above.abs())
                    .collect();
                let boxes = kernels.norms().unwrap();
                for (n, (exact, bound)) in exact.iter().zip(&boxes.norms).enumerate() {
                    assert!(
                        *exact <= *bound && *exact >= bound / 1.2,
                        "ρ = {rho}, φ = {phase}: ‖K{}‖₁ = {exact:e}, boxes {bound:e}",
                        n + 2
                    );
                }
            }
        }
    }

    /// ∫ K_{N+1} = I_{N+1}/(N+1)! and the jump at 0 is I_N/N!, from the kernels' values.
    #[test]
    fn kernels_integrate_to_the_next_coefficient_and_jump_by_the_last() {
        for (rho, phase) in [(0.5, 1.0), (2.0, 0.3), (1.3, 2.6)] {
            let kernels = PeanoKernels::new(&rho, &phase, 3).unwrap();
            let coefficients = series_coefficients(&rho, &phase, 4).unwrap();
            let low = -kernels.reach();
            // Composite Simpson on each side of the jump.
            let simpson = |from: f64, to: f64, upper: bool| {
                let n = 4000;
                let h = (to - from) / n as f64;
                let mut sums = vec![0.0; 4];
                for i in 0..=n {
                    let w = if i == 0 || i == n {
                        1.0
                    } else if i % 2 == 1 {
                        4.0
                    } else {
                        2.0
                    };
                    for (sum, k) in sums.iter_mut().zip(kernels.at(&(from + i as f64 * h), upper).unwrap()) {
                        *sum += w * k * h / 3.0;
                    }
                }
                sums
            };
            let (below, above) = (simpson(low, 0.0, false), simpson(0.0, 1.0, true));
            let mut factorial = 1.0;
            for n in 1..=3 {
                factorial *= (n + 1) as f64;
                let integral = below[n] + above[n];
                let expected = coefficients[n + 1].0 / factorial;
                assert!(
                    (integral - expected).abs() < 1e-6 * (1.0 + expected.abs()),
                    "{rho} {phase} {n}: {integral} {expected}"
                );
                let jump = kernels.at(&0.0, true).unwrap()[n] - kernels.at(&0.0, false).unwrap()[n];
                let last = coefficients[n].0 / (factorial / (n + 1) as f64);
                assert!((jump - last).abs() < 1e-12 * (1.0 + last.abs()), "{rho} {phase} {n}");
            }
        }
    }
}
