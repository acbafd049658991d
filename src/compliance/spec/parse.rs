//! SPEC text to its tree: terms split at '+', a term's multiplier, family and key=value
//! parameters read as exact decimals, tables read once.

use super::vocabulary::{family_names, Family, FAMILIES, TABLE};
use super::{Exact, SpecError, Term};
use crate::compliance::table::{cached_table, parse_table_term, TableError};
use crate::messages::{did_you_mean, printable};
use crate::phase::decimal;

/// The terms of a SPEC, or why it is not one.
pub(super) fn terms(spec: &str) -> Result<Vec<Term>, SpecError> {
    split_terms(spec)
        .into_iter()
        .map(|text| {
            term(text).map_err(|problem| match problem {
                TermError::Problem(problem) => SpecError::Text {
                    spec: printable(spec).into_owned(),
                    problem,
                },
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
    let value = decimal(text).ok_or_else(|| format!("{key}='{}' is not a decimal number", printable(text)))?;
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
                .ok_or_else(|| format!("'{}' in {family} is not key=value", printable(item)))?;
            let key = key.trim();
            if pairs.iter().any(|(k, _)| *k == key) {
                return Err(format!("{family} gives '{}' twice", printable(key)));
            }
            pairs.push((key, value.trim()));
        }
        Ok(Parameters { family, pairs })
    }

    /// The values of exactly the family's keys, in their order: a key the family does not
    /// take, or one it needs and is not given, is an error naming what the family takes.
    fn take<const N: usize>(&self, family: &Family) -> Result<[Parameter<'a>; N], String> {
        let keys = family.keys;
        if let Some((unknown, _)) = self.pairs.iter().find(|(k, _)| !keys.contains(k)) {
            return Err(format!(
                "{} has no parameter '{}'{} (it takes {})",
                self.family,
                printable(unknown),
                did_you_mean(unknown, keys),
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
        let parameters: Vec<Parameter<'a>> = keys
            .iter()
            .map(|&key| Parameter {
                family: self.family,
                key,
                text: self.pairs.iter().find(|(k, _)| *k == key).map_or("", |(_, text)| text),
            })
            .collect();
        parameters
            .try_into()
            .map_err(|_| format!("{} takes {} parameters, not {N}", self.family, keys.len()))
    }
}

/// One parameter of a family: its key (for messages) and its text.
struct Parameter<'a> {
    family: &'a str,
    key: &'static str,
    text: &'a str,
}

impl Parameter<'_> {
    fn value(&self) -> Result<Exact, String> {
        number(self.key, self.text)
    }

    /// A list written with ';' between its numbers.
    fn list(&self) -> Result<Vec<Exact>, String> {
        self.text.split(';').map(|c| number(self.key, c.trim())).collect()
    }

    fn positive(&self) -> Result<Exact, String> {
        let value = self.value()?;
        if value.value <= 0 {
            return Err(format!(
                "{} needs {} > 0, got {}",
                self.family,
                self.key,
                printable(self.text)
            ));
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

fn family_term(name: &str, parameters: &str) -> Result<Term, TermError> {
    if name.is_empty() {
        return Err(TermError::Problem("a term names no family".to_string()));
    }
    let Some(family) = FAMILIES.iter().find(|family| family.name == name) else {
        return Err(TermError::Problem(format!(
            "unknown family '{}'{} (known: {})",
            printable(name),
            did_you_mean(name, &family_names()),
            family_names().join(", ")
        )));
    };
    if family.name == TABLE {
        let (path, smoothing) = parse_table_term(parameters)?;
        return cached_table(&path, smoothing)
            .map(Term::Table)
            .map_err(TermError::Table);
    }
    let params = Parameters::parse(family.name, parameters)?;
    let term = match family.name {
        "power" => {
            let [coefficient, exponent] = params.take(family)?;
            Term::Power {
                coefficient: coefficient.value()?,
                exponent: exponent.value()?,
            }
        }
        "persson" => {
            let [gamma, sigma] = params.take(family)?;
            Term::Persson {
                gamma: gamma.positive()?,
                sigma: sigma.positive()?,
            }
        }
        "hertz" => {
            let [radius, contact_modulus] = params.take(family)?;
            Term::Hertz {
                radius: radius.positive()?,
                contact_modulus: contact_modulus.positive()?,
            }
        }
        "poly" => {
            let [reference, coefficients] = params.take(family)?;
            Term::Polynomial {
                reference: reference.value()?,
                coefficients: coefficients.list()?,
            }
        }
        "rational" => {
            let [constant, numerator, offset] = params.take(family)?;
            Term::Rational {
                constant: constant.value()?,
                numerator: numerator.value()?,
                offset: offset.value()?,
            }
        }
        "exp" => {
            let [amplitude, decay_load, constant] = params.take(family)?;
            Term::Exponential {
                amplitude: amplitude.value()?,
                decay_load: decay_load.positive()?,
                constant: constant.value()?,
            }
        }
        "const" => {
            let [slope] = params.take(family)?;
            Term::Constant { slope: slope.value()? }
        }
        other => return Err(TermError::Problem(format!("the family '{other}' has no reader"))),
    };
    Ok(term)
}
