//! Quadrature rules, generic over [`Real`](crate::real::Real).
//!
//! One rule per file. Every rule returns an [`Estimate`]: the value together with
//! an error estimate and the number of integrand evaluations it cost. `sinh_map` is
//! the change of variable that lets the rules resolve a narrow peak.

pub mod gauss_legendre;
pub mod sinh_map;
pub mod tanh_sinh;

use crate::real::Real;

/// An integral's value with an estimate of its absolute error.
#[derive(Clone, Debug)]
pub struct Estimate<R> {
    /// The best value found.
    pub value: R,
    /// An estimate of |value − exact|: the difference between the last two
    /// refinements, which bounds the error of the better one when the rule converges.
    pub error: R,
    /// Integrand evaluations spent, over all refinements.
    pub evaluations: usize,
    /// Whether the requested tolerance was met.
    pub converged: bool,
}

impl<R: Real> Estimate<R> {
    /// The error estimate relative to |value| (infinite when the value is 0 and the error is not).
    pub fn relative_error(&self) -> f64 {
        let value = self.value.abs().to_f64_lossy();
        let error = self.error.to_f64_lossy();
        if error == 0.0 {
            0.0
        } else if value == 0.0 {
            f64::INFINITY
        } else {
            error / value
        }
    }
}
