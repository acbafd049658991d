//! A value as printed: its decimal by the one printing rule ([`super::printing`]), the
//! interval its digits were read from, and the binary64 number an f64 program reads.

use rug::Float;

use super::printing::{decimal_f64, decimal_interval, rounded_alike_expanded, Decimal};
use super::rounding::{scientific, DecimalEnd, ENCLOSURE_DIGITS};

/// One value as printed, with the interval its digits were read from.
#[derive(Clone, Debug, PartialEq)]
pub struct Value {
    /// The value by the one printing rule.
    pub decimal: Decimal,
    /// Decimal strings, rounded outwards, of an interval that contains the value (for a
    /// proven provenance, proven to): `None` for an exact value.
    pub enclosure: Option<(String, String)>,
    /// The binary64 number nearest the middle of the enclosure (the value an f64 program
    /// reads), where it is finite and the value is not exact.
    pub binary64: Option<f64>,
}

/// Bits at which [`Value::to_at_most`] reads an enclosure's decimal ends (outwards): far
/// more than their [`ENCLOSURE_DIGITS`] or more digits need.
const ENCLOSURE_BITS: u32 = 256;

impl Value {
    /// Exactly zero.
    pub fn zero() -> Self {
        Value {
            decimal: Decimal::Zero,
            enclosure: None,
            binary64: None,
        }
    }

    /// The value in [`lower`, `upper`], with at most `most` significant digits.
    pub fn within(lower: &Float, upper: &Float, most: u32) -> Self {
        Value::between(lower, upper, most)
    }

    /// [`Value::within`] for ends of either kind.
    fn between<T: DecimalEnd>(lower: &T, upper: &T, most: u32) -> Self {
        let digits = T::enclosure_digits(most);
        let (decimal, expansions) = rounded_alike_expanded(lower, upper, most, digits);
        let enclosure = match expansions {
            Some((low, high)) => (
                scientific(&low.directed(digits, rug::float::Round::Down)),
                scientific(&high.directed(digits, rug::float::Round::Up)),
            ),
            None => (
                lower.directed(digits, rug::float::Round::Down),
                upper.directed(digits, rug::float::Round::Up),
            ),
        };
        let (lower_exact, upper_exact) = (lower.exact(), upper.exact());
        Value {
            decimal,
            enclosure: Some(enclosure),
            binary64: Some(
                Float::with_val(
                    lower_exact.prec().max(upper_exact.prec()) + 1,
                    &lower_exact + &upper_exact,
                )
                .to_f64()
                    / 2.0,
            )
            // Not where f64's range loses the value: infinite, or zero for a value that is not.
            .filter(|middle| middle.is_finite() && (*middle != 0.0 || (lower.is_zero() && upper.is_zero()))),
        }
    }

    /// The value in the ball's real interval (read at `bits`), with at most `most`
    /// significant digits, however far its size lies beyond the range of MPFR.
    #[cfg(feature = "certified")]
    pub fn of_ball(ball: &crate::ball::Ball, bits: u32, most: u32) -> Self {
        let Some((scaled, shift)) = ball.decimal_scaled() else {
            let (lower, upper) = ball.bounds(bits);
            return Value::within(&lower, &upper, most);
        };
        let (lower, upper) = scaled.bounds(bits);
        let value = Value::within(&lower, &upper, most);
        let shift_text = |text: String| crate::decimal::printing::shift_exponent(&text, shift);
        // Beyond MPFR's exponents the value is far beyond f64's too.
        Value {
            decimal: value.decimal.shifted(shift),
            enclosure: value
                .enclosure
                .map(|(lower, upper)| (shift_text(lower), shift_text(upper))),
            binary64: None,
        }
    }

    /// The value in the interval's real part, with at most `most` significant digits:
    /// its two doubles are exact rationals, read as they are.
    pub fn of_interval(interval: &crate::interval::Interval, most: u32) -> Self {
        let (lower, upper) = interval.real_bounds();
        Value::between(&lower, &upper, most)
    }

    /// The value in [`value` − `radius`, `value` + `radius`], with at most `most`
    /// significant digits.
    pub fn about(value: &Float, radius: &Float, most: u32) -> Self {
        let (lower, upper) = crate::decimal::printing::ends(value, &radius.clone().abs());
        Value::within(&lower, &upper, most)
    }

    /// An f64 `value` with an absolute `bound` on its error.
    pub fn from_f64(value: f64, bound: f64) -> Self {
        let (lower, upper) = (Float::with_val(64, value) - bound, Float::with_val(64, value) + bound);
        Value {
            decimal: decimal_f64(value, bound),
            enclosure: Some((
                lower.directed(ENCLOSURE_DIGITS, rug::float::Round::Down),
                upper.directed(ENCLOSURE_DIGITS, rug::float::Round::Up),
            )),
            binary64: Some(value),
        }
    }

    /// The significant digits printed (`u32::MAX` for an exact zero, 0 where none is
    /// determined).
    pub fn digits(&self) -> u32 {
        self.decimal.digits()
    }

    /// The value printed by the one rule to at most `most` significant digits (fewer
    /// where its enclosure does not settle them): rounding the printed digits again would
    /// round twice.
    pub fn to_at_most(&self, most: u32) -> Decimal {
        match (&self.decimal, &self.enclosure) {
            (Decimal::Zero, _) | (_, None) => self.decimal.clone(),
            (_, Some((lower, upper))) => {
                // Read outwards, so that the interval still holds the value.
                let read = |text: &str, round| {
                    Float::parse(text).map(|parsed| Float::with_val_round(ENCLOSURE_BITS, parsed, round).0)
                };
                match (read(lower, rug::float::Round::Down), read(upper, rug::float::Round::Up)) {
                    (Ok(lower), Ok(upper)) => decimal_interval(&lower, &upper, most),
                    _ => self.decimal.clone(),
                }
            }
        }
    }

    /// The value as a binary64 number: the one nearest the middle of its enclosure, 0 for
    /// an exact zero, the nearest double for an exact decimal; `None` where the value lies
    /// beyond f64's range (or rounds to 0 in f64 though it is not 0).
    ///
    /// ```
    /// use microslip::answer::Value;
    ///
    /// assert_eq!(Value::from_f64(0.25, 1e-17).to_f64(), Some(0.25));
    /// assert_eq!(Value::zero().to_f64(), Some(0.0));
    /// ```
    pub fn to_f64(&self) -> Option<f64> {
        if self.decimal == Decimal::Zero {
            return Some(0.0);
        }
        if self.binary64.is_some() {
            return self.binary64;
        }
        let (lower, upper) = self.enclosure_f64().unwrap_or_else(|| {
            let exact = self.decimal.to_string().parse().unwrap_or(f64::NAN);
            (exact, exact)
        });
        let middle = lower / 2.0 + upper / 2.0;
        (middle.is_finite() && middle != 0.0).then_some(middle)
    }

    /// The enclosure as binary64 numbers rounded outwards, so that every number it holds
    /// lies between them (`(0, 0)` for an exact zero; `None` for an exact value other than
    /// zero, which has no enclosure to round).
    ///
    /// ```
    /// use microslip::answer::Value;
    ///
    /// let value = Value::from_f64(0.1, 1e-17);
    /// let (lower, upper) = value.enclosure_f64().unwrap();
    /// assert!(lower < 0.1 && 0.1 < upper && upper - lower < 1e-16);
    /// assert_eq!(Value::zero().enclosure_f64(), Some((0.0, 0.0)));
    /// ```
    pub fn enclosure_f64(&self) -> Option<(f64, f64)> {
        if self.decimal == Decimal::Zero {
            return Some((0.0, 0.0));
        }
        let (lower, upper) = self.enclosure.as_ref()?;
        let outward = |text: &str, round: rug::float::Round| {
            let (rounded, _) = Float::with_val_round(53, Float::parse(text).ok()?, round);
            Some(rounded.to_f64())
        };
        Some((
            outward(lower, rug::float::Round::Down)?,
            outward(upper, rug::float::Round::Up)?,
        ))
    }
}
