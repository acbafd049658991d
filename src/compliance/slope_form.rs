//! The shape of v' read from a SPEC's exact decimals, to decide by reason, not by
//! rounding, when W is exactly what it is: v'' ≡ 0 (every non-constant term cancels, so
//! W = 0 by the constant-term theorem), or v' a polynomial of degree d (so the
//! small-amplitude series ends at order d and its partial sums from W_d on are W).
//!
//! Each term contributes coefficients of the functions it is made of — P^β (power, Persson,
//! and the monomials of a polynomial expanded about 0), 1/(P + c) (rational), exp(−P/c)
//! (exp) — and constants, which do not matter. Two terms cancel where their coefficients of
//! the same function sum to zero, exactly, in rationals. Hertz is never constant, nor is
//! a table unless its slopes are all equal (proofs/exact-values.md).

use rug::ops::Pow;
use rug::{Integer, Rational};

use super::spec::{ComplianceSpec, Term};

/// A non-constant function of P that a SPEC term may contain.
#[derive(Clone, Debug, PartialEq)]
enum Shape {
    /// P^β, β ≠ 0.
    Power(Rational),
    /// 1/(P + c).
    Reciprocal(Rational),
    /// exp(−P/c).
    Decay(Rational),
}

/// v' as a sum of coefficients times shapes (constants dropped), or a term that has no
/// such form (Hertz, a table). Hertz terms are kept apart, each (R, E*) with its summed
/// factor: their v' carries a cube root, so they never make v' exactly constant, but their
/// signs decide concavity.
#[derive(Debug, Default)]
struct SlopeForm {
    terms: Vec<(Shape, Rational)>,
    hertz: Vec<((Rational, Rational), Rational)>,
    /// A table term whose slopes are not all equal.
    table: bool,
    opaque: bool,
}

impl SlopeForm {
    fn add(&mut self, shape: Shape, coefficient: Rational) {
        match self.terms.iter_mut().find(|(s, _)| *s == shape) {
            Some((_, sum)) => *sum += coefficient,
            None => self.terms.push((shape, coefficient)),
        }
    }

    /// The shapes whose coefficients do not cancel.
    fn remaining(&self) -> impl Iterator<Item = &Shape> {
        self.terms.iter().filter(|(_, c)| *c != 0).map(|(s, _)| s)
    }
}

impl SlopeForm {
    /// The form of a sum of terms.
    fn of(terms: &[Term]) -> SlopeForm {
        let mut form = SlopeForm::default();
        for term in terms {
            form.add_term(term, &Rational::from(1));
        }
        form
    }

    /// Adds `factor` times the term's v'.
    fn add_term(&mut self, term: &Term, factor: &Rational) {
        let mut add = |shape: Shape, coefficient: Rational| self.add(shape, coefficient * factor);
        match term {
            Term::Power { coefficient, exponent } => {
                if exponent.value != 0 {
                    add(Shape::Power(exponent.value.clone()), coefficient.value.clone());
                }
            }
            Term::Persson { gamma, sigma } => add(Shape::Power(Rational::from(-1)), gamma.value.clone() * &sigma.value),
            Term::Polynomial {
                reference,
                coefficients,
            } => {
                // Σ c_k (P − p0)^k = Σ_j P^j Σ_{k≥j} c_k C(k, j) (−p0)^(k−j).
                for j in 1..coefficients.len() {
                    let mut sum = Rational::from(0);
                    for (k, c) in coefficients.iter().enumerate().skip(j) {
                        let binomial = Integer::from(k).binomial(j as u32);
                        sum += c.value.clone() * binomial * (-reference.value.clone()).pow((k - j) as i32);
                    }
                    add(Shape::Power(Rational::from(j)), sum);
                }
            }
            Term::Rational { numerator, offset, .. } => {
                add(Shape::Reciprocal(offset.value.clone()), numerator.value.clone())
            }
            Term::Exponential {
                amplitude, decay_load, ..
            } => add(Shape::Decay(decay_load.value.clone()), amplitude.value.clone()),
            Term::Constant { .. } => {}
            // A table whose slopes are all equal is interpolated by that constant.
            Term::Table(table) if table.has_constant_slope() => {}
            Term::Hertz {
                radius,
                contact_modulus,
            } => {
                let key = (radius.value.clone(), contact_modulus.value.clone());
                match self.hertz.iter_mut().find(|(k, _)| *k == key) {
                    Some((_, sum)) => *sum += factor,
                    None => self.hertz.push((key, factor.clone())),
                }
                self.opaque = true;
            }
            Term::Table(_) => {
                self.table = true;
                self.opaque = true;
            }
            Term::Scaled { factor: scale, inner } => self.add_term(inner, &(scale.value.clone() * factor)),
        }
    }
}

impl ComplianceSpec {
    /// Whether v' is constant, exactly (v'' ≡ 0 at every load): every term is a constant
    /// or has a zero coefficient, or the non-constant terms cancel exactly.
    pub fn is_constant_slope(&self) -> bool {
        let form = SlopeForm::of(self.terms());
        !form.opaque && form.remaining().next().is_none()
    }

    /// Whether v'' ≤ 0 at every positive load follows from the exact form: after exact
    /// cancellation, every function that remains has a coefficient whose sign makes its own
    /// v'' ≤ 0 (c·β ≤ 0 for c·P^β; c ≥ 0 for c/(P + o) with o ≥ 0; c/o ≥ 0 for c·e^(−P/o);
    /// c ≥ 0 for c times a Hertz v' ∝ P^(−1/3)). False for a form with a table term, or with a
    /// term of the wrong sign.
    pub fn is_concave_by_form(&self) -> bool {
        let form = SlopeForm::of(self.terms());
        !form.table
            && form.hertz.iter().all(|(_, c)| *c >= 0)
            && form.terms.iter().all(|(shape, c)| match shape {
                Shape::Power(beta) => Rational::from(c * beta) <= 0,
                Shape::Reciprocal(offset) => *c >= 0 && *offset >= 0,
                Shape::Decay(decay_load) => Rational::from(c * decay_load) >= 0,
            })
    }

    /// The degree of v' where it is exactly a polynomial in P (0 for a constant), None otherwise.
    pub fn slope_polynomial_degree(&self) -> Option<usize> {
        let form = SlopeForm::of(self.terms());
        if form.opaque {
            return None;
        }
        let degree = form.remaining().try_fold(0usize, |degree, shape| match shape {
            Shape::Power(beta) if *beta.denom() == 1 && *beta > 0 => Some(degree.max(beta.numer().to_usize()?)),
            _ => None,
        });
        degree
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn constant_slope(text: &str) -> bool {
        ComplianceSpec::parse(text).is_ok_and(|spec| spec.is_constant_slope())
    }

    fn slope_polynomial_degree(text: &str) -> Option<usize> {
        ComplianceSpec::parse(text).ok()?.slope_polynomial_degree()
    }

    #[test]
    fn constant_slopes_are_recognised_exactly() {
        for spec in [
            "const:c=0.8",
            "2*const:c=1",
            "const:c=1+const:c=2",
            "poly:p0=1,coeffs=1;0;0",
            "rational:a=1,b=0,c=1",
            "exp:a=0,c=1,d=1",
            "power:c=1,beta=-1+power:c=-1,beta=-1+const:c=1",
            "power:c=5,beta=0",
            "0*persson:gamma=1,sigma=1",
            "power:c=0.3,beta=-1+power:c=-0.1,beta=-1+power:c=-0.2,beta=-1",
            "persson:gamma=2,sigma=0.5+power:c=-1,beta=-1",
            "poly:p0=2,coeffs=0;1+poly:p0=0,coeffs=3;-1",
            "poly:p0=1,coeffs=0;0;1+power:c=-1,beta=2+poly:p0=0,coeffs=0;2",
        ] {
            assert!(constant_slope(spec), "{spec}");
        }
        for spec in [
            "persson:gamma=1,sigma=1",
            "power:c=1,beta=-1+power:c=-1,beta=-1.0000000000000000000001",
            "power:c=0.3,beta=-1+power:c=-0.1,beta=-1+power:c=-0.2000000000000000001,beta=-1",
            "hertz:r=1,estar=1",
            "0*hertz:r=1,estar=1",
            "rational:a=1,b=1,c=1+rational:a=1,b=-1,c=2",
            "exp:a=1,c=1,d=0",
            "poly:p0=1,coeffs=1;1e-300",
            "table:missing.csv",
            "power:c=1,beta=x",
        ] {
            assert!(!constant_slope(spec), "{spec}");
        }
    }

    #[test]
    fn polynomial_degrees_are_read_exactly() {
        assert_eq!(slope_polynomial_degree("poly:p0=1,coeffs=2;-0.5"), Some(1));
        assert_eq!(slope_polynomial_degree("const:c=1"), Some(0));
        assert_eq!(slope_polynomial_degree("poly:p0=1,coeffs=1;2;3;0"), Some(2));
        assert_eq!(
            slope_polynomial_degree("power:c=1,beta=3+power:c=-1,beta=3+power:c=1,beta=1"),
            Some(1)
        );
        assert_eq!(slope_polynomial_degree("persson:gamma=1,sigma=1"), None);
        assert_eq!(slope_polynomial_degree("power:c=1,beta=0.5"), None);
    }
}
