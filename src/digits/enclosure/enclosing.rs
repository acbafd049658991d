//! What a rung of the certified ladder brings beyond [`Real`]: its own rule for one
//! piece's integral with a rigorous error bound, the tolerance that rule is asked for,
//! and how an enclosure is sized, compared and printed.

use rug::Float;

use super::pieces::CertifiedPiece;
use crate::answer::Value;
use crate::real::Real;

/// A number type whose values are enclosures of the exact values they compute (Arb
/// balls, f64 intervals), with a rigorous quadrature on it.
pub trait Enclosing: Real + Send + Sync {
    /// An upper bound of the absolute error one piece's rule may leave.
    type Tolerance;

    /// 2^−`goal_bits` of an upper bound of |`scale`|, or zero where there is no scale.
    fn tolerance(scale: Option<&Self>, goal_bits: u32) -> Self::Tolerance;

    /// An enclosure of the piece's integral at `bits` of working precision, within
    /// `tolerance` where the rule can (wider otherwise); not finite where the integrand
    /// has no enclosure that the rule can bound.
    fn integrate_piece(
        piece: &CertifiedPiece<'_, Self>,
        goal_bits: u32,
        tolerance: &Self::Tolerance,
        bits: u32,
    ) -> Self;

    /// Whether every |x| in `self` is below 2^`log2_factor` times the least |y| in
    /// `scale`: how a value that should be much smaller than another is recognised.
    fn is_below_scaled(&self, scale: &Self, log2_factor: i64) -> bool;

    /// Of two enclosures of one value, the one whose bound on the absolute value is
    /// smaller.
    fn tighter(self, other: Self) -> Self;

    /// Whether the enclosure's size has a decimal exponent that microslip prints.
    fn decimal_exponent_fits(&self) -> bool;

    /// An upper bound of the radius relative to the midpoint (infinite where the
    /// enclosure holds zero and is not zero).
    fn relative_radius(&self) -> Float;

    /// The enclosed value by the one printing rule, with at most `most` significant
    /// digits: those that every number of the enclosure rounds to.
    fn decimal_value(&self, most: u32) -> Value;
}
