//! The range of v⁽ᵏ⁾ over a load interval, for the proven remainder of the
//! small-amplitude series (proofs/cubic-law-remainder.md).
//!
//! Every analytic family has, for k ≥ 2, a derivative of one sign whose magnitude is
//! monotone in the load on its domain: C·β(β − 1)…·P^(β − k + 1) for the power laws (Persson's
//! and Hertz's among them), b·(k − 2)!·(P + c)^(1 − k) up to sign for the rational family,
//! a·c^(1 − k)·e^(−P/c) for the exponential. Its range over [low, high] then lies between its
//! values at the ends, and on Arb balls the ends' values enclose it. A polynomial is bounded
//! by its Taylor coefficients about the middle; sums, multiples and load scalings combine
//! their terms' ranges. A table's cubic interpolant has derivatives that jump at its knots and
//! gives no bound.

use super::{falling_factorial, Compliance};
use crate::real::Real;

/// v⁽ᵏ⁾ at the ends of [low, high], least first: the range there of a derivative that is
/// monotone (the caller's family guarantees it on the domain it checks).
pub(super) fn at_the_ends<R: Real>(compliance: &dyn Compliance<R>, order: usize, low: &R, high: &R) -> Option<(R, R)> {
    let ends = [low, high].map(|load| compliance.derivative(order, load));
    let [Some(at_low), Some(at_high)] = ends else {
        return None;
    };
    (at_low.is_finite() && at_high.is_finite()).then(|| scaled_range(&at_low.int(1), &(at_low, at_high)))
}

/// {c·x : x in the range}, least first, for a factor c of either sign.
pub(crate) fn scaled_range<R: Real>(factor: &R, (least, greatest): &(R, R)) -> (R, R) {
    let (a, b) = (factor.clone() * least, factor.clone() * greatest);
    (a.min_of(&b), a.max_of(&b))
}

/// Whether `low` is surely positive and `low ≤ high`: the loads of a family singular at 0.
pub(super) fn positive_range<R: Real>(low: &R, high: &R) -> bool {
    *low > low.int(0) && *low <= *high
}

/// A bound on |p⁽ʲ⁾| over [low, high] for the polynomial p = Σ cₖ (P − reference)^k (j the
/// order of the derivative of p): p⁽ʲ⁾ re-expanded about the middle m of the interval,
/// Σ |dᵢ| hⁱ with h the half-width.
pub(super) fn polynomial_bound<R: Real>(reference: &R, coefficients: &[R], order: usize, low: &R, high: &R) -> R {
    let zero = low.int(0);
    let two = zero.int(2);
    let middle = (low.clone() + high) / &two;
    let half_width = ((high.clone() - low) / &two).abs();
    // The coefficients of p⁽ʲ⁾ in x = P − reference.
    let mut derived: Vec<R> = coefficients
        .iter()
        .enumerate()
        .skip(order)
        .map(|(k, c)| c.clone() * &falling_factorial(&zero.int(k as i64), order))
        .collect();
    // Taylor shift to the middle (synthetic division), then Σ |dᵢ| hⁱ.
    let shift = middle - reference;
    let degree = derived.len();
    for i in 0..degree {
        for k in (i..degree.saturating_sub(1)).rev() {
            let carried = derived[k + 1].clone() * &shift;
            derived[k] += &carried;
        }
    }
    derived
        .iter()
        .rev()
        .fold(zero.clone(), |acc, d| acc * &half_width + &d.abs())
}

#[cfg(test)]
mod tests {
    use super::super::{Exponential, Hertz, Persson, Polynomial, PowerLaw, Rational, Sum};
    use super::*;

    /// Every range holds v⁽ᵏ⁾ on a fine grid, and every bound is at least the largest
    /// |v⁽ᵏ⁾| there, and close to it.
    #[test]
    fn bounds_hold_on_a_grid_and_are_attained_at_an_end() {
        let families: Vec<Box<dyn Compliance<f64>>> = vec![
            Box::new(PowerLaw {
                coefficient: 1.3,
                exponent: -0.37,
            }),
            Box::new(Persson { gamma: 1.0, sigma: 0.5 }),
            Box::new(Hertz {
                radius: 2.0,
                contact_modulus: 3.0,
            }),
            Box::new(Rational {
                constant: 0.2,
                numerator: 1.5,
                offset: 0.4,
            }),
            Box::new(Exponential {
                amplitude: 1.0,
                decay_load: 0.7,
                constant: 0.1,
            }),
            Box::new(Polynomial {
                reference: 1.0,
                coefficients: vec![2.0, -0.5, 0.3, -0.2, 0.05],
            }),
            Box::new(Sum {
                terms: vec![
                    Box::new(Persson { gamma: 1.0, sigma: 1.0 }),
                    Box::new(PowerLaw {
                        coefficient: 2.0,
                        exponent: -0.5,
                    }),
                ],
            }),
        ];
        let (low, high) = (0.6, 1.7);
        for v in &families {
            for order in 2..=6 {
                let bound = v.derivative_bound(order, &low, &high).unwrap();
                let (least, greatest) = v.derivative_range(order, &low, &high).unwrap();
                let values: Vec<f64> = (0..=1000)
                    .map(|i| v.derivative(order, &(low + (high - low) * i as f64 / 1000.0)).unwrap())
                    .collect();
                let slack = 1e-12 * bound;
                assert!(
                    values.iter().all(|x| least - slack <= *x && *x <= greatest + slack),
                    "{} {order}: [{least}, {greatest}]",
                    v.describe()
                );
                let largest = values.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                assert!(
                    bound >= largest * (1.0 - 1e-12),
                    "{} {order}: {bound} < {largest}",
                    v.describe()
                );
                // The families' bounds are their ends' values; the polynomial's (by its
                // coefficients about the middle) and the sum's (of its terms) may exceed.
                assert!(
                    bound <= largest * 8.0 + 1e-12,
                    "{} {order}: {bound} vs {largest}",
                    v.describe()
                );
            }
        }
        // A family singular at P = 0 refuses a range that reaches it.
        assert!(PowerLaw {
            coefficient: 1.0,
            exponent: -0.5
        }
        .derivative_bound(3, &0.0, &1.0)
        .is_none());
        assert!(Rational {
            constant: 0.0,
            numerator: 1.0,
            offset: -0.5
        }
        .derivative_bound(3, &0.2, &1.0)
        .is_none());
    }
}
