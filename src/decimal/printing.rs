//! The one printing rule: a digit is printed only if every point of a value's interval
//! rounds to it. Exact ends in (MPFR floats or doubles, expanded once by
//! `rounding`), a [`Decimal`] out.

use rug::float::Round;
use rug::Float;

use super::rounding::{scientific, DecimalEnd, Expansion};

/// The most significant digits an f64 result is printed with: binary64 carries 15.95
/// decimal digits, and 15 always survive a round trip through decimal text.
pub const F64_MOST_DIGITS: u32 = 15;

/// A value as printed by the one rule: an N-digit decimal is printed only if every point
/// of the value's interval [value − bound, value + bound] rounds to it (to nearest);
/// otherwise fewer digits, and where not even one is determined, the interval itself.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Decimal {
    /// Exactly zero: the interval is the point 0.
    Zero,
    /// The decimal in scientific notation (`5.25214879245e-1`) with its significant digits.
    Digits {
        /// The decimal as printed.
        text: String,
        /// Its significant digits.
        digits: u32,
    },
    /// Not one significant digit is determined: the interval, rounded outwards to two
    /// digits.
    Undetermined {
        /// The interval's lower end, rounded down.
        lower: String,
        /// The interval's upper end, rounded up.
        upper: String,
    },
}

/// A decimal in scientific notation (`8.26e-5`) times 10^`shift` (`8.26e-872038342` for a
/// shift of −872038337); text without an exponent (`0`, `inf`) as it is.
#[cfg(feature = "certified")]
pub(crate) fn shift_exponent(text: &str, shift: i64) -> String {
    match text
        .split_once('e')
        .map(|(mantissa, exponent)| (mantissa, exponent.parse::<i64>()))
    {
        Some((mantissa, Ok(exponent))) if shift != 0 => format!("{mantissa}e{}", exponent + shift),
        _ => text.to_string(),
    }
}

impl Decimal {
    /// The same decimal times 10^`shift`.
    #[cfg(feature = "certified")]
    pub(crate) fn shifted(self, shift: i64) -> Decimal {
        match self {
            Decimal::Zero => Decimal::Zero,
            Decimal::Digits { text, digits } => Decimal::Digits {
                text: shift_exponent(&text, shift),
                digits,
            },
            Decimal::Undetermined { lower, upper } => Decimal::Undetermined {
                lower: shift_exponent(&lower, shift),
                upper: shift_exponent(&upper, shift),
            },
        }
    }

    /// The significant digits determined: `u32::MAX` for an exact zero, 0 where none is.
    pub fn digits(&self) -> u32 {
        match self {
            Decimal::Zero => u32::MAX,
            Decimal::Digits { digits, .. } => *digits,
            Decimal::Undetermined { .. } => 0,
        }
    }
}

impl std::fmt::Display for Decimal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Decimal::Zero => f.write_str("0"),
            Decimal::Digits { text, .. } => f.write_str(text),
            Decimal::Undetermined { lower, upper } => write!(f, "no digit determined: in [{lower}, {upper}]"),
        }
    }
}

/// The f64 `value` printed with at most [`F64_MOST_DIGITS`] digits by the one rule, for an
/// absolute `bound` on its error ([`decimal_ball`], which it agrees with). Most digit counts
/// are settled in f64 alone (a few hundred nanoseconds); only an end within a few units
/// in the last place of a rounding boundary is settled in exact arithmetic.
pub fn decimal_f64(value: f64, bound: f64) -> Decimal {
    if !value.is_finite() || bound.is_nan() || bound.is_infinite() {
        let text = |x: f64| {
            if x.is_nan() {
                "NaN".to_string()
            } else {
                format!("{x:e}")
            }
        };
        return Decimal::Undetermined {
            lower: text(if bound.is_nan() { f64::NAN } else { value - bound.abs() }),
            upper: text(if bound.is_nan() { f64::NAN } else { value + bound.abs() }),
        };
    }
    let bound = bound.max(0.0);
    let exact = || (Float::with_val(53, value), Float::with_val(53, bound));
    if value.abs() <= bound {
        let (value, bound) = exact();
        return decimal_ball(&value, &bound, F64_MOST_DIGITS);
    }
    // A cell of N digits about a value of exponent e is 10^(e − N + 1) wide (one exponent
    // more where the value may round up to a power of ten), and must be wider than 2·bound.
    let most = match bound {
        0.0 => F64_MOST_DIGITS,
        _ => {
            let exponent = value.abs().log10().floor();
            let carry = if value.abs() >= 9.0 * 10f64.powf(exponent) {
                1.0
            } else {
                0.0
            };
            let width = exponent + 1.0 + carry - (2.0 * bound).log10() + 1e-6;
            (width.floor().max(0.0) as u32).min(F64_MOST_DIGITS)
        }
    };
    (1..=most)
        .rev()
        .find_map(|digits| {
            let text = match rounds_alike_in_f64(value - bound, value + bound, digits) {
                Ok(text) => text,
                Err(Undecided) => {
                    let (value, bound) = exact();
                    let (lower, upper) = ends(&value, &bound);
                    alike(
                        &lower.expansion(digits as usize + 1),
                        &upper.expansion(digits as usize + 1),
                        digits,
                    )
                }
            };
            text.map(|text| Decimal::Digits { text, digits })
        })
        .unwrap_or_else(|| {
            let (value, bound) = exact();
            decimal_ball(&value, &bound, F64_MOST_DIGITS)
        })
}

/// f64 arithmetic cannot tell: an end lies within a few ulps of a rounding boundary.
struct Undecided;

/// The `digits`-digit decimal to which every point of [`lower`, `upper`] rounds, where f64
/// can tell: `lower` and `upper` are the interval's ends rounded to nearest, so the true
/// ends lie within half an ulp of them, and two ulps further out on each side still
/// rounding alike (Rust's decimal formatting is correctly rounded) leaves no rounding
/// boundary inside. `Ok(None)` where each end's own rounding is certain and they differ.
fn rounds_alike_in_f64(lower: f64, upper: f64, digits: u32) -> Result<Option<String>, Undecided> {
    if !lower.is_finite() || !upper.is_finite() {
        return Err(Undecided);
    }
    let text = |y: f64| format!("{:.*e}", digits as usize - 1, y);
    let (outer_low, outer_high) = (text(lower.next_down().next_down()), text(upper.next_up().next_up()));
    if outer_low == outer_high {
        return Ok(Some(outer_low));
    }
    let (inner_low, inner_high) = (text(lower.next_up().next_up()), text(upper.next_down().next_down()));
    if inner_low == outer_low && inner_high == outer_high {
        Ok(None)
    } else {
        Err(Undecided)
    }
}

/// `value` printed with at most `most` significant digits by the one rule, for an absolute
/// `radius` about it: the most digits N for which every point of [`value` − `radius`,
/// `value` + `radius`] rounds to nearest to the same N-digit decimal, with neither end
/// on a rounding boundary (where ties would decide). The ends are rounded outwards, so
/// the interval tested contains the one given.
pub fn decimal_ball(value: &Float, radius: &Float, most: u32) -> Decimal {
    let radius = radius.clone().abs();
    if value.is_zero() && radius.is_zero() {
        return Decimal::Zero;
    }
    let (lower, upper) = ends(value, &radius);
    decimal_interval(&lower, &upper, most)
}

/// The interval [`lower`, `upper`] printed with at most `most` significant digits by the
/// one rule: the most digits N for which every point of it rounds to nearest to the same
/// N-digit decimal, with neither end on a rounding boundary.
pub fn decimal_interval(lower: &Float, upper: &Float, most: u32) -> Decimal {
    rounded_alike_expanded(lower, upper, most, 0).0
}

/// [`decimal_interval`] over ends of either kind (MPFR floats, or doubles: the same digits
/// without MPFR's conversions), and the ends' expansions it read, to at least `at_least`
/// digits (for the caller's other roundings of them; `None` for a zero or an infinite end).
pub(crate) fn rounded_alike_expanded<T: DecimalEnd>(
    lower: &T,
    upper: &T,
    most: u32,
    at_least: usize,
) -> (Decimal, Option<(Expansion, Expansion)>) {
    if lower.is_zero() && upper.is_zero() {
        return (Decimal::Zero, None);
    }
    let undetermined = || Decimal::Undetermined {
        lower: lower.directed(2, Round::Down),
        upper: upper.directed(2, Round::Up),
    };
    if !lower.is_finite() || !upper.is_finite() || lower.is_zero() || upper.is_zero() {
        return (undetermined(), None);
    }
    // Each end expanded once, to one digit more than the most that may be printed.
    let expand = at_least.max(most as usize + 1);
    let expansions = (lower.expansion(expand), upper.expansion(expand));
    if lower.is_sign_negative() != upper.is_sign_negative() {
        return (undetermined(), Some(expansions));
    }
    // A cell of N digits is wider than the interval only for N ≤ log10(|value|/width) + 2.
    let (lower_exact, upper_exact) = (lower.exact(), upper.exact());
    let width = Float::with_val(64, &upper_exact - &lower_exact);
    let magnitude = lower_exact.get_exp().max(upper_exact.get_exp());
    let most = match (magnitude, width.get_exp()) {
        (Some(v), Some(r)) => {
            let ratio_digits = (f64::from(v) - f64::from(r) + 1.0) * std::f64::consts::LOG10_2;
            (ratio_digits.floor().max(-1.0) as u32 + 2).min(most)
        }
        _ => most,
    };
    let decimal = (1..=most.max(1))
        .rev()
        .find_map(|digits| alike(&expansions.0, &expansions.1, digits).map(|text| Decimal::Digits { text, digits }))
        .unwrap_or_else(undetermined);
    (decimal, Some(expansions))
}

/// The `digits`-digit decimal to which every point between two expanded ends rounds, if
/// there is one and neither end is a tie.
fn alike(lower: &Expansion, upper: &Expansion, digits: u32) -> Option<String> {
    let low = lower.nearest(digits as usize)?;
    (upper.nearest(digits as usize)? == low).then(|| scientific(&low))
}

/// The ends of [`value` − `radius`, `value` + `radius`], rounded outwards (exact for f64
/// operands: 64 bits more than either holds).
pub(crate) fn ends(value: &Float, radius: &Float) -> (Float, Float) {
    let bits = value.prec().max(radius.prec()) + 64;
    let (lower, _) = Float::with_val_round(bits, value - radius, Round::Down);
    let (upper, _) = Float::with_val_round(bits, value + radius, Round::Up);
    (lower, upper)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::real::{Precision, Real};

    fn at(p: Precision, text: &str) -> Float {
        Float::parse_decimal(text, p).unwrap()
    }

    fn digits(text: &str, digits: u32) -> Decimal {
        Decimal::Digits {
            text: text.to_string(),
            digits,
        }
    }

    #[test]
    fn a_decimal_is_printed_only_where_the_whole_interval_rounds_to_it() {
        // 0.12345 ± 1e-9 rounds to 1.2345000e-1 at 8 digits and to nothing finer: at 9 its
        // ends are 1.23449999e-1 and 1.23450001e-1.
        assert_eq!(decimal_f64(0.12345, 1e-9), digits("1.2345000e-1", 8));
        // Straddling a rounding boundary costs the digit it straddles: [0.123454, 0.123458]
        // holds the boundary 0.123455 of 5 digits, so it has 4, though its width allows 5.
        assert_eq!(decimal_f64(0.123456, 2e-6), digits("1.235e-1", 4));
        // The most digits, not the fewest: [0.123549, 0.123551] straddles 4 digits' boundary
        // 0.12355 but lies inside a cell of 5.
        assert_eq!(decimal_f64(0.12355, 1e-6), digits("1.2355e-1", 5));
        // A carry into the next power of ten: [9.9996, 9.9998] rounds to 1.000e1 at 4 digits.
        assert_eq!(decimal_f64(9.9997, 1e-4), digits("1.000e1", 4));
        // An exact value has all of f64's digits; an end exactly on a rounding boundary is a
        // tie, which decides nothing: [0.375, 0.3828125] is not 3.8e-1 (0.375 ties between
        // 3.7e-1 and 3.8e-1), only 4e-1.
        assert_eq!(decimal_f64(0.25, 0.0), digits("2.50000000000000e-1", 15));
        assert_eq!(decimal_f64(0.37890625, 0.00390625), digits("4e-1", 1));
        assert!(matches!(decimal_f64(0.25, 0.05), Decimal::Undetermined { .. }));
        // Zero exactly is "0"; an interval about zero determines no digit, and says where W is.
        assert_eq!(decimal_f64(0.0, 0.0), Decimal::Zero);
        assert_eq!(decimal_f64(0.0, 0.0).to_string(), "0");
        let about_zero = decimal_f64(1e-17, 1.234e-16);
        assert_eq!(about_zero.digits(), 0);
        assert_eq!(about_zero.to_string(), "no digit determined: in [-1.2e-16, 1.4e-16]");
        // An interval not about zero but across a first-digit boundary: no digit either.
        assert_eq!(decimal_f64(0.95, 0.01).digits(), 0);
        // Negative values round by magnitude; f64's 15 digits are the most.
        assert_eq!(decimal_f64(-0.12345, 1e-9), digits("-1.2345000e-1", 8));
        assert_eq!(
            decimal_f64(1.0 / 3.0, 0.0),
            digits("3.33333333333333e-1", F64_MOST_DIGITS)
        );
        // MPFR values: 1/3 ± 10⁻⁴⁰ at up to 50 digits has 39 (its 40th is within a unit).
        let p = Precision::bits(300);
        let third = Float::with_val(p.in_bits(), 1) / 3u32;
        let ball = decimal_ball(&third, &at(p, "1e-40"), 50);
        assert_eq!(ball, digits(&format!("3.{}e-1", "3".repeat(38)), 39));
    }

    #[test]
    fn the_f64_shortcut_prints_what_exact_arithmetic_prints() {
        // Random values over 40 decades, both signs, bounds from 1e-17 to 1 of the value
        // and exact values: the f64 path equals the exact MPFR one on every draw
        // (300,000 draws in proofs/printing.md).
        let mut state: u64 = 88172645463325252;
        for _ in 0..20_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let sign = if state & 1 == 0 { 1.0 } else { -1.0 };
            let mantissa = f64::from_bits((state >> 12) | 0x3FE0_0000_0000_0000);
            let value = sign * mantissa * 10f64.powi((state % 40) as i32 - 20);
            let bound = match state % 97 {
                0 => 0.0,
                _ => value.abs() * 10f64.powf(-(((state >> 20) % 1700) as f64) / 100.0),
            };
            let exact = decimal_ball(
                &Float::with_val(53, value),
                &Float::with_val(53, bound),
                F64_MOST_DIGITS,
            );
            assert_eq!(decimal_f64(value, bound), exact, "{value:e} ± {bound:e}");
        }
    }

    #[test]
    fn the_two_misrounded_reproducers_lose_the_digit_their_bound_straddles() {
        // Persson (P1 = 0.82575): f64 W = 0.5252148792448502 with error estimate 2.6e-14;
        // W = 5.2521487924484932684e-1 (Arb), whose 13th digit is 8, not 9.
        let w = decimal_f64(0.5252148792448502, 2.6218303737392632e-14);
        assert_eq!(w, digits("5.25214879245e-1", 12));
        // v' = P⁻³: f64 W = 14018.010208534673, estimate 7.7e-10; W = 14018.01020853501…
        assert_eq!(
            decimal_f64(14018.010208534673, 7.72750012239026e-10),
            digits("1.40180102085e4", 12)
        );
    }
}
