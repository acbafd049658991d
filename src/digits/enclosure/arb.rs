//! The Arb rung: balls at 64 bits and more, each piece integrated by Gauss–Legendre rules
//! whose error is bounded by the integrand's size on a complex ball around the piece
//! (Arb's bound: `ball_gauss` at the fewest points it allows, Arb's `acb_calc_integrate`
//! where that needs bisection).

use rug::Float;

use super::enclosing::CertifiedPiece;
use super::enclosing::Enclosing;
use crate::arb::bisection;
use crate::ball::{Ball, Mag};
use crate::ball_gauss;
use crate::decimal::value::Value;
use crate::real::Real;

impl Enclosing for Ball {
    type Tolerance = Mag;

    fn tolerance(scale: Option<&Ball>, goal_bits: u32) -> Mag {
        Mag::tolerance(scale, goal_bits)
    }

    fn integrate_piece(piece: &CertifiedPiece<'_, Ball>, goal_bits: u32, tolerance: &Mag, bits: u32) -> Ball {
        integrate_piece(piece, goal_bits, tolerance, bits)
    }

    fn is_below_scaled(&self, scale: &Ball, log2_factor: i64) -> bool {
        Ball::is_below_scaled(self, scale, log2_factor)
    }

    fn tighter(self, other: Ball) -> Ball {
        Ball::tighter(self, other)
    }

    fn decimal_exponent_fits(&self) -> bool {
        Ball::decimal_exponent_fits(self)
    }

    fn relative_radius(&self) -> Float {
        Ball::relative_radius(self)
    }

    fn decimal_value(&self, most: u32) -> Value {
        Value::of_ball(self, self.precision().in_bits(), most)
    }
}

/// Integrand evaluations Arb may spend on one piece, besides 16 per bit of precision
/// (an ordinary piece needs a few hundred).
const EVALUATION_LIMIT: i64 = 20_000;

/// The enclosure of one piece's integral at `bits` of working precision: Gauss–Legendre
/// rules at the fewest points their bounds allow (`ball_gauss`), Arb's adaptive
/// bisection on what they leave.
fn integrate_piece(piece: &CertifiedPiece<'_, Ball>, goal_bits: u32, tolerance: &Mag, bits: u32) -> Ball {
    let integrand = |x: &Ball, analytic: bool| piece.value(x, analytic);
    let otherwise = |start: &Ball, end: &Ball| {
        let left = evaluation_limit(bits) - piece.evaluations.get();
        if left <= 0 {
            return start.indeterminate();
        }
        bisection::integrate(&integrand, (start, end), goal_bits, tolerance, bits, left)
    };
    if tolerance.is_zero() {
        // Arb's relative goal alone: no rule of this module can meet a zero tolerance.
        return otherwise(&piece.start, &piece.end);
    }
    let rule = ball_gauss::Rule {
        integrand: &integrand,
        tolerance: &tolerance.0,
        // Arb's own limit on the degree.
        degree_limit: u64::from(goal_bits.min(bits) / 2 + 60),
        otherwise: &otherwise,
    };
    rule.integrate(&piece.start, &piece.end, ball_gauss::OWN_DEPTH)
}

/// The integrand evaluations a piece may spend at `bits`: Arb's default, 1000·prec +
/// prec², lets a piece that cannot be enclosed (an integrand undecided near a point) run
/// for minutes at high precision.
fn evaluation_limit(bits: u32) -> i64 {
    EVALUATION_LIMIT + 16 * i64::from(bits)
}
