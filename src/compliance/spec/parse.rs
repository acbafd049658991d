//! SPEC text to its tree: terms split at '+', a term's multiplier, family and key=value
//! parameters read as exact decimals, tables read once.

use super::{Exact, SpecError, SpecReadError, Term};
use crate::compliance::table::{cached_table, parse_table_term, TableError};
use crate::phase::decimal;

/// The terms of a SPEC, or why it is not one.
pub(super) fn terms(spec: &str) -> Result<Vec<Term>, SpecReadError> {
    split_terms(spec)
        .into_iter()
        .map(|text| {
            term(text).map_err(|problem| match problem {
                TermError::Problem(problem) => SpecError {
                    spec: spec.to_string(),
                    problem,
                }
                .into(),
                TermError::Table(error) => error.into(),
            })
        })
        .collect()
}

/// Splits at each '+' that joins two terms, not at the sign of an exponent (1e+3).
fn split_terms(spec: &str) -> Vec<&str> {
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

/// Why one term is not a term.
enum TermError {
    Problem(String),
    Table(TableError),
}

impl From<String> for TermError {
    fn from(problem: String) -> Self {
        TermError::Problem(problem)
    }
}

/// A decimal of the SPEC, exactly.
fn number(key: &'static str, text: &str) -> Result<Exact, String> {
    let value = decimal(text).ok_or_else(|| format!("{key}='{text}' is not a decimal number"))?;
    Ok(Exact {
        key,
        text: text.to_string(),
        value,
    })
}

/// The key=value pairs of one family, each key used once and all of them expected.
struct Parameters<'a> {
    family: &'a str,
    pairs: Vec<(&'a str, &'a str)>,
}

impl<'a> Parameters<'a> {
    fn parse(family: &'a str, text: &'a str) -> Result<Self, String> {
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

    fn text(&self, key: &str) -> &'a str {
        self.pairs
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, v)| *v)
            .unwrap_or("")
    }

    fn value(&self, key: &'static str) -> Result<Exact, String> {
        number(key, self.text(key))
    }

    fn positive(&self, key: &'static str) -> Result<Exact, String> {
        let value = self.value(key)?;
        if value.value <= 0 {
            return Err(format!("{} needs {key} > 0, got {}", self.family, self.text(key)));
        }
        Ok(value)
    }
}

fn term(text: &str) -> Result<Term, TermError> {
    let text = text.trim();
    if text.is_empty() {
        return Err(TermError::Problem(
            "empty term (a '+' with nothing beside it?)".to_string(),
        ));
    }
    let (factor, body) = match text.split_once('*') {
        Some((factor, body)) => (Some(number("multiplier", factor.trim())?), body.trim()),
        None => (None, text),
    };
    let (family, parameters) = body.split_once(':').unwrap_or((body, ""));
    let term = family_term(family.trim(), parameters)?;
    Ok(match factor {
        Some(factor) => Term::Scaled {
            factor,
            inner: Box::new(term),
        },
        None => term,
    })
}

fn family_term(family: &str, parameters: &str) -> Result<Term, TermError> {
    if family == "table" {
        let (path, smoothing) = parse_table_term(parameters)?;
        return cached_table(&path, smoothing)
            .map(Term::Table)
            .map_err(TermError::Table);
    }
    let params = Parameters::parse(family, parameters)?;
    let term = match family {
        "power" => {
            params.expect(&["c", "beta"])?;
            Term::Power {
                coefficient: params.value("c")?,
                exponent: params.value("beta")?,
            }
        }
        "persson" => {
            params.expect(&["gamma", "sigma"])?;
            Term::Persson {
                gamma: params.positive("gamma")?,
                sigma: params.positive("sigma")?,
            }
        }
        "hertz" => {
            params.expect(&["r", "estar"])?;
            Term::Hertz {
                radius: params.positive("r")?,
                contact_modulus: params.positive("estar")?,
            }
        }
        "poly" => {
            params.expect(&["p0", "coeffs"])?;
            let coefficients = params
                .text("coeffs")
                .split(';')
                .map(|c| number("coeffs", c.trim()))
                .collect::<Result<Vec<_>, _>>()?;
            Term::Polynomial {
                reference: params.value("p0")?,
                coefficients,
            }
        }
        "rational" => {
            params.expect(&["a", "b", "c"])?;
            Term::Rational {
                constant: params.value("a")?,
                numerator: params.value("b")?,
                offset: params.value("c")?,
            }
        }
        "exp" => {
            params.expect(&["a", "c", "d"])?;
            Term::Exponential {
                amplitude: params.value("a")?,
                decay_load: params.positive("c")?,
                constant: params.value("d")?,
            }
        }
        "const" => {
            params.expect(&["c"])?;
            Term::Constant {
                slope: params.value("c")?,
            }
        }
        "" => return Err(TermError::Problem("a term names no family".to_string())),
        other => {
            return Err(TermError::Problem(format!(
                "unknown family '{other}' (known: power, persson, hertz, poly, rational, exp, const, table)"
            )))
        }
    };
    Ok(term)
}
