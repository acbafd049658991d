//! Gauss–Legendre quadrature at any precision.
//!
//! An n-point rule integrates polynomials of degree 2n − 1 exactly and converges
//! geometrically for integrands analytic near the interval, which is what every
//! segment integrand of the dissipation is when written in the cycle angle θ.
//! Nodes and weights are computed at the working precision (Newton's method on
//! the three-term Legendre recurrence, started from an asymptotic guess polished
//! in f64) and cached per (number type, n, precision): the first call at a new
//! precision pays for the table, later calls reuse it.

use std::sync::Arc;

mod fixed;
mod stored;

use fixed::Fixed;

use crate::real::{Precision, Real};

/// The nodes x_k in (−1, 1) and weights w_k of an n-point rule, ∫₋₁¹ g ≈ Σ w_k g(x_k).
#[derive(Clone, Debug)]
pub struct NodeTable<R> {
    /// Nodes, in increasing order.
    pub nodes: Vec<R>,
    /// Weights, matching `nodes`.
    pub weights: Vec<R>,
}

/// The n-point node table at `precision`, computed once and then served from the cache.
pub fn node_table<R: Real>(points: usize, precision: Precision) -> Arc<NodeTable<R>> {
    super::cache::cached(points, precision, || {
        stored::stored_table::<R>(points, precision).unwrap_or_else(|| compute_node_table::<R>(points, precision))
    })
}

/// Forget every cached table, Gauss–Legendre and tanh–sinh (for measuring the cold cost).
pub fn clear_node_cache() {
    super::cache::clear();
}

/// P_n(x) and P_{n−1}(x) by the three-term recurrence, written as
/// P_{j+1} = t − (P_{j−1} − t)·j/(j+1) with t = x P_j, where `ratios[j]` = j/(j+1):
/// two multiplications a step, no division, and (in MPFR) no allocation after the first.
/// The result carries the precision of `x`.
fn legendre_pair<R: Real>(ratios: &[R], x: &R) -> (R, R) {
    let mut previous = x.int(1);
    let mut current = x.clone();
    let mut scratch = x.clone();
    for ratio in ratios.iter().skip(1) {
        scratch.clone_from(x);
        scratch *= &current;
        previous -= &scratch;
        previous *= ratio;
        scratch -= &previous;
        std::mem::swap(&mut previous, &mut current);
        std::mem::swap(&mut current, &mut scratch);
    }
    (current, previous)
}

/// P_n'(x) from P_n(x) and P_{n−1}(x): n (x P_n − P_{n−1}) / (x² − 1).
fn legendre_derivative<R: Real>(points: usize, x: &R, value: &R, below: &R) -> R {
    (x.clone() * value - below) * x.int(points as i64) / (x.square() - x.int(1))
}

/// j/(j + 1) for j = 0 … n − 1, the recurrence's coefficients.
fn recurrence_ratios<R: Real>(points: usize, precision: Precision) -> Vec<R> {
    (0..points as i64)
        .map(|j| R::from_i64(j, precision) / R::from_i64(j + 1, precision))
        .collect()
}

/// The precisions of the Newton steps that take a node from the ~52 correct bits of the
/// f64 polish to `precision`: each step doubles the correct bits less the condition of
/// the root (about log₂ n bits), so each step's precision is half the next one's plus
/// `guard` bits; the last runs at `precision` itself.
fn newton_schedule(precision: u32, guard: u32) -> Vec<u32> {
    let mut schedule = vec![precision];
    while let Some(&last) = schedule.last() {
        let needed = last / 2 + guard;
        if needed <= 64 || needed >= last {
            break;
        }
        schedule.push(needed);
    }
    schedule.reverse();
    schedule
}

/// Tables of at least this many points above f64 precision are computed on several threads.
const PARALLEL_POINTS: usize = 96;

/// The most threads a table is computed on.
const MAX_THREADS: usize = 4;

/// Computes the table from scratch (no cache).
///
/// Each node comes from Tricomi's asymptotic guess polished in f64; above f64, Newton
/// steps follow at precisions that double up to the working one (`newton_schedule`),
/// each evaluating the recurrence in fixed point (`fixed`) with guard bits, so that only
/// the last runs at the working precision. That last evaluation also gives the weight:
/// P_n' at the corrected node follows from P_n' and the Legendre equation at the
/// evaluated point by Taylor's theorem, to second order in the (half-precision) step.
pub fn compute_node_table<R: Real>(points: usize, precision: Precision) -> NodeTable<R> {
    assert!(points >= 1, "a Gauss–Legendre rule needs at least one point");
    let half = points / 2;
    let double_ratios = recurrence_ratios::<f64>(points, Precision::DOUBLE);
    let log_points = usize::BITS - points.leading_zeros();
    let schedule = newton_schedule(precision.in_bits(), 4 + log_points);
    // Guard bits: the linear growth of the recurrence's rounding, and the cancellation
    // in P_n' = n (x P_n − P_{n−1})/(x² − 1) at nodes within ~1/n² of ±1.
    let guarded = |bits: u32| bits + 2 * log_points + 16;
    let limbs = |bits: u32| guarded(bits).div_ceil(64) as usize;
    let low_ratios = if precision > Precision::DOUBLE {
        Vec::new()
    } else {
        recurrence_ratios::<R>(points, precision)
    };
    let fixed_ratios: Vec<Fixed> = if precision > Precision::DOUBLE {
        let length = limbs(precision.in_bits());
        (0..points as u64).map(|j| Fixed::ratio(j, j + 1, length)).collect()
    } else {
        Vec::new()
    };
    let step_ratios: Vec<Vec<Fixed>> = schedule
        .iter()
        .map(|&bits| fixed_ratios.iter().map(|ratio| ratio.resized(limbs(bits))).collect())
        .collect();
    // P_n(x) and P_{n−1}(x) with the guard bits of a step at `bits`, at x's precision or more.
    let evaluate = |x: &R, step: usize| -> (R, R) {
        if precision <= Precision::DOUBLE {
            return legendre_pair(&low_ratios, x);
        }
        let bits = schedule[step];
        let (value, below) = fixed::legendre_quarters(&step_ratios[step], &Fixed::from_real(x, limbs(bits)));
        let working = Precision::bits(guarded(bits).max(x.precision().in_bits()));
        let four = R::from_i64(4, working);
        (value.to_real::<R>(working) * &four, below.to_real::<R>(working) * &four)
    };
    let n = points as f64;
    // The k-th node from the right, with its weight.
    let node_and_weight = |k: usize| -> (R, R) {
        // Tricomi's asymptotic guess, then Newton in f64.
        let angle = std::f64::consts::PI * (k as f64 - 0.25) / (n + 0.5);
        let mut guess = (1.0 - (n - 1.0) / (8.0 * n * n * n)) * angle.cos();
        for _ in 0..100 {
            let (p, below) = legendre_pair(&double_ratios, &guess);
            let step = p / legendre_derivative(points, &guess, &p, &below);
            guess -= step;
            if step.abs() <= 4.0 * f64::EPSILON * guess.abs().max(1e-300) {
                break;
            }
        }
        let middle = 2 * k - 1 == points;
        if middle {
            let x = R::from_f64(0.0, precision);
            let (_, below) = evaluate(&x, schedule.len() - 1);
            let derivative = below * x.int(points as i64);
            let weight = R::from_f64(0.0, precision) + &(x.int(2) / derivative.square());
            return (x, weight);
        }
        let mut x = R::from_f64(guess, precision);
        if precision > Precision::DOUBLE {
            // All but the last step at reduced precision.
            for step in 0..schedule.len() - 1 {
                let (p, below) = evaluate(&x, step);
                let at_step = R::from_f64(0.0, p.precision()) + &x;
                let derivative = legendre_derivative(points, &at_step, &p, &below);
                x -= &(p / &derivative);
            }
        }
        let (p, below) = evaluate(&x, schedule.len() - 1);
        let mut x_guarded = R::from_f64(0.0, p.precision()) + &x;
        let derivative = legendre_derivative(points, &x_guarded, &p, &below);
        let step = p.clone() / &derivative;
        // (1 − x²) P″ = 2x P′ − n(n+1) P and (1 − x²) P‴ = 4x P″ − (n(n+1) − 2) P′.
        let x = &x_guarded;
        let one_minus_square = x.int(1) - x.square();
        let eigenvalue = x.int((points * (points + 1)) as i64);
        let second = (x.int(2) * x * &derivative - eigenvalue.clone() * &p) / &one_minus_square;
        let third = (x.int(4) * x * &second - (eigenvalue - x.int(2)) * &derivative) / &one_minus_square;
        let corrected_derivative = derivative - step.clone() * &second + step.square() * &third / x.int(2);
        x_guarded -= &step;
        let x = &x_guarded;
        let weight = x.int(2) / ((x.int(1) - x.square()) * corrected_derivative.square());
        (R::from_f64(0.0, precision) + x, R::from_f64(0.0, precision) + &weight)
    };
    // Large tables at high precision are shared among the cores, in contiguous runs of roots.
    let roots = points.div_ceil(2);
    let threads = if precision > Precision::DOUBLE && points >= PARALLEL_POINTS {
        std::thread::available_parallelism()
            .map_or(1, |n| n.get())
            .min(MAX_THREADS)
    } else {
        1
    };
    let pairs: Vec<(R, R)> = if threads <= 1 {
        (1..=roots).map(node_and_weight).collect()
    } else {
        let run = roots.div_ceil(threads);
        std::thread::scope(|scope| {
            let handles: Vec<_> = (0..threads)
                .map(|t| {
                    let node_and_weight = &node_and_weight;
                    scope.spawn(move || {
                        (1 + t * run..=((t + 1) * run).min(roots))
                            .map(node_and_weight)
                            .collect::<Vec<_>>()
                    })
                })
                .collect();
            handles
                .into_iter()
                .flat_map(|handle| handle.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic)))
                .collect()
        })
    };
    let (positive_nodes, positive_weights): (Vec<R>, Vec<R>) = pairs.into_iter().unzip();
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

    /// Σ w x^(2j) = 2/(2j + 1) for every 2j ≤ 2n − 1, to within a few hundred ulps of the
    /// working precision: the nodes and weights are right to (nearly) the last bit,
    /// including the weights taken from the Taylor-corrected derivative.
    #[test]
    fn rules_integrate_even_powers_to_the_working_precision() {
        for (n, bits) in [
            (7usize, 113u32),
            (33, 200),
            (64, 224),
            (128, 284),
            (256, 284),
            (512, 300),
            (256, 470),
            (100, 1100),
            (300, 3400),
        ] {
            let precision = Precision::bits(bits);
            let table = compute_node_table::<Float>(n, precision);
            let tolerance = Float::with_val(bits, 1) >> (bits as i32 - 12);
            for j in (0..n).step_by((n / 8).max(1)).chain([n - 1]) {
                let sum = table
                    .nodes
                    .iter()
                    .zip(&table.weights)
                    .fold(Float::with_val(bits, 0), |acc, (x, w)| acc + x.powi(2 * j as i32) * w);
                let exact = Float::with_val(bits, 2) / (2 * j as u32 + 1);
                let error = (sum - &exact).abs();
                assert!(error <= tolerance, "n={n} bits={bits} j={j}: error {error:.3e}");
            }
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
