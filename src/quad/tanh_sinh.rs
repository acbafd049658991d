//! Tanh–sinh (double-exponential) quadrature at any precision.
//!
//! The substitution x = tanh(π/2 · sinh u) crowds nodes toward both ends
//! double-exponentially, so integrable end-point singularities (x^(−1/2),
//! ln x, square-root end points) converge about as fast as smooth integrands:
//! each halving of the step roughly doubles the correct digits. Abscissae near
//! an end are formed from the distance to that end, never as 1 − tanh(·), so
//! no digits are lost there.

use std::sync::Arc;

use super::Estimate;
use crate::real::{Precision, Real};

/// One level's nodes u = offset + j·spacing, j = 0, 1, … ≤ u_max (level 0: u = 0, 1, 2, …;
/// level k ≥ 1: the odd multiples of 2^−k, the nodes the level adds), each as the
/// distance of x(u) from the nearer end in half widths and the weight.
#[derive(Clone, Debug)]
pub struct Level<R> {
    /// Whether the first node is the midpoint u = 0 (level 0), counted once.
    pub has_middle: bool,
    /// (1 − tanh s, w(u)) with s = π/2 · sinh u, for u increasing.
    pub nodes: Vec<(R, R)>,
}

/// Levels up to this one are cached; the rarely reached finer ones (each twice the
/// nodes of the one before) are computed per call rather than held.
const MAX_CACHED_LEVEL: u32 = 12;

/// The nodes of `level` at `precision`, computed once per (number type, level, precision)
/// for the levels up to `MAX_CACHED_LEVEL`.
pub fn nodes<R: Real>(level: u32, precision: Precision) -> Arc<Level<R>> {
    if level > MAX_CACHED_LEVEL {
        return Arc::new(compute_level(level, precision));
    }
    super::cache::cached(level as usize, precision, || compute_level(level, precision))
}

/// The largest u at `precision`: where the weight falls below 2^(−2·bits), the tails
/// being negligible there.
fn u_max(precision: Precision) -> f64 {
    let s_max = f64::from(precision.in_bits()) * std::f64::consts::LN_2 + 20.0;
    (2.0 * s_max / std::f64::consts::PI).asinh()
}

fn compute_level<R: Real>(level: u32, precision: Precision) -> Level<R> {
    let (start, spacing) = if level == 0 {
        (0.0, 1.0)
    } else {
        let spacing = 0.5f64.powi(level as i32);
        (spacing, 2.0 * spacing)
    };
    let half_pi = R::pi(precision) / R::from_i64(2, precision);
    let u_max = u_max(precision);
    let mut nodes = Vec::new();
    for index in 0usize.. {
        let u_f64 = start + spacing * index as f64;
        if u_f64 > u_max {
            break;
        }
        let u = R::from_f64(u_f64, precision);
        let exp_u = u.exp();
        let sinh_u = (exp_u.clone() - &(exp_u.int(1) / &exp_u)) / u.int(2);
        let cosh_u = (exp_u.clone() + &(exp_u.int(1) / &exp_u)) / u.int(2);
        let s = half_pi.clone() * &sinh_u;
        // Distance of the node from the nearer end, in units of the half width: 1 − tanh s = 2/(1 + e^{2s}).
        let e2s = (s.clone() * s.int(2)).exp();
        let complement = s.int(2) / (e2s.clone() + s.int(1));
        let one_plus_t = s.int(2) - &complement;
        let weight = half_pi.clone() * &cosh_u * &complement * &one_plus_t;
        nodes.push((complement, weight));
    }
    Level {
        has_middle: level == 0,
        nodes,
    }
}

/// The integrand at the abscissae of one level on [a, b].
struct Transform<R> {
    a: R,
    b: R,
    half_width: R,
}

impl<R: Real> Transform<R> {
    fn new(a: &R, b: &R) -> Self {
        Transform {
            a: a.clone(),
            b: b.clone(),
            half_width: (b.clone() - a) / a.int(2),
        }
    }

    /// Σ over the level's nodes (and their mirrors −u) of w(u)·[f(x(u)) + f(x(−u))]; the
    /// midpoint of level 0 is counted once.
    fn sum<F: FnMut(&R) -> R>(&self, integrand: &mut F, level: &Level<R>, evaluations: &mut usize) -> R {
        let mut total = self.a.int(0);
        for (index, (complement, weight)) in level.nodes.iter().enumerate() {
            if level.has_middle && index == 0 {
                let middle = (self.a.clone() + &self.b) / self.a.int(2);
                total += weight.clone() * integrand(&middle);
                *evaluations += 1;
                continue;
            }
            // A node that rounds onto an end is skipped on that side only: near a
            // singular end the other side's nodes still matter far below the rounding of b − offset.
            let offset = self.half_width.clone() * complement;
            let left = self.a.clone() + &offset;
            let right = self.b.clone() - &offset;
            let mut values = self.a.int(0);
            let mut inside = false;
            for (node, is_inside) in [(&left, left > self.a), (&right, right < self.b)] {
                if is_inside {
                    values += integrand(node);
                    *evaluations += 1;
                    inside = true;
                }
            }
            if !inside {
                break;
            }
            total += weight.clone() * &values;
        }
        total
    }
}

/// ∫ₐᵇ f to an absolute tolerance, halving the step (one level) until two
/// successive levels agree to `tolerance` or `max_level` is reached (then
/// `converged` is false). The integrand is never evaluated at a or b.
///
/// It also gives up (not converged) when two levels running, from level 5 on, fail to
/// bring the difference between levels below a tenth of the smallest seen: a rule that
/// converges gains digits with every level by then, and one that stops gaining has
/// reached the rounding noise of the integrand, which further levels, each twice as
/// costly, cannot get below. A reversed interval (b < a) gives −∫_b^a f.
pub fn integrate<R: Real, F: FnMut(&R) -> R>(
    mut integrand: F,
    a: &R,
    b: &R,
    tolerance: &R,
    max_level: u32,
) -> Estimate<R> {
    if b < a {
        // The node placement below assumes a < b (nodes inside (a, b)).
        let reversed = integrate(integrand, b, a, tolerance, max_level);
        return Estimate {
            value: -reversed.value,
            ..reversed
        };
    }
    let transform = Transform::new(a, b);
    let precision = a.precision();
    let mut evaluations = 0;
    let mut spacing = 1.0f64;
    let mut sum = transform.sum(&mut integrand, &nodes(0, precision), &mut evaluations);
    let mut previous = sum.clone() * &transform.half_width;
    let mut level = 0;
    let (mut smallest, mut stalled): (Option<R>, u32) = (None, 0);
    loop {
        level += 1;
        // The new level's nodes are the odd multiples of the new spacing.
        spacing /= 2.0;
        sum += transform.sum(&mut integrand, &nodes(level, precision), &mut evaluations);
        let current = sum.clone() * &transform.half_width * &R::from_f64(spacing, precision);
        let error = (current.clone() - &previous).abs();
        let converged = level >= 3 && error <= *tolerance;
        let gained = smallest
            .as_ref()
            .is_none_or(|smallest| error.clone() * &error.int(10) <= *smallest);
        stalled = if level >= 5 && !gained { stalled + 1 } else { 0 };
        if gained {
            smallest = Some(error.clone());
        }
        if converged || level >= max_level || stalled >= 2 {
            return Estimate {
                value: current,
                error,
                evaluations,
                converged,
            };
        }
        previous = current;
    }
}
