//! The f64 interval rung: each piece integrated by `interval::gauss`, Gauss–Legendre
//! rules whose error is bounded on a Bernstein ellipse through one evaluation of the
//! integrand on a complex rectangle; a piece it cannot bound has no enclosure here, and
//! the ladder climbs to Arb.

use rug::Float;

use super::enclosing::CertifiedPiece;
use super::enclosing::Enclosing;
use crate::decimal::value::Value;
use crate::interval::{gauss, Interval};
use crate::real::Real;

/// The most points of one interval rule: beyond them a piece is halved.
const DEGREE_LIMIT: u64 = 256;

impl Enclosing for Interval {
    /// An upper bound of the absolute error, as a double (zero: no rule can meet it).
    type Tolerance = f64;

    fn tolerance(scale: Option<&Interval>, goal_bits: u32) -> f64 {
        // Scaling by a power of two is exact above the subnormals; a tolerance need only
        // be near its aim, the enclosure is rigorous whatever it is.
        scale.map_or(0.0, |scale| {
            scale.magnitude_bound() * 2f64.powi(-i32::try_from(goal_bits).unwrap_or(i32::MAX))
        })
    }

    fn integrate_piece(piece: &CertifiedPiece<'_, Interval>, _: u32, tolerance: &f64, _: u32) -> Interval {
        let integrand = |x: &Interval, analytic: bool| piece.value(x, analytic);
        let refused = Interval::new(f64::NEG_INFINITY, f64::INFINITY);
        if !(*tolerance > 0.0 && tolerance.is_finite()) {
            return refused;
        }
        gauss::integrate(&integrand, &piece.start, &piece.end, *tolerance, DEGREE_LIMIT).unwrap_or(refused)
    }

    fn is_below_scaled(&self, scale: &Interval, log2_factor: i64) -> bool {
        let (lo, hi) = scale.real_bounds();
        let least = if lo > 0.0 {
            lo
        } else if hi < 0.0 {
            -hi
        } else {
            0.0
        };
        let factor = 2f64.powi(log2_factor.clamp(-2000, 2000) as i32);
        self.magnitude_bound() < least * factor
    }

    fn tighter(self, other: Interval) -> Interval {
        if other.magnitude_bound() < self.magnitude_bound() {
            other
        } else {
            self
        }
    }

    /// Every finite double's exponent is printed.
    fn decimal_exponent_fits(&self) -> bool {
        true
    }

    fn relative_radius(&self) -> Float {
        let (lo, hi) = self.real_bounds();
        let up = rug::float::Round::Up;
        if lo == 0.0 && hi == 0.0 {
            return Float::new(64);
        }
        if !(lo.is_finite() && hi.is_finite())
            || lo.is_sign_negative() != hi.is_sign_negative()
            || lo == 0.0
            || hi == 0.0
        {
            return Float::with_val(64, rug::float::Special::Infinity);
        }
        let width = Float::with_val_round(64, Float::with_val(53, hi) - lo, up).0;
        let smallest = lo.abs().min(hi.abs());
        Float::with_val_round(64, width / smallest, up).0
    }

    fn decimal_value(&self, most: u32) -> Value {
        Value::of_interval(self, most)
    }
}
