//! Gauss–Legendre quadrature at any precision.
//!
//! An n-point rule integrates polynomials of degree 2n − 1 exactly and converges
//! geometrically for integrands analytic near the interval, which is what every
//! segment integrand of the dissipation is when written in the cycle angle θ.
//! Nodes and weights are computed at the working precision (Newton's method on
//! the three-term Legendre recurrence, started from an asymptotic guess polished
//! in f64) and cached per (number type, n) at the highest precision asked for; a lower
//! precision is served by rounding (see `quad::cache`).

use std::sync::Arc;
use std::time::Instant;

use rayon::prelude::*;

mod fixed;
mod stored;

use fixed::FixedPoint;

use super::cache::{self, Table};
use crate::real::{Precision, Real};

/// The nodes x_k in (−1, 1) and weights w_k of an n-point rule, ∫₋₁¹ g ≈ Σ w_k g(x_k).
#[derive(Clone, Debug)]
pub struct NodeTable<R> {
    /// Nodes, in increasing order.
    pub nodes: Vec<R>,
    /// Weights, matching `nodes`.
    pub weights: Vec<R>,
}

impl<R: Real> Table for NodeTable<R> {
    fn precision(&self) -> Precision {
        self.nodes.first().map_or(Precision::DOUBLE, Real::precision)
    }

    fn rounded(&self, precision: Precision) -> Self {
        let round = |values: &[R]| values.iter().map(|x| R::from_f64(0.0, precision) + x).collect();
        NodeTable {
            nodes: round(&self.nodes),
            weights: round(&self.weights),
        }
    }

    fn bytes(&self) -> usize {
        let per_value = std::mem::size_of::<R>() + self.precision().in_bits().div_ceil(8) as usize;
        2 * self.nodes.len() * per_value
    }
}

/// The n-point node table at `precision`, computed once and then served from the cache.
pub fn node_table<R: Real>(points: usize, precision: Precision) -> Arc<NodeTable<R>> {
    match node_table_before(points, precision, None) {
        Some(table) => table,
        // Without a deadline the computation always completes.
        None => Arc::new(compute_node_table(points, precision)),
    }
}

/// The n-point node table at `precision`, or `None` when computing it would run past
/// `deadline` (the computation then stops, and nothing is cached).
pub fn node_table_before<R: Real>(
    points: usize,
    precision: Precision,
    deadline: Option<Instant>,
) -> Option<Arc<NodeTable<R>>> {
    // Where the rule is stored, the cache holds it at the highest precision storage serves,
    // so that every lower precision is rounded from the same values, whatever came first.
    let stored = stored::serves(points, precision);
    let held = if stored {
        Precision::bits(stored::SERVED_BITS)
    } else {
        precision
    };
    let table = cache::cached(points, held, || match stored::stored_table::<R>(points, held) {
        Some(table) => Some(table),
        None => compute_node_table_before(points, held, deadline),
    })?;
    if table.precision() == precision {
        return Some(table);
    }
    cache::cached(points, precision, || Some(table.rounded(precision)))
}

/// Forget every cached table, Gauss–Legendre and tanh–sinh (for measuring the cold cost).
pub fn clear_node_cache() {
    cache::clear();
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

/// Tables of at least this many points above f64 precision are computed in parallel, on
/// the caller's rayon pool.
const PARALLEL_POINTS: usize = 96;

/// Computes the table from scratch (no cache).
///
/// Each node comes from Tricomi's asymptotic guess polished in f64; above f64, Newton
/// steps follow at precisions that double up to the working one (`newton_schedule`),
/// each evaluating the recurrence in fixed point (`fixed`) with guard bits, so that only
/// the last runs at the working precision. That last evaluation also gives the weight:
/// P_n' at the corrected node follows from P_n' and the Legendre equation at the
/// evaluated point by Taylor's theorem, to second order in the (half-precision) step.
pub fn compute_node_table<R: Real>(points: usize, precision: Precision) -> NodeTable<R> {
    match compute_node_table_before(points, precision, None) {
        Some(table) => table,
        None => unreachable!("a computation without a deadline completes"),
    }
}

/// [`compute_node_table`], giving up with `None` once `deadline` has passed (checked
/// before each node, each costing O(n) operations at the working precision).
fn compute_node_table_before<R: Real>(
    points: usize,
    precision: Precision,
    deadline: Option<Instant>,
) -> Option<NodeTable<R>> {
    let points = points.max(1);
    let double_ratios = recurrence_ratios::<f64>(points, Precision::DOUBLE);
    let log_points = usize::BITS - points.leading_zeros();
    let schedule = newton_schedule(precision.in_bits(), 4 + log_points);
    // Guard bits: the linear growth of the recurrence's rounding, and the cancellation
    // in P_n' = n (x P_n − P_{n−1})/(x² − 1) at nodes within ~1/n² of ±1.
    let guarded = |bits: u32| bits + 2 * log_points + 16;
    let scales: Vec<FixedPoint> = schedule
        .iter()
        .map(|&bits| FixedPoint { bits: guarded(bits) })
        .collect();
    let low_ratios = if precision > Precision::DOUBLE {
        Vec::new()
    } else {
        recurrence_ratios::<R>(points, precision)
    };
    let step_ratios: Vec<Vec<rug::Integer>> = match scales.last() {
        Some(&finest) if precision > Precision::DOUBLE => {
            let ratios = finest.ratios(points);
            scales
                .iter()
                .map(|scale| ratios.iter().map(|ratio| scale.rescaled(ratio, finest)).collect())
                .collect()
        }
        _ => Vec::new(),
    };
    // P_n(x) and P_{n−1}(x) with the guard bits of a step, at x's precision or more.
    let evaluate = |x: &R, step: usize| -> (R, R) {
        if precision <= Precision::DOUBLE {
            return legendre_pair(&low_ratios, x);
        }
        let scale = scales[step];
        let (value, below) = scale.legendre_pair(&step_ratios[step], &scale.scaled(x));
        let working = Precision::bits(scale.bits.max(x.precision().in_bits()));
        (scale.to_real(&value, working), scale.to_real(&below, working))
    };
    // The k-th node from the right, with its weight.
    let node_and_weight = |k: usize| -> (R, R) {
        let guess = node_in_f64(points, k, &double_ratios);
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
        let (x, weight) = last_newton_step(points, &(R::from_f64(0.0, p.precision()) + &x), &p, &below);
        (R::from_f64(0.0, precision) + &x, R::from_f64(0.0, precision) + &weight)
    };
    // Large tables at high precision are shared among the cores of the caller's pool.
    let roots = points.div_ceil(2);
    let in_time = |k: usize| {
        let late = deadline.is_some_and(|deadline| Instant::now() >= deadline);
        (!late).then(|| node_and_weight(k))
    };
    let pairs: Vec<(R, R)> = if precision > Precision::DOUBLE && points >= PARALLEL_POINTS {
        (1..=roots).into_par_iter().map(in_time).collect::<Option<_>>()?
    } else {
        (1..=roots).map(in_time).collect::<Option<_>>()?
    };
    Some(mirrored(pairs, points))
}

/// The k-th node from the right of the `points`-point rule in f64: Tricomi's asymptotic
/// guess, then Newton's method.
fn node_in_f64(points: usize, k: usize, ratios: &[f64]) -> f64 {
    let n = points as f64;
    let angle = std::f64::consts::PI * (k as f64 - 0.25) / (n + 0.5);
    let mut guess = (1.0 - (n - 1.0) / (8.0 * n * n * n)) * angle.cos();
    for _ in 0..100 {
        let (p, below) = legendre_pair(ratios, &guess);
        let step = p / legendre_derivative(points, &guess, &p, &below);
        guess -= step;
        if step.abs() <= 4.0 * f64::EPSILON * guess.abs().max(1e-300) {
            break;
        }
    }
    guess
}

/// The last Newton step from `x`, where P_n = `p` and P_{n−1} = `below`, and the weight at
/// the corrected node: P_n′ there follows from P_n′, P_n″ and P_n‴ at x by Taylor's
/// theorem, with (1 − x²) P″ = 2x P′ − n(n+1) P and (1 − x²) P‴ = 4x P″ − (n(n+1) − 2) P′.
fn last_newton_step<R: Real>(points: usize, x: &R, p: &R, below: &R) -> (R, R) {
    let derivative = legendre_derivative(points, x, p, below);
    let step = p.clone() / &derivative;
    let one_minus_square = x.int(1) - x.square();
    let eigenvalue = x.int((points * (points + 1)) as i64);
    let second = (x.int(2) * x * &derivative - eigenvalue.clone() * p) / &one_minus_square;
    let third = (x.int(4) * x * &second - (eigenvalue - x.int(2)) * &derivative) / &one_minus_square;
    let corrected_derivative = derivative - step.clone() * &second + step.square() * &third / x.int(2);
    let x = x.clone() - &step;
    let weight = x.int(2) / ((x.int(1) - x.square()) * corrected_derivative.square());
    (x, weight)
}

/// The rule from its nodes in [0, 1] with their weights, largest node first, mirrored
/// into increasing order over [−1, 1].
fn mirrored<R: Real>(positive: Vec<(R, R)>, points: usize) -> NodeTable<R> {
    let mut nodes = Vec::with_capacity(points);
    let mut weights = Vec::with_capacity(points);
    for (x, w) in positive.iter().take(points / 2) {
        nodes.push(-x.clone());
        weights.push(w.clone());
    }
    for (x, w) in positive.iter().rev() {
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
    fn cached_table_is_reused_and_replaced_by_a_higher_precision() {
        let first = node_table::<Float>(24, Precision::bits(200));
        let second = node_table::<Float>(24, Precision::bits(200));
        assert!(Arc::ptr_eq(&first, &second));
        let higher = node_table::<Float>(24, Precision::bits(201));
        assert!(!Arc::ptr_eq(&first, &higher));
        assert_eq!(higher.nodes[0].prec(), 201);
    }

    /// A table served by rounding a higher-precision one is within one unit in the last
    /// place of the exact values (a computation 64 bits above the higher one, rounded),
    /// and within the direct computation's own few hundred units (those of
    /// `stored_tables_equal_computed_ones`) of a direct computation at the lower precision.
    #[test]
    fn rounded_down_tables_are_within_one_ulp_of_the_exact_values() {
        for (points, high, low) in [(37usize, 900u32, 300u32), (130, 1200, 700), (33, 160, 100)] {
            let held = node_table::<Float>(points, Precision::bits(high));
            let served = node_table::<Float>(points, Precision::bits(low));
            assert_eq!(held.nodes[0].prec(), high, "the entry keeps the highest precision");
            let exact = compute_node_table::<Float>(points, Precision::bits(high + 64)).rounded(Precision::bits(low));
            let direct = compute_node_table::<Float>(points, Precision::bits(low));
            let pairs = served.nodes.iter().zip(&exact.nodes).zip(&direct.nodes);
            let weights = served.weights.iter().zip(&exact.weights).zip(&direct.weights);
            for (what, ((a, b), c)) in pairs.map(|x| ("node", x)).chain(weights.map(|x| ("weight", x))) {
                assert_eq!(a.prec(), low);
                let ulp =
                    |units: i32| Float::with_val(low, Float::i_exp(1, b.get_exp().unwrap_or(0) - low as i32 + units));
                let off = |x: &Float| Float::with_val(low, a - x).abs();
                assert!(
                    off(b) <= ulp(0),
                    "{points} points, {low} bits from {high}: {what} {a} against {b}"
                );
                assert!(
                    off(c) <= ulp(8),
                    "{points} points, {low} bits: {what} {a} against direct {c}"
                );
            }
        }
    }

    #[test]
    fn a_node_table_past_its_deadline_stops_and_is_not_cached() {
        let precision = Precision::bits(3000);
        let past = Some(Instant::now());
        assert!(node_table_before::<Float>(1500, precision, past).is_none());
        assert!(compute_node_table_before::<Float>(150, precision, past).is_none());
        // Nothing was cached: a later request without a deadline computes it.
        let table = node_table_before::<Float>(23, Precision::bits(3001), None).unwrap();
        assert_eq!(table.points(), 23);
    }

    /// Large tables are computed on the caller's rayon pool; requests from many of its
    /// jobs at once finish (no thread waits for itself) and agree.
    #[test]
    fn tables_requested_from_many_rayon_jobs_agree() {
        let precision = Precision::bits(700);
        let tables: Vec<Arc<NodeTable<Float>>> = (0..16)
            .into_par_iter()
            .map(|_| node_table::<Float>(161, precision))
            .collect();
        for table in &tables {
            assert_eq!(table.nodes, tables[0].nodes);
            assert_eq!(table.weights, tables[0].weights);
        }
    }
}
