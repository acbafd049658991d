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
    let cancellation = cycle.cancellation_amplification();
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
    let integrated = integrate(&pieces.pieces, &options.settings(&zero))?;
    let segments = pieces.sum_by_segment(integrated.values(), &zero);
    let mut parts = Parts::from_integrals(segments, integrated.error.clone(), &integrated);
    parts.piece_points = integrated.check_rules();
    assemble(cycle, parts, Method::FourSegment, options)
}
