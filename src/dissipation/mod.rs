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

mod closed_forms;
mod driver;

pub use closed_forms::{constant_normal_load, in_phase, HertzConfiguration, MindlinDeresiewicz};

use crate::compliance::{check_admissible, AdmissibilityError, Compliance};
use crate::cycle::{CycleError, CycleKind, LoadCycle};
use crate::real::Real;
use driver::{converge, Converged, Piece};

/// The four segment contributions to W, each ∫ (Q − Q0) du over the segment.
#[derive(Clone, Debug, PartialEq)]
pub struct Segments<R> {
    /// E → B: reverse slip spreading inward.
    pub eb: R,
    /// B → C: the whole contact sticks.
    pub bc: R,
    /// C → H: forward slip, governed by the mirror point Y.
    pub ch: R,
    /// H → E: forward slip, governed by P_K.
    pub he: R,
}

impl<R: Real> Segments<R> {
    /// EB + BC + CH + HE.
    pub fn total(&self) -> R {
        self.eb.clone() + &self.bc + &self.ch + &self.he
    }

    /// The segments as (name, value) pairs, in cycle order.
    pub fn named(&self) -> [(&'static str, &R); 4] {
        [("EB", &self.eb), ("BC", &self.bc), ("CH", &self.ch), ("HE", &self.he)]
    }
}

/// How W was computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// The four-segment integrals in θ.
    FourSegment,
    /// The in-phase closed form (paper appendix, Eqs. 26–32).
    InPhase,
    /// The constant-normal-load closed form (Cattaneo–Mindlin with Masing's rule).
    ConstantNormalLoad,
    /// Q1 = 0: nothing oscillates tangentially, W = 0.
    NoTangentialOscillation,
}

/// The dissipation per cycle and how it was obtained.
#[derive(Clone, Debug)]
pub struct Dissipation<R> {
    /// W, the energy dissipated per cycle.
    pub total: R,
    /// Its split over the four segments.
    pub segments: Segments<R>,
    /// An estimate of the absolute quadrature error of `total`.
    pub error_estimate: R,
    /// Integrand evaluations spent.
    pub evaluations: usize,
    /// The largest Gauss–Legendre rule used on any one piece.
    pub points: usize,
    /// Which formula produced it.
    pub method: Method,
}

/// Accuracy and checking controls.
#[derive(Clone, Debug)]
pub struct Options<R> {
    /// Target relative accuracy; `None` is 256 ulps of the working precision.
    pub relative_tolerance: Option<R>,
    /// The smallest Gauss–Legendre rule per segment (the first of the doubling sequence).
    pub min_points: usize,
    /// The largest Gauss–Legendre rule per segment before giving up.
    pub max_points: usize,
    /// Integrate with v'(x) − v'(P0) in place of v'(x) (exact, and free of cancellation).
    pub remove_constant_slope: bool,
    /// Refuse compliances with v' ≤ 0 or v'' > 0 over the loads the cycle reaches.
    /// The dissipation functional is linear in v' and defined for any v'; turn this
    /// off to apply it to non-physical v' (as the small-amplitude coefficient does).
    pub check_compliance: bool,
}

impl<R> Default for Options<R> {
    fn default() -> Self {
        Options {
            relative_tolerance: None,
            min_points: 8,
            max_points: 512,
            remove_constant_slope: true,
            check_compliance: true,
        }
    }
}

impl<R: Real> Options<R> {
    fn tolerance_for(&self, like: &R) -> R {
        self.relative_tolerance
            .clone()
            .unwrap_or_else(|| like.epsilon_like() * &like.int(256))
    }
}

/// Why W could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DissipationError {
    /// The load cycle is outside the theory.
    #[error(transparent)]
    Cycle(#[from] CycleError),
    /// The compliance is not physical over the cycle's loads.
    #[error(transparent)]
    Compliance(#[from] AdmissibilityError),
    /// The quadrature did not reach the tolerance.
    #[error("the integrals did not converge: relative change {relative_error:.2e} at {points} points per segment, {requested:.2e} requested; the case is too stiff at this precision (try --digits with more digits)")]
    NotConverged {
        points: usize,
        relative_error: f64,
        requested: f64,
    },
    /// An integrand produced NaN or infinity (compliance undefined at some load).
    #[error("the {segment} integral is not finite: the compliance is undefined at some load the cycle reaches")]
    NotFinite { segment: &'static str },
}

/// W for a valid cycle, by the closed form where the cycle is degenerate
/// (Q1 = 0, P1 = 0, or in phase) and by the four-segment integrals otherwise.
pub fn dissipation<R: Real>(
    cycle: &LoadCycle<R>,
    compliance: &dyn Compliance<R>,
    options: &Options<R>,
) -> Result<Dissipation<R>, DissipationError> {
    prepare(cycle, compliance, options)?;
    match cycle.kind() {
        CycleKind::NoTangentialOscillation => {
            let zero = cycle.mean_normal_load.int(0);
            Ok(Dissipation {
                total: zero.clone(),
                segments: Segments {
                    eb: zero.clone(),
                    bc: zero.clone(),
                    ch: zero.clone(),
                    he: zero.clone(),
                },
                error_estimate: zero,
                evaluations: 0,
                points: 0,
                method: Method::NoTangentialOscillation,
            })
        }
        CycleKind::ConstantNormalLoad => constant_normal_load(cycle, compliance, options),
        CycleKind::InPhase => in_phase(cycle, compliance, options),
        CycleKind::Elliptic => integrate_segments(cycle, compliance, options),
    }
}

/// W by the four-segment integrals whatever the cycle (also for P1 = 0 and for
/// phases close to 0 or π, where it converges to the closed forms).
pub fn four_segment<R: Real>(
    cycle: &LoadCycle<R>,
    compliance: &dyn Compliance<R>,
    options: &Options<R>,
) -> Result<Dissipation<R>, DissipationError> {
    prepare(cycle, compliance, options)?;
    integrate_segments(cycle, compliance, options)
}

/// Validates the cycle and, when asked, the compliance over the loads reached.
fn prepare<R: Real>(
    cycle: &LoadCycle<R>,
    compliance: &dyn Compliance<R>,
    options: &Options<R>,
) -> Result<(), DissipationError> {
    cycle.validate()?;
    if options.check_compliance {
        let low = (cycle.mean_normal_load.clone() - &cycle.normal_amplitude).min_of(&cycle.permanent_stick_load());
        let high = cycle.mean_normal_load.clone() + &cycle.normal_amplitude;
        check_admissible(compliance, &low, &high)?;
    }
    Ok(())
}

/// v'(P0 + offset), or v'(P0 + offset) − v'(P0) when the constant slope is removed.
pub(crate) fn slope_at<'a, R: Real>(
    compliance: &'a dyn Compliance<R>,
    mean_load: &'a R,
    remove_constant_slope: bool,
) -> impl Fn(&R) -> R + 'a {
    move |offset: &R| {
        if remove_constant_slope {
            compliance.slope_change(mean_load, offset)
        } else {
            compliance.slope(&(mean_load.clone() + offset))
        }
    }
}

fn integrate_segments<R: Real>(
    cycle: &LoadCycle<R>,
    compliance: &dyn Compliance<R>,
    options: &Options<R>,
) -> Result<Dissipation<R>, DissipationError> {
    let geometry = cycle.geometry()?;
    let g = &geometry;
    let slope = slope_at(compliance, &g.mean_normal_load, options.remove_constant_slope);
    let slope = &slope;
    // f v'(P) dP/dθ, shared by EB (with the opposite sign), CH and HE.
    let normal_term = move |theta: &R| g.friction.clone() * &slope(&g.normal_offset(theta)) * &g.normal_rate(theta);
    // Each integrand takes s, the angle from the start of its segment.
    let eb = move |s: &R| {
        let theta = g.theta_e.clone() + s;
        let from_b = s.clone() - &g.slip_angle;
        let reverse = slope(&g.reverse_slip_offset(&from_b)) * &g.sum_amplitude * &from_b.sin();
        g.tangential_offset(&theta) * &(reverse - &normal_term(&theta))
    };
    let bc = move |s: &R| {
        let theta = g.theta_b.clone() + s;
        g.tangential_offset(&theta) * &slope(&g.normal_offset(&theta)) * &g.tangential_rate(&theta)
    };
    let ch = move |s: &R| {
        let theta = g.theta_c.clone() + s;
        let mirror = g.theta_c.clone() - s;
        // sin(θ − θ_E) = sin(π + s) = −sin s.
        let forward = slope(&g.normal_offset(&mirror)) * &g.difference_amplitude * &s.sin();
        g.tangential_offset(&theta) * &(normal_term(&theta) + &forward)
    };
    let he = move |s: &R| {
        let theta = g.theta_h.clone() + s;
        let from_e = s.clone() - &g.slip_angle;
        let forward = slope(&g.forward_slip_offset(&from_e)) * &g.difference_amplitude * &from_e.sin();
        g.tangential_offset(&theta) * &(normal_term(&theta) - &forward)
    };
    let segments = [
        Segment {
            name: "EB",
            integrand: &eb,
            start: &g.theta_e,
            length: &g.slip_angle,
            mirrored: false,
        },
        Segment {
            name: "BC",
            integrand: &bc,
            start: &g.theta_b,
            length: &g.stick_angle,
            mirrored: false,
        },
        Segment {
            name: "CH",
            integrand: &ch,
            start: &g.theta_c,
            length: &g.stick_angle,
            mirrored: true,
        },
        Segment {
            name: "HE",
            integrand: &he,
            start: &g.theta_h,
            length: &g.slip_angle,
            mirrored: false,
        },
    ];
    let mut pieces = Vec::new();
    let mut owners = Vec::new();
    for (index, segment) in segments.iter().enumerate() {
        let breaks = lowest_load_points(segment, &g.theta_c);
        for window in breaks.windows(2) {
            pieces.push(Piece {
                name: segment.name,
                integrand: Box::new(segment.integrand),
                start: window[0].clone(),
                end: window[1].clone(),
            });
            owners.push(index);
        }
    }
    let zero = g.phase.int(0);
    let converged = converge(&pieces, &options.tolerance_for(&zero), options)?;
    let mut values = vec![zero.clone(); 4];
    for (value, owner) in converged.values.iter().zip(&owners) {
        values[*owner] += value;
    }
    let combined = Converged::combined(values, converged.error, converged.evaluations, converged.points);
    Ok(scaled_result(cycle, combined, Method::FourSegment))
}

/// One segment's integrand in s, the angle from the segment's start θ = `start`.
struct Segment<'a, R> {
    name: &'static str,
    integrand: &'a dyn Fn(&R) -> R,
    start: &'a R,
    length: &'a R,
    /// Whether the integrand also reads P at the mirror point θ_C − s (segment CH).
    mirrored: bool,
}

/// The break points 0 = s₀ < s₁ < … < L of a segment: the angles where P (and,
/// for CH, P at the mirror point θ_C − s) is least, θ ≡ π (mod 2π). A compliance
/// singular at P → 0 is nearly singular there when the cycle nears separation,
/// and a break puts the trouble at an end of a piece.
fn lowest_load_points<R: Real>(segment: &Segment<'_, R>, theta_c: &R) -> Vec<R> {
    let length = segment.length;
    let zero = length.int(0);
    let pi = length.pi_like();
    let mut breaks = vec![zero.clone()];
    for k in -2..=3i64 {
        let lowest = pi.clone() * &pi.int(2 * k + 1);
        let mut candidates = vec![lowest.clone() - segment.start];
        if segment.mirrored {
            candidates.push(theta_c.clone() - &lowest);
        }
        breaks.extend(candidates.into_iter().filter(|s| *s > zero && s < length));
    }
    breaks.push(length.clone());
    breaks.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
    breaks
}

/// Multiplies the per-unit-λ segment integrals by λ and assembles the result.
pub(crate) fn scaled_result<R: Real>(cycle: &LoadCycle<R>, converged: Converged<R>, method: Method) -> Dissipation<R> {
    let lambda = &cycle.compliance_ratio;
    let mut scaled = converged.values.into_iter().map(|v| v * lambda);
    let mut next = || scaled.next().unwrap_or_else(|| lambda.int(0));
    let segments = Segments {
        eb: next(),
        bc: next(),
        ch: next(),
        he: next(),
    };
    Dissipation {
        total: segments.total(),
        segments,
        error_estimate: converged.error * lambda,
        evaluations: converged.evaluations,
        points: converged.points,
        method,
    }
}
