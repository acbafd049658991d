//! The slope v' the integrands are taken with, as a function of the offset x = P − P0.

use crate::compliance::{Compliance, SlopeChange};
use crate::real::Real;

/// x ↦ v'(P0 + x) − v'(P0) (prepared once), or x ↦ v'(P0 + x) when the constant
/// slope is kept.
pub(crate) fn slope_at<'a, R: Real>(
    compliance: &'a dyn Compliance<R>,
    mean_load: &R,
    remove_constant_slope: bool,
) -> SlopeChange<'a, R> {
    if remove_constant_slope {
        compliance.slope_change_about(mean_load)
    } else {
        let mean_load = mean_load.clone();
        Box::new(move |offset: &R| compliance.slope(&(mean_load.clone() + offset)))
    }
}

/// The compliance's breakpoints as offsets x = P − P0 (empty for an analytic v').
pub(crate) fn knot_offsets<R: Real>(compliance: &dyn Compliance<R>, mean_load: &R) -> Vec<R> {
    compliance
        .breakpoints(mean_load)
        .into_iter()
        .map(|knot| knot - mean_load)
        .collect()
}
