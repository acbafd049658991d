//! The compliance SPEC language of the command line.
//!
//! ```text
//! spec   := term ('+' term)*            sum of compliances
//! term   := [number '*'] family [':' key=value (',' key=value)*]
//! family := power:c,beta      v' = c·P^beta
//!         | persson:gamma,sigma  v' = gamma·sigma/P
//!         | hertz:r,estar     v = (9P²/(16 r estar²))^(1/3)
//!         | poly:p0,coeffs    v' = Σ coeffs[k]·(P − p0)^k, coeffs separated by ';'
//!         | rational:a,b,c    v' = a + b/(P + c)
//!         | exp:a,c,d         v' = a·exp(−P/c) + d
//!         | const:c           v' = c
//!         | table:FILE[,smoothing=TOL]  v' from a CSV table (see table.rs)
//! ```
//! Numbers are read as exact decimals at the working precision.

use std::sync::Arc;

use super::table::{cached_table, parse_table_term, ComplianceTable, TableCompliance, TableError, TableInterpolant};
use super::{Compliance, Exponential, Hertz, Persson, Polynomial, PowerLaw, Rational, Scaled, Sum};
use crate::real::{Precision, Real};

/// A SPEC string that does not describe a compliance.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("compliance spec '{spec}': {problem}")]
pub struct SpecError {
    /// The whole SPEC.
    pub spec: String,
    /// What is wrong with it.
    pub problem: String,
}

/// Parses a SPEC at the given precision.
pub fn parse_spec<R: Real>(spec: &str, precision: Precision) -> Result<Box<dyn Compliance<R>>, SpecError> {
    parse_spec_with(spec, precision, TableInterpolant::Cubic)
}

/// Parses a SPEC at the given precision, its tables (if any) evaluated by `interpolant`.
pub fn parse_spec_with<R: Real>(
    spec: &str,
    precision: Precision,
    interpolant: TableInterpolant,
) -> Result<Box<dyn Compliance<R>>, SpecError> {
    let error = |problem: String| SpecError {
        spec: spec.to_string(),
        problem,
    };
    let mut terms = split_terms(spec)
        .into_iter()
        .map(|term| parse_term::<R>(term, precision, interpolant).map_err(error))
        .collect::<Result<Vec<_>, _>>()?;
    if terms.len() == 1 {
        Ok(terms.remove(0))
    } else {
        Ok(Box::new(Sum { terms }))
    }
}

/// The tables a SPEC's `table:` terms name, read (once per process) and validated.
pub fn tables_in_spec(spec: &str) -> Result<Vec<Arc<ComplianceTable>>, TableError> {
    let mut tables = Vec::new();
    for term in split_terms(spec) {
        let body = term.split_once('*').map_or(term, |(_, body)| body).trim();
        if let Some(("table", text)) = body.split_once(':').map(|(f, t)| (f.trim(), t)) {
            if let Ok((path, smoothing)) = parse_table_term(text) {
                tables.push(cached_table(&path, smoothing)?);
            }
        }
    }
    Ok(tables)
}

/// Splits at each '+' that joins two terms, not at the sign of an exponent (1e+3).
pub(super) fn split_terms(spec: &str) -> Vec<&str> {
    let bytes = spec.as_bytes();
    let mut terms = Vec::new();
    let mut start = 0;
    for (i, &byte) in bytes.iter().enumerate() {
        if byte != b'+' {
            continue;
        }
        let after_exponent_marker = i > 0 && matches!(bytes[i - 1], b'e' | b'E');
        let before_name = bytes.get(i + 1).is_some_and(|b| b.is_ascii_alphabetic());
        if !after_exponent_marker || before_name {
            terms.push(&spec[start..i]);
            start = i + 1;
        }
    }
    terms.push(&spec[start..]);
    terms
}

fn number<R: Real>(key: &str, text: &str, precision: Precision) -> Result<R, String> {
    let value = R::parse_decimal(text, precision).map_err(|_| format!("{key}='{text}' is not a decimal number"))?;
    if crate::inputs::outside_f64_range(&value, text) {
        return Err(format!(
            "{key}={text} lies outside the range of f64 (normal magnitudes 2.2e-308 to 1.8e308)"
        ));
    }
    if !value.is_finite() {
        return Err(format!("{key}={text} is not finite"));
    }
    Ok(value)
}

/// The key=value pairs of one family, each key used once and all of them expected.
pub(super) struct Parameters<'a> {
    family: &'a str,
    pairs: Vec<(&'a str, &'a str)>,
}

impl<'a> Parameters<'a> {
    pub(super) fn parse(family: &'a str, text: &'a str) -> Result<Self, String> {
        let mut pairs: Vec<(&str, &str)> = Vec::new();
        for item in text.split(',').map(str::trim).filter(|s| !s.is_empty()) {
            let (key, value) = item
                .split_once('=')
                .ok_or_else(|| format!("'{item}' in {family} is not key=value"))?;
            let key = key.trim();
            if pairs.iter().any(|(k, _)| *k == key) {
                return Err(format!("{family} gives '{key}' twice"));
            }
            pairs.push((key, value.trim()));
        }
        Ok(Parameters { family, pairs })
    }

    fn expect(&self, keys: &[&str]) -> Result<(), String> {
        if let Some((unknown, _)) = self.pairs.iter().find(|(k, _)| !keys.contains(k)) {
            return Err(format!(
                "{} has no parameter '{unknown}' (it takes {})",
                self.family,
                keys.join(", ")
            ));
        }
        if let Some(missing) = keys.iter().find(|k| !self.pairs.iter().any(|(key, _)| key == *k)) {
            return Err(format!(
                "{} needs {missing}= (it takes {})",
                self.family,
                keys.join(", ")
            ));
        }
        Ok(())
    }

    pub(super) fn text(&self, key: &str) -> &'a str {
        self.pairs
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, v)| *v)
            .unwrap_or("")
    }

    fn value<R: Real>(&self, key: &str, precision: Precision) -> Result<R, String> {
        number(key, self.text(key), precision)
    }

    fn positive<R: Real>(&self, key: &str, precision: Precision) -> Result<R, String> {
        let value: R = self.value(key, precision)?;
        if value <= R::from_i64(0, precision) {
            return Err(format!("{} needs {key} > 0, got {}", self.family, self.text(key)));
        }
        Ok(value)
    }
}

fn parse_term<R: Real>(
    term: &str,
    precision: Precision,
    interpolant: TableInterpolant,
) -> Result<Box<dyn Compliance<R>>, String> {
    let term = term.trim();
    if term.is_empty() {
        return Err("empty term (a '+' with nothing beside it?)".to_string());
    }
    let (factor, body) = match term.split_once('*') {
        Some((factor, body)) => (Some(number::<R>("multiplier", factor.trim(), precision)?), body.trim()),
        None => (None, term),
    };
    let (family, parameters) = body.split_once(':').unwrap_or((body, ""));
    let family = family.trim();
    if family == "table" {
        let (path, smoothing) = parse_table_term(parameters)?;
        let table = cached_table(&path, smoothing).map_err(|e| e.to_string())?;
        let compliance: Box<dyn Compliance<R>> = Box::new(TableCompliance { table, interpolant });
        return Ok(match factor {
            Some(factor) => Box::new(Scaled {
                factor,
                inner: compliance,
            }),
            None => compliance,
        });
    }
    let params = Parameters::parse(family, parameters)?;
    let compliance: Box<dyn Compliance<R>> = match family {
        "power" => {
            params.expect(&["c", "beta"])?;
            Box::new(PowerLaw {
                coefficient: params.value("c", precision)?,
                exponent: params.value("beta", precision)?,
            })
        }
        "persson" => {
            params.expect(&["gamma", "sigma"])?;
            Box::new(Persson {
                gamma: params.positive("gamma", precision)?,
                sigma: params.positive("sigma", precision)?,
            })
        }
        "hertz" => {
            params.expect(&["r", "estar"])?;
            Box::new(Hertz {
                radius: params.positive("r", precision)?,
                contact_modulus: params.positive("estar", precision)?,
            })
        }
        "poly" => {
            params.expect(&["p0", "coeffs"])?;
            let coefficients = params
                .text("coeffs")
                .split(';')
                .map(|c| number::<R>("coeffs", c.trim(), precision))
                .collect::<Result<Vec<_>, _>>()?;
            Box::new(Polynomial {
                reference: params.value("p0", precision)?,
                coefficients,
            })
        }
        "rational" => {
            params.expect(&["a", "b", "c"])?;
            Box::new(Rational {
                constant: params.value("a", precision)?,
                numerator: params.value("b", precision)?,
                offset: params.value("c", precision)?,
            })
        }
        "exp" => {
            params.expect(&["a", "c", "d"])?;
            Box::new(Exponential {
                amplitude: params.value("a", precision)?,
                decay_load: params.positive("c", precision)?,
                constant: params.value("d", precision)?,
            })
        }
        "const" => {
            params.expect(&["c"])?;
            Box::new(Polynomial {
                reference: R::from_i64(0, precision),
                coefficients: vec![params.value("c", precision)?],
            })
        }
        "" => return Err("a term names no family".to_string()),
        other => {
            return Err(format!(
                "unknown family '{other}' (known: power, persson, hertz, poly, rational, exp, const, table)"
            ))
        }
    };
    Ok(match factor {
        Some(factor) => Box::new(Scaled {
            factor,
            inner: compliance,
        }),
        None => compliance,
    })
}
