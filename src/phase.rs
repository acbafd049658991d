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
use rug::{Float, Integer, Rational};

use crate::cycle::MAX_PHASE;
pub(crate) use crate::decimal::decimal;
use crate::real::{Precision, Real};

/// The forms a phase may be written in, for refusals.
pub const PHASE_FORMS: &str = "radians (0.3, -1e-6), a multiple of π (pi, pi/2, 3pi/4, -pi/3, 0.4pi, 0.4*pi, π/2), \
either plus or minus radians (pi-1e-6, pi/2+1e-3), or degrees (72deg, 72°)";

/// How close to an odd multiple of π a phase is read as the mirror image of its cycle.
pub const MIRROR_BELOW: f64 = 1.0 / 1_048_576.0;

/// Bits carried beyond the working precision in a reduction.
const GUARD_BITS: u32 = 64;
/// The bits of ψ kept from the reduction: precisions up to them round from it.
const STORED_BITS: u32 = 128;
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

/// A phase reduced modulo π: φ = nπ + ψ with ψ = mπ + x ∈ [−π/2, π/2], m and x exact.
#[derive(Clone, Debug, PartialEq)]
pub struct ReducedPhase {
    /// n is odd: the cycle is the mirror image (Q − Q0 reversed) of the one at ψ.
    reverses: bool,
    /// m = k − n, the multiple of π left in ψ (0 when ψ is the rational x).
    multiple: Rational,
    /// x, the offset in radians as written.
    offset: Rational,
    /// The binary exponent of |φ| (at least 0): the bits the multiple of π cancels.
    exponent: u32,
    /// ψ = mπ + x to [`STORED_BITS`] and a guard beyond its cancellation, computed once
    /// (None when ψ is the rational x): what f64 and ordinary MPFR precisions round from.
    stored: Option<Float>,
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

    /// n = round(φ/π): whether it is odd, m = k − n, and the bits of φ's integer part.
    fn nearest_half_turns(&self) -> Result<(bool, Rational, u32), PhaseError> {
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
        Ok((
            half_turns.is_odd(),
            self.multiple.clone() - Rational::from(half_turns),
            exponent,
        ))
    }

    /// φ reduced once, exactly, modulo π: the nearest multiple nπ and the exact offset ψ from
    /// it. Refused beyond [`MAX_PHASE`], or where ψ cancels more bits than a reduction may use
    /// (never for a decimal written by hand). The offset is then evaluated at any precision
    /// ([`ReducedPhase::offset_float`]) without reducing again.
    pub fn reduce(&self) -> Result<ReducedPhase, PhaseError> {
        let (reverses, multiple, exponent) = self.nearest_half_turns()?;
        let mut reduced = ReducedPhase {
            reverses,
            multiple,
            offset: self.offset.clone(),
            exponent,
            stored: None,
        };
        if reduced.multiple != 0 {
            let stored = reduced.irrational_offset(STORED_BITS, MAX_REDUCTION_BITS);
            reduced.stored = Some(stored.ok_or(PhaseError::TooLarge { phi: self.to_f64() })?);
        }
        Ok(reduced)
    }
}

impl ReducedPhase {
    /// φ ≡ 0 (mod π) exactly.
    pub fn is_in_phase(&self) -> bool {
        self.multiple == 0 && self.offset == 0
    }

    /// n is odd: φ = ψ + nπ describes the mirror image of the cycle at ψ.
    pub fn reverses(&self) -> bool {
        self.reverses
    }

    /// φ = nπ + ψ with ψ = mπ + x ∈ [−π/2, π/2]: whether n is odd, and the exact m and x
    /// (for arithmetic that encloses ψ from its exact parts).
    pub fn offset_parts(&self) -> (bool, &Rational, &Rational) {
        (self.reverses, &self.multiple, &self.offset)
    }

    /// ψ as a multiple-precision number of `bits` bits, correctly rounded where ψ is exact
    /// (a rational), and otherwise computed with the bits its cancellation needs.
    pub fn offset_float(&self, bits: u32) -> Float {
        if self.multiple == 0 {
            return Float::with_val(bits, &self.offset);
        }
        if let Some(stored) = self.stored.as_ref().filter(|_| bits <= STORED_BITS) {
            return Float::with_val(bits, stored);
        }
        // `reduce` found the cancellation finite; at more bits it needs no more than that.
        let psi = self
            .irrational_offset(bits, u32::MAX)
            .unwrap_or_else(|| Float::with_val(bits, 0));
        Float::with_val(bits, psi)
    }

    /// ψ = mπ + x ≠ 0 (π is irrational) to `bits` bits and a guard beyond its last bit of
    /// cancellation: the bits are raised until the sum keeps them above its rounding error;
    /// None beyond `limit` bits.
    fn irrational_offset(&self, bits: u32, limit: u32) -> Option<Float> {
        let wanted = bits + GUARD_BITS;
        let mut bits = wanted + self.exponent + GUARD_BITS;
        loop {
            let multiple_part = Float::with_val(bits, &self.multiple) * Float::with_val(bits, Constant::Pi);
            let offset_part = Float::with_val(bits, &self.offset);
            let size = Float::with_val(bits, multiple_part.abs_ref()) + Float::with_val(bits, offset_part.abs_ref());
            let sum = multiple_part + offset_part;
            // The rounding error of the sum is below 4 ulps of `size`.
            let kept = sum.get_exp().unwrap_or(i32::MIN) as i64 - size.get_exp().unwrap_or(0) as i64 + bits as i64 - 2;
            if !sum.is_zero() && kept >= wanted as i64 {
                return Some(sum);
            }
            let missing = (wanted as i64 - kept).max(64) as u32;
            bits = bits.saturating_add(missing + bits / 2);
            if bits > limit {
                return None;
            }
        }
    }

    /// Whether a cycle is read as the mirror image of the one at ψ (Q0 negated): within
    /// [`MIRROR_BELOW`] of an odd multiple of π ([`ReducedPhase::cycle_phase`]).
    pub fn is_mirror_image(&self) -> bool {
        self.reverses && self.offset_float(GUARD_BITS).abs() < MIRROR_BELOW
    }

    /// ψ at the precision.
    pub fn offset<R: Real>(&self, precision: Precision) -> R {
        R::enclose_pi_multiple(&self.multiple, &self.offset, precision)
            .unwrap_or_else(|| R::from_float(&self.offset_float(precision.in_bits()), precision))
    }

    /// The phase a cycle is read with, and whether it is the mirror image's (Q0 to be
    /// negated): φ modulo 2π in (−π, π], rounded once from the exact offset, except within
    /// [`MIRROR_BELOW`] of ±π, where rounding ψ ± π would lose the offset's low bits: there
    /// ψ itself, for the mirror image (φ + π is the cycle with Q − Q0 reversed).
    pub fn cycle_phase<R: Real>(&self, precision: Precision) -> (R, bool) {
        // A ball encloses ψ from its exact parts, and ψ ∓ π with a ball of π.
        if let Some(offset) = R::enclose_pi_multiple(&self.multiple, &self.offset, precision) {
            if !self.reverses || self.is_mirror_image() {
                return (offset, self.reverses);
            }
            let pi = R::pi(precision);
            let turned = if offset.to_f64_lossy() > 0.0 {
                offset - &pi
            } else {
                offset + &pi
            };
            return (turned, false);
        }
        let bits = precision.in_bits();
        let offset = self.offset_float(bits + GUARD_BITS);
        if !self.reverses {
            return (R::from_float(&Float::with_val(bits, &offset), precision), false);
        }
        if self.is_mirror_image() {
            return (R::from_float(&Float::with_val(bits, &offset), precision), true);
        }
        let pi = Float::with_val(bits + GUARD_BITS, Constant::Pi);
        let turned = if offset > 0 { offset - pi } else { offset + pi };
        (R::from_float(&Float::with_val(bits, &turned), precision), false)
    }
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
            assert!(phase.reduce().unwrap().is_in_phase(), "{text}");
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
            assert!(!phase.reduce().unwrap().is_in_phase(), "{text}");
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
            let reduced = ExactPhase::parse(text).unwrap().reduce().unwrap();
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
            // Below the stored bits, rounded from the one reduction; above, computed again.
            assert_eq!(reduced.offset_float(100), Float::with_val(100, &expected), "{text}");
            assert_eq!(psi, Float::with_val(200, expected), "{text}");
            let f: f64 = reduced.offset(Precision::DOUBLE);
            assert_eq!(f, psi.to_f64(), "{text}");
        }
    }

    #[test]
    fn phases_beyond_the_bound_are_refused() {
        assert!(matches!(
            ExactPhase::parse("1e101").unwrap().reduce(),
            Err(PhaseError::TooLarge { .. })
        ));
        assert!(ExactPhase::parse("3e99pi").unwrap().reduce().is_ok());
    }
}
