//! Gauss–Legendre nodes and weights as Arb balls, computed once and cached for every
//! computation (proofs/certified-digits.md, "Node tables").
//!
//! Arb's `arb_hypgeom_legendre_p_ui_root` encloses a root of P_n by Newton steps at
//! doubling precisions, and its weight 2/((1 − x²)P_n′(x)²) by one more evaluation of P_n′
//! on the root's ball: two evaluations at the full precision. From [`REFINE_FROM_BITS`] a
//! root is taken from it at half the precision (and guard bits) instead, and finished by
//! one Newton step whose evaluation of P_n and P_n′ at the half-precision midpoint also
//! gives the weight, by Taylor's theorem and the Legendre equation: one evaluation at the
//! full precision.

use std::sync::Arc;

use flint_sys::acb::{acb_init, acb_set_round};
use flint_sys::acb_types::acb_struct;
use flint_sys::arb::arb_add_error_mag;
use flint_sys::arb_hypgeom::{
    arb_hypgeom_legendre_p_ui, arb_hypgeom_legendre_p_ui_deriv_bound, arb_hypgeom_legendre_p_ui_root,
};
use flint_sys::mag::mag_zero;
use rayon::prelude::*;

use super::Mag;
use crate::ball::Ball;
use crate::quad::cache::{cached, least_held, Table};
use crate::real::{Precision, Real};

/// The nodes x_k ≥ 0 (k < (n + 1)/2, decreasing) of an n-point Gauss–Legendre rule on
/// [−1, 1] and their weights, as balls that contain them; the rule's other nodes are −x_k.
pub(crate) struct BallRule {
    pub(crate) bits: u32,
    pub(crate) nodes: Vec<(Ball, Ball)>,
}

impl Table for BallRule {
    fn precision(&self) -> Precision {
        Precision::bits(self.bits)
    }

    fn rounded(&self, precision: Precision) -> Self {
        let bits = precision.in_bits();
        BallRule {
            bits,
            nodes: self
                .nodes
                .iter()
                .map(|(x, w)| (round(x, bits), round(w, bits)))
                .collect(),
        }
    }

    fn bytes(&self) -> usize {
        2 * self.nodes.len() * (std::mem::size_of::<Ball>() + self.bits.div_ceil(8) as usize)
    }
}

/// The least n² × bits of a node table computed in parallel: about a millisecond of
/// work, a hundred times what handing it to the pool costs.
const PARALLEL_WORK: u64 = 1 << 21;

/// The least working precision at which a root is finished by one Newton step from half
/// the precision: below it, Arb's own root costs no more.
const REFINE_FROM_BITS: u32 = 512;

/// The n-point rule at `bits`, from the node cache every computation shares (rounded
/// down from a table at a higher precision where it holds one). A large table is shared
/// among the cores of the caller's rayon pool: its cost grows as n² and faster than the
/// bits, and it is most of the cost of a first run at hundreds of digits.
pub(crate) fn nodes(n: u64, bits: u32) -> Option<Arc<BallRule>> {
    cached(n as usize, Precision::bits(bits), || {
        let roots = 0..n.div_ceil(2);
        let root = |k| legendre_root(n, k, bits);
        let nodes = if n * n * u64::from(bits) >= PARALLEL_WORK {
            roots.into_par_iter().map(root).collect()
        } else {
            roots.map(root).collect()
        };
        Some(BallRule { bits, nodes })
    })
}

/// The least degree in `degrees` whose rule is held at `bits` or above, if any.
pub(crate) fn held_degree(degrees: std::ops::RangeInclusive<u64>, bits: u32) -> Option<u64> {
    let (low, high) = (*degrees.start() as usize, *degrees.end() as usize);
    least_held::<BallRule>(low..=high, Precision::bits(bits)).map(|n| n as u64)
}

/// Guard bits for P_n's rounding and conditioning: Arb's padding, and twice it for the
/// squared step of the Newton step, whose factor P_n‴/P_n′ grows as n²/(1 − x²) ≤ n⁴.
fn guard_bits(n: u64) -> u32 {
    8 + 2 * (u64::BITS - n.leading_zeros())
}

/// The k-th root of the Legendre polynomial P_n (decreasing order) and its Gauss weight.
fn legendre_root(n: u64, k: u64, bits: u32) -> (Ball, Ball) {
    let middle = n % 2 == 1 && k == n / 2;
    if middle || bits < REFINE_FROM_BITS {
        return arb_root(n, k, bits);
    }
    newton_step(n, &half_precision_root(n, k, bits), bits).unwrap_or_else(|| arb_root(n, k, bits))
}

/// Arb's enclosure of the k-th root of P_n at half of `bits` and guard bits, from which one
/// Newton step reaches `bits`.
fn half_precision_root(n: u64, k: u64, bits: u32) -> Ball {
    let half = bits / 2 + 2 * guard_bits(n);
    let mut root = Ball::from_i64(0, Precision::bits(half));
    // SAFETY: initialised; Arb sets the real part (no weight asked for).
    unsafe { arb_hypgeom_legendre_p_ui_root(root.real_mut(), std::ptr::null_mut(), n, k, i64::from(half)) };
    root
}

/// Arb's enclosure of the k-th root of P_n and of its weight.
fn arb_root(n: u64, k: u64, bits: u32) -> (Ball, Ball) {
    let precision = Precision::bits(bits);
    let (mut root, mut weight) = (Ball::from_i64(0, precision), Ball::from_i64(0, precision));
    // SAFETY: initialised; Arb sets the real parts (the imaginary parts stay exact 0).
    unsafe { arb_hypgeom_legendre_p_ui_root(root.real_mut(), weight.real_mut(), n, k, i64::from(bits)) };
    (root, weight)
}

/// The root of P_n in the ball `around` (which holds exactly one, from Arb) and its weight
/// at `bits`, from P_n and P_n′ at the ball's midpoint m; `None` where the result is not
/// narrower than `around` (the caller then asks Arb at the full precision).
///
/// With h = root − m and ξ, ζ between m and the root (inside `around`):
/// - 0 = P(m) + P′(ξ)h, and P′(ξ) lies in P′(m) + P″(`around`)·(`around` − m), so the root
///   lies in m − P(m)/that;
/// - P′(root) = P′(m) + P″(m)h + P‴(ζ)h²/2, with P″(m) from the Legendre equation
///   (1 − x²)P″ = 2xP′ − n(n+1)P and P‴ over `around` from its derivative
///   (1 − x²)P‴ = 4xP″ − (n(n+1) − 2)P′ and Arb's bounds of |P′| and |P″| over `around`.
fn newton_step(n: u64, around: &Ball, bits: u32) -> Option<(Ball, Ball)> {
    let working = bits + guard_bits(n);
    let precision = Precision::bits(working);
    let reach = Ball::from_i64(0, precision) + around;
    let mut mid = reach.clone();
    // SAFETY: an initialised real ball; its radius is set to exact zero.
    unsafe { mag_zero(&mut mid.real_mut().rad) };
    let one = mid.int(1);
    let (value, slope) = {
        let (mut value, mut slope) = (mid.int(0), mid.int(0));
        // SAFETY: initialised balls; Arb sets their real parts.
        unsafe {
            arb_hypgeom_legendre_p_ui(
                value.real_mut(),
                slope.real_mut(),
                n,
                &mid.as_raw().real,
                i64::from(working),
            )
        };
        (value, slope)
    };
    let reach_square = reach.square();
    let (slope_range, curvature_range) = derivative_ranges(n, &reach, &(reach_square.clone() - &one), precision);
    let slope_between = slope.clone() + &(curvature_range.clone() * &(reach.clone() - &mid));
    let root = mid.clone() - &(value.clone() / &slope_between);
    if !root.is_finite() || root.relative_radius() >= around.relative_radius() {
        return None;
    }
    let step = root.clone() - &mid;
    let eigenvalue = mid.int((n * (n + 1)) as i64);
    let curvature = (mid.int(2) * &mid * &slope - eigenvalue.clone() * &value) / &(one.clone() - &mid.square());
    let third_range = (reach.int(4) * &reach * &curvature_range - (eigenvalue - &mid.int(2)) * &slope_range)
        / &(one.clone() - &reach_square);
    let slope_at_root = slope + &(curvature * &step) + &(third_range * &step.square()).times_power_of_two(-1);
    let weight = mid.int(2) / &((one - &root.square()) * &slope_at_root.square());
    weight.is_finite().then(|| (round(&root, bits), round(&weight, bits)))
}

/// Balls that hold P_n′ and P_n″ everywhere on `x` (Arb's bounds of their magnitudes).
fn derivative_ranges(n: u64, x: &Ball, square_less_one: &Ball, precision: Precision) -> (Ball, Ball) {
    let (mut slope, mut curvature) = (Mag::new(), Mag::new());
    // SAFETY: initialised; Arb writes the two magnitudes.
    unsafe {
        arb_hypgeom_legendre_p_ui_deriv_bound(
            &mut slope.0,
            &mut curvature.0,
            n,
            &x.as_raw().real,
            &square_less_one.as_raw().real,
        )
    };
    let range = |bound: &Mag| {
        let mut ball = Ball::from_i64(0, precision);
        // SAFETY: an initialised real ball; only its radius grows.
        unsafe { arb_add_error_mag(ball.real_mut(), &bound.0) };
        ball
    };
    (range(&slope), range(&curvature))
}

/// `x` rounded to `bits` (a ball that contains it).
fn round(x: &Ball, bits: u32) -> Ball {
    let mut raw = acb_struct::default();
    // SAFETY: initialised; `wrap` takes it over.
    unsafe {
        acb_init(&mut raw);
        acb_set_round(&mut raw, x.as_raw(), i64::from(bits));
    }
    Ball::wrap(raw, bits)
}

#[cfg(test)]
mod tests {
    use rug::Float;

    use super::*;

    #[test]
    fn node_tables_are_the_gauss_legendre_rules() {
        // The 3-point rule: nodes ±√(3/5), 0 and weights 5/9, 8/9, 5/9.
        let table = nodes(3, 64).unwrap().nodes.clone();
        let root = (Float::with_val(400, 3) / 5u32).sqrt();
        assert!(table[0].0.contains(&root) && table[1].0.contains(&Float::new(400)));
        assert!(table[0].1.contains(&(Float::with_val(400, 5) / 9u32)));
        assert!(table[1].1.contains(&(Float::with_val(400, 8) / 9u32)));
        // Rounded from a table at higher precision, still the same nodes.
        let fine = nodes(3, 256).unwrap();
        let coarse = nodes(3, 64).unwrap();
        assert!(fine.nodes[0].0.contains(&root) && coarse.nodes[0].0.contains(&root));
        assert_eq!((fine.bits, coarse.bits), (256, 64));
    }

    #[test]
    fn a_newton_step_from_half_the_precision_encloses_arbs_root_and_weight_as_narrowly() {
        for (n, bits) in [(2u64, 256u32), (17, 256), (64, 512), (137, 1024), (416, 2112)] {
            for k in [0, 1, n / 3, n / 2 - 1] {
                let around = half_precision_root(n, k, bits);
                let (root, weight) = newton_step(n, &around, bits).expect("the step narrows the root");
                // Arb's, at 200 bits more: its midpoints are the true values to far
                // below the radii tested.
                let (exact_root, exact_weight) = arb_root(n, k, bits + 200);
                for (ours, exact) in [(&root, &exact_root), (&weight, &exact_weight)] {
                    let (low, high) = exact.bounds(bits + 264);
                    assert!(
                        ours.contains(&low) && ours.contains(&high),
                        "n = {n}, k = {k}: {ours:?} ∌ {exact:?}"
                    );
                    let radius = ours.relative_radius();
                    assert!(
                        radius < Float::with_val(64, 1) >> (bits - 8),
                        "n = {n}, k = {k}: {ours:?}"
                    );
                }
            }
        }
    }
}
