//! A case: the loads, friction, λ or ν and compliance of one load cycle on a contact.
//!
//! The command line, batch files and the reference catalogue describe a case as text
//! ([`CaseText`]). It is read once into a [`CaseSpec`]: exact decimals (`0.4` means 4/10
//! at every precision), the phase reduced exactly once modulo π (`0.4pi` means 0.4·π,
//! `pi-1e-100` keeps its offset), and the compliance as a [`ComplianceSpec`] tree with its
//! tables read. [`CaseSpec::at`] then gives the cycle and compliance at any precision
//! (f64, MPFR, Arb balls) without reading text again, and [`CaseSpec::exact_zero`] says
//! from the exact numbers why W is exactly 0, if it is.

use rug::Rational;
use serde::{Deserialize, Serialize};

use crate::boundaries::{self, compliance_ratio_of_poisson, ExactCycle};
use crate::compliance::{Compliance, ComplianceSpec, SpecError};
use crate::cycle::{CycleError, LoadCycle};
use crate::decimal::{decimal, rounded};
use crate::dissipation::ExactZero;
use crate::phase::{ExactPhase, PhaseError, ReducedPhase};
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
        /// The text that does not read as a number.
        #[source]
        source: ParseRealError,
    },
    /// Neither or both of λ and ν.
    #[error("give exactly one of the compliance ratio λ and Poisson's ratio ν")]
    LambdaOrNu,
    /// A field the case needs was not given.
    #[error("{} ({field}) is missing: give it", quantity_of(.field))]
    Missing {
        /// The field of the case (`p0`, `phi`, …).
        field: &'static str,
    },
    /// The compliance SPEC is wrong, or a table it names cannot be read or is not a
    /// compliance.
    #[error(transparent)]
    Compliance(#[from] SpecError),
    /// The cycle leaves the theory (separation, gross slip, λ or ν out of range, …),
    /// decided exactly from the decimals ([`crate::boundaries`]).
    #[error(transparent)]
    Cycle(#[from] CycleError),
    /// The phase is not written in an accepted form, or is too large.
    #[error(transparent)]
    Phase(#[from] PhaseError),
    /// A decimal that f64 cannot hold: it overflows, or underflows to zero or to a
    /// subnormal (which keeps fewer than 53 bits). Higher precision reads it exactly.
    #[error("{quantity} = {text} lies outside the range of f64 (normal magnitudes 2.2e-308 to 1.8e308)")]
    OutsideF64Range {
        /// The quantity, as the theory writes it.
        quantity: &'static str,
        /// The decimal as given.
        text: String,
    },
}

/// Reads a phase (see [`ExactPhase::parse`] for the forms), reduces it exactly modulo π, and
/// gives the phase a cycle is read with ([`crate::phase::ReducedPhase::cycle_phase`]: φ modulo 2π, or within
/// 2⁻²⁰ of an odd multiple of π the offset ψ from it) and whether that is the mirror image's.
pub fn parse_phase<R: Real>(text: &str, precision: Precision) -> Result<(R, bool), PhaseError> {
    Ok(ExactPhase::parse(text)?.reduce()?.cycle_phase(precision))
}

/// A case read at a precision: the load cycle and the compliance.
#[derive(Debug)]
pub struct Case<R: Real> {
    /// The load cycle (not yet validated).
    pub cycle: LoadCycle<R>,
    /// The normal compliance.
    pub compliance: Box<dyn Compliance<R>>,
}

/// A decimal field of a case: which field (for messages), its text, its exact value.
#[derive(Clone, Debug, PartialEq)]
struct Field {
    name: &'static str,
    text: String,
    value: Rational,
}

impl Field {
    fn read(name: &'static str, text: &str) -> Result<Field, InputError> {
        let value = decimal(text).ok_or_else(|| InputError::Number {
            field: name,
            source: ParseRealError { text: text.to_string() },
        })?;
        Ok(Field {
            name,
            text: text.trim().to_string(),
            value,
        })
    }

    /// The value rounded once to the precision; refused where f64 cannot hold it.
    fn at<R: Real>(&self, precision: Precision) -> Result<R, InputError> {
        rounded(&self.value, precision).ok_or_else(|| InputError::OutsideF64Range {
            quantity: quantity_of(self.name),
            text: self.text.clone(),
        })
    }
}

/// A case read once from its text: exact decimals, the phase reduced exactly modulo π,
/// the compliance as a tree with its tables read, and its cycle inside the theory, decided
/// exactly ([`crate::boundaries`]). A cycle rounded to a working precision may still cross
/// a boundary the exact one keeps off (P0 − P1 = 1e-17 in f64): the computations check
/// their rounded cycle and go to a higher precision where it does.
#[derive(Clone, Debug)]
pub struct CaseSpec {
    mean_normal_load: Field,
    normal_amplitude: Field,
    mean_tangential_load: Field,
    tangential_amplitude: Field,
    friction: Field,
    /// λ, exactly: as given, or (2 − ν)/(2(1 − ν)) from Poisson's ratio ν.
    compliance_ratio: Field,
    phase: ReducedPhase,
    compliance: ComplianceSpec,
    /// The text it was read from, for the reports that echo the inputs.
    text: CaseText,
}

impl CaseText {
    /// Reads the case once ([`CaseSpec`]); refuses text that does not describe a case.
    ///
    /// ```
    /// use microslip::case::CaseText;
    /// use microslip::real::Precision;
    ///
    /// let text = CaseText {
    ///     p0: "1".into(),
    ///     p1: "0.4".into(),
    ///     q0: "0".into(),
    ///     q1: "0.2".into(),
    ///     phi: "0.4pi".into(),
    ///     friction: "1".into(),
    ///     lambda: Some("1".into()),
    ///     nu: None,
    ///     compliance: "persson:gamma=1,sigma=1".into(),
    /// };
    /// let spec = text.spec().unwrap();
    /// let case = spec.at::<f64>(Precision::DOUBLE).unwrap();
    /// assert_eq!(case.cycle.normal_amplitude, 0.4);
    /// assert_eq!(spec.exact_zero(), None);
    /// ```
    pub fn spec(&self) -> Result<CaseSpec, InputError> {
        let compliance_ratio = match (&self.lambda, &self.nu) {
            (Some(lambda), None) => Field::read("lambda", lambda)?,
            (None, Some(nu)) => {
                let nu = Field::read("nu", nu)?;
                Field {
                    value: compliance_ratio_of_poisson(&nu.value, &nu.text)?,
                    ..nu
                }
            }
            _ => return Err(InputError::LambdaOrNu),
        };
        let phase = ExactPhase::parse(&self.phi)?.reduce()?;
        let mean_tangential_load = Field::read("q0", &self.q0)?;
        let compliance = ComplianceSpec::parse(&self.compliance)?;
        let spec = CaseSpec {
            mean_normal_load: Field::read("p0", &self.p0)?,
            normal_amplitude: Field::read("p1", &self.p1)?,
            mean_tangential_load,
            tangential_amplitude: Field::read("q1", &self.q1)?,
            friction: Field::read("friction", &self.friction)?,
            compliance_ratio,
            phase,
            compliance,
            text: self.clone(),
        };
        boundaries::decide(&spec.exact_cycle())?;
        Ok(spec)
    }

    /// A builder of a case from numbers or exact decimal strings, checked whole by
    /// [`CaseBuilder::build`].
    ///
    /// ```
    /// use microslip::case::CaseText;
    ///
    /// let case = CaseText::builder()
    ///     .p0(1.0)
    ///     .p1("0.4")
    ///     .q1(0.5)
    ///     .phi("0.4pi")
    ///     .friction(1)
    ///     .lambda(1)
    ///     .compliance("persson:gamma=1,sigma=1")
    ///     .build()
    ///     .unwrap();
    /// assert_eq!(case.text().p1, "0.4");
    /// assert_eq!(case.text().q0, "0");
    /// // A case outside the theory does not exist: gross slip is refused on building.
    /// let refused = CaseText::builder()
    ///     .p0(1).p1(0.4).q1(2).phi("0.4pi").friction(1).lambda(1)
    ///     .compliance("persson:gamma=1,sigma=1")
    ///     .build();
    /// assert!(refused.unwrap_err().to_string().contains("gross slip"));
    /// ```
    pub fn builder() -> CaseBuilder {
        CaseBuilder::default()
    }

    /// The load cycle and compliance at `precision` (`self.spec()?.at(precision)`); a caller
    /// that needs more than one precision reads the [`CaseSpec`] once instead.
    pub fn read<R: Real>(&self, precision: Precision) -> Result<Case<R>, InputError> {
        self.spec()?.at(precision)
    }
}

impl CaseSpec {
    /// The load cycle and compliance at `precision`, each exact number rounded once. The
    /// cycle is not validated here: the computations validate it and say what is wrong. In
    /// f64, a number that f64 cannot hold (1e-400) is refused, higher precisions read it.
    pub fn at<R: Real>(&self, precision: Precision) -> Result<Case<R>, InputError> {
        let compliance_ratio = self.compliance_ratio.at(precision)?;
        let (phase, mirrored) = self.cycle_phase(precision)?;
        let mean_tangential_load: R = self.mean_tangential_load.at(precision)?;
        let cycle = LoadCycle {
            mean_normal_load: self.mean_normal_load.at(precision)?,
            normal_amplitude: self.normal_amplitude.at(precision)?,
            // Within 2⁻²⁰ of an odd multiple of π, φ = nπ + ψ is read as the mirror image, the
            // cycle at ψ with Q0 reversed: the same W, segments and validity (proofs/exact-values.md).
            mean_tangential_load: if mirrored {
                -mean_tangential_load
            } else {
                mean_tangential_load
            },
            tangential_amplitude: self.tangential_amplitude.at(precision)?,
            phase,
            friction: self.friction.at(precision)?,
            compliance_ratio,
        };
        let compliance = self.compliance.build::<R>(precision)?;
        Ok(Case { cycle, compliance })
    }

    /// P0 − P1, the lowest normal load, from the exact decimals rounded once to the
    /// precision (enclosed by the two doubles around it in intervals), where the
    /// difference of P0 and P1 each rounded would carry their rounding amplified
    /// P0/(P0 − P1)-fold ([`crate::cycle::EllipseGeometry::with_lowest_normal_load`]).
    pub fn lowest_normal_load<R: Real>(&self, precision: Precision) -> Result<R, InputError> {
        let lowest = Rational::from(&self.mean_normal_load.value - &self.normal_amplitude.value);
        rounded(&lowest, precision).ok_or_else(|| InputError::OutsideF64Range {
            quantity: "the lowest normal load P0 − P1",
            text: format!("{} − {}", self.mean_normal_load.text, self.normal_amplitude.text),
        })
    }

    /// The phase the cycle is read with at the precision ([`ReducedPhase::cycle_phase`]) and
    /// whether it is the mirror image's. An offset from a multiple of π that f64 cannot hold
    /// (1e-400) is refused in f64 like any number.
    fn cycle_phase<R: Real>(&self, precision: Precision) -> Result<(R, bool), InputError> {
        let reduced = &self.phase;
        let (phase, mirrored): (R, bool) = reduced.cycle_phase(precision);
        if precision == Precision::DOUBLE && !reduced.is_in_phase() {
            let offset: R = reduced.offset(precision);
            let zero = offset.int(0);
            let smallest_normal = R::smallest_full_precision(precision) * &R::epsilon(precision);
            if offset == zero || offset.abs() < smallest_normal {
                return Err(InputError::OutsideF64Range {
                    quantity: "the phase's offset from the nearest multiple of π",
                    text: reduced.offset_float(64).to_string_radix(10, Some(6)),
                });
            }
        }
        Ok((phase, mirrored))
    }

    /// Why W is exactly 0, if it is, decided from the exact numbers: v'' ≡ 0 (a SPEC whose
    /// non-constant terms cancel exactly), Q1 = 0, or exactly in phase (φ = kπ) with
    /// Q1 ≤ fP1, where nothing slips. The cycle itself is not validated here.
    pub fn exact_zero(&self) -> Option<ExactZero> {
        let q1 = &self.tangential_amplitude.value;
        if *q1 == 0 {
            return Some(ExactZero::NoTangentialOscillation);
        }
        if self.phase.is_in_phase() && *q1 <= Rational::from(&self.friction.value * &self.normal_amplitude.value) {
            return Some(ExactZero::InPhaseWithoutSlip);
        }
        self.compliance.is_constant_slope().then_some(ExactZero::ConstantSlope)
    }

    /// P1 = 0 exactly: the normal load is constant (the Cattaneo–Mindlin closed form).
    pub fn has_constant_normal_load(&self) -> bool {
        self.normal_amplitude.value == 0
    }

    /// The cycle's exact quantities, for deciding its boundaries.
    fn exact_cycle(&self) -> ExactCycle<'_> {
        ExactCycle {
            mean_normal_load: &self.mean_normal_load.value,
            normal_amplitude: &self.normal_amplitude.value,
            mean_tangential_load: &self.mean_tangential_load.value,
            tangential_amplitude: &self.tangential_amplitude.value,
            friction: &self.friction.value,
            compliance_ratio: &self.compliance_ratio.value,
            compliance_ratio_text: &self.compliance_ratio.text,
            phase: &self.phase,
        }
    }

    /// The phase, reduced exactly modulo π.
    pub fn phase(&self) -> &ReducedPhase {
        &self.phase
    }

    /// The compliance as read.
    pub fn compliance(&self) -> &ComplianceSpec {
        &self.compliance
    }

    /// The text the case was read from.
    pub fn text(&self) -> &CaseText {
        &self.text
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
        "compliance" => "the compliance SPEC",
        other => other,
    }
}

/// A number of a case as the builder takes it: an exact decimal string (`"0.4"`, `"0.4pi"`,
/// `"1e-300"`), an integer, or an f64, read as its shortest round-trip decimal (`0.1` is
/// `"0.1"`, the decimal a user wrote, not the binary64 nearest it).
#[derive(Clone, Debug, PartialEq)]
pub struct Number(String);

impl From<&str> for Number {
    fn from(text: &str) -> Number {
        Number(text.to_string())
    }
}

impl From<String> for Number {
    fn from(text: String) -> Number {
        Number(text)
    }
}

impl From<f64> for Number {
    fn from(x: f64) -> Number {
        // Rust's `Debug` of an f64 is its shortest round-trip decimal; NaN and infinities
        // stay words, which the reader refuses with their field's name.
        Number(format!("{x:?}"))
    }
}

impl From<i64> for Number {
    fn from(n: i64) -> Number {
        Number(n.to_string())
    }
}

impl From<i32> for Number {
    fn from(n: i32) -> Number {
        Number(n.to_string())
    }
}

impl From<&String> for Number {
    fn from(text: &String) -> Number {
        Number(text.clone())
    }
}

/// A case put together field by field ([`CaseText::builder`]); Q0 is 0 unless given, and
/// of λ and ν the one given last counts (one must be).
#[derive(Clone, Debug, Default)]
pub struct CaseBuilder {
    p0: Option<String>,
    p1: Option<String>,
    q0: Option<String>,
    q1: Option<String>,
    phi: Option<String>,
    friction: Option<String>,
    lambda: Option<String>,
    nu: Option<String>,
    compliance: Option<String>,
}

/// A setter of the builder per number of a case.
macro_rules! number_setters {
    ($($(#[$doc:meta])* $field:ident),+) => {$(
        $(#[$doc])*
        pub fn $field(mut self, value: impl Into<Number>) -> Self {
            self.$field = Some(value.into().0);
            self
        }
    )+};
}

impl CaseBuilder {
    number_setters!(
        /// P0, the mean normal load (> 0).
        p0,
        /// P1, the normal load amplitude (0 ≤ P1 < P0).
        p1,
        /// Q0, the mean tangential load (default 0).
        q0,
        /// Q1, the tangential load amplitude (≥ 0).
        q1,
        /// φ, the phase: radians, or a decimal string in any form the command line takes
        /// (`"0.4pi"`, `"pi/2"`, `"72deg"`, `"pi-1e-100"`).
        phi,
        /// f, the friction coefficient (> 0).
        friction
    );

    /// λ, the compliance ratio, in [1, 2] (in place of a ν given before).
    pub fn lambda(mut self, value: impl Into<Number>) -> Self {
        self.lambda = Some(value.into().0);
        self.nu = None;
        self
    }

    /// ν, Poisson's ratio, in [0, 2/3] (in place of a λ given before).
    pub fn nu(mut self, value: impl Into<Number>) -> Self {
        self.nu = Some(value.into().0);
        self.lambda = None;
        self
    }

    /// The compliance SPEC (`"persson:gamma=1,sigma=1"`, `"table:FILE"`, …).
    pub fn compliance(mut self, spec: impl Into<String>) -> Self {
        self.compliance = Some(spec.into());
        self
    }

    /// The case as written, not yet read or checked (a field not given is empty, and
    /// refused as such when the case is read): a case to hand to a command, or one a test
    /// expects to be refused.
    pub fn text(self) -> CaseText {
        CaseText {
            p0: self.p0.unwrap_or_default(),
            p1: self.p1.unwrap_or_default(),
            q0: self.q0.unwrap_or_else(zero_text),
            q1: self.q1.unwrap_or_default(),
            phi: self.phi.unwrap_or_default(),
            friction: self.friction.unwrap_or_default(),
            lambda: self.lambda,
            nu: self.nu,
            compliance: self.compliance.unwrap_or_default(),
        }
    }

    /// The case, read and checked whole as [`CaseText::spec`] does, or why it is not one (a
    /// missing field is named).
    pub fn build(self) -> Result<CaseSpec, InputError> {
        let required = |field: Option<String>, name: &'static str| field.ok_or(InputError::Missing { field: name });
        CaseText {
            p0: required(self.p0, "p0")?,
            p1: required(self.p1, "p1")?,
            q0: self.q0.unwrap_or_else(zero_text),
            q1: required(self.q1, "q1")?,
            phi: required(self.phi, "phi")?,
            friction: required(self.friction, "friction")?,
            lambda: self.lambda,
            nu: self.nu,
            compliance: required(self.compliance, "compliance")?,
        }
        .spec()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compliance::TableError;
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

    fn text(p0: &str, q1: &str, phi: &str, compliance: &str) -> CaseText {
        CaseText {
            p0: p0.into(),
            p1: "0.4".into(),
            q0: "-0.1".into(),
            q1: q1.into(),
            phi: phi.into(),
            friction: "0.7".into(),
            lambda: None,
            nu: Some("0.3".into()),
            compliance: compliance.into(),
        }
    }

    #[test]
    fn a_case_is_read_once_and_gives_its_decimals_at_every_precision() {
        let spec = text("1.5", "0.2", "0.4pi", "persson:gamma=1,sigma=1").spec().unwrap();
        let Case { cycle, .. } = spec.at::<f64>(Precision::DOUBLE).unwrap();
        let loads = |c: &LoadCycle<f64>| {
            [
                c.mean_normal_load,
                c.normal_amplitude,
                c.mean_tangential_load,
                c.tangential_amplitude,
                c.friction,
            ]
        };
        let decimals = ["1.5", "0.4", "-0.1", "0.2", "0.7"];
        assert_eq!(loads(&cycle), decimals.map(|d| d.parse::<f64>().unwrap()));
        assert!(
            (cycle.compliance_ratio - 17.0 / 14.0).abs() <= f64::EPSILON,
            "{}",
            cycle.compliance_ratio
        );
        let p = Precision::bits(200);
        let Case { cycle, .. } = spec.at::<Float>(p).unwrap();
        let fields = [
            &cycle.mean_normal_load,
            &cycle.normal_amplitude,
            &cycle.mean_tangential_load,
            &cycle.tangential_amplitude,
            &cycle.friction,
        ];
        for (value, decimal) in fields.into_iter().zip(decimals) {
            assert_eq!(
                *value,
                Float::with_val(200, Float::parse(decimal).unwrap()),
                "{decimal}"
            );
        }
        let ratio = Float::with_val(200, Rational::from((17, 14)));
        assert!(
            (cycle.compliance_ratio - ratio).abs() < Float::with_val(200, 1e-58),
            "λ = 17/14"
        );
    }

    #[test]
    fn why_w_is_exactly_zero_comes_from_the_exact_case() {
        let zero = |q1: &str, phi: &str, compliance: &str| text("1", q1, phi, compliance).spec().unwrap().exact_zero();
        let persson = "persson:gamma=1,sigma=1";
        assert_eq!(zero("0", "0.4pi", persson), Some(ExactZero::NoTangentialOscillation));
        // f·P1 = 0.28 exactly.
        assert_eq!(zero("0.28", "pi", persson), Some(ExactZero::InPhaseWithoutSlip));
        assert_eq!(zero("0.2800000000000000001", "pi", persson), None);
        assert_eq!(zero("0.2", "3.141592653589793", persson), None);
        assert_eq!(zero("0.2", "pi-1e-100", persson), None);
        assert_eq!(zero("0.2", "0.4pi", "const:c=0.8"), Some(ExactZero::ConstantSlope));
        let cancelling = "power:c=1,beta=-1+power:c=-1,beta=-1+const:c=1";
        assert_eq!(zero("0.2", "0.4pi", cancelling), Some(ExactZero::ConstantSlope));
        assert_eq!(zero("0.2", "0.4pi", persson), None);
    }

    #[test]
    fn text_that_is_not_a_case_is_refused_once_and_ranges_at_each_precision() {
        let persson = "persson:gamma=1,sigma=1";
        assert!(matches!(
            text("x", "0.2", "1", persson).spec(),
            Err(InputError::Number { field: "p0", .. })
        ));
        assert!(matches!(
            text("1", "0.2", "1e101", persson).spec(),
            Err(InputError::Phase(PhaseError::TooLarge { .. }))
        ));
        assert!(matches!(
            text("1", "0.2", "1", "table:no-such-table.csv").spec(),
            Err(InputError::Compliance(SpecError::Table(TableError::File { .. })))
        ));
        assert!(matches!(
            text("1", "0.2", "1", "persson:gamma=0,sigma=1").spec(),
            Err(InputError::Compliance(SpecError::Text { .. }))
        ));
        let mut both = text("1", "0.2", "1", persson);
        both.lambda = Some("1".into());
        assert_eq!(both.spec().unwrap_err(), InputError::LambdaOrNu);
        // P0 = 1e-400 with P1 = 0.4 separates, decided exactly when read.
        assert!(matches!(
            text("1e-400", "0.2", "1", persson).spec(),
            Err(InputError::Cycle(CycleError::Separation { .. }))
        ));
        let tiny = text("1", "1e-400", "1", persson).spec().unwrap();
        assert!(matches!(
            tiny.at::<f64>(Precision::DOUBLE),
            Err(InputError::OutsideF64Range { quantity: "Q1", .. })
        ));
        assert!(tiny.at::<Float>(Precision::bits(64)).is_ok());
    }
}
