//! The frictional dissipation per cycle, W = ∮ Q du (paper Eq. 6), for any compliance.
//!
//! In each segment the tangential displacement u follows from the
//! Ciavarella–Jäger superposition (paper Eqs. 10–18, errata items 2, 4, 5). In
//! the cycle angle θ its rate is, with σ₊, σ₋ the amplitudes of Q ± fP:
//!
//! ```text
//! EB:  du/dθ = λ[−f v'(P) P' + v'(P_S) σ₊ sin(θ − θ_B)]     P_S = P_T + σ₊ sin²((θ − θ_B)/2)/f
//! BC:  du/dθ = λ v'(P) Q'
//! CH:  du/dθ = λ[ f v'(P) P' − v'(P_Y) σ₋ sin(θ − θ_E)]     P_Y = P(2θ_C − θ)
//! HE:  du/dθ = λ[ f v'(P) P' − v'(P_K) σ₋ sin(θ − θ_E)]     P_K = P_T + σ₋ sin²((θ − θ_E)/2)/f
//! ```
//!
//! (the CH form uses Q_Y − fP_Y = Q − fP, Eq. 15). Every integrand is smooth in θ,
//! so Gauss–Legendre rules in θ converge geometrically, where the same integrals in
//! P would have square-root end points. Because u closes over the cycle, W is the
//! sum of ∫ (Q − Q0) du over the segments.
//!
//! By default v'(x) is replaced by v'(x) − v'(P0). A constant v' = c gives
//! du/dθ = λ c Q' in every segment, so its contribution λc ∮ (Q − Q0) dQ vanishes
//! over the cycle (proofs/constant-term.md); removing it before integrating changes
//! W only by rounding, and keeps small-amplitude results from cancelling away.
//! The segment values reported are ∫ (Q − Q0) du with u from v' − v'(P0): so
//! defined they depend neither on Q0 nor on a constant added to v'.
//!
//! A computation takes a [`ValidCycle`] (validated once) through `conditioning`
//! (rounding amplification, magnitudes, admissibility), then one formula — the closed forms of
//! `closed_forms`, or the integrands of `segments` summed per [`Segment`] by
//! `four_segment` — whose pieces go to the quadrature engine ([`crate::quad::integrate`]);
//! `assemble` scales the segment values by λ and adds what rounding can do to the
//! error estimate. [`Options`] and [`DissipationError`] have files of their own.

mod assemble;
pub(crate) mod closed_forms;
mod conditioning;
mod error;
mod four_segment;
mod options;
mod range;
mod segment;
mod segments;
pub(crate) mod slope;

pub use assemble::{Dissipation, ExactZero, Method};
pub use closed_forms::{constant_normal_load, in_phase, HertzConfiguration, MindlinDeresiewicz};
pub use error::DissipationError;
pub use four_segment::four_segment;
pub use options::{Options, Rules};
pub use segment::{Segment, Segments};
pub use segments::{SegmentIntegrands, SegmentPieces};
#[cfg(feature = "certified")]
pub(crate) use segments::{SlopeBetween, SlopesAtLoads, NEAR_SEPARATION};

use crate::compliance::Compliance;
use crate::cycle::{CycleKind, LoadCycle, ValidCycle};
use crate::real::Real;
use assemble::{assemble, Parts};
use conditioning::check_case;
use four_segment::four_segment_integrals;

/// W for a valid cycle, by the closed form where the cycle is degenerate
/// (Q1 = 0, P1 = 0, or in phase) and by the four-segment integrals otherwise.
///
/// ```
/// use microslip::compliance::{Persson, Shifted};
/// use microslip::cycle::LoadCycle;
/// use microslip::dissipation::{dissipation, Method, Options};
///
/// let cycle = LoadCycle {
///     mean_normal_load: 1.0,
///     normal_amplitude: 0.4,
///     mean_tangential_load: 0.0,
///     tangential_amplitude: 0.5,
///     phase: 0.4 * std::f64::consts::PI,
///     friction: 1.0,
///     compliance_ratio: 1.0,
/// };
/// let persson = Persson { gamma: 1.0, sigma: 1.0 };
/// let w = dissipation(&cycle, &persson, &Options::default())?;
/// assert_eq!(w.method, Method::FourSegment);
/// let sum = w.segments.eb + w.segments.bc + w.segments.ch + w.segments.he;
/// assert!((sum - w.total).abs() <= w.error_estimate);
///
/// // A constant added to v' dissipates nothing (the constant-term theorem).
/// let stiffer = Shifted { extra_slope: 3.0, inner: Box::new(persson) };
/// let shifted = dissipation(&cycle, &stiffer, &Options::default())?;
/// assert!((shifted.total - w.total).abs() <= 2.0 * w.error_estimate);
/// # Ok::<(), microslip::dissipation::DissipationError>(())
/// ```
pub fn dissipation<R: Real>(
    cycle: &LoadCycle<R>,
    compliance: &dyn Compliance<R>,
    options: &Options<R>,
) -> Result<Dissipation<R>, DissipationError> {
    let cycle = ValidCycle::new(cycle.clone())?;
    match cycle.kind() {
        CycleKind::NoTangentialOscillation => {
            check_case(&cycle, compliance, options)?;
            let nothing = Parts::nothing(&cycle.mean_normal_load.int(0));
            assemble(&cycle, nothing, Method::NoTangentialOscillation, options)
        }
        CycleKind::ConstantNormalLoad => constant_normal_load(&cycle, compliance, options),
        CycleKind::InPhase => in_phase(&cycle, compliance, options),
        CycleKind::Elliptic => four_segment_integrals(&cycle, compliance, options),
    }
}
