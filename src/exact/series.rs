//! The coefficients Iₙ(ρ, φ) = W[v' = (P − P0)ⁿ]/(λ f² P1ⁿ⁺²) of the small-amplitude
//! series, exactly (no quadrature), at the working precision (proofs/series.md).
//!
//! For v' analytic at P0, W = λ f² Σ_{n≥1} v⁽ⁿ⁺¹⁾(P0)/n! · P1ⁿ⁺² Iₙ(Q1/(fP1), φ):
//! I₀ = 0 is the constant-term theorem and I₁ = I the cubic-law coefficient.

use crate::compliance::Compliance;
use crate::cycle::{CycleError, EllipseGeometry, LoadCycle};
use crate::real::Real;

use super::polynomial_w::monomials_with_scale;

/// Why the series could not be formed.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SeriesError {
    /// ρ ≤ 0 or not finite.
    #[error("the amplitude ratio ρ = Q1/(fP1) must be a positive finite number (got {rho:e})")]
    NonPositiveRatio {
        /// The ratio given.
        rho: f64,
    },
    /// The cycle is outside the theory.
    #[error(transparent)]
    Cycle(#[from] CycleError),
    /// The series needs P1 > 0 (ρ = Q1/(fP1)).
    #[error("the series in P1 needs a normal load amplitude P1 > 0")]
    NoNormalAmplitude,
    /// The compliance cannot give the derivative the order asked needs.
    #[error("the compliance {describe} gives no v^({order}) at P0, which the partial sums to this order need (a table's interpolant has v'' but not v''', which jumps at its knots: give --order 1)")]
    NoDerivatives {
        /// The compliance, described.
        describe: String,
        /// The order of the derivative of v.
        order: usize,
    },
    /// A derivative is not finite at P0.
    #[error("the derivative of order {order} of the compliance is not finite at P0")]
    NotFinite {
        /// The order of the derivative.
        order: usize,
    },
}

/// I₀ … I_`order` at (ρ, φ), each with a bound on the magnitudes of the terms it is
/// summed from (its rounding error is a few ulps of that; I₀ = 0 is resolved to it).
///
/// ```
/// use microslip::exact::{closed_form_coefficient, series_coefficients};
///
/// let (rho, phase) = (0.5, 1.0);
/// let coefficients = series_coefficients(&rho, &phase, 2)?;
/// // I₀ = 0 (a constant v' dissipates nothing), here to the rounding of the terms
/// // it is summed from; I₁ is the cubic law's I(ρ, φ).
/// let (constant_term, terms) = coefficients[0];
/// assert!(constant_term.abs() <= 8.0 * f64::EPSILON * terms);
/// let cubic = closed_form_coefficient(&rho, &phase);
/// assert!((coefficients[1].0 / cubic - 1.0).abs() < 1e-13);
/// # Ok::<(), microslip::exact::SeriesError>(())
/// ```
pub fn series_coefficients<R: Real>(rho: &R, phase: &R, order: usize) -> Result<Vec<(R, R)>, SeriesError> {
    let geometry = scaled_geometry(rho, phase)?;
    let (segments, scales) = monomials_with_scale(&geometry, order);
    Ok(segments.iter().map(|s| s.total()).zip(scales).collect())
}

/// The geometry of the scaled cycle P1 = f = λ = 1, Q1 = ρ, on which W[v' = (P − P0)ⁿ]
/// is Iₙ (P0 only has to keep the cycle inside the theory).
pub(super) fn scaled_geometry<R: Real>(rho: &R, phase: &R) -> Result<EllipseGeometry<R>, SeriesError> {
    let zero = rho.int(0);
    if !(rho.is_finite() && *rho > zero) {
        return Err(SeriesError::NonPositiveRatio {
            rho: rho.to_f64_lossy(),
        });
    }
    let one = rho.int(1);
    // P1 = f = λ = 1, Q1 = ρ; P0 only has to keep the cycle inside the theory.
    let cycle = LoadCycle {
        mean_normal_load: (rho.clone() + &one) * &rho.int(2) + &one,
        normal_amplitude: one.clone(),
        mean_tangential_load: zero.clone(),
        tangential_amplitude: rho.clone(),
        phase: phase.clone(),
        friction: one.clone(),
        compliance_ratio: one,
    };
    Ok(cycle.geometry()?)
}

/// The partial sums W_N = λ f² Σ_{n=1}^{N} v⁽ⁿ⁺¹⁾(P0)/n! · P1ⁿ⁺² Iₙ, N = 1 … `order`,
/// of the small-amplitude series of a cycle on a compliance (index N − 1).
///
/// ```
/// use microslip::compliance::Polynomial;
/// use microslip::cycle::LoadCycle;
/// use microslip::dissipation::{dissipation, Options};
/// use microslip::exact::partial_sums;
///
/// // v' quadratic in P − P0: the series ends at N = 2, so W_2 is W.
/// let cycle = LoadCycle {
///     mean_normal_load: 1.0,
///     normal_amplitude: 0.2,
///     mean_tangential_load: 0.0,
///     tangential_amplitude: 0.15,
///     phase: 1.0,
///     friction: 1.0,
///     compliance_ratio: 1.5,
/// };
/// let v = Polynomial { reference: 1.0, coefficients: vec![2.0, -1.0, -0.5] };
/// let sums = partial_sums(&cycle, &v, 2)?;
/// let w = dissipation(&cycle, &v, &Options::default())?;
/// assert!((sums[1] - w.total).abs() <= w.error_estimate + 1e-16 * w.total.abs());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn partial_sums<R: Real>(
    cycle: &LoadCycle<R>,
    compliance: &dyn Compliance<R>,
    order: usize,
) -> Result<Vec<R>, SeriesError> {
    cycle.validate()?;
    let zero = cycle.mean_normal_load.int(0);
    if cycle.normal_amplitude == zero {
        return Err(SeriesError::NoNormalAmplitude);
    }
    let p1 = &cycle.normal_amplitude;
    let rho = cycle.tangential_amplitude.clone() / &(cycle.friction.clone() * p1);
    if rho == zero {
        return Ok(vec![zero; order]);
    }
    let coefficients: Vec<R> = series_coefficients(&rho, &cycle.phase, order)?
        .into_iter()
        .map(|(value, _)| value)
        .collect();
    sums_at_amplitude(&coefficients, cycle, compliance, p1)
}

/// W_1 … W_N from I₀ … I_N for the cycle's P0, f, λ and compliance at normal amplitude
/// `amplitude` (the shape ρ, φ the coefficients belong to kept).
pub(super) fn sums_at_amplitude<R: Real>(
    coefficients: &[R],
    cycle: &LoadCycle<R>,
    compliance: &dyn Compliance<R>,
    amplitude: &R,
) -> Result<Vec<R>, SeriesError> {
    let zero = cycle.mean_normal_load.int(0);
    let prefactor = cycle.compliance_ratio.clone() * &cycle.friction.square() * &amplitude.square();
    let mut sums = Vec::with_capacity(coefficients.len());
    let (mut total, mut power, mut factorial) = (zero.clone(), amplitude.clone(), zero.int(1));
    for (n, value) in coefficients.iter().enumerate().skip(1) {
        factorial *= &zero.int(n as i64);
        let derivative =
            compliance
                .derivative(n + 1, &cycle.mean_normal_load)
                .ok_or_else(|| SeriesError::NoDerivatives {
                    describe: compliance.describe(),
                    order: n + 1,
                })?;
        if !derivative.is_finite() {
            return Err(SeriesError::NotFinite { order: n + 1 });
        }
        total += derivative / &factorial * &power * value * &prefactor;
        power *= amplitude;
        sums.push(total.clone());
    }
    Ok(sums)
}
