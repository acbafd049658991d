//! A case as text — loads, friction, λ or ν, compliance SPEC — read at a chosen
//! precision. The command line and the reference catalogue both describe cases
//! this way, so that `0.4` means 4/10 at every precision and `0.4pi` means 0.4·π.

use rug::float::Constant;
use rug::Float;
use serde::{Deserialize, Serialize};

use crate::compliance::{parse_spec, Compliance, SpecError};
use crate::cycle::{compliance_ratio_from_poisson, CycleError, LoadCycle, MAX_PHASE};
use crate::real::{ParseRealError, Precision, Real};

/// The text of one case. Numbers are decimal strings; `phase` may end in `pi`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CaseText {
    /// P0.
    pub p0: String,
    /// P1.
    pub p1: String,
    /// Q0 (default 0).
    #[serde(default = "zero_text")]
    pub q0: String,
    /// Q1.
    pub q1: String,
    /// φ in radians, or a multiple of π written `0.4pi`.
    pub phi: String,
    /// f.
    pub friction: String,
    /// λ; exactly one of `lambda` and `nu` is given.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lambda: Option<String>,
    /// ν, giving λ = (2 − ν)/(2(1 − ν)).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nu: Option<String>,
    /// The compliance SPEC (see [`crate::compliance::parse_spec`]).
    pub compliance: String,
}

fn zero_text() -> String {
    "0".to_string()
}

/// Why a case's text does not describe a case.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InputError {
    /// A number that does not parse.
    #[error("{} ({field}): {source}", quantity_of(.field))]
    Number {
        /// The field of the case (`p0`, `phi`, …).
        field: &'static str,
        #[source]
        source: ParseRealError,
    },
    /// Neither or both of λ and ν.
    #[error("give exactly one of the compliance ratio λ and Poisson's ratio ν")]
    LambdaOrNu,
    /// The compliance SPEC is wrong.
    #[error(transparent)]
    Spec(#[from] SpecError),
    /// ν is out of range or not finite, or φ is too large.
    #[error(transparent)]
    Cycle(#[from] CycleError),
    /// A decimal that f64 cannot hold: it overflows, or underflows to zero or to a
    /// subnormal (which keeps fewer than 53 bits). Higher precision reads it exactly.
    #[error("{quantity} = {text} lies outside the range of f64 (normal magnitudes 2.2e-308 to 1.8e308)")]
    OutsideF64Range { quantity: &'static str, text: String },
}

/// Whether `value`, read in f64 from the decimal `text`, lost it to the range of f64:
/// infinite, zero for a non-zero decimal, or subnormal. Always false above 53 bits,
/// whose exponent range reaches far beyond any decimal given by hand.
pub(crate) fn outside_f64_range<R: Real>(value: &R, text: &str) -> bool {
    let precision = value.precision();
    let text = text.trim();
    let plain = text
        .chars()
        .all(|c| c.is_ascii_digit() || matches!(c, '.' | 'e' | 'E' | '+' | '-'));
    if precision != Precision::DOUBLE || !plain || !text.chars().any(|c| c.is_ascii_digit()) {
        return false;
    }
    if !value.is_finite() {
        return true;
    }
    let zero = value.int(0);
    let significand = text.split(['e', 'E']).next().unwrap_or("");
    let nonzero_text = significand.chars().any(|c| ('1'..='9').contains(&c));
    let smallest_normal = R::smallest_full_precision(precision) * &R::epsilon(precision);
    (*value == zero && nonzero_text) || (*value != zero && value.abs() < smallest_normal)
}

/// Bits carried through a phase reduction beyond the working precision and φ's exponent.
const PHASE_GUARD_BITS: u32 = 64;

/// Reads a phase: a decimal (radians), a multiple of π (`0.4pi`, `pi`, `-2pi`), or a
/// multiple of π plus a decimal offset (`pi-1e-6`, `0.5pi+0.01`), each part read
/// exactly at the precision.
///
/// A phase beyond 2π in size is reduced modulo 2π (which changes no cycle) before it
/// is rounded to the precision: the text is exact, so it is read and reduced in MPFR
/// with the working bits plus the bits of its exponent plus a guard, and the reduced
/// angle, in [−π, π], is then rounded once. Reducing after rounding would lose about
/// log2|φ| bits (3 of 15 digits at φ = 1e4). Phases beyond [`MAX_PHASE`] are returned
/// unreduced, for the cycle's validation to refuse.
pub fn parse_phase<R: Real>(text: &str, precision: Precision) -> Result<R, ParseRealError> {
    let estimate: Float = phase_at(text, Precision::bits(64))?;
    let full_turn = Float::with_val(64, Constant::Pi) * 2u32;
    if !estimate.is_finite() || estimate.clone().abs() <= full_turn || estimate.clone().abs() > MAX_PHASE {
        return phase_at(text, precision);
    }
    let exponent = estimate.get_exp().unwrap_or(0).max(0).unsigned_abs();
    let bits = precision.in_bits() + exponent + PHASE_GUARD_BITS;
    let phase: Float = phase_at(text, Precision::bits(bits))?;
    let full_turn = Float::with_val(bits, Constant::Pi) * 2u32;
    let turns = (phase.clone() / &full_turn).round();
    let reduced = Float::with_val(precision.in_bits(), phase - turns * full_turn);
    // Enough digits to read back as the same number at this precision (f64 reads decimals correctly rounded).
    R::parse_decimal(&reduced.to_string_radix(10, None), precision)
}

/// The phase as written, at the precision (no reduction).
fn phase_at<R: Real>(text: &str, precision: Precision) -> Result<R, ParseRealError> {
    let error = || ParseRealError { text: text.to_string() };
    let trimmed = text.trim().replace('π', "pi");
    let Some((multiple, offset)) = trimmed.split_once("pi") else {
        return R::parse_decimal(&trimmed, precision);
    };
    let multiple = multiple.trim().trim_end_matches('*');
    let factor = match multiple {
        "" | "+" => R::from_i64(1, precision),
        "-" => R::from_i64(-1, precision),
        m => R::parse_decimal(m, precision).map_err(|_| error())?,
    };
    let angle = factor * &R::pi(precision);
    let offset = offset.trim();
    if offset.is_empty() {
        return Ok(angle);
    }
    if !offset.starts_with(['+', '-']) {
        return Err(error());
    }
    let offset = R::parse_decimal(offset, precision).map_err(|_| error())?;
    Ok(angle + &offset)
}

/// A case read at a precision: the load cycle and the compliance.
#[derive(Debug)]
pub struct Case<R: Real> {
    /// The load cycle (not yet validated).
    pub cycle: LoadCycle<R>,
    /// The normal compliance.
    pub compliance: Box<dyn Compliance<R>>,
}

impl CaseText {
    /// The load cycle and compliance at `precision`. The cycle is not validated here:
    /// the computations validate it and say what is wrong.
    pub fn read<R: Real>(&self, precision: Precision) -> Result<Case<R>, InputError> {
        let number = |flag: &'static str, text: &str| {
            let value =
                R::parse_decimal(text, precision).map_err(|source| InputError::Number { field: flag, source })?;
            if outside_f64_range(&value, text) {
                return Err(InputError::OutsideF64Range {
                    quantity: quantity_of(flag),
                    text: text.trim().to_string(),
                });
            }
            Ok(value)
        };
        let compliance_ratio = match (&self.lambda, &self.nu) {
            (Some(lambda), None) => number("lambda", lambda)?,
            (None, Some(nu)) => compliance_ratio_from_poisson(&number("nu", nu)?)?,
            _ => return Err(InputError::LambdaOrNu),
        };
        let cycle = LoadCycle {
            mean_normal_load: number("p0", &self.p0)?,
            normal_amplitude: number("p1", &self.p1)?,
            mean_tangential_load: number("q0", &self.q0)?,
            tangential_amplitude: number("q1", &self.q1)?,
            phase: self.phase(precision)?,
            friction: number("friction", &self.friction)?,
            compliance_ratio,
        };
        let compliance = parse_spec::<R>(&self.compliance, precision)?;
        Ok(Case { cycle, compliance })
    }

    /// φ at the precision, reduced modulo 2π where that matters; refused beyond [`MAX_PHASE`].
    fn phase<R: Real>(&self, precision: Precision) -> Result<R, InputError> {
        let number = |source| InputError::Number { field: "phi", source };
        let estimate: Float = phase_at(&self.phi, Precision::bits(64)).map_err(number)?;
        if estimate.is_finite() && estimate.clone().abs() > MAX_PHASE {
            return Err(CycleError::PhaseTooLarge { phi: estimate.to_f64() }.into());
        }
        parse_phase(&self.phi, precision).map_err(number)
    }
}

/// The name of the quantity a case field gives, as the theory writes it.
fn quantity_of(flag: &'static str) -> &'static str {
    match flag {
        "p0" => "P0",
        "p1" => "P1",
        "q0" => "Q0",
        "q1" => "Q1",
        "friction" => "the friction coefficient f",
        "lambda" => "the compliance ratio λ",
        "nu" => "Poisson's ratio ν",
        "phi" => "the phase φ",
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rug::Float;

    #[test]
    fn phase_accepts_multiples_of_pi() {
        let p = Precision::bits(200);
        let x: Float = parse_phase("0.4pi", p).unwrap();
        let expected = Float::pi(p) * Float::parse_decimal("0.4", p).unwrap();
        assert_eq!(x, expected);
        let y: f64 = parse_phase("pi", Precision::DOUBLE).unwrap();
        assert_eq!(y, std::f64::consts::PI);
        let z: f64 = parse_phase("-0.5pi", Precision::DOUBLE).unwrap();
        assert_eq!(z, -std::f64::consts::FRAC_PI_2);
        assert!(parse_phase::<f64>("xpi", Precision::DOUBLE).is_err());
        assert!(parse_phase::<f64>("pi1", Precision::DOUBLE).is_err());
        let w: Float = parse_phase("pi-1e-6", p).unwrap();
        let expected = Float::pi(p) - Float::parse_decimal("1e-6", p).unwrap();
        assert_eq!(w, expected);
        assert!(parse_phase::<f64>("0.3", Precision::DOUBLE).is_ok());
    }

    #[test]
    fn large_phases_are_reduced_modulo_two_pi_before_rounding() {
        let exact = |text: &str, bits: u32| {
            let phase = Float::with_val(2000, Float::parse(text).unwrap());
            let turn = Float::with_val(2000, Constant::Pi) * 2u32;
            let turns = (phase.clone() / &turn).round();
            Float::with_val(bits, phase - turns * turn)
        };
        for text in ["12345.678", "999999", "-1e5", "1e50", "123456789.123456789"] {
            let reduced: f64 = parse_phase(text, Precision::DOUBLE).unwrap();
            assert_eq!(reduced, exact(text, 53).to_f64(), "{text}");
            let reduced: Float = parse_phase(text, Precision::bits(300)).unwrap();
            assert_eq!(reduced, exact(text, 300), "{text}");
        }
        // A multiple of π: 1e6·π + 0.3 ≡ 0.3.
        let reduced: f64 = parse_phase("1e6pi+0.3", Precision::DOUBLE).unwrap();
        assert_eq!(reduced, 0.3);
    }
}
