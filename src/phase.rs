//! The phase φ as written: an exact quantity kπ + x, with k a rational multiple of π and
//! x a decimal offset in radians, reduced once, exactly, modulo π.
//!
//! W has period π in φ (φ + π is the mirror image of the cycle, Q − Q0 reversed), so
//! what a computation needs is the offset ψ = φ − nπ ∈ [−π/2, π/2] from the nearest
//! multiple nπ, and whether n is odd. ψ is small near both 0 and π, so a phase such as
//! `pi-1e-100` keeps its offset −10⁻¹⁰⁰ at every working precision, and the decimal
//! `3.141592653589793`, which is not π, keeps its offset of about −1.2e−16.
//! Whether the cycle is exactly in phase is decided from the text: ψ = 0 exactly.

use rug::float::Constant;
use rug::ops::Pow;
use rug::{Float, Integer, Rational};

use crate::cycle::MAX_PHASE;
use crate::real::{Precision, Real};

/// The forms a phase may be written in, for refusals.
pub const PHASE_FORMS: &str = "radians (0.3, -1e-6), a multiple of π (pi, pi/2, 3pi/4, -pi/3, 0.4pi, 0.4*pi, π/2), \
either plus or minus radians (pi-1e-6, pi/2+1e-3), or degrees (72deg, 72°)";

/// How close to an odd multiple of π a phase is read as the mirror image of its cycle.
pub const MIRROR_BELOW: f64 = 1.0 / 1_048_576.0;

/// Bits carried beyond the working precision in a reduction.
const GUARD_BITS: u32 = 64;
/// The largest power of ten a phase's decimal may carry (1e-100000 is read; 1e-10000000 is not).
const MAX_DECIMAL_EXPONENT: i64 = 100_000;
/// The most bits a reduction may use before it gives up (never reached by a decimal written by hand).
const MAX_REDUCTION_BITS: u32 = 1 << 22;

/// Why a phase's text is not a phase.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PhaseError {
    /// The text is none of the accepted forms.
    #[error("the phase φ = '{text}' is not a phase: write {PHASE_FORMS}")]
    Syntax {
        /// The text given.
        text: String,
    },
    /// |φ| beyond [`MAX_PHASE`].
    #[error("the phase φ = {phi:e} rad is too large: |φ| must be at most 1e100 rad (reducing it modulo π exactly needs as many extra bits as its binary exponent)")]
    TooLarge {
        /// φ, roughly.
        phi: f64,
    },
}

/// A phase as written: `multiple`·π + `offset`, both exact rationals.
#[derive(Clone, Debug, PartialEq)]
pub struct ExactPhase {
    multiple: Rational,
    offset: Rational,
}

/// A phase reduced modulo π: φ = nπ + ψ with ψ ∈ [−π/2, π/2].
#[derive(Clone, Debug)]
pub struct ReducedPhase {
    /// n is odd: the cycle is the mirror image (Q − Q0 reversed) of the one at ψ.
    reverses: bool,
    /// ψ when it is an exact rational (the multiple of π was the integer n).
    exact: Option<Rational>,
    /// ψ to at least the bits of the precision it was reduced for, beyond its last
    /// bit of cancellation (None when `exact` is given).
    approximate: Option<Float>,
}

impl ExactPhase {
    /// Reads a phase: radians (`0.3`), a multiple of π (`pi`, `pi/2`, `3pi/4`, `-pi/3`,
    /// `0.4pi`, `0.4*pi`, `π/2`, `3*pi/4`), one of them plus or minus radians
    /// (`pi-1e-6`, `pi/2+1e-3`), or degrees (`72deg`, `72°`, = 72/180·π exactly).
    pub fn parse(text: &str) -> Result<ExactPhase, PhaseError> {
        let error = || PhaseError::Syntax { text: text.to_string() };
        let trimmed = text.trim().replace('π', "pi");
        let zero = || Rational::from(0);
        if let Some(degrees) = trimmed.strip_suffix("deg").or_else(|| trimmed.strip_suffix('°')) {
            let degrees = decimal(degrees.trim()).ok_or_else(error)?;
            return Ok(ExactPhase {
                multiple: degrees / Rational::from(180),
                offset: zero(),
            });
        }
        let Some((before, after)) = trimmed.split_once("pi") else {
            let offset = decimal(&trimmed).ok_or_else(error)?;
            return Ok(ExactPhase {
                multiple: zero(),
                offset,
            });
        };
        let before = before.trim();
        let before = before.strip_suffix('*').map_or(before, str::trim_end);
        let numerator = match before {
            "" | "+" => Rational::from(1),
            "-" => Rational::from(-1),
            factor => decimal(factor).ok_or_else(error)?,
        };
        let after = after.trim_start();
        // An optional divisor `/q` (a positive integer), then an optional `± radians`.
        let (divisor, rest) = match after.strip_prefix('/') {
            Some(rest) => {
                let rest = rest.trim_start();
                let end = rest.find(|c: char| !c.is_ascii_digit()).unwrap_or(rest.len());
                let divisor: Integer = rest[..end].parse().map_err(|_| error())?;
                if divisor == 0 {
                    return Err(error());
                }
                (divisor, rest[end..].trim())
            }
            None => (Integer::from(1), after.trim()),
        };
        let offset = if rest.is_empty() {
            zero()
        } else if rest.starts_with(['+', '-']) {
            let (sign, magnitude) = rest.split_at(1);
            let magnitude = magnitude.trim();
            if magnitude.starts_with(['+', '-']) {
                return Err(error());
            }
            decimal(&format!("{sign}{magnitude}")).ok_or_else(error)?
        } else {
            return Err(error());
        };
        Ok(ExactPhase {
            multiple: numerator / divisor,
            offset,
        })
    }

    /// The phase's two exact parts: φ = `multiple`·π + `offset` (radians).
    pub fn parts(&self) -> (&Rational, &Rational) {
        (&self.multiple, &self.offset)
    }

    /// Whether the phase is exactly a multiple of π: an integer multiple and no offset.
    pub fn is_in_phase(&self) -> bool {
        self.offset == 0 && *self.multiple.denom() == 1
    }

    /// φ in f64 (for messages and range checks).
    pub fn to_f64(&self) -> f64 {
        let bits = 64;
        (Float::with_val(bits, &self.multiple) * Float::with_val(bits, Constant::Pi)
            + Float::with_val(bits, &self.offset))
        .to_f64()
    }

    /// φ reduced once, exactly, modulo π; refused beyond [`MAX_PHASE`].
    pub fn reduce(&self, precision: Precision) -> Result<ReducedPhase, PhaseError> {
        let estimate = self.to_f64();
        if !estimate.is_finite() || estimate.abs() > MAX_PHASE {
            return Err(PhaseError::TooLarge { phi: estimate });
        }
        // n = round(φ/π) = round(k + x/π): x/π needs the bits of its integer part and a guard.
        let exponent = estimate.abs().max(1.0).log2().ceil() as u32;
        let bits = exponent + GUARD_BITS;
        let turns = Float::with_val(bits, &self.offset) / Float::with_val(bits, Constant::Pi)
            + Float::with_val(bits, &self.multiple);
        let half_turns = turns.round().to_integer().unwrap_or_default();
        let reverses = half_turns.is_odd();
        let multiple = self.multiple.clone() - Rational::from(half_turns);
        if multiple == 0 {
            return Ok(ReducedPhase {
                reverses,
                exact: Some(self.offset.clone()),
                approximate: None,
            });
        }
        // ψ = (k − n)π + x ≠ 0 (π is irrational): raise the bits until the sum keeps
        // the working bits and a guard above its rounding error.
        let wanted = precision.in_bits() + GUARD_BITS;
        let mut bits = wanted + exponent + GUARD_BITS;
        loop {
            let multiple_part = Float::with_val(bits, &multiple) * Float::with_val(bits, Constant::Pi);
            let offset_part = Float::with_val(bits, &self.offset);
            let size = Float::with_val(bits, multiple_part.abs_ref()) + Float::with_val(bits, offset_part.abs_ref());
            let sum = multiple_part + offset_part;
            // The rounding error of the sum is below 4 ulps of `size`.
            let kept = sum.get_exp().unwrap_or(i32::MIN) as i64 - size.get_exp().unwrap_or(0) as i64 + bits as i64 - 2;
            if !sum.is_zero() && kept >= wanted as i64 {
                return Ok(ReducedPhase {
                    reverses,
                    exact: None,
                    approximate: Some(sum),
                });
            }
            let missing = (wanted as i64 - kept).max(64) as u32;
            bits = bits.saturating_add(missing + bits / 2);
            if bits > MAX_REDUCTION_BITS {
                return Err(PhaseError::TooLarge { phi: estimate });
            }
        }
    }
}

impl ReducedPhase {
    /// φ ≡ 0 (mod π) exactly.
    pub fn is_in_phase(&self) -> bool {
        self.exact.as_ref().is_some_and(|psi| *psi == 0)
    }

    /// n is odd: φ = ψ + nπ describes the mirror image of the cycle at ψ.
    pub fn reverses(&self) -> bool {
        self.reverses
    }

    /// ψ as a multiple-precision number of `bits` bits, correctly rounded where ψ is exact.
    pub fn offset_float(&self, bits: u32) -> Float {
        match (&self.exact, &self.approximate) {
            (Some(exact), _) => Float::with_val(bits, exact),
            (None, Some(approximate)) => Float::with_val(bits, approximate),
            (None, None) => Float::with_val(bits, 0),
        }
    }

    /// ψ at the precision.
    pub fn offset<R: Real>(&self, precision: Precision) -> R {
        R::from_float(&self.offset_float(precision.in_bits()), precision)
    }

    /// The phase a cycle is read with, and whether it is the mirror image's (Q0 to be
    /// negated): φ modulo 2π in (−π, π], rounded once from the exact offset, except within
    /// [`MIRROR_BELOW`] of ±π, where rounding ψ ± π would lose the offset's low bits: there
    /// ψ itself, for the mirror image (φ + π is the cycle with Q − Q0 reversed).
    pub fn cycle_phase<R: Real>(&self, precision: Precision) -> (R, bool) {
        let bits = precision.in_bits();
        let offset = self.offset_float(bits + GUARD_BITS);
        if !self.reverses {
            return (R::from_float(&Float::with_val(bits, &offset), precision), false);
        }
        if offset.clone().abs() < MIRROR_BELOW {
            return (R::from_float(&Float::with_val(bits, &offset), precision), true);
        }
        let pi = Float::with_val(bits + GUARD_BITS, Constant::Pi);
        let turned = if offset > 0 { offset - pi } else { offset + pi };
        (R::from_float(&Float::with_val(bits, &turned), precision), false)
    }
}

/// A plain decimal (`-1.5e-3`) as an exact rational; None for anything else.
pub(crate) fn decimal(text: &str) -> Option<Rational> {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn parsed(text: &str) -> (Rational, Rational) {
        let phase = ExactPhase::parse(text).unwrap_or_else(|e| panic!("{text}: {e}"));
        (phase.multiple, phase.offset)
    }

    fn ratio(n: i64, d: i64) -> Rational {
        Rational::from((n, d))
    }

    #[test]
    fn phases_read_as_people_write_them_exactly() {
        let zero = Rational::from(0);
        for (text, multiple, offset) in [
            ("pi/2", ratio(1, 2), zero.clone()),
            ("π/2", ratio(1, 2), zero.clone()),
            ("3pi/4", ratio(3, 4), zero.clone()),
            ("3*pi/4", ratio(3, 4), zero.clone()),
            ("-pi/3", ratio(-1, 3), zero.clone()),
            ("0.4pi", ratio(2, 5), zero.clone()),
            ("0.4*pi", ratio(2, 5), zero.clone()),
            ("0.4π", ratio(2, 5), zero.clone()),
            ("72deg", ratio(2, 5), zero.clone()),
            ("72°", ratio(2, 5), zero.clone()),
            ("-45deg", ratio(-1, 4), zero.clone()),
            ("pi/2+1e-3", ratio(1, 2), ratio(1, 1000)),
            ("pi - 1e-6", ratio(1, 1), ratio(-1, 1_000_000)),
            ("1e6pi+0.3", ratio(1_000_000, 1), ratio(3, 10)),
            ("0.25", zero.clone(), ratio(1, 4)),
            ("-2.5e-1", zero.clone(), ratio(-1, 4)),
        ] {
            assert_eq!(parsed(text), (multiple, offset), "{text}");
        }
    }

    #[test]
    fn refusals_name_the_forms_accepted() {
        for text in [
            "xpi",
            "pi1",
            "pi/0",
            "pi/x",
            "pi/2*3",
            "deg",
            "1e",
            "pi+-1",
            "",
            "72 degrees",
            "1/2",
        ] {
            let error = ExactPhase::parse(text).expect_err(text).to_string();
            assert!(error.contains("pi/2") && error.contains("72deg"), "{text}: {error}");
        }
    }

    #[test]
    fn exactly_in_phase_is_decided_from_the_text() {
        for text in ["0", "0.0", "pi", "-pi", "2pi", "180deg", "1e6pi", "0pi+0"] {
            let phase = ExactPhase::parse(text).unwrap();
            assert!(phase.is_in_phase(), "{text}");
            assert!(phase.reduce(Precision::DOUBLE).unwrap().is_in_phase(), "{text}");
        }
        for text in [
            "3.141592653589793",
            "pi-1e-100",
            "1e-300",
            "pi/2",
            "179.9999deg",
            "1e-400",
        ] {
            let phase = ExactPhase::parse(text).unwrap();
            assert!(!phase.is_in_phase(), "{text}");
            assert!(!phase.reduce(Precision::DOUBLE).unwrap().is_in_phase(), "{text}");
        }
    }

    #[test]
    fn the_offset_from_the_nearest_multiple_of_pi_is_exact() {
        let bits = 3000;
        let pi = Float::with_val(bits, Constant::Pi);
        let at = |text: &str| Float::with_val(bits, Float::parse(text).unwrap());
        // (text, n, independent ψ at 3000 bits)
        let cases = [
            ("pi-1e-100", 1, -at("1e-100")),
            ("-pi+1e-100", -1, at("1e-100")),
            ("3.141592653589793", 1, at("3.141592653589793") - &pi),
            ("0.75pi", 1, -pi.clone() / 4u32),
            ("12345.678", 3930, at("12345.678") - pi.clone() * 3930u32),
            ("1e50", 0, Float::with_val(bits, 0)),
            ("2pi+1e-300", 2, at("1e-300")),
        ];
        for (text, half_turns, expected) in cases {
            let reduced = ExactPhase::parse(text).unwrap().reduce(Precision::bits(200)).unwrap();
            let psi = reduced.offset_float(200);
            if text == "1e50" {
                // Independent: 1e50 − round(1e50/π)·π at 3000 bits.
                let phi = at("1e50");
                let n = (phi.clone() / &pi).round();
                let odd = n.to_integer().unwrap().is_odd();
                assert_eq!(reduced.reverses(), odd, "{text}");
                let expected = Float::with_val(200, phi - n * &pi);
                assert_eq!(psi, expected, "{text}");
                continue;
            }
            assert_eq!(reduced.reverses(), half_turns % 2 != 0, "{text}");
            assert_eq!(psi, Float::with_val(200, expected), "{text}");
            let f: f64 = reduced.offset(Precision::DOUBLE);
            assert_eq!(f, psi.to_f64(), "{text}");
        }
    }

    #[test]
    fn phases_beyond_the_bound_are_refused() {
        assert!(matches!(
            ExactPhase::parse("1e101").unwrap().reduce(Precision::DOUBLE),
            Err(PhaseError::TooLarge { .. })
        ));
        assert!(ExactPhase::parse("3e99pi").unwrap().reduce(Precision::DOUBLE).is_ok());
    }
}
