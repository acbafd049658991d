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
    check_conditioning(
        &cancellation,
        options,
        format!(
            "Q1/(fP1) = {:.3e}, and the slip terms of the segment integrands cancel to a difference that much smaller",
            (cycle.tangential_amplitude.clone() / &cycle.normal_amplitude / &cycle.friction).to_f64_lossy()
        ),
    )?;
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
