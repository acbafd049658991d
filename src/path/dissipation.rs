//! W of a periodic path: W = λ f² ∮ q dU over the steady cycle's smooth segments.
//!
//! With q̃ = q − q̄ (∮ dU = 0 on the closed loop, so the mean load does no work) and
//! ∮ v'(P) q̃ dq̃ = −½ ∮ v''(P) q̃² dP (an exact differential less its P-part), the
//! integrand on each segment is q̃ [(v'(s₋) − v'(P)) x' + (v'(s₊) − v'(P)) y'] − ½ v''(P) q̃² P':
//! at constant P the second term vanishes identically, and what is left is slip alone.

use std::time::Instant;

use crate::compliance::{check_admissible, Compliance};
use crate::doubts::if_decided;
use crate::quad::{integrate, Piece, QuadError, Settings};
use crate::real::Real;

pub use super::events::SlopeChanges;
use super::events::{Point, Segment, SteadyCycle};
use super::input::{LoadPath, PathError};
use super::Contact;

/// The integrand of W/(λf²) at θ in `segment`: q̃ [(v'(s₋) − v'(P)) x' + (v'(s₊) − v'(P)) y']
/// − ½ v''(P) q̃² P', with q̃ = q − q̄. Analytic in θ over a segment, whose front formulas
/// are fixed: what both the quadrature and the enclosure integrate.
pub fn work_rate<R: Real>(
    cycle: &SteadyCycle<R>,
    segment: &Segment<R>,
    theta: &R,
    compliance: &dyn Compliance<R>,
) -> R {
    work_rate_at(cycle, segment, &cycle.point(theta), compliance, None, SlopeChanges::Own)
}

/// [`work_rate`] with the slope changes formed as `changes` says.
pub fn work_rate_with<R: Real>(
    cycle: &SteadyCycle<R>,
    segment: &Segment<R>,
    theta: &R,
    compliance: &dyn Compliance<R>,
    changes: SlopeChanges,
) -> R {
    work_rate_at(cycle, segment, &cycle.point(theta), compliance, None, changes)
}

/// The same integrand in the entry angle θₑ of the segment's front (`forward` or not)
/// inside an entry piece: at θ(θₑ), where that front is at the load P(θₑ), times
/// dθ/dθₑ = −∂D/∂θₑ / ∂D/∂θ, D the divided difference (v(θ) − v(θₑ))/(θ − θₑ) of the slip
/// variable, finite where θ and θₑ meet at a turning point of v.
pub fn work_rate_in_entry_angle<R: Real>(
    cycle: &SteadyCycle<R>,
    segment: &Segment<R>,
    entered: &R,
    forward: bool,
    compliance: &dyn Compliance<R>,
    changes: SlopeChanges,
) -> R {
    let theta = cycle.current_angle(segment, entered, forward);
    let point = cycle.point(&theta);
    let load = cycle.point(entered).p;
    let rate = work_rate_at(cycle, segment, &point, compliance, Some((forward, &load)), changes);
    rate * &cycle.current_angle_rate(&theta, entered, forward)
}

/// [`work_rate`] at a point, one front's load `known` where given.
fn work_rate_at<R: Real>(
    cycle: &SteadyCycle<R>,
    segment: &Segment<R>,
    point: &Point<R>,
    compliance: &dyn Compliance<R>,
    known: Option<(bool, &R)>,
    changes: SlopeChanges,
) -> R {
    let q = point.q.clone() - &cycle.mean_tangential();
    let slip = cycle.slip_rate_with(segment, point, compliance, known, changes);
    q.clone() * &slip - &(compliance.curvature(&point.p) * &q.square() * &point.dp * &q.ratio(1, 2))
}

/// W of a path, with its quadrature's error estimate.
#[derive(Clone, Debug)]
pub struct PathDissipation<R> {
    /// The energy dissipated per cycle.
    pub total: R,
    /// The quadrature's estimate of |error| plus the rounding floor 64ε Σ|pieces|: an
    /// estimate, not a bound.
    pub error_estimate: R,
    /// The smooth segments the cycle splits into.
    pub segments: usize,
    /// Integrand evaluations spent.
    pub evaluations: usize,
}

/// How much looser the second attempt's tolerance is.
const LOOSER: i64 = 1 << 20;

/// The relative tolerance of the quadrature: 256 ε of the working precision.
fn tolerance<R: Real>(like: &R) -> R {
    like.epsilon_like() * &like.int(256)
}

/// W of the steady cycle of `path` on a contact with compliance v, force-driven.
///
/// ```
/// use microslip::compliance::Persson;
/// use microslip::path::{path_dissipation, Contact, LoadPath};
///
/// let path = LoadPath::harmonic(&1.0, &0.4, &0.0, &0.5, &(0.4 * std::f64::consts::PI));
/// let contact = Contact { friction: 1.0, compliance_ratio: 1.0 };
/// let w = path_dissipation(&path, &contact, &Persson { gamma: 1.0, sigma: 1.0 }, None)?;
/// assert!(w.total > 0.0 && w.error_estimate < 1e-12 * w.total);
/// # Ok::<(), microslip::path::PathError>(())
/// ```
pub fn path_dissipation<R: Real>(
    path: &LoadPath<R>,
    contact: &Contact<R>,
    compliance: &dyn Compliance<R>,
    deadline: Option<Instant>,
) -> Result<PathDissipation<R>, PathError> {
    let cycle = SteadyCycle::new(path, contact)?;
    dissipation_of(&cycle, contact, compliance, deadline)
}

/// W of a steady cycle already split into segments.
pub fn dissipation_of<R: Real>(
    cycle: &SteadyCycle<R>,
    contact: &Contact<R>,
    compliance: &dyn Compliance<R>,
    deadline: Option<Instant>,
) -> Result<PathDissipation<R>, PathError> {
    check_admissible(compliance, &cycle.lowest_slip, &cycle.highest_load)?;
    let like = cycle.lowest_slip.clone();
    // Q constant (every harmonic k ≥ 1 exactly 0): q̃ ≡ 0, and W = Q ∮ du = 0 exactly
    // over the closed loop, whatever P does.
    if if_decided(|| cycle.loads.tangential_is_constant()) == Some(true) {
        let zero = like.int(0);
        return Ok(PathDissipation {
            total: zero.clone(),
            error_estimate: zero,
            segments: cycle.segments.len(),
            evaluations: 0,
        });
    }
    let pieces: Vec<Piece<'_, R>> = cycle
        .segments
        .iter()
        .map(|segment| {
            Piece::new(
                "path segment",
                segment.start.clone(),
                segment.end.clone(),
                move |theta: &R| work_rate(cycle, segment, theta, compliance),
            )
        })
        .collect();
    let mut settings = Settings::new(tolerance(&like));
    settings.deadline = deadline;
    let integrated = match integrate(&pieces, &settings) {
        // A front racing through an entry piece where x' nearly vanished leaves a piece
        // that no rule resolves to 256 ε: a looser tolerance, whose estimate is reported.
        Err(QuadError::NotConverged { .. }) => {
            settings.relative_tolerance = tolerance(&like) * &like.int(LOOSER);
            integrate(&pieces, &settings)?
        }
        outcome => outcome?,
    };
    let scale = contact.compliance_ratio.clone() * &contact.friction.square();
    let mut total = like.int(0);
    let mut magnitude = like.int(0);
    for piece in &integrated.pieces {
        total += &piece.estimate.value;
        magnitude += &piece.magnitude;
    }
    let rounding = magnitude * &like.epsilon_like() * &like.int(64);
    Ok(PathDissipation {
        total: total * &scale,
        error_estimate: (integrated.error.clone() + &rounding) * &scale,
        segments: cycle.segments.len(),
        evaluations: integrated.evaluations,
    })
}
