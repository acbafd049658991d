//! The small-amplitude coefficient I(ρ, φ) of the cubic law
//! W ≈ λ f² P1³ v''(P0) · I(Q1/(fP1), φ) (paper Section 5.1, errata item 3).
//!
//! W is linear in v', and for v' = P − P0 (v'' = 1, v''' = 0) every load scales
//! with P1, so W = λ f² P1³ I exactly at any amplitude: I is that W divided by
//! λ f² P1³. That v' is not a physical compliance (it is negative below P0), so
//! the admissibility check is off here.
//!
//! The functions here compute I by the four-segment quadrature (the gate checks the
//! closed form against them); what `microslip small-amplitude` prints is the closed form
//! of [`crate::exact::coefficient`], enclosed ([`crate::answer::series::coefficient_answer`]).

use crate::compliance::Polynomial;
use crate::cycle::LoadCycle;
use crate::dissipation::{dissipation, Dissipation, DissipationError, Options};
use crate::real::Real;

/// W[v' = P − P0] on the cycle P0 = 1, P1 = `amplitude`, Q1 = ρP1, f = λ = 1, so that
/// I = W / P1³. `amplitude` must keep the cycle inside the theory: P1 (1 + ρ) < 1 does.
fn linear_dissipation<R: Real>(
    rho: &R,
    phase: &R,
    amplitude: &R,
    options: Options<R>,
) -> Result<Dissipation<R>, DissipationError> {
    let one = rho.int(1);
    let cycle = LoadCycle {
        mean_normal_load: one.clone(),
        normal_amplitude: amplitude.clone(),
        mean_tangential_load: one.int(0),
        tangential_amplitude: rho.clone() * amplitude,
        phase: phase.clone(),
        friction: one.clone(),
        compliance_ratio: one.clone(),
    };
    let linear = Polynomial {
        reference: one.clone(),
        coefficients: vec![one.int(0), one.clone()],
    };
    let options = Options {
        check_compliance: false,
        ..options
    };
    dissipation(&cycle, &linear, &options)
}

/// I(ρ, φ) from the cycle P0 = 1, P1 = `amplitude`, Q1 = ρP1, f = λ = 1.
/// `amplitude` must keep the cycle inside the theory: P1 (1 + ρ) < 1 does.
pub fn coefficient_at<R: Real>(rho: &R, phase: &R, amplitude: &R) -> Result<R, DissipationError> {
    let w = linear_dissipation(rho, phase, amplitude, Options::default())?.total;
    Ok(w / (amplitude.clone() * amplitude * amplitude))
}

/// The amplitude every coefficient is computed at: P1 = 1/(2(1 + ρ)), half-way to gross slip.
fn standard_amplitude<R: Real>(rho: &R) -> R {
    rho.int(1) / ((rho.clone() + &rho.int(1)) * &rho.int(2))
}

/// I(ρ, φ) (≤ 0), computed at the amplitude P1 = 1/(2(1 + ρ)).
pub fn coefficient<R: Real>(rho: &R, phase: &R) -> Result<R, DissipationError> {
    coefficient_at(rho, phase, &standard_amplitude(rho))
}

/// I(ρ, φ) with an estimate of its absolute error (quadrature and rounding), and the
/// options to compute it with.
pub fn coefficient_with_error<R: Real>(rho: &R, phase: &R, options: Options<R>) -> Result<(R, R), DissipationError> {
    let amplitude = standard_amplitude(rho);
    let cube = amplitude.clone() * &amplitude * &amplitude;
    let result = linear_dissipation(rho, phase, &amplitude, options)?;
    Ok((result.total / &cube, result.error_estimate / &cube))
}
