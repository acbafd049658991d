//! The accuracy and checking controls of a dissipation computation.

use std::time::Instant;

use crate::quad::{FixedRule, RuleError, Settings};
use crate::real::Real;

/// How the pieces of a computation are integrated.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Rules {
    /// Gauss–Legendre rules of doubling degree until the tolerance is met, tanh–sinh
    /// where they stall.
    Adaptive {
        /// The first rule of the doubling sequence; `None` chooses (16 points).
        first_points: Option<usize>,
        /// The largest Gauss–Legendre rule per piece before tanh–sinh takes over.
        max_points: usize,
    },
    /// Every piece once with a fixed Gauss–Legendre rule, no refinement: for checking a
    /// converged result with another rule.
    Fixed(FixedRule),
}

impl Default for Rules {
    /// Adaptive, from 16 points up to 512.
    fn default() -> Self {
        Rules::Adaptive {
            first_points: None,
            max_points: 512,
        }
    }
}

/// Accuracy and checking controls. [`Options::default`] converges to 256 ulps of the
/// working precision with no deadline; the builder methods change one control each:
///
/// ```
/// use microslip::dissipation::Options;
/// use std::time::{Duration, Instant};
///
/// let options = Options::default()
///     .with_tolerance(1e-10)
///     .with_max_points(1024)
///     .with_deadline(Instant::now() + Duration::from_secs(2));
/// assert_eq!(options.relative_tolerance, Some(1e-10));
/// ```
#[derive(Clone, Debug)]
pub struct Options<R> {
    /// Target relative accuracy; `None` is 256 ulps of the working precision.
    pub relative_tolerance: Option<R>,
    /// Adaptive or fixed rules.
    pub rules: Rules,
    /// Integrate with v'(x) − v'(P0) in place of v'(x) (exact, and free of cancellation).
    pub remove_constant_slope: bool,
    /// Refuse cycles whose loads alone, rounded at the working precision, would move W
    /// by more than this relative amount (ε × `LoadCycle::rounding_amplification`):
    /// in f64 that is a cycle within about P0/4500 of separation or of gross slip.
    pub rounding_limit: f64,
    /// Give up with [`super::DissipationError::OutOfTime`] rather than run past this instant.
    pub deadline: Option<Instant>,
    /// Refuse compliances with v' ≤ 0 or v'' > 0 over the loads the cycle reaches.
    /// The dissipation functional is linear in v' and defined for any v'; turn this
    /// off to apply it to non-physical v' (as the small-amplitude coefficient does).
    pub check_compliance: bool,
}

impl<R> Default for Options<R> {
    fn default() -> Self {
        Options {
            relative_tolerance: None,
            rules: Rules::default(),
            remove_constant_slope: true,
            rounding_limit: 1e-12,
            deadline: None,
            check_compliance: true,
        }
    }
}

impl<R> Options<R> {
    /// The target relative accuracy.
    pub fn with_tolerance(self, relative_tolerance: R) -> Self {
        Options {
            relative_tolerance: Some(relative_tolerance),
            ..self
        }
    }

    /// Adaptive rules from `first_points` (the first of the doubling sequence).
    pub fn with_first_points(self, first_points: usize) -> Self {
        let max_points = self.max_points();
        Options {
            rules: Rules::Adaptive {
                first_points: Some(first_points),
                max_points,
            },
            ..self
        }
    }

    /// Adaptive rules up to `max_points` before tanh–sinh takes over.
    pub fn with_max_points(self, max_points: usize) -> Self {
        let first_points = match self.rules {
            Rules::Adaptive { first_points, .. } => first_points,
            Rules::Fixed(_) => None,
        };
        Options {
            rules: Rules::Adaptive {
                first_points,
                max_points,
            },
            ..self
        }
    }

    /// Every piece once with the `points`-point rule, its error sized as `error` says.
    pub fn with_fixed_rule(self, points: usize, error: RuleError) -> Self {
        self.with_fixed_rules(FixedRule {
            points,
            per_piece: None,
            error,
        })
    }

    /// Every piece once with the rule given.
    pub fn with_fixed_rules(self, rule: FixedRule) -> Self {
        Options {
            rules: Rules::Fixed(rule),
            ..self
        }
    }

    /// Give up rather than run past `deadline`.
    pub fn with_deadline(self, deadline: Instant) -> Self {
        Options {
            deadline: Some(deadline),
            ..self
        }
    }

    /// Integrate v' itself, not v'(x) − v'(P0) (for showing what the subtraction saves).
    pub fn keeping_constant_slope(self) -> Self {
        Options {
            remove_constant_slope: false,
            ..self
        }
    }

    /// Refuse cycles whose loads' rounding alone would move W by more than `limit`, relative.
    pub fn with_rounding_limit(self, limit: f64) -> Self {
        Options {
            rounding_limit: limit,
            ..self
        }
    }

    /// Apply the functional to any v', physical or not.
    pub fn without_compliance_check(self) -> Self {
        Options {
            check_compliance: false,
            ..self
        }
    }

    /// The largest Gauss–Legendre rule the computation may use (the fixed rule's largest).
    fn max_points(&self) -> usize {
        match &self.rules {
            Rules::Adaptive { max_points, .. } => *max_points,
            Rules::Fixed(rule) => rule.largest(),
        }
    }
}

/// The automatic first rule: 16 points, where an ordinary case already has several
/// digits in f64; at higher precision a larger start would skip the small rules whose
/// changes let the engine's predicted error stop a doubling early.
const FIRST_POINTS: usize = 16;

impl<R: Real> Options<R> {
    /// What the quadrature engine is asked for: the tolerance (256 ulps of `like`'s
    /// precision unless given), the rules, the deadline.
    pub(crate) fn settings(&self, like: &R) -> Settings<R> {
        let relative_tolerance = self
            .relative_tolerance
            .clone()
            .unwrap_or_else(|| like.epsilon_like() * &like.int(256));
        let mut settings = Settings::new(relative_tolerance);
        settings.deadline = self.deadline;
        match &self.rules {
            Rules::Adaptive {
                first_points,
                max_points,
            } => {
                settings.first_points = first_points.unwrap_or(FIRST_POINTS).max(2);
                settings.max_points = (*max_points).max(settings.first_points);
            }
            Rules::Fixed(rule) => settings.fixed = Some(rule.clone()),
        }
        settings
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_converges_from_16_points_to_512_at_256_ulps() {
        let settings = Options::<f64>::default().settings(&1.0);
        assert_eq!((settings.first_points, settings.max_points), (16, 512));
        assert_eq!(settings.relative_tolerance, 256.0 * f64::EPSILON);
        assert!(settings.fixed.is_none() && settings.deadline.is_none());
    }

    #[test]
    fn adaptive_rules_keep_a_sensible_order_of_first_and_largest() {
        let options = Options::<f64>::default().with_max_points(64).with_first_points(128);
        assert_eq!(
            options.rules,
            Rules::Adaptive {
                first_points: Some(128),
                max_points: 64
            }
        );
        // The largest rule is never below the first, and the first is at least 2 points.
        let settings = options.settings(&1.0);
        assert_eq!((settings.first_points, settings.max_points), (128, 128));
        let settings = Options::<f64>::default().with_first_points(0).settings(&1.0);
        assert_eq!(settings.first_points, 2);
    }

    #[test]
    fn a_fixed_rule_replaces_the_adaptive_one_and_back() {
        let deadline = Instant::now();
        let options = Options::<f64>::default()
            .with_tolerance(1e-9)
            .with_deadline(deadline)
            .with_fixed_rule(64, RuleError::RoundingFloor);
        let settings = options.settings(&1.0);
        let fixed = settings.fixed.expect("a fixed rule");
        assert_eq!(
            (fixed.points, fixed.per_piece, fixed.error),
            (64, None, RuleError::RoundingFloor)
        );
        assert_eq!((settings.relative_tolerance, settings.deadline), (1e-9, Some(deadline)));
        // Asking for adaptive rules again starts from the automatic first rule.
        let adaptive = options.with_max_points(1024);
        assert_eq!(
            adaptive.rules,
            Rules::Adaptive {
                first_points: None,
                max_points: 1024
            }
        );
        let per_piece = Options::<f64>::default().with_fixed_rules(FixedRule {
            points: 32,
            per_piece: Some(vec![16, 256]),
            error: RuleError::QuarterRule,
        });
        // Switching from per-piece fixed rules keeps the largest of them as the cap.
        assert_eq!(
            per_piece.with_first_points(8).rules,
            Rules::Adaptive {
                first_points: Some(8),
                max_points: 256
            }
        );
    }

    #[test]
    fn the_checks_can_be_relaxed_one_by_one() {
        let options = Options::<f64>::default()
            .keeping_constant_slope()
            .without_compliance_check()
            .with_rounding_limit(1.0);
        assert!(!options.remove_constant_slope && !options.check_compliance);
        assert_eq!(options.rounding_limit, 1.0);
    }
}
