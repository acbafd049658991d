//! Tanh–sinh (double-exponential) quadrature at any precision.
//!
//! The substitution x = tanh(π/2 · sinh u) crowds nodes toward both ends
//! double-exponentially, so integrable end-point singularities (x^(−1/2),
//! ln x, square-root end points) converge about as fast as smooth integrands:
//! each halving of the step roughly doubles the correct digits. Abscissae near
//! an end are formed from the distance to that end, never as 1 − tanh(·), so
//! no digits are lost there.

use std::sync::Arc;
use std::time::Instant;

use super::cache::{self, Table};
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
    /// The level.
    level: u32,
}

/// Levels up to this one are cached; the rarely reached finer ones (each twice the
/// nodes of the one before) are computed per call rather than held.
const MAX_CACHED_LEVEL: u32 = 12;

impl<R: Real> Table for Level<R> {
    fn precision(&self) -> Precision {
        self.nodes
            .first()
            .map_or(Precision::DOUBLE, |(complement, _)| complement.precision())
    }

    /// The nodes up to the lower precision's u_max, each rounded once.
    fn rounded(&self, precision: Precision) -> Self {
        let round = |x: &R| R::from_f64(0.0, precision) + x;
        let (start, spacing) = level_grid(self.level);
        let u_max = u_max(precision);
        Level {
            has_middle: self.has_middle,
            nodes: self
                .nodes
                .iter()
                .enumerate()
                .take_while(|(index, _)| start + spacing * *index as f64 <= u_max)
                .map(|(_, (complement, weight))| (round(complement), round(weight)))
                .collect(),
            level: self.level,
        }
    }

    fn bytes(&self) -> usize {
        let per_value = std::mem::size_of::<R>() + self.precision().in_bits().div_ceil(8) as usize;
        2 * self.nodes.len() * per_value
    }
}

/// The nodes of `level` at `precision`, computed once per (number type, level) for the
/// levels up to `MAX_CACHED_LEVEL` and served by rounding at lower precisions.
pub fn nodes<R: Real>(level: u32, precision: Precision) -> Arc<Level<R>> {
    let compute = || Some(compute_level(level, precision));
    let cached = (level <= MAX_CACHED_LEVEL)
        .then(|| cache::cached(level as usize, precision, compute))
        .flatten();
    cached.unwrap_or_else(|| Arc::new(compute_level(level, precision)))
}

/// The largest u at `precision`: where the weight falls below 2^(−2·bits), the tails
/// being negligible there.
fn u_max(precision: Precision) -> f64 {
    let s_max = f64::from(precision.in_bits()) * std::f64::consts::LN_2 + 20.0;
    (2.0 * s_max / std::f64::consts::PI).asinh()
}

/// The first u of a level's nodes and their spacing.
fn level_grid(level: u32) -> (f64, f64) {
    if level == 0 {
        (0.0, 1.0)
    } else {
        let spacing = 0.5f64.powi(level as i32);
        (spacing, 2.0 * spacing)
    }
}

fn compute_level<R: Real>(level: u32, precision: Precision) -> Level<R> {
    let (start, spacing) = level_grid(level);
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
        level,
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
pub fn integrate<R: Real, F: FnMut(&R) -> R>(integrand: F, a: &R, b: &R, tolerance: &R, max_level: u32) -> Estimate<R> {
    levels(integrand, a, b, tolerance, max_level, None).estimate
}

/// [`integrate`], stopping before a level whose predicted cost (twice the last level's
/// time: each level doubles the nodes) would end past `deadline`; `None` then.
pub fn integrate_before<R: Real, F: FnMut(&R) -> R>(
    integrand: F,
    a: &R,
    b: &R,
    tolerance: &R,
    max_level: u32,
    deadline: Instant,
) -> Option<Estimate<R>> {
    let outcome = levels(integrand, a, b, tolerance, max_level, Some(deadline));
    (!outcome.out_of_time).then_some(outcome.estimate)
}

/// The levels' estimate, and whether they stopped for the deadline.
struct Outcome<R> {
    estimate: Estimate<R>,
    out_of_time: bool,
}

fn levels<R: Real, F: FnMut(&R) -> R>(
    mut integrand: F,
    a: &R,
    b: &R,
    tolerance: &R,
    max_level: u32,
    deadline: Option<Instant>,
) -> Outcome<R> {
    if b < a {
        // The node placement below assumes a < b (nodes inside (a, b)).
        let reversed = levels(integrand, b, a, tolerance, max_level, deadline);
        return Outcome {
            estimate: Estimate {
                value: -reversed.estimate.value,
                ..reversed.estimate
            },
            ..reversed
        };
    }
    let transform = Transform::new(a, b);
    let precision = a.precision();
    let mut evaluations = 0;
    let mut spacing = 1.0f64;
    let mut started = Instant::now();
    let mut sum = transform.sum(&mut integrand, &nodes(0, precision), &mut evaluations);
    let mut previous = sum.clone() * &transform.half_width;
    let mut level = 0;
    let (mut smallest, mut stalled): (Option<R>, u32) = (None, 0);
    loop {
        let now = Instant::now();
        if deadline.is_some_and(|deadline| now + (now - started) * 2 > deadline) {
            let error = previous.abs();
            return Outcome {
                estimate: Estimate {
                    value: previous,
                    error,
                    evaluations,
                    converged: false,
                },
                out_of_time: true,
            };
        }
        started = now;
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
            return Outcome {
                estimate: Estimate {
                    value: current,
                    error,
                    evaluations,
                    converged,
                },
                out_of_time: false,
            };
        }
        previous = current;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rug::Float;

    /// A level rounded from a higher precision has the nodes a direct computation at the
    /// lower precision has (those up to its own u_max), each within one unit in the last
    /// place of the exact value (a computation at 64 bits more, rounded) and within a few
    /// hundred units of the direct one (which rounds at every operation).
    #[test]
    fn rounded_levels_match_direct_computation() {
        for level in [0, 1, 4] {
            let (high, low) = (Precision::bits(600), Precision::bits(200));
            let rounded = compute_level::<Float>(level, high).rounded(low);
            let direct = compute_level::<Float>(level, low);
            let exact = compute_level::<Float>(level, Precision::bits(664));
            assert_eq!(rounded.nodes.len(), direct.nodes.len(), "level {level}");
            assert!(rounded.nodes.len() < compute_level::<Float>(level, high).nodes.len());
            for (((a, w), (b, v)), (c, u)) in rounded.nodes.iter().zip(&exact.nodes).zip(&direct.nodes) {
                for (x, y, z) in [(a, b, c), (w, v, u)] {
                    let ulp =
                        |units: i32| Float::with_val(200, Float::i_exp(1, y.get_exp().unwrap_or(0) - 200 + units));
                    assert!(
                        Float::with_val(200, x - y).abs() <= ulp(0),
                        "level {level}: {x} against {y}"
                    );
                    assert!(
                        Float::with_val(200, x - z).abs() <= ulp(8),
                        "level {level}: {x} against direct {z}"
                    );
                }
            }
        }
    }
}
