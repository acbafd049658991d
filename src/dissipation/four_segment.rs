//! W by the four segment integrals in the cycle angle, for any valid cycle.

use super::assemble::{assemble, Dissipation, Method, Parts};
use super::conditioning::{check_case, check_conditioning};
use super::error::DissipationError;
use super::options::Options;
use super::segments::SegmentIntegrands;
use crate::compliance::Compliance;
use crate::cycle::{LoadCycle, ValidCycle};
use crate::quad::integrate;
use crate::real::Real;

/// W by the four-segment integrals whatever the cycle (also for P1 = 0 and for
/// phases close to 0 or π, where it converges to the closed forms).
///
/// ```
/// use microslip::compliance::Polynomial;
/// use microslip::cycle::LoadCycle;
/// use microslip::dissipation::{four_segment, Options};
/// use microslip::exact::closed_form_coefficient;
///
/// // For a linear v' = 1 − (P − P0) the cubic law is exact: W = λ f² P1³ v'' I(ρ, φ),
/// // ρ = Q1/(f P1), with I in closed form.
/// let (p1, q1, phase) = (0.1, 0.05, 0.4 * std::f64::consts::PI);
/// let cycle = LoadCycle {
///     mean_normal_load: 1.0,
///     normal_amplitude: p1,
///     mean_tangential_load: 0.0,
///     tangential_amplitude: q1,
///     phase,
///     friction: 1.0,
///     compliance_ratio: 1.0,
/// };
/// let linear = Polynomial { reference: 1.0, coefficients: vec![1.0, -1.0] };
/// let w = four_segment(&cycle, &linear, &Options::default())?.total;
/// let cubic_law = -p1.powi(3) * closed_form_coefficient(&(q1 / p1), &phase);
/// assert!((w / cubic_law - 1.0).abs() < 1e-12);
/// # Ok::<(), microslip::dissipation::DissipationError>(())
/// ```
pub fn four_segment<R: Real>(
    cycle: &LoadCycle<R>,
    compliance: &dyn Compliance<R>,
    options: &Options<R>,
) -> Result<Dissipation<R>, DissipationError> {
    four_segment_integrals(&ValidCycle::new(cycle.clone())?, compliance, options)
}

/// W = λ Σ ∫ (Q − Q0) ψ ds over the segments (see [`SegmentIntegrands`]).
pub(crate) fn four_segment_integrals<R: Real>(
    cycle: &ValidCycle<R>,
    compliance: &dyn Compliance<R>,
    options: &Options<R>,
) -> Result<Dissipation<R>, DissipationError> {
    check_case(cycle, compliance, options)?;
    let geometry = cycle.geometry();
    // The slip terms' cancellation only: near in phase f64 is not refused but its error
    // estimate covers the cancellation of BC and CH (`assemble`), and a verified run starts
    // at the precision it needs.
    let cancellation = cycle.cancellation_amplification() / &cycle.in_phase_cancellation();
    check_conditioning(&cancellation, options, || {
        format!(
            "Q1/(fP1) = {:.3e}, and the slip terms of the segment integrands cancel to a difference that much smaller",
            (cycle.tangential_amplitude.clone() / &cycle.normal_amplitude / &cycle.friction).to_f64_lossy()
        )
    })?;
    let integrands = SegmentIntegrands {
        geometry: &geometry,
        compliance,
        remove_constant_slope: options.remove_constant_slope,
    };
    let zero = geometry.phase.int(0);
    let pieces = integrands.pieces();
    let mut settings = options.settings(&zero);
    // The engine holds each piece to the tolerance times the sum of |pieces|; near in phase
    // that sum exceeds W by the predicted cancellation, so the tolerance is divided by it
    // (not below the default of 256 ulps, where rounding, not the rule, decides).
    let floor = zero.epsilon_like() * &zero.int(256);
    settings.relative_tolerance = (settings.relative_tolerance.clone() / &cycle.in_phase_cancellation())
        .max_of(&floor)
        .min_of(&settings.relative_tolerance);
    let integrated = integrate(&pieces.pieces, &settings)?;
    let segments = pieces.sum_by_segment(integrated.values(), &zero);
    let mut parts = Parts::from_integrals(segments, integrated.error.clone(), &integrated);
    parts.piece_points = integrated.check_rules();
    assemble(cycle, parts, Method::FourSegment, options)
}
