//! Quadrature, generic over [`Real`](crate::real::Real).
//!
//! [`engine`] is the one way to integrate a list of pieces to a tolerance: Gauss–Legendre
//! rules of doubling degree ([`gauss_legendre`]), with tanh–sinh ([`tanh_sinh`]) where
//! they stall; both rules' nodes and weights are computed once and cached at the highest precision
//! asked for, lower precisions being rounded from them.
//! `sinh_map` is the change of variable that lets the rules resolve a narrow peak, and
//! `bottom_map` the one that resolves the lowest load of a cycle near separation.

pub mod bottom_map;
pub(crate) mod cache;
pub mod engine;
pub mod gauss_legendre;
pub mod sinh_map;
pub mod tanh_sinh;

pub use engine::{integrate, FixedRule, Integrated, Piece, PieceEstimate, QuadError, Rule, RuleError, Settings, Stop};

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
