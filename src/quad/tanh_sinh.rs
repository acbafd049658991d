//! Tanh–sinh (double-exponential) quadrature at any precision.
//!
//! The substitution x = tanh(π/2 · sinh u) crowds nodes toward both ends
//! double-exponentially, so integrable end-point singularities (x^(−1/2),
//! ln x, square-root end points) converge about as fast as smooth integrands:
//! each halving of the step roughly doubles the correct digits. Abscissae near
//! an end are formed from the distance to that end, never as 1 − tanh(·), so
//! no digits are lost there.

use super::Estimate;
use crate::real::Real;

/// The integrand at the abscissae of one level: returns Σ w·f over the nodes
/// u = offset + j·spacing, j = 0, 1, …, on both sides of the midpoint.
struct Transform<R> {
    a: R,
    b: R,
    half_width: R,
    half_pi: R,
    u_max: f64,
}

impl<R: Real> Transform<R> {
    fn new(a: &R, b: &R) -> Self {
        let precision = a.precision();
        // Stop where the weight falls below 2^(−2·bits): the tails are negligible there.
        let s_max = f64::from(precision.in_bits()) * std::f64::consts::LN_2 + 20.0;
        Transform {
            a: a.clone(),
            b: b.clone(),
            half_width: (b.clone() - a) / a.int(2),
            half_pi: R::pi(precision) / a.int(2),
            u_max: (2.0 * s_max / std::f64::consts::PI).asinh(),
        }
    }

    /// Σ over the nodes u = start, start + spacing, … ≤ u_max (and their mirrors −u) of w(u)·[f(x(u)) + f(x(−u))];
    /// the midpoint u = 0 is counted once when `start` is 0.
    fn sum<F: FnMut(&R) -> R>(&self, integrand: &mut F, start: f64, spacing: f64, evaluations: &mut usize) -> R {
        let mut total = self.a.int(0);
        let mut index = 0usize;
        loop {
            let u_f64 = start + spacing * index as f64;
            if u_f64 > self.u_max {
                break;
            }
            index += 1;
            let u = R::from_f64(u_f64, self.a.precision());
            let exp_u = u.exp();
            let sinh_u = (exp_u.clone() - &(exp_u.int(1) / &exp_u)) / u.int(2);
            let cosh_u = (exp_u.clone() + &(exp_u.int(1) / &exp_u)) / u.int(2);
            let s = self.half_pi.clone() * &sinh_u;
            // Distance of the node from the nearer end, in units of the half width: 1 − tanh s = 2/(1 + e^{2s}).
            let e2s = (s.clone() * s.int(2)).exp();
            let complement = s.int(2) / (e2s.clone() + s.int(1));
            let one_plus_t = s.int(2) - &complement;
            let weight = self.half_pi.clone() * &cosh_u * &complement * &one_plus_t;
            if u_f64 == 0.0 {
                let middle = (self.a.clone() + &self.b) / self.a.int(2);
                total += weight * integrand(&middle);
                *evaluations += 1;
                continue;
            }
            // A node that rounds onto an end is skipped on that side only: near a
            // singular end the other side's nodes still matter far below the rounding of b − offset.
            let offset = self.half_width.clone() * &complement;
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
            total += weight * &values;
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
    let mut evaluations = 0;
    let mut spacing = 1.0f64;
    let mut sum = transform.sum(&mut integrand, 0.0, spacing, &mut evaluations);
    let mut previous = sum.clone() * &transform.half_width;
    let mut level = 0;
    let (mut smallest, mut stalled): (Option<R>, u32) = (None, 0);
    loop {
        level += 1;
        // The new level's nodes are the odd multiples of the new spacing.
        spacing /= 2.0;
        sum += transform.sum(&mut integrand, spacing, 2.0 * spacing, &mut evaluations);
        let current = sum.clone() * &transform.half_width * &R::from_f64(spacing, a.precision());
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
