//! A case as text — loads, friction, λ or ν, compliance SPEC — read at a chosen
//! precision. The command line and the reference catalogue both describe cases
//! this way, so that `0.4` means 4/10 at every precision and `0.4pi` means 0.4·π.

use serde::{Deserialize, Serialize};

use crate::compliance::{parse_spec, Compliance, SpecError};
use crate::cycle::{compliance_ratio_from_poisson, CycleError, LoadCycle};
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
    #[error("--{flag}: {source}")]
    Number {
        flag: &'static str,
        #[source]
        source: ParseRealError,
    },
    /// Neither or both of λ and ν.
    #[error("give exactly one of --lambda and --nu")]
    LambdaOrNu,
    /// The compliance SPEC is wrong.
    #[error(transparent)]
    Spec(#[from] SpecError),
    /// ν is out of range or not finite.
    #[error(transparent)]
    Cycle(#[from] CycleError),
}

/// Reads a phase: a decimal (radians), a multiple of π (`0.4pi`, `pi`, `-2pi`), or a
/// multiple of π plus a decimal offset (`pi-1e-6`, `0.5pi+0.01`), each part read
/// exactly at the precision.
pub fn parse_phase<R: Real>(text: &str, precision: Precision) -> Result<R, ParseRealError> {
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
            R::parse_decimal(text, precision).map_err(|source| InputError::Number { flag, source })
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
            phase: parse_phase(&self.phi, precision).map_err(|source| InputError::Number { flag: "phi", source })?,
            friction: number("friction", &self.friction)?,
            compliance_ratio,
        };
        let compliance = parse_spec::<R>(&self.compliance, precision)?;
        Ok(Case { cycle, compliance })
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
}
