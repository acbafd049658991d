//! Exact (quadrature-free) dissipation for polynomial compliances, the closed-form
//! small-amplitude coefficient I(ρ, φ), and the coefficients Iₙ(ρ, φ) of the
//! small-amplitude series W = λ f² Σₙ v⁽ⁿ⁺¹⁾(P0)/n! · P1ⁿ⁺² Iₙ (proofs/series.md,
//! proofs/small-amplitude-coefficient.md).

pub mod coefficient;
pub mod kernel;
pub mod polynomial_w;
pub mod remainder;
pub mod series;
pub mod trig;

pub use coefficient::closed_form_coefficient;
pub use kernel::{cubic_kernel_majorant, AtOrigin, KernelNorms, PeanoKernels};
pub use polynomial_w::{coefficients_about, monomial_dissipations, polynomial_dissipation};
pub use remainder::{remainder_bounds, remainders, Remainder, RemainderError, SeriesShape};
pub use series::{partial_sums, series_coefficients, SeriesError};
pub use trig::TrigPolynomial;
