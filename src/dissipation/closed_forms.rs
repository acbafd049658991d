//! Closed forms for the degenerate cycles, each a one-dimensional integral of v'
//! against a linear weight, valid for any compliance:
//!
//! - in phase (φ ≡ 0 mod π), the paper's appendix (Eqs. 26–32), derived again in
//!   proofs/in-phase.md;
//! - constant normal load (P1 = 0): the Cattaneo–Mindlin initial loading curve
//!   u = λf[v(P0) − v(P0 − Q/f)] with Masing's rule gives
//!   W = 4λf² ∫ₐᵇ (a + b − 2y) v'(y) dy, a = P0 − Q1/f, b = P0 (proofs/constant-normal-load.md);
//! - for the Hertz sphere, the Mindlin–Deresiewicz formula.
//!
//! The integrals are written in the offset x = P − P0 and use v'(P0 + x) − v'(P0)
//! where the options ask for it (the weights integrate a constant to zero).

use std::rc::Rc;

use super::assemble::{assemble, Dissipation, Method, Parts};
use super::conditioning::check_case;
use super::error::DissipationError;
use super::options::Options;
use super::segment::Segments;
use super::slope::{knot_offsets, slope_at};
use crate::compliance::{Compliance, SlopeChange};
use crate::cycle::{LoadCycle, ValidCycle};
use crate::quad::{integrate, Integrated, Piece};
use crate::real::Real;

/// W for an in-phase cycle (φ ≡ 0 mod π), the paper's appendix. No slip occurs
/// when Q1 ≤ fP1; otherwise the loading half (HE, the appendix's BA) gives W1 + W2
/// and the unloading half (EB, the appendix's AB) gives W3 + W4, with W3 = W1:
///
/// ```text
/// W1 = λf (Q1/P1) ∫_{−P1}^{P1} x v'(P0 + x) dx
/// W2 = 2λfQ1/(Q1/f − P1) ∫_{−P1}^{−Q1/f} (2x + P1 + Q1/f) v'(P0 + x) dx
/// W4 = 2λfQ1/(Q1/f + P1) ∫_{P1}^{−Q1/f} (2x − P1 + Q1/f) v'(P0 + x) dx
/// ```
/// The phase is not checked: the formula is that of the line the ellipse collapses to.
///
/// ```
/// use microslip::compliance::Persson;
/// use microslip::cycle::{LoadCycle, ValidCycle};
/// use microslip::dissipation::{four_segment, in_phase, Options};
///
/// let cycle = |phase: f64| LoadCycle {
///     mean_normal_load: 1.0,
///     normal_amplitude: 0.4,
///     mean_tangential_load: 0.0,
///     tangential_amplitude: 0.5,
///     phase,
///     friction: 1.0,
///     compliance_ratio: 1.0,
/// };
/// let persson = Persson { gamma: 1.0, sigma: 1.0 };
/// let closed = in_phase(&ValidCycle::new(cycle(0.0))?, &persson, &Options::default())?.total;
/// // The four-segment integrals approach it as φ → 0 (W − W(0) = O(φ)).
/// let near = four_segment(&cycle(1e-4), &persson, &Options::default())?.total;
/// assert!((near / closed - 1.0).abs() < 1e-3);
///
/// // Q1 ≤ fP1: the load line stays inside the stick range and nothing slips.
/// let stuck = LoadCycle { tangential_amplitude: 0.3, ..cycle(0.0) };
/// assert_eq!(in_phase(&ValidCycle::new(stuck)?, &persson, &Options::default())?.total, 0.0);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn in_phase<R: Real>(
    cycle: &ValidCycle<R>,
    compliance: &dyn Compliance<R>,
    options: &Options<R>,
) -> Result<Dissipation<R>, DissipationError> {
    let f = &cycle.friction;
    let p1 = &cycle.normal_amplitude;
    let q1 = &cycle.tangential_amplitude;
    let zero = p1.int(0);
    let Some(terms) = in_phase_terms(cycle) else {
        check_case(cycle, compliance, options)?;
        return assemble(cycle, Parts::nothing(&zero), Method::InPhase, options);
    };
    let q = q1.clone() / f;
    let (j, integrated) = integrate_terms(cycle, compliance, options, terms)?;
    // Error: each piece's estimate carries at most the largest of the three prefactors.
    let prefactor = (f.clone() * q1 * &zero.int(2) / &(q.clone() - p1)).max_of(&(f.clone() * q1 / p1));
    let error = integrated.error.clone() * &prefactor;
    let parts = Parts::from_integrals(in_phase_segments(cycle, j), error, &integrated);
    assemble(cycle, parts, Method::InPhase, options)
}

/// The in-phase closed form's three integrals W1, W2, W4 (without their prefactors) as
/// weighted pieces in the offset x = P − P0, or None when nothing slips (Q1 ≤ fP1).
pub(crate) fn in_phase_terms<'a, R: Real + 'a>(cycle: &LoadCycle<R>) -> Option<[Piece<'a, R>; 3]> {
    let f = &cycle.friction;
    let p1 = &cycle.normal_amplitude;
    let q1 = &cycle.tangential_amplitude;
    if q1.clone() <= f.clone() * p1 {
        return None;
    }
    let q = q1.clone() / f;
    let (q_two, p1_two) = (q.clone(), p1.clone());
    let (q_four, p1_four) = (q.clone(), p1.clone());
    Some([
        Piece::new("W1", -p1.clone(), p1.clone(), |x: &R| x.clone()),
        Piece::new("W2", -p1.clone(), -q.clone(), move |x: &R| {
            x.clone() * &x.int(2) + &p1_two + &q_two
        }),
        Piece::new("W4", p1.clone(), -q.clone(), move |x: &R| {
            x.clone() * &x.int(2) - &p1_four + &q_four
        }),
    ])
}

/// The in-phase segments per unit λ from the integrals of [`in_phase_terms`]: the
/// unloading half (EB) is W1 + W4, the loading half (HE) W1 + W2; BC and CH are empty.
pub(crate) fn in_phase_segments<R: Real>(cycle: &LoadCycle<R>, [j1, j2, j4]: [R; 3]) -> Segments<R> {
    let f = &cycle.friction;
    let p1 = &cycle.normal_amplitude;
    let q1 = &cycle.tangential_amplitude;
    let zero = p1.int(0);
    let q = q1.clone() / f;
    let w1 = f.clone() * q1 / p1 * &j1;
    let w2 = f.clone() * q1 * &zero.int(2) / &(q.clone() - p1) * &j2;
    let w4 = f.clone() * q1 * &zero.int(2) / &(q.clone() + p1) * &j4;
    Segments {
        eb: w1.clone() + &w4,
        bc: zero.clone(),
        ch: zero,
        he: w1 + &w2,
    }
}

/// W at constant normal load (P1 = 0; the phase is irrelevant):
/// W = 4λf² ∫_{−Q1/f}^{0} (−Q1/f − 2x) v'(P0 + x) dx. By the symmetry Q → −Q the
/// unloading (EB) and reloading (HE) halves carry W/2 each.
///
/// ```
/// use microslip::compliance::Polynomial;
/// use microslip::cycle::{LoadCycle, ValidCycle};
/// use microslip::dissipation::{constant_normal_load, Options};
///
/// // v' = 1 − ½(P − P0): the integral above gives W = λ f² (Q1/f)³ · ½ · 2/3 = 0.009
/// // for f = λ = 1 and Q1 = 0.3.
/// let cycle = LoadCycle {
///     mean_normal_load: 1.0,
///     normal_amplitude: 0.0,
///     mean_tangential_load: 0.0,
///     tangential_amplitude: 0.3,
///     phase: 0.0,
///     friction: 1.0,
///     compliance_ratio: 1.0,
/// };
/// let linear = Polynomial { reference: 1.0, coefficients: vec![1.0, -0.5] };
/// let w = constant_normal_load(&ValidCycle::new(cycle)?, &linear, &Options::default())?;
/// assert!((w.total - 0.009).abs() < 1e-16);
/// assert!((w.segments.eb - w.segments.he).abs() < 1e-16);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn constant_normal_load<R: Real>(
    cycle: &ValidCycle<R>,
    compliance: &dyn Compliance<R>,
    options: &Options<R>,
) -> Result<Dissipation<R>, DissipationError> {
    let f = &cycle.friction;
    let ([loop_integral], integrated) =
        integrate_terms(cycle, compliance, options, [constant_normal_load_term(cycle)])?;
    let factor = f.clone() * f * &f.int(2);
    let error = integrated.error.clone() * &factor * &f.int(2);
    let parts = Parts::from_integrals(constant_normal_load_segments(cycle, loop_integral), error, &integrated);
    assemble(cycle, parts, Method::ConstantNormalLoad, options)
}

/// The Masing loop's integral ∫_{−Q1/f}^{0} (−Q1/f − 2x) v'(P0 + x) dx as a weighted piece.
pub(crate) fn constant_normal_load_term<'a, R: Real + 'a>(cycle: &LoadCycle<R>) -> Piece<'a, R> {
    let f = &cycle.friction;
    let q = cycle.tangential_amplitude.clone() / f;
    let q_weight = q.clone();
    Piece::new("Masing loop", -q, f.int(0), move |x: &R| {
        -(x.clone() * &x.int(2)) - &q_weight
    })
}

/// The segments per unit λ at constant normal load from the loop integral: EB and HE
/// carry 2f² times it each.
pub(crate) fn constant_normal_load_segments<R: Real>(cycle: &LoadCycle<R>, loop_integral: R) -> Segments<R> {
    let f = &cycle.friction;
    let zero = f.int(0);
    let half = loop_integral * &(f.clone() * f * &zero.int(2));
    Segments {
        eb: half.clone(),
        bc: zero.clone(),
        ch: zero,
        he: half,
    }
}

/// ∫ w(x) v'(P0 + x) dx for each term, each split at the compliance's knots, integrated
/// together; the values per term, in the order given. A term is the piece of its weight
/// w(x), in the offset x = P − P0. The case is checked (conditioning, admissibility) first.
fn integrate_terms<'a, R: Real, const N: usize>(
    cycle: &ValidCycle<R>,
    compliance: &'a dyn Compliance<R>,
    options: &Options<R>,
    terms: [Piece<'a, R>; N],
) -> Result<([R; N], Integrated<R>), DissipationError> {
    check_case(cycle, compliance, options)?;
    let zero = cycle.mean_normal_load.int(0);
    let slope = Rc::new(slope_at(
        compliance,
        &cycle.mean_normal_load,
        options.remove_constant_slope,
    ));
    let knots = knot_offsets(compliance, &cycle.mean_normal_load);
    let (pieces, term_of_piece) = weighted_pieces(terms, slope, &knots);
    let integrated = integrate(&pieces, &options.settings(&zero))?;
    let mut sums = std::array::from_fn(|_| zero.clone());
    for (value, term) in integrated.values().zip(&term_of_piece) {
        sums[*term] += value;
    }
    Ok((sums, integrated))
}

/// Each term's weight times `slope` (of the offset x = P − P0), split at the `knots`; the
/// pieces, and which term each belongs to.
pub(crate) fn weighted_pieces<'a, R: Real, const N: usize>(
    terms: [Piece<'a, R>; N],
    slope: Rc<SlopeChange<'a, R>>,
    knots: &[R],
) -> (Vec<Piece<'a, R>>, Vec<usize>) {
    let mut pieces = Vec::new();
    let mut term_of_piece = Vec::new();
    for (term, weighted) in terms.into_iter().enumerate() {
        let (slope, weight) = (Rc::clone(&slope), weighted.integrand);
        let integrand: Weighted<'a, R> = Rc::new(move |x: &R| weight(x) * &slope(x));
        for piece in split_at_knots(weighted.label, integrand, &weighted.start, &weighted.end, knots) {
            pieces.push(piece);
            term_of_piece.push(term);
        }
    }
    (pieces, term_of_piece)
}

/// A closed form's integrand in the offset x = P − P0, shared by the pieces it is split into.
type Weighted<'a, R> = Rc<dyn Fn(&R) -> R + 'a>;

/// ∫ₛₜₐᵣₜ^ₑₙd of `integrand` as pieces split at the knots strictly between the limits
/// (in either order), so that v' is one analytic piece on each: a quadrature rule
/// converges only algebraically across a knot, where v'' or v''' jumps.
fn split_at_knots<'a, R: Real>(
    label: &'static str,
    integrand: Weighted<'a, R>,
    start: &R,
    end: &R,
    knots: &[R],
) -> Vec<Piece<'a, R>> {
    let (low, high) = if start <= end { (start, end) } else { (end, start) };
    let mut points = vec![start.clone()];
    let inside = knots.iter().filter(|x| *x > low && *x < high).cloned();
    if start <= end {
        points.extend(inside);
    } else {
        points.extend(inside.rev());
    }
    points.push(end.clone());
    points
        .windows(2)
        .map(|limits| {
            let integrand = Rc::clone(&integrand);
            Piece {
                label,
                integrand: Box::new(move |x: &R| integrand(x)),
                start: limits[0].clone(),
                end: limits[1].clone(),
            }
        })
        .collect()
}

/// How the elastic constants of a Hertz contact map onto E* (λ is (2 − ν)/(2(1 − ν)) in both).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HertzConfiguration {
    /// One elastic sphere (G, ν) on a rigid flat: E* = 2G/(1 − ν); the constant k is 10.
    SphereOnRigidFlat,
    /// Two identical elastic bodies (G, ν): E* = G/(1 − ν); the constant k is 5.
    TwoIdenticalBodies,
}

/// The Mindlin–Deresiewicz dissipation of a Hertz contact under constant normal
/// load P0 and tangential amplitude Q1 (errata item 8):
/// W = 9(2 − ν) f² P0² / (k G a) · [1 − (1 − q)^(5/3) − (5q/6)(1 + (1 − q)^(2/3))], q = Q1/(fP0).
///
/// ```
/// use microslip::compliance::Hertz;
/// use microslip::cycle::{LoadCycle, ValidCycle};
/// use microslip::dissipation::{constant_normal_load, HertzConfiguration, MindlinDeresiewicz, Options};
///
/// let md = MindlinDeresiewicz {
///     shear_modulus: 80.0,
///     poisson_ratio: 0.3,
///     configuration: HertzConfiguration::SphereOnRigidFlat,
/// };
/// let sphere = Hertz { radius: 1.0, contact_modulus: md.contact_modulus() };
/// let (friction, p0, q1) = (0.5, 1.0, 0.25);
/// let cycle = LoadCycle {
///     mean_normal_load: p0,
///     normal_amplitude: 0.0,
///     mean_tangential_load: 0.0,
///     tangential_amplitude: q1,
///     phase: 0.0,
///     friction,
///     compliance_ratio: (2.0 - 0.3) / (2.0 * (1.0 - 0.3)),
/// };
/// let general = constant_normal_load(&ValidCycle::new(cycle)?, &sphere, &Options::default())?.total;
/// let formula = md.dissipation(&friction, &p0, &q1, &sphere.contact_radius(&p0));
/// assert!((general / formula - 1.0).abs() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct MindlinDeresiewicz<R> {
    /// Shear modulus G.
    pub shear_modulus: R,
    /// Poisson's ratio ν.
    pub poisson_ratio: R,
    /// Which bodies are elastic.
    pub configuration: HertzConfiguration,
}

impl<R: Real> MindlinDeresiewicz<R> {
    /// E* for this configuration.
    pub fn contact_modulus(&self) -> R {
        let g = &self.shear_modulus;
        let one_minus_nu = g.int(1) - &self.poisson_ratio;
        match self.configuration {
            HertzConfiguration::SphereOnRigidFlat => g.clone() * &g.int(2) / one_minus_nu,
            HertzConfiguration::TwoIdenticalBodies => g.clone() / one_minus_nu,
        }
    }

    /// The constant k of the formula.
    fn k(&self) -> i64 {
        match self.configuration {
            HertzConfiguration::SphereOnRigidFlat => 10,
            HertzConfiguration::TwoIdenticalBodies => 5,
        }
    }

    /// W for friction f, normal load P0, tangential amplitude Q1 < fP0 and Hertz contact radius a at P0.
    pub fn dissipation(&self, friction: &R, normal_load: &R, tangential_amplitude: &R, contact_radius: &R) -> R {
        let nu = &self.poisson_ratio;
        let q = tangential_amplitude.clone() / &(friction.clone() * normal_load);
        let remaining = q.int(1) - &q;
        let bracket = q.int(1)
            - remaining.powr(&q.ratio(5, 3))
            - q.clone() * &q.ratio(5, 6) * &(q.int(1) + &remaining.powr(&q.ratio(2, 3)));
        let prefactor = (nu.int(2) - nu) * &nu.int(9) * &friction.square() * &normal_load.square()
            / (nu.int(self.k()) * &self.shear_modulus * contact_radius);
        prefactor * &bracket
    }
}
