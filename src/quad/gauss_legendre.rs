//! Gauss–Legendre quadrature at any precision.
//!
//! An n-point rule integrates polynomials of degree 2n − 1 exactly and converges
//! geometrically for integrands analytic near the interval, which is what every
//! segment integrand of the dissipation is when written in the cycle angle θ.
//! Nodes and weights are computed at the working precision (Newton's method on
//! the three-term Legendre recurrence, started from an asymptotic guess polished
//! in f64) and cached per (number type, n, precision): the first call at a new
//! precision pays for the table, later calls reuse it.

use std::any::{Any, TypeId};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use super::Estimate;
use crate::real::{Precision, Real};

/// The nodes x_k in (−1, 1) and weights w_k of an n-point rule, ∫₋₁¹ g ≈ Σ w_k g(x_k).
#[derive(Clone, Debug)]
pub struct NodeTable<R> {
    /// Nodes, in increasing order.
    pub nodes: Vec<R>,
    /// Weights, matching `nodes`.
    pub weights: Vec<R>,
}

type CacheKey = (TypeId, usize, u32);
type CacheMap = HashMap<CacheKey, Arc<dyn Any + Send + Sync>>;

fn cache() -> &'static Mutex<CacheMap> {
    static CACHE: OnceLock<Mutex<CacheMap>> = OnceLock::new();
    CACHE.get_or_init(|| Mutex::new(HashMap::new()))
}

/// The n-point node table at `precision`, computed once and then served from the cache.
pub fn node_table<R: Real>(points: usize, precision: Precision) -> Arc<NodeTable<R>> {
    let key = (TypeId::of::<R>(), points, precision.in_bits());
    if let Some(table) = cache().lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
        if let Ok(table) = Arc::clone(table).downcast::<NodeTable<R>>() {
            return table;
        }
    }
    let table = Arc::new(compute_node_table::<R>(points, precision));
    cache()
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .insert(key, Arc::clone(&table) as Arc<dyn Any + Send + Sync>);
    table
}

/// Forget every cached node table (for measuring the cold cost).
pub fn clear_node_cache() {
    cache().lock().unwrap_or_else(|e| e.into_inner()).clear();
}

/// P_n(x) and P_n'(x) by the three-term recurrence, written as
/// P_{j+1} = t + (t − P_{j−1})·j/(j+1) with t = x P_j, where `ratios[j]` = j/(j+1):
/// two multiplications a step and no division.
fn legendre_with_derivative<R: Real>(ratios: &[R], x: &R) -> (R, R) {
    let points = ratios.len();
    let mut previous = x.int(1);
    let mut current = x.clone();
    for ratio in ratios.iter().take(points).skip(1) {
        let t = x.clone() * &current;
        let next = (t.clone() - &previous) * ratio + &t;
        previous = current;
        current = next;
    }
    let derivative = (x.clone() * &current - previous) * x.int(points as i64) / (x.square() - x.int(1));
    (current, derivative)
}

/// j/(j + 1) for j = 0 … n − 1, the recurrence's coefficients.
fn recurrence_ratios<R: Real>(points: usize, precision: Precision) -> Vec<R> {
    (0..points as i64)
        .map(|j| R::from_i64(j, precision) / R::from_i64(j + 1, precision))
        .collect()
}

/// Computes the table from scratch (no cache).
pub fn compute_node_table<R: Real>(points: usize, precision: Precision) -> NodeTable<R> {
    assert!(points >= 1, "a Gauss–Legendre rule needs at least one point");
    let half = points / 2;
    let ratios = recurrence_ratios::<R>(points, precision);
    let double_ratios = recurrence_ratios::<f64>(points, Precision::DOUBLE);
    let mut positive_nodes = Vec::with_capacity(half + 1);
    let mut positive_weights = Vec::with_capacity(half + 1);
    for k in 1..=points.div_ceil(2) {
        // Tricomi's asymptotic guess, then Newton in f64, then Newton at full precision.
        let n = points as f64;
        let angle = std::f64::consts::PI * (k as f64 - 0.25) / (n + 0.5);
        let mut guess = (1.0 - (n - 1.0) / (8.0 * n * n * n)) * angle.cos();
        for _ in 0..100 {
            let (p, dp) = legendre_with_derivative(&double_ratios, &guess);
            let step = p / dp;
            guess -= step;
            if step.abs() <= 4.0 * f64::EPSILON * guess.abs().max(1e-300) {
                break;
            }
        }
        let mut x = R::from_f64(guess, precision);
        if 2 * k - 1 == points {
            x = R::from_i64(0, precision);
        } else if precision > Precision::DOUBLE {
            // Newton doubles the correct bits per step, so each step need only carry twice
            // the bits of the last: from ~50 bits, the steps run at 100, 200, … bits and
            // just the last one or two at the working precision.
            let mut bits = 50u32;
            while bits < precision.in_bits() + 8 {
                bits = (2 * bits).min(precision.in_bits() + 8);
                let step_precision = Precision::bits(bits.min(precision.in_bits()));
                let at_step = R::from_f64(0.0, step_precision) + &x;
                let (p, dp) = legendre_with_derivative(&ratios, &at_step);
                x -= &(p / dp);
            }
        }
        let (_, dp) = legendre_with_derivative(&ratios, &x);
        let weight = x.int(2) / ((x.int(1) - x.square()) * dp.square());
        positive_nodes.push(x);
        positive_weights.push(weight);
    }
    // positive_nodes run from the largest node down; mirror them into increasing order.
    let mut nodes = Vec::with_capacity(points);
    let mut weights = Vec::with_capacity(points);
    for (x, w) in positive_nodes.iter().zip(&positive_weights).take(half) {
        nodes.push(-x.clone());
        weights.push(w.clone());
    }
    for (x, w) in positive_nodes.iter().zip(&positive_weights).rev() {
        nodes.push(x.clone());
        weights.push(w.clone());
    }
    NodeTable { nodes, weights }
}

impl<R: Real> NodeTable<R> {
    /// ∫ₐᵇ f with this rule (one pass, no error estimate).
    pub fn integrate<F: FnMut(&R) -> R>(&self, integrand: F, a: &R, b: &R) -> R {
        self.integrate_with_magnitude(integrand, a, b).0
    }

    /// ∫ₐᵇ f and the same rule applied to |f|: the second sizes the rounding error
    /// of the first (a sum whose terms cancel can be no better than ε·∫|f|).
    pub fn integrate_with_magnitude<F: FnMut(&R) -> R>(&self, mut integrand: F, a: &R, b: &R) -> (R, R) {
        let half_width = (b.clone() - a) / a.int(2);
        let middle = (b.clone() + a) / a.int(2);
        let (mut sum, mut magnitude) = (a.int(0), a.int(0));
        for (x, w) in self.nodes.iter().zip(&self.weights) {
            let point = middle.clone() + &(half_width.clone() * x);
            let term = integrand(&point) * w;
            magnitude += term.abs();
            sum += term;
        }
        (sum * &half_width, magnitude * &half_width.abs())
    }

    /// The number of points.
    pub fn points(&self) -> usize {
        self.nodes.len()
    }
}

/// ∫ₐᵇ f to an absolute tolerance, doubling the number of points from `start_points`
/// until two successive rules agree to `tolerance`, or `max_points` is passed
/// (then `converged` is false and `error` says how far apart the last two were).
pub fn integrate<R: Real, F: FnMut(&R) -> R>(
    mut integrand: F,
    a: &R,
    b: &R,
    tolerance: &R,
    start_points: usize,
    max_points: usize,
) -> Estimate<R> {
    let precision = a.precision();
    let mut points = start_points.max(1);
    let mut evaluations = points;
    let mut previous = node_table::<R>(points, precision).integrate(&mut integrand, a, b);
    loop {
        points *= 2;
        let current = node_table::<R>(points, precision).integrate(&mut integrand, a, b);
        evaluations += points;
        let error = (current.clone() - &previous).abs();
        let converged = error <= *tolerance;
        if converged || points * 2 > max_points {
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

#[cfg(test)]
mod tests {
    use super::*;
    use rug::Float;

    #[test]
    fn weights_sum_to_two_and_nodes_are_symmetric() {
        for n in [1, 2, 5, 16, 33] {
            let table = compute_node_table::<f64>(n, Precision::DOUBLE);
            let total: f64 = table.weights.iter().sum();
            assert!((total - 2.0).abs() < 1e-14, "n={n}: {total}");
            for i in 0..n {
                assert!((table.nodes[i] + table.nodes[n - 1 - i]).abs() < 1e-15);
            }
            assert!(table.nodes.windows(2).all(|w| w[0] < w[1]));
        }
    }

    #[test]
    fn cached_table_is_reused() {
        let first = node_table::<Float>(24, Precision::bits(200));
        let second = node_table::<Float>(24, Precision::bits(200));
        assert!(Arc::ptr_eq(&first, &second));
        let other = node_table::<Float>(24, Precision::bits(201));
        assert!(!Arc::ptr_eq(&first, &other));
    }
}
