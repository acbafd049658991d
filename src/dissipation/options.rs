//! The accuracy and checking controls of a dissipation computation.

use crate::quad::{FixedRule, Settings};
use crate::real::Real;

/// Accuracy and checking controls.
#[derive(Clone, Debug)]
pub struct Options<R> {
    /// Target relative accuracy; `None` is 256 ulps of the working precision.
    pub relative_tolerance: Option<R>,
    /// The smallest Gauss–Legendre rule per segment (the first of the doubling sequence);
    /// 0 chooses (16 points).
    pub min_points: usize,
    /// Integrate every piece once with this Gauss–Legendre rule, no refinement; the error
    /// estimate is the change from the rule of a quarter of the points. For checking a
    /// converged result with another rule.
    pub fixed_points: Option<usize>,
    /// With `fixed_points`, size the error by the rule of a quarter of the points (on by
    /// default). Off where the value is only compared with an independent one, as the
    /// verification's check run is: the estimate would cost a fifth more and go unused.
    pub fixed_rule_error: bool,
    /// With `fixed_points`, the rule of each piece in turn (as [`super::Dissipation::piece_points`]
    /// gives them for the same case); where the count differs, `fixed_points` for all.
    pub fixed_points_per_piece: Option<Vec<usize>>,
    /// The largest Gauss–Legendre rule per segment before giving up.
    pub max_points: usize,
    /// Integrate with v'(x) − v'(P0) in place of v'(x) (exact, and free of cancellation).
    pub remove_constant_slope: bool,
    /// With `remove_constant_slope`, also take the linear part v''(P0)·(P − P0) out of
    /// v' and add its contribution v''(P0)·W[P − P0] from a separate integral
    /// (four-segment path only). Exact by linearity; proofs/stability.md shows it
    /// changes nothing beyond rounding, so it is off by default.
    pub remove_linear_slope: bool,
    /// Refuse cycles whose loads alone, rounded at the working precision, would move W
    /// by more than this relative amount (ε × `LoadCycle::rounding_amplification`):
    /// in f64 that is a cycle within about P0/4500 of separation or of gross slip.
    pub rounding_limit: f64,
    /// Give up with [`super::DissipationError::OutOfTime`] once this instant has passed
    /// (checked between refinements).
    pub deadline: Option<std::time::Instant>,
    /// Refuse compliances with v' ≤ 0 or v'' > 0 over the loads the cycle reaches.
    /// The dissipation functional is linear in v' and defined for any v'; turn this
    /// off to apply it to non-physical v' (as the small-amplitude coefficient does).
    pub check_compliance: bool,
}

impl<R> Default for Options<R> {
    fn default() -> Self {
        Options {
            relative_tolerance: None,
            min_points: 0,
            fixed_points: None,
            fixed_rule_error: true,
            fixed_points_per_piece: None,
            max_points: 512,
            remove_constant_slope: true,
            remove_linear_slope: false,
            rounding_limit: 1e-12,
            deadline: None,
            check_compliance: true,
        }
    }
}

impl<R: Real> Options<R> {
    /// What the quadrature engine is asked for: the tolerance (256 ulps of `like`'s
    /// precision unless given), the rules, the deadline.
    pub(crate) fn settings(&self, like: &R) -> Settings<R> {
        let relative_tolerance = self
            .relative_tolerance
            .clone()
            .unwrap_or_else(|| like.epsilon_like() * &like.int(256));
        // Automatic first rule: 16 points, where an ordinary case already has several
        // digits in f64; at higher precision a larger start would skip the small rules
        // whose changes let the engine's predicted error stop a doubling early.
        let first_points = match self.min_points {
            0 => 16,
            points => points.max(2),
        };
        Settings {
            relative_tolerance,
            first_points,
            max_points: self.max_points.max(first_points),
            fixed: self.fixed_points.map(|points| FixedRule {
                points,
                per_piece: self.fixed_points_per_piece.clone(),
                quarter_rule_error: self.fixed_rule_error,
            }),
            deadline: self.deadline,
        }
    }
}
