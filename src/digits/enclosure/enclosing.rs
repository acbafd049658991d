//! What a rung of the certified ladder brings beyond [`Real`]: its own rule for one
//! piece's integral with a rigorous error bound, the tolerance that rule is asked for,
//! and how an enclosure is sized, compared and printed; and the piece such a rule
//! integrates ([`CertifiedPiece`]).

use std::cell::Cell;
use std::panic::{catch_unwind, AssertUnwindSafe};

use rug::Float;

use crate::decimal::value::Value;
use crate::doubts::{watch, with_analytic};
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

/// One integral of W: ∫ from `start` to `end` of `integrand`, summed into `group`.
pub struct CertifiedPiece<'a, R> {
    /// The segment's (or the closed form's term's) position.
    pub(super) group: usize,
    /// Its name, for messages.
    pub(super) label: &'static str,
    pub(super) start: R,
    pub(super) end: R,
    /// The integrand at real points, with the slope change formed without cancellation.
    pub(super) integrand: PieceIntegrand<'a, R>,
    /// The same analytic function with the slope change as a plain difference of slopes,
    /// for Arb's bound on complex balls: the precision of a bound does not matter, its
    /// width does, and the algebraic forms of the slope change (a root raised to powers
    /// and divided) widen far more on a complex ball than one `acb_pow` does.
    /// `None` where the integrand serves for both.
    pub(super) bound: Option<PieceIntegrand<'a, R>>,
    /// Integrand evaluations so far, against the piece's budget ([`evaluation_limit`]).
    pub(super) evaluations: Cell<i64>,
}

pub(super) type PieceIntegrand<'a, R> = Box<dyn Fn(&R) -> R + 'a>;

impl<R: Enclosing> CertifiedPiece<'_, R> {
    /// The integrand on `x` (required to be analytic there where `analytic`), or `None`
    /// where the evaluation met an undecided comparison or a branch cut, or panicked.
    pub(super) fn value(&self, x: &R, analytic: bool) -> Option<R> {
        self.evaluations.set(self.evaluations.get() + 1);
        let integrand = match (&self.bound, analytic) {
            (Some(bound), true) => bound,
            _ => &self.integrand,
        };
        let outcome = catch_unwind(AssertUnwindSafe(|| watch(|| with_analytic(analytic, || integrand(x)))));
        match outcome {
            Ok((value, doubts)) if doubts.none() => Some(value),
            _ => None,
        }
    }

    /// A rough value of the integral (three-point Gauss–Legendre on the midpoints),
    /// only to scale the tolerance Arb aims at; `None` where an evaluation fails.
    pub(super) fn rough_integral(&self) -> Option<R> {
        let half = (self.end.clone() - &self.start) / &self.start.int(2);
        let middle = self.start.clone() + &half;
        let offset = half.clone() * &(self.start.int(3) / &self.start.int(5)).sqrt();
        let mut sum = self.value(&middle, false)? * &self.start.int(8);
        for node in [middle.clone() - &offset, middle + &offset] {
            sum += self.value(&node, false)? * &self.start.int(5);
        }
        Some(sum * &half / &self.start.int(9))
    }

    /// A rough value of the integral that also sees the ends, where the pieces' narrow
    /// peaks lie (five-point Gauss–Lobatto); the three-point value where an end cannot
    /// be evaluated.
    pub(super) fn rough_integral_with_ends(&self) -> Option<R> {
        let (Some(at_start), Some(at_end)) = (self.value(&self.start, false), self.value(&self.end, false)) else {
            return self.rough_integral();
        };
        let int = |n: i64| self.start.int(n);
        let half = (self.end.clone() - &self.start) / &int(2);
        let middle = self.start.clone() + &half;
        let offset = half.clone() * &(int(3) / &int(7)).sqrt();
        // Weights 1/10, 49/90, 32/45, 49/90, 1/10 on [−1, 1], over 90.
        let mut sum = (at_start + &at_end) * &int(9) + &(self.value(&middle, false)? * &int(64));
        for node in [middle.clone() - &offset, middle + &offset] {
            sum += self.value(&node, false)? * &int(49);
        }
        Some(sum * &half / &int(90))
    }
}
