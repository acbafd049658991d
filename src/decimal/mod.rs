//! Exact decimals in, the printing rule out.
//!
//! Decimals as written are read exactly: `0.4` is the rational 4/10, rounded once to each
//! working precision, and refused in f64 where f64 cannot hold it. [`printing`] holds the
//! one rule by which every value is printed, and [`value`] a value as printed with its
//! interval.

pub mod printing;
pub(crate) mod rounding;
pub mod value;

use rug::ops::Pow;
use rug::{Integer, Rational};

use crate::real::{Precision, Real};

/// The largest power of ten a decimal may carry (1e-100000 is read; 1e-10000000 is not).
const MAX_DECIMAL_EXPONENT: i64 = 100_000;

/// A plain decimal (`-1.5e-3`) as an exact rational; None for anything else.
pub fn decimal(text: &str) -> Option<Rational> {
    let text = text.trim();
    let (mantissa, exponent) = match text.split_once(['e', 'E']) {
        Some((mantissa, exponent)) => (mantissa, exponent.parse::<i64>().ok()?),
        None => (text, 0),
    };
    let (negative, mantissa) = match mantissa.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, mantissa.strip_prefix('+').unwrap_or(mantissa)),
    };
    let (whole, fraction) = mantissa.split_once('.').unwrap_or((mantissa, ""));
    let digits = format!("{whole}{fraction}");
    if digits.is_empty() || !digits.chars().all(|c| c.is_ascii_digit()) {
        return None;
    }
    let power = exponent.checked_sub(fraction.len() as i64)?;
    if power.abs() > MAX_DECIMAL_EXPONENT {
        return None;
    }
    let significand: Integer = digits.parse().ok()?;
    let scale = Integer::from(10).pow(power.unsigned_abs() as u32);
    let magnitude = if power >= 0 {
        Rational::from(significand * scale)
    } else {
        Rational::from((significand, scale))
    };
    Some(if negative { -magnitude } else { magnitude })
}

/// The exact `value` rounded once to `precision`, or None in f64 where it is lost to the
/// range of f64: it overflows, or underflows to zero or to a subnormal (which keeps fewer
/// than 53 bits). Above 53 bits the exponent range reaches far beyond any decimal given by hand.
pub fn rounded<R: Real>(value: &Rational, precision: Precision) -> Option<R> {
    let rounded = R::from_rational(value, precision);
    if precision != Precision::DOUBLE {
        return Some(rounded);
    }
    let zero = rounded.int(0);
    let smallest_normal = R::smallest_full_precision(precision) * &R::epsilon(precision);
    let lost = !rounded.is_finite()
        || (rounded == zero && *value != 0)
        || (rounded != zero && rounded.abs() < smallest_normal);
    (!lost).then_some(rounded)
}
