//! The one number type every integral in microslip runs on.
//!
//! [`Real`] is implemented for `f64` and for [`rug::Float`] (MPFR) at a precision
//! chosen at run time. Generic code never names either type: it builds constants
//! at the precision of the values it already holds (`x.int(2)`, `x.ratio(5, 6)`)
//! or at an explicit [`Precision`], and calls the elementary functions through
//! this trait. Arithmetic follows the owned-left, borrowed-right pattern
//! (`a.clone() * &b`), which both types support without copies for `f64`.

use std::fmt::Debug;
use std::ops::Neg;

use num_traits::{NumAssignOps, NumOps, ToPrimitive};
use rug::float::{Constant, Round};
use rug::ops::Pow;
use rug::Float;

/// Working precision: the number of bits in the significand.
///
/// `f64` always works at 53 bits whatever is asked; `rug::Float` works at
/// exactly the precision asked.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Precision(u32);

impl Precision {
    /// The precision of an IEEE double.
    pub const DOUBLE: Precision = Precision(53);

    /// A precision of `bits` significand bits (at least 2).
    pub fn bits(bits: u32) -> Precision {
        Precision(bits.max(2))
    }

    /// The smallest precision that holds `digits` significant decimal digits.
    pub fn decimal_digits(digits: u32) -> Precision {
        Precision::bits((f64::from(digits) * std::f64::consts::LOG2_10).ceil() as u32 + 1)
    }

    /// Significand bits.
    pub fn in_bits(self) -> u32 {
        self.0
    }

    /// Decimal digits this precision carries (rounded down).
    pub fn in_decimal_digits(self) -> u32 {
        (f64::from(self.0 - 1) / std::f64::consts::LOG2_10).floor() as u32
    }
}

/// A decimal string that is not a number.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("'{text}' is not a decimal number")]
pub struct ParseRealError {
    /// The text that failed to parse.
    pub text: String,
}

/// A real number at a definite precision: `f64`, or `rug::Float` at any precision.
pub trait Real:
    Clone
    + Debug
    + PartialOrd
    + Send
    + Sync
    + 'static
    + Neg<Output = Self>
    + NumOps<Self, Self>
    + for<'a> NumOps<&'a Self, Self>
    + NumAssignOps<Self>
    + for<'a> NumAssignOps<&'a Self>
    + ToPrimitive
{
    /// The precision this value carries.
    fn precision(&self) -> Precision;
    /// `x` exactly (every f64 is representable at 53 bits or more).
    fn from_f64(x: f64, precision: Precision) -> Self;
    /// The integer `n`, rounded to the precision.
    fn from_i64(n: i64, precision: Precision) -> Self;
    /// An MPFR value rounded once to the precision (to nearest).
    fn from_float(x: &rug::Float, precision: Precision) -> Self;
    /// A decimal string read as an exact decimal, rounded once to the precision
    /// (`"0.4"` means 4/10, not the double nearest to it).
    fn parse_decimal(text: &str, precision: Precision) -> Result<Self, ParseRealError>;
    /// An exact rational rounded once to the precision (to nearest), as [`Real::parse_decimal`]
    /// rounds the decimal it reads; a ball encloses it instead.
    fn from_rational(x: &rug::Rational, precision: Precision) -> Self {
        Self::from_float(&rug::Float::with_val(precision.in_bits(), x), precision)
    }
    /// An enclosure of mπ + x (m, x rational) with the precision's relative accuracy, for
    /// a type that encloses values (a ball); `None` for a type that rounds (f64, MPFR),
    /// which reads the phase rounded once from its exact reduction instead.
    fn enclose_pi_multiple(multiple: &rug::Rational, offset: &rug::Rational, precision: Precision) -> Option<Self> {
        let _ = (multiple, offset, precision);
        None
    }
    /// π at the precision.
    fn pi(precision: Precision) -> Self;
    /// The distance from 1 to the next larger number at the precision.
    fn epsilon(precision: Precision) -> Self;
    /// The smallest magnitude that still carries the full precision: below it (f64
    /// subnormals) results lose digits silently.
    fn smallest_full_precision(precision: Precision) -> Self;

    /// The square root, correctly rounded.
    fn sqrt(&self) -> Self;
    /// The real cube root (negative for a negative argument).
    fn cbrt(&self) -> Self;
    /// The natural logarithm.
    fn ln(&self) -> Self;
    /// ln(1 + x), accurate for small x.
    fn ln_1p(&self) -> Self;
    /// eˣ.
    fn exp(&self) -> Self;
    /// eˣ − 1, accurate for small x.
    fn exp_m1(&self) -> Self;
    /// `self` raised to a real power.
    fn powr(&self, exponent: &Self) -> Self;
    /// `self` raised to an integer power.
    fn powi(&self, exponent: i32) -> Self;
    /// The sine (argument in radians).
    fn sin(&self) -> Self;
    /// The cosine (argument in radians).
    fn cos(&self) -> Self;
    /// (sin, cos) together, for about the price of one.
    fn sin_cos(&self) -> (Self, Self);
    /// √(self² + other²) without overflow or underflow in the squares.
    fn hypot(&self, other: &Self) -> Self;
    /// The angle of the point (x, y) = (`x`, `self`), in (−π, π].
    fn atan2(&self, x: &Self) -> Self;
    /// The magnitude.
    fn abs(&self) -> Self;
    /// The largest integer not above `self`.
    fn floor(&self) -> Self;
    /// Neither infinite nor NaN.
    fn is_finite(&self) -> bool;
    /// Scientific notation with `digits` significant digits, e.g. `1.2345e-3`.
    fn to_scientific(&self, digits: usize) -> String;

    /// The integer `n` at this value's precision.
    fn int(&self, n: i64) -> Self {
        Self::from_i64(n, self.precision())
    }
    /// The ratio `n / d` at this value's precision, rounded once.
    fn ratio(&self, n: i64, d: i64) -> Self {
        self.int(n) / self.int(d)
    }
    /// π at this value's precision.
    fn pi_like(&self) -> Self {
        Self::pi(self.precision())
    }
    /// The machine epsilon of this value's precision.
    fn epsilon_like(&self) -> Self {
        Self::epsilon(self.precision())
    }
    /// The nearest f64 (NaN if it has none).
    fn to_f64_lossy(&self) -> f64 {
        self.to_f64().unwrap_or(f64::NAN)
    }
    /// The f64 to quote in a message: a number is itself; an enclosure is its middle
    /// rounded to the most significant digits (at most 15, which f64 keeps) to which both
    /// ends of its [`real_span`](Real::real_span) round alike, so that every digit quoted
    /// holds for every value it encloses; `None` where no digit does.
    fn to_f64_quoted(&self) -> Option<f64> {
        let Some((low, high)) = self.real_span() else {
            return self.to_f64();
        };
        if low == high {
            return Some(low);
        }
        if !(low.is_finite() && high.is_finite()) {
            return None;
        }
        // Rounding is monotone: where both ends round to one decimal, everything between does.
        (1..=15usize).rev().find_map(|digits| {
            let decimal = format!("{low:.*e}", digits - 1);
            (decimal == format!("{high:.*e}", digits - 1))
                .then(|| decimal.parse().ok())
                .flatten()
        })
    }
    /// The larger of two values.
    fn max_of(&self, other: &Self) -> Self {
        if *self >= *other {
            self.clone()
        } else {
            other.clone()
        }
    }
    /// The smaller of two values.
    fn min_of(&self, other: &Self) -> Self {
        if *self <= *other {
            self.clone()
        } else {
            other.clone()
        }
    }
    /// The real interval this value stands for, rounded outward to f64: `None` for a
    /// number (f64, MPFR), which stands for itself; for a ball, its real part. Code that
    /// picks a formula by where a value lies takes every formula a ball may need.
    fn real_span(&self) -> Option<(f64, f64)> {
        None
    }
    /// A value that contains `self` and `other`: for a ball their union; a number, which
    /// stands for itself alone and has no `real_span`, is kept.
    fn union(&self, other: &Self) -> Self {
        let _ = other;
        self.clone()
    }
    /// Whether every number `self` holds lies in the interior of `outer`: the real parts
    /// strictly inside, and the imaginary parts strictly inside or both exactly zero (a
    /// real enclosure inside a real one). What Krawczyk's test of a root asks; `false`
    /// for a number, which holds no interior.
    fn lies_inside(&self, outer: &Self) -> bool {
        let _ = outer;
        false
    }
    /// The ends of the real part as values with no width, rounded outward at the working
    /// precision: the points just outside an enclosure on either side; a number is both.
    fn real_ends(&self) -> (Self, Self) {
        (self.clone(), self.clone())
    }
    /// The box [−m, m] + i[−m, m] about zero, m an upper bound of |`self`| (the interval
    /// [−m, m] where `self` is real): a neighbourhood of zero reaching as far in every
    /// direction as `self` does, as Krawczyk's box about a root needs; a number is itself.
    fn centred_square(&self) -> Self {
        self.clone()
    }
    /// A number of the value, with no width: for an enclosure the midpoint of its real
    /// part (Newton's steps on enclosures start from such points, or their widths grow
    /// with every step); a number is itself.
    fn midpoint_value(&self) -> Self {
        self.clone()
    }
    /// (sinh x, cosh x), free of cancellation near x = 0 and accurate for large |x|.
    fn sinh_cosh(&self) -> (Self, Self) {
        // With m = e^|x| − 1: sinh|x| = (m + m/(1 + m))/2 and cosh x = 1 + m²/(2(1 + m)).
        let m = self.abs().exp_m1();
        let one_plus = m.clone() + &self.int(1);
        let sinh_abs = (m.clone() + &(m.clone() / &one_plus)) / &self.int(2);
        let cosh = m.square() / &(one_plus * &self.int(2)) + &self.int(1);
        let sinh = if *self < self.int(0) { -sinh_abs } else { sinh_abs };
        (sinh, cosh)
    }
    /// The square.
    fn square(&self) -> Self {
        self.clone() * self
    }
    /// `self` · 2^`exponent`, rounded once as the product with that power of two is (so
    /// exact unless it over- or underflows): `x.times_power_of_two(1)` equals `x * 2`
    /// and `x.times_power_of_two(-1)` equals `x / 2` in every type, where a type may
    /// compute it without a multiplication (a ball shifts its exponents).
    fn times_power_of_two(self, exponent: i32) -> Self {
        let precision = self.precision();
        self * Self::from_f64(2f64.powi(exponent), precision)
    }
}

/// The one-argument functions both types provide under the same name.
macro_rules! elementary_functions {
    (f64: $($name:ident),*) => {
        $(fn $name(&self) -> Self {
            f64::$name(*self)
        })*
    };
    (Float: $($name:ident),*) => {
        $(fn $name(&self) -> Self {
            self.clone().$name()
        })*
    };
}

impl Real for f64 {
    elementary_functions!(f64: sqrt, cbrt, ln, ln_1p, exp, exp_m1, sin, cos, abs, floor);
    fn precision(&self) -> Precision {
        Precision::DOUBLE
    }
    fn from_f64(x: f64, _: Precision) -> Self {
        x
    }
    fn from_i64(n: i64, _: Precision) -> Self {
        n as f64
    }
    fn from_float(x: &rug::Float, _: Precision) -> Self {
        x.to_f64()
    }
    fn parse_decimal(text: &str, _: Precision) -> Result<Self, ParseRealError> {
        text.trim()
            .parse::<f64>()
            .map_err(|_| ParseRealError { text: text.to_string() })
    }
    fn from_rational(x: &rug::Rational, precision: Precision) -> Self {
        // Both integers exact in f64: one IEEE division rounds the quotient once.
        const EXACT: u32 = f64::MANTISSA_DIGITS;
        if x.numer().significant_bits() <= EXACT && x.denom().significant_bits() <= EXACT {
            return x.numer().to_f64() / x.denom().to_f64();
        }
        rug::Float::with_val(precision.in_bits(), x).to_f64()
    }
    fn pi(_: Precision) -> Self {
        std::f64::consts::PI
    }
    fn epsilon(_: Precision) -> Self {
        f64::EPSILON
    }
    fn smallest_full_precision(_: Precision) -> Self {
        f64::MIN_POSITIVE / f64::EPSILON
    }
    fn powr(&self, exponent: &Self) -> Self {
        f64::powf(*self, *exponent)
    }
    fn powi(&self, exponent: i32) -> Self {
        f64::powi(*self, exponent)
    }
    fn sin_cos(&self) -> (Self, Self) {
        f64::sin_cos(*self)
    }
    fn atan2(&self, x: &Self) -> Self {
        f64::atan2(*self, *x)
    }
    fn hypot(&self, other: &Self) -> Self {
        f64::hypot(*self, *other)
    }
    fn is_finite(&self) -> bool {
        f64::is_finite(*self)
    }
    fn to_scientific(&self, digits: usize) -> String {
        format!("{:.*e}", digits.max(1) - 1, self)
    }
}

impl Real for Float {
    elementary_functions!(Float: sqrt, cbrt, ln, ln_1p, exp, exp_m1, sin, cos, abs, floor);
    fn precision(&self) -> Precision {
        Precision::bits(self.prec())
    }
    fn from_f64(x: f64, precision: Precision) -> Self {
        Float::with_val(precision.in_bits().max(53), x)
    }
    fn from_i64(n: i64, precision: Precision) -> Self {
        Float::with_val(precision.in_bits(), n)
    }
    fn from_float(x: &Float, precision: Precision) -> Self {
        Float::with_val(precision.in_bits(), x)
    }
    fn parse_decimal(text: &str, precision: Precision) -> Result<Self, ParseRealError> {
        let error = || ParseRealError { text: text.to_string() };
        let trimmed = text.trim();
        // MPFR also reads "@inf@", hexadecimal and other radices; only plain decimals are numbers here.
        if trimmed.is_empty()
            || !trimmed
                .chars()
                .all(|c| c.is_ascii_digit() || matches!(c, '.' | 'e' | 'E' | '+' | '-'))
        {
            return Err(error());
        }
        let parsed = Float::parse(trimmed).map_err(|_| error())?;
        Ok(Float::with_val(precision.in_bits(), parsed))
    }
    fn pi(precision: Precision) -> Self {
        Float::with_val(precision.in_bits(), Constant::Pi)
    }
    fn epsilon(precision: Precision) -> Self {
        Float::with_val(precision.in_bits(), 1) >> (precision.in_bits() - 1)
    }
    fn smallest_full_precision(precision: Precision) -> Self {
        // MPFR has no subnormals; its exponent range reaches far below anything physical.
        Float::with_val(precision.in_bits(), 1) >> (1u32 << 28)
    }
    fn powr(&self, exponent: &Self) -> Self {
        self.clone().pow(exponent)
    }
    fn powi(&self, exponent: i32) -> Self {
        self.clone().pow(exponent)
    }
    fn sin_cos(&self) -> (Self, Self) {
        self.clone().sin_cos(Float::new(self.prec()))
    }
    fn atan2(&self, x: &Self) -> Self {
        self.clone().atan2(x)
    }
    fn hypot(&self, other: &Self) -> Self {
        self.clone().hypot(other)
    }
    fn is_finite(&self) -> bool {
        Float::is_finite(self)
    }
    fn to_scientific(&self, digits: usize) -> String {
        if !Float::is_finite(self) || self.is_zero() {
            return Real::to_scientific(&self.to_f64(), digits);
        }
        // MPFR gives the digits d₁d₂… and e with value 0.d₁d₂… × 10^e; print d₁.d₂… e(e − 1) as f64 does.
        let (negative, mantissa, exponent) = self.to_sign_string_exp_round(10, Some(digits.max(1)), Round::Nearest);
        let exponent = exponent.unwrap_or(1) - 1;
        let (first, rest) = mantissa.split_at(1);
        let sign = if negative { "-" } else { "" };
        if rest.is_empty() {
            format!("{sign}{first}e{exponent}")
        } else {
            format!("{sign}{first}.{rest}e{exponent}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimal_strings_are_read_exactly_at_high_precision() {
        let p = Precision::bits(256);
        let tenth = Float::parse_decimal("0.1", p).unwrap();
        let ten = tenth.int(10);
        let one = tenth.clone() * &ten;
        assert!((one - 1i32).abs() < Float::epsilon(p) * 2i32);
        // The double nearest 0.1 differs from 1/10 by about 5.5e-18.
        let from_double = Float::from_f64(0.1, p);
        let gap = (from_double - &tenth).abs().to_f64();
        assert!(gap > 5e-18 && gap < 6e-18, "gap {gap}");
    }

    #[test]
    fn non_decimal_text_is_rejected() {
        for text in ["", "abc", "@inf@", "0x10", "nan", "1.0.0"] {
            assert!(Float::parse_decimal(text, Precision::bits(64)).is_err(), "{text}");
        }
        assert!(f64::parse_decimal("abc", Precision::DOUBLE).is_err());
    }

    #[test]
    fn powers_of_two_scale_as_the_product_and_quotient_do() {
        // Halving and doubling round as x / 2 and x * 2 do, down to subnormals and at overflow.
        for x in [0.1, -3.7, 1e-310, f64::MIN_POSITIVE, f64::MAX, 5e-324] {
            assert_eq!(x.times_power_of_two(-1).to_bits(), (x / 2.0).to_bits(), "{x}");
            assert_eq!(x.times_power_of_two(1).to_bits(), (x * 2.0).to_bits(), "{x}");
            assert_eq!(x.times_power_of_two(-5).to_bits(), (x / 32.0).to_bits(), "{x}");
        }
        let p = Precision::bits(200);
        let third = Float::from_i64(1, p) / Float::from_i64(3, p);
        assert_eq!(third.clone().times_power_of_two(-1), third.clone() / 2);
        assert_eq!(third.clone().times_power_of_two(7), third.clone() * 128);
        assert_eq!(third.clone().times_power_of_two(7).prec(), 200);
    }

    #[test]
    fn precision_in_digits_round_trips() {
        let p = Precision::decimal_digits(50);
        assert!(p.in_decimal_digits() >= 50);
        assert!(p.in_bits() < 170);
    }

    #[test]
    fn scientific_format_agrees_between_types() {
        let x = 1.0 / 3.0f64;
        let y = Float::from_f64(x, Precision::bits(53));
        assert_eq!(x.to_scientific(6), y.to_scientific(6));
        assert_eq!(x.to_scientific(6), "3.33333e-1");
        for value in [30.677678, -0.00123, 1.0, 9.999999e20] {
            let y = Float::from_f64(value, Precision::bits(80));
            assert_eq!(value.to_scientific(5), y.to_scientific(5), "{value}");
        }
        assert_eq!(Float::from_f64(0.0, Precision::bits(80)).to_scientific(3), "0.00e0");
    }
}
