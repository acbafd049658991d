//! mπ + x for an exact rational m and x, enclosed to a relative accuracy however much x
//! cancels mπ: what a phase near a multiple of π needs, and what no fixed precision gives.

use rug::{Float, Rational};

use super::ball::Ball;
use crate::real::{Precision, Real};

/// Bits a phase offset is computed with beyond the working precision and its exponent.
const PHASE_GUARD_BITS: u32 = 64;
/// The most bits the offset of a phase from its nearest multiple of π may need.
const MAX_PHASE_BITS: u32 = 1 << 22;

/// A ball that contains mπ + x with the relative accuracy of `precision` (the working
/// bits are raised while x cancels mπ; it is not zero unless m = x = 0, π being
/// irrational), or as close to it as the largest working precision allowed (2²² bits) gives.
pub fn enclose_pi_multiple(multiple: &Rational, offset: &Rational, precision: Precision) -> Ball {
    if *multiple == 0 {
        return Ball::from_rational(offset, precision);
    }
    let exponent = (multiple.to_f64().abs() * std::f64::consts::PI + offset.to_f64().abs())
        .max(1.0)
        .log2()
        .ceil() as u32;
    let mut working = precision.in_bits() + exponent + PHASE_GUARD_BITS;
    loop {
        let at = Precision::bits(working);
        let psi = Ball::from_rational(multiple, at) * &Ball::pi(at) + &Ball::from_rational(offset, at);
        if relatively_within(&psi, precision.in_bits()) || working.saturating_mul(2) > MAX_PHASE_BITS {
            // SAFETY: `psi` is an initialised ball; the copy keeps its midpoint and radius.
            return unsafe { Ball::from_raw(psi.as_raw(), precision.in_bits()) };
        }
        working = working.saturating_mul(2);
    }
}

/// Whether the ball's width is at most 2^−`bits` of its smallest magnitude (a ball
/// that contains zero is not).
pub(crate) fn relatively_within(ball: &Ball, bits: u32) -> bool {
    let (lower, upper) = ball.bounds(ball.precision().in_bits() + 64);
    if lower.is_zero() || upper.is_zero() || lower.is_sign_negative() != upper.is_sign_negative() {
        return false;
    }
    let width = Float::with_val(64, &upper - &lower);
    let smallest = lower.get_exp().min(upper.get_exp()).unwrap_or(i32::MIN);
    width.is_zero() || i64::from(width.get_exp().unwrap_or(i32::MAX)) + i64::from(bits) < i64::from(smallest)
}
