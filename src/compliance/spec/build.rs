//! A SPEC's tree to its compliance at a precision: each exact parameter rounded once.

use super::{Exact, Term};
use crate::compliance::table::{TableCompliance, TableInterpolant};
use crate::compliance::{Compliance, Exponential, Hertz, Persson, Polynomial, PowerLaw, Rational, Scaled, Sum};
use crate::decimal::rounded;
use crate::real::{Precision, Real};

/// The sum of the terms (the term itself where there is one), or what f64 cannot hold.
pub(super) fn compliance<R: Real>(
    terms: &[Term],
    precision: Precision,
    interpolant: TableInterpolant,
) -> Result<Box<dyn Compliance<R>>, String> {
    let mut built = terms
        .iter()
        .map(|term| term_compliance(term, precision, interpolant))
        .collect::<Result<Vec<_>, _>>()?;
    if built.len() == 1 {
        Ok(built.remove(0))
    } else {
        Ok(Box::new(Sum { terms: built }))
    }
}

/// A parameter at the precision.
fn value<R: Real>(exact: &Exact, precision: Precision) -> Result<R, String> {
    rounded(&exact.value, precision).ok_or_else(|| {
        format!(
            "{}={} lies outside the range of f64 (normal magnitudes 2.2e-308 to 1.8e308)",
            exact.key, exact.text
        )
    })
}

fn term_compliance<R: Real>(
    term: &Term,
    precision: Precision,
    interpolant: TableInterpolant,
) -> Result<Box<dyn Compliance<R>>, String> {
    let at = |exact: &Exact| value::<R>(exact, precision);
    Ok(match term {
        Term::Power { coefficient, exponent } => Box::new(PowerLaw {
            coefficient: at(coefficient)?,
            exponent: at(exponent)?,
        }),
        Term::Persson { gamma, sigma } => Box::new(Persson {
            gamma: at(gamma)?,
            sigma: at(sigma)?,
        }),
        Term::Hertz {
            radius,
            contact_modulus,
        } => Box::new(Hertz {
            radius: at(radius)?,
            contact_modulus: at(contact_modulus)?,
        }),
        Term::Polynomial {
            reference,
            coefficients,
        } => Box::new(Polynomial {
            coefficients: coefficients.iter().map(at).collect::<Result<Vec<_>, _>>()?,
            reference: at(reference)?,
        }),
        Term::Rational {
            constant,
            numerator,
            offset,
        } => Box::new(Rational {
            constant: at(constant)?,
            numerator: at(numerator)?,
            offset: at(offset)?,
        }),
        Term::Exponential {
            amplitude,
            decay_load,
            constant,
        } => Box::new(Exponential {
            amplitude: at(amplitude)?,
            decay_load: at(decay_load)?,
            constant: at(constant)?,
        }),
        Term::Constant { slope } => Box::new(Polynomial {
            reference: R::from_i64(0, precision),
            coefficients: vec![at(slope)?],
        }),
        Term::Table(table) => Box::new(TableCompliance {
            table: table.clone(),
            interpolant,
        }),
        Term::Scaled { factor, inner } => Box::new(Scaled {
            factor: at(factor)?,
            inner: term_compliance(inner, precision, interpolant)?,
        }),
    })
}
