//! A case as text — loads, friction, λ or ν, compliance SPEC — read at a chosen
//! precision. The command line and the reference catalogue both describe cases
//! this way, so that `0.4` means 4/10 at every precision and `0.4pi` means 0.4·π.

use rug::Rational;
use serde::{Deserialize, Serialize};

use crate::compliance::constant_slope;
use crate::compliance::{parse_spec, Compliance, SpecError};
use crate::cycle::{compliance_ratio_from_poisson, CycleError, LoadCycle};
use crate::dissipation::ExactZero;
use crate::phase::{decimal, ExactPhase, PhaseError};
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
        /// Why it does not parse.
        #[source]
        source: ParseRealError,
    },
    /// Neither or both of λ and ν.
    #[error("give exactly one of the compliance ratio λ and Poisson's ratio ν")]
    LambdaOrNu,
    /// The compliance SPEC is wrong.
    #[error(transparent)]
    Spec(#[from] SpecError),
    /// ν is out of range or not finite.
    #[error(transparent)]
    Cycle(#[from] CycleError),
    /// The phase is not written in an accepted form, or is too large.
    #[error(transparent)]
    Phase(#[from] PhaseError),
    /// A decimal that f64 cannot hold: it overflows, or underflows to zero or to a
    /// subnormal (which keeps fewer than 53 bits). Higher precision reads it exactly.
    #[error("{quantity} = {text} lies outside the range of f64 (normal magnitudes 2.2e-308 to 1.8e308)")]
    OutsideF64Range {
        /// The quantity's name.
        quantity: &'static str,
        /// The decimal as written.
        text: String,
    },
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

/// Reads a phase (see [`ExactPhase::parse`] for the forms), reduces it exactly modulo π, and
/// gives the phase a cycle is read with ([`crate::phase::ReducedPhase::cycle_phase`]: φ modulo 2π, or within
/// 2⁻²⁰ of an odd multiple of π the offset ψ from it) and whether that is the mirror image's.
pub fn parse_phase<R: Real>(text: &str, precision: Precision) -> Result<(R, bool), PhaseError> {
    Ok(ExactPhase::parse(text)?.reduce(precision)?.cycle_phase(precision))
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
        let (phase, mirrored) = self.phase(precision)?;
        let mean_tangential_load = number("q0", &self.q0)?;
        let cycle = LoadCycle {
            mean_normal_load: number("p0", &self.p0)?,
            normal_amplitude: number("p1", &self.p1)?,
            // Within 2⁻²⁰ of an odd multiple of π, φ = nπ + ψ is read as the mirror image, the
            // cycle at ψ with Q0 reversed: the same W, segments and validity (proofs/exact-values.md).
            mean_tangential_load: if mirrored {
                -mean_tangential_load
            } else {
                mean_tangential_load
            },
            tangential_amplitude: number("q1", &self.q1)?,
            phase,
            friction: number("friction", &self.friction)?,
            compliance_ratio,
        };
        let compliance = parse_spec::<R>(&self.compliance, precision)?;
        Ok(Case { cycle, compliance })
    }

    /// The phase at the precision ([`parse_phase`]) and whether it is the mirror image's. An
    /// offset from a multiple of π that f64 cannot hold (1e-400) is refused in f64 like any number.
    fn phase<R: Real>(&self, precision: Precision) -> Result<(R, bool), InputError> {
        let reduced = ExactPhase::parse(&self.phi)?.reduce(precision)?;
        let (phase, mirrored): (R, bool) = reduced.cycle_phase(precision);
        let offset: R = reduced.offset(precision);
        let zero = offset.int(0);
        let smallest_normal = R::smallest_full_precision(precision) * &R::epsilon(precision);
        let lost = precision == Precision::DOUBLE
            && !reduced.is_in_phase()
            && (offset == zero || offset.abs() < smallest_normal);
        if lost {
            return Err(InputError::OutsideF64Range {
                quantity: "the phase's offset from the nearest multiple of π",
                text: reduced.offset_float(64).to_string_radix(10, Some(6)),
            });
        }
        Ok((phase, mirrored))
    }

    /// Why W is exactly 0, if it is, decided from the exact text: v'' ≡ 0 (a SPEC whose
    /// non-constant terms cancel exactly), Q1 = 0, or exactly in phase (φ = kπ) with
    /// Q1 ≤ fP1, where nothing slips. The cycle itself is not validated here.
    pub fn exact_zero(&self) -> Result<Option<ExactZero>, InputError> {
        let exact = |field: &'static str, text: &str| {
            decimal(text).ok_or_else(|| InputError::Number {
                field,
                source: ParseRealError { text: text.to_string() },
            })
        };
        let q1 = exact("q1", &self.q1)?;
        if q1 == 0 {
            return Ok(Some(ExactZero::NoTangentialOscillation));
        }
        if ExactPhase::parse(&self.phi)?.is_in_phase() {
            let limit: Rational = exact("friction", &self.friction)? * exact("p1", &self.p1)?;
            if q1 <= limit {
                return Ok(Some(ExactZero::InPhaseWithoutSlip));
            }
        }
        if constant_slope(&self.compliance) {
            return Ok(Some(ExactZero::ConstantSlope));
        }
        Ok(None)
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
    fn phase_reads_to_its_offset_from_the_nearest_multiple_of_pi() {
        let p = Precision::bits(200);
        let (x, mirrored): (Float, bool) = parse_phase("0.4pi", p).unwrap();
        let pi = Float::with_val(1000, rug::float::Constant::Pi);
        let expected = Float::with_val(200, pi.clone() * Float::with_val(1000, Rational::from((2, 5))));
        assert_eq!((x, mirrored), (expected, false));
        let (y, mirrored): (f64, bool) = parse_phase("pi", Precision::DOUBLE).unwrap();
        assert_eq!((y, mirrored), (0.0, true));
        let (w, mirrored): (Float, bool) = parse_phase("pi-1e-7", p).unwrap();
        assert_eq!((w, mirrored), (-Float::parse_decimal("1e-7", p).unwrap(), true));
        // Away from π: φ modulo 2π, the cycle as written.
        let (v, mirrored): (Float, bool) = parse_phase("0.75pi", p).unwrap();
        let expected = Float::with_val(200, pi * Float::with_val(1000, Rational::from((3, 4))));
        assert_eq!((v, mirrored), (expected, false));
        assert!(parse_phase::<f64>("xpi", Precision::DOUBLE).is_err());
    }

    #[test]
    fn an_odd_multiple_of_pi_reads_as_the_mirror_image() {
        let case = |phi: &str| CaseText {
            p0: "1".into(),
            p1: "0.4".into(),
            q0: "0.1".into(),
            q1: "0.2".into(),
            phi: phi.into(),
            friction: "1".into(),
            lambda: Some("1".into()),
            nu: None,
            compliance: "persson:gamma=1,sigma=1".into(),
        };
        let Case { cycle, .. } = case("pi-1e-30").read::<f64>(Precision::DOUBLE).unwrap();
        assert_eq!((cycle.mean_tangential_load, cycle.phase), (-0.1, -1e-30));
        let Case { cycle, .. } = case("0.75pi").read::<f64>(Precision::DOUBLE).unwrap();
        assert_eq!(cycle.mean_tangential_load, 0.1);
        assert_eq!(cycle.phase, 0.75 * std::f64::consts::PI);
        let Case { cycle, .. } = case("2pi+0.3").read::<f64>(Precision::DOUBLE).unwrap();
        assert_eq!((cycle.mean_tangential_load, cycle.phase), (0.1, 0.3));
        assert!(matches!(
            case("pi-1e-400").read::<f64>(Precision::DOUBLE),
            Err(InputError::OutsideF64Range { .. })
        ));
        assert!(case("pi-1e-400").read::<Float>(Precision::bits(64)).is_ok());
    }
}
