//! The compliance SPEC language of the command line, read once into a tree.
//!
//! ```text
//! spec   := term ('+' term)*            sum of compliances
//! term   := [number '*'] family [':' key=value (',' key=value)*]
//! ```
//!
//! The families and their keys are listed once, in [`FAMILIES`] (power, persson, hertz,
//! poly, rational, exp, const, and `table:FILE[,smoothing=TOL]` for measured data).
//!
//! [`ComplianceSpec::parse`] reads the text once: numbers as exact decimals (rationals),
//! tables read and validated. [`ComplianceSpec::build`] then gives the compliance at any
//! precision (f64, MPFR, Arb balls) without reading text again, and the tree answers
//! what is decided from exact numbers: which tables it uses, whether v' is constant, and
//! the degree of v' where it is a polynomial.

mod build;
mod parse;
mod vocabulary;

pub use vocabulary::{family_names, spec_help, spec_summary, Family, FAMILIES};

use std::fmt;
use std::sync::Arc;

use rug::Rational;

use super::table::{ComplianceTable, TableError, TableInterpolant};
use super::Compliance;
use crate::real::{Precision, Real};

/// Why a SPEC does not give a compliance: its text, or a table it names.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SpecError {
    /// The text is not a SPEC, or a number in it cannot be held at the precision asked.
    #[error("compliance spec '{spec}': {problem}")]
    Text {
        /// The whole SPEC.
        spec: String,
        /// What is wrong with it.
        problem: String,
    },
    /// A table the SPEC names cannot be read or is not a compliance.
    #[error(transparent)]
    Table(#[from] TableError),
}

/// A number of a SPEC: its key (for messages), its text as written, and its exact value.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Exact {
    key: &'static str,
    text: String,
    /// The number, exactly.
    pub(super) value: Rational,
}

/// One term of a SPEC: a family with exact parameters, a table, or a multiple of a term.
#[derive(Clone, Debug)]
pub(super) enum Term {
    Power {
        coefficient: Exact,
        exponent: Exact,
    },
    Persson {
        gamma: Exact,
        sigma: Exact,
    },
    Hertz {
        radius: Exact,
        contact_modulus: Exact,
    },
    Polynomial {
        reference: Exact,
        coefficients: Vec<Exact>,
    },
    Rational {
        constant: Exact,
        numerator: Exact,
        offset: Exact,
    },
    Exponential {
        amplitude: Exact,
        decay_load: Exact,
        constant: Exact,
    },
    Constant {
        slope: Exact,
    },
    Table(Arc<ComplianceTable>),
    Scaled {
        factor: Exact,
        inner: Box<Term>,
    },
}

/// A compliance SPEC read once: the sum of its terms, each a family with exact rational
/// parameters, a table with its data, or a multiple of one of them.
#[derive(Clone, Debug)]
pub struct ComplianceSpec {
    /// The text it was read from (for messages).
    text: String,
    /// The terms of the sum (at least one).
    terms: Vec<Term>,
}

impl ComplianceSpec {
    /// Reads a SPEC: its numbers as exact decimals, its tables read (once per process and
    /// file version) and validated.
    ///
    /// ```
    /// use microslip::compliance::ComplianceSpec;
    /// use microslip::real::Precision;
    ///
    /// let spec = ComplianceSpec::parse("persson:gamma=1,sigma=2 + 0.5*const:c=1").unwrap();
    /// let compliance = spec.build::<f64>(Precision::DOUBLE).unwrap();
    /// assert_eq!(compliance.slope(&4.0), 2.0 / 4.0 + 0.5);
    /// assert!(!spec.is_constant_slope());
    /// ```
    pub fn parse(text: &str) -> Result<ComplianceSpec, SpecError> {
        let terms = parse::terms(text)?;
        Ok(ComplianceSpec {
            text: text.to_string(),
            terms,
        })
    }

    /// The compliance at `precision`, its tables evaluated by their full cubic interpolant.
    /// Refused in f64 where a number lies outside the range of f64.
    pub fn build<R: Real>(&self, precision: Precision) -> Result<Box<dyn Compliance<R>>, SpecError> {
        self.build_with(precision, TableInterpolant::Cubic)
    }

    /// The compliance at `precision`, its tables (if any) evaluated by `interpolant` (the
    /// half tables give the table error).
    pub fn build_with<R: Real>(
        &self,
        precision: Precision,
        interpolant: TableInterpolant,
    ) -> Result<Box<dyn Compliance<R>>, SpecError> {
        build::compliance(&self.terms, precision, interpolant).map_err(|problem| SpecError::Text {
            spec: self.text.clone(),
            problem,
        })
    }

    /// The tables the SPEC's `table:` terms name, in order, as read when it was parsed.
    pub fn tables(&self) -> Vec<Arc<ComplianceTable>> {
        fn table(term: &Term) -> Option<&Arc<ComplianceTable>> {
            match term {
                Term::Table(table) => Some(table),
                Term::Scaled { inner, .. } => table(inner),
                _ => None,
            }
        }
        self.terms.iter().filter_map(table).cloned().collect()
    }

    /// The terms of the sum.
    pub(super) fn terms(&self) -> &[Term] {
        &self.terms
    }

    /// The SPEC as written.
    pub fn text(&self) -> &str {
        &self.text
    }
}

impl fmt::Display for ComplianceSpec {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        formatter.write_str(&self.text)
    }
}

/// Parses a SPEC at the given precision (`ComplianceSpec::parse(spec)?.build(precision)`).
pub fn parse_spec<R: Real>(spec: &str, precision: Precision) -> Result<Box<dyn Compliance<R>>, SpecError> {
    ComplianceSpec::parse(spec)?.build(precision)
}
