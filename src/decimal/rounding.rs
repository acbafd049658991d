//! Decimal rounding of the two kinds of number an enclosure's ends are: MPFR floats and
//! doubles. Each end is expanded once, exactly, to the digits the printing rule may need
//! (MPFR truncates a float; Rust's float formatting, which is exact, expands a double),
//! and every rounding the rule tries is then read off that expansion. The doubles' way
//! skips MPFR's conversion, which costs more than the rest of printing an f64 interval;
//! where one formatting cannot settle a double's expansion (a rounding that may have
//! carried), the double is expanded exactly as an MPFR float.

use rug::float::Round;
use rug::Float;

/// The fewest significant digits of the outward-rounded ends of an enclosure in MPFR
/// floats.
pub(crate) const ENCLOSURE_DIGITS: usize = 20;

/// A decimal as MPFR gives it: sign, significant digits, exponent of 0.d₁d₂….
pub(crate) type DecimalParts = (bool, String, i32);

/// The leading significant digits of a nonzero number's exact decimal expansion, and
/// whether any nonzero digit follows them.
pub(crate) struct Expansion {
    negative: bool,
    digits: String,
    /// e of 0.d₁d₂… × 10^e.
    exponent: i32,
    more: bool,
}

impl Expansion {
    /// The number rounded to nearest to `digits` significant digits (fewer than the
    /// expansion holds), or `None` where it lies exactly halfway between two such decimals.
    pub(crate) fn nearest(&self, digits: usize) -> Option<DecimalParts> {
        let (kept, rest) = self.digits.split_at(digits);
        let up = match rest.as_bytes()[0] {
            b'0'..=b'4' => false,
            b'5' if !self.more && rest.bytes().skip(1).all(|d| d == b'0') => return None,
            _ => true,
        };
        Some(self.rounded(kept, up))
    }

    /// The number to `digits` significant digits (at most as many as the expansion holds)
    /// rounded in the direction `round`.
    pub(crate) fn directed(&self, digits: usize, round: Round) -> DecimalParts {
        let (kept, rest) = self.digits.split_at(digits);
        let cut = self.more || rest.bytes().any(|d| d != b'0');
        let away_from_zero = match round {
            Round::Up => !self.negative,
            Round::Down => self.negative,
            Round::AwayZero => true,
            _ => false,
        };
        self.rounded(kept, cut && away_from_zero)
    }

    /// `kept` (the leading digits), one unit in its last place larger in magnitude if `up`.
    fn rounded(&self, kept: &str, up: bool) -> DecimalParts {
        let (digits, exponent) = if up {
            next_decimal(kept, self.exponent)
        } else {
            (kept.to_string(), self.exponent)
        };
        (self.negative, digits, exponent)
    }
}

/// A number the printing rule rounds to decimals.
pub(crate) trait DecimalEnd {
    /// Whether the number is zero.
    fn is_zero(&self) -> bool;
    /// Whether the number is finite.
    fn is_finite(&self) -> bool;
    /// Whether the sign bit is set.
    fn is_sign_negative(&self) -> bool;
    /// The number exactly as an MPFR float.
    fn exact(&self) -> Float;
    /// The significant digits of an enclosure's ends rounded outwards when at most
    /// `most` are printed: enough that the decimal ends are not wider than the digits.
    fn enclosure_digits(most: u32) -> usize;
    /// The first `digits` significant digits of the number's exact decimal expansion (a
    /// finite nonzero number).
    fn expansion(&self, digits: usize) -> Expansion;

    /// The number to `digits` significant digits rounded in the direction `round`, in
    /// scientific notation.
    fn directed(&self, digits: usize, round: Round) -> String {
        if self.is_zero() || !self.is_finite() {
            return self.exact().to_f64().to_string();
        }
        scientific(&self.expansion(digits).directed(digits, round))
    }
}

impl DecimalEnd for Float {
    fn is_zero(&self) -> bool {
        Float::is_zero(self)
    }

    fn is_finite(&self) -> bool {
        Float::is_finite(self)
    }

    fn is_sign_negative(&self) -> bool {
        Float::is_sign_negative(self)
    }

    fn exact(&self) -> Float {
        self.clone()
    }

    fn enclosure_digits(most: u32) -> usize {
        ENCLOSURE_DIGITS.max(most as usize + 2)
    }

    fn expansion(&self, digits: usize) -> Expansion {
        let (negative, truncated, exponent) = self.to_sign_string_exp_round(10, Some(digits), Round::Zero);
        let away = self.to_sign_string_exp_round(10, Some(digits), Round::AwayZero).1;
        Expansion {
            negative,
            more: away != truncated,
            digits: truncated,
            exponent: exponent.unwrap_or(1),
        }
    }
}

impl DecimalEnd for f64 {
    fn is_zero(&self) -> bool {
        *self == 0.0
    }

    fn is_finite(&self) -> bool {
        f64::is_finite(*self)
    }

    fn is_sign_negative(&self) -> bool {
        f64::is_sign_negative(*self)
    }

    fn exact(&self) -> Float {
        Float::with_val(53, *self)
    }

    /// Sixteen at least: a double's ends lie at least an ulp apart, about 1e−16 of them,
    /// and sixteen digits are the most Rust's formatting expands on its fast path.
    fn enclosure_digits(most: u32) -> usize {
        16.max(most as usize + 1)
    }

    fn expansion(&self, digits: usize) -> Expansion {
        // One digit more, rounded to nearest: the first `digits` are the exact truncation
        // and something nonzero was cut off, unless the last reads 0 (the rounding carried,
        // or what was cut off is too small to show). Up to 17 digits Rust's formatting
        // takes its fast path.
        let text = format!("{:.*e}", digits, self.abs());
        let (mantissa, exponent) = text
            .split_once('e')
            .expect("Rust's scientific notation has an exponent");
        let mantissa = mantissa.replace('.', "");
        let (kept, cut) = mantissa.split_at(digits);
        if cut == "0" {
            return self.exact().expansion(digits);
        }
        Expansion {
            negative: self.is_sign_negative(),
            digits: kept.to_string(),
            exponent: exponent.parse::<i32>().expect("Rust's exponent is an integer") + 1,
            more: true,
        }
    }
}

/// The significant digits one unit in their last place above `digits` (a carry past the
/// first digit raises the exponent and keeps the count).
fn next_decimal(digits: &str, exponent: i32) -> (String, i32) {
    let mut bytes = digits.as_bytes().to_vec();
    for byte in bytes.iter_mut().rev() {
        if *byte == b'9' {
            *byte = b'0';
        } else {
            *byte += 1;
            return (String::from_utf8(bytes).expect("ASCII digits"), exponent);
        }
    }
    let mut carried = "1".to_string();
    carried.push_str(&"0".repeat(digits.len() - 1));
    (carried, exponent + 1)
}

/// MPFR's digits d₁d₂… and exponent e of 0.d₁d₂… × 10^e as `d₁.d₂…e(e − 1)`.
pub(crate) fn scientific((negative, mantissa, exponent): &DecimalParts) -> String {
    let (first, rest) = mantissa.split_at(1);
    let sign = if *negative { "-" } else { "" };
    let dot = if rest.is_empty() { "" } else { "." };
    format!("{sign}{first}{dot}{rest}e{}", exponent - 1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Nonzero doubles near decimal boundaries: few significant digits, halves, or random bits.
    fn double() -> impl Strategy<Value = f64> {
        prop_oneof![
            (1u64..100_000, -30i32..30).prop_map(|(m, e)| m as f64 * 10f64.powi(e)),
            (1u64..2000, -8i32..8).prop_map(|(m, e)| (m as f64 + 0.5) * 10f64.powi(e)),
            any::<f64>().prop_filter("finite and nonzero", |x| x.is_finite() && *x != 0.0),
        ]
    }

    /// MPFR's own rounding of `x` to nearest at `digits`, `None` on a tie.
    fn mpfr_nearest(x: &Float, digits: usize) -> Option<DecimalParts> {
        let finer = x.to_sign_string_exp_round(10, Some(digits + 1), Round::Down).1;
        if finer.ends_with('5') && x.to_sign_string_exp_round(10, Some(digits + 1), Round::Up).1 == finer {
            return None;
        }
        let (negative, mantissa, exponent) = x.to_sign_string_exp_round(10, Some(digits), Round::Nearest);
        Some((negative, mantissa, exponent.unwrap_or(1)))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20_000))]
        #[test]
        fn expansions_round_as_mpfr_rounds(x in double(), digits in 1usize..25, sign in any::<bool>()) {
            let x = if sign { -x } else { x };
            let float = Float::with_val(53, x);
            for expansion in [x.expansion(digits + 1), float.expansion(digits + 1)] {
                prop_assert_eq!(expansion.nearest(digits), mpfr_nearest(&float, digits));
            }
            for round in [Round::Up, Round::Down] {
                let (negative, mantissa, exponent) = float.to_sign_string_exp_round(10, Some(digits), round);
                let mpfr = scientific(&(negative, mantissa, exponent.unwrap_or(1)));
                prop_assert_eq!(x.directed(digits, round), mpfr.clone());
                prop_assert_eq!(float.directed(digits, round), mpfr);
            }
        }
    }

    #[test]
    fn ties_and_carries_are_settled_exactly() {
        // 0.125 is a tie at two digits; 9.9996 carries at four digits.
        assert_eq!(0.125.expansion(3).nearest(2), None);
        assert_eq!(0.125.expansion(4).nearest(3), Some((false, "125".to_string(), 0)));
        assert_eq!(9.9996.directed(4, Round::Up), "1.000e1");
        assert_eq!(9.9996.directed(4, Round::Down), "9.999e0");
        assert_eq!((-9.9996f64).directed(4, Round::Down), "-1.000e1");
        assert_eq!(2.0.directed(3, Round::Up), "2.00e0");
    }
}
