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
mod range;
mod segments;

pub use closed_forms::{constant_normal_load, in_phase, HertzConfiguration, MindlinDeresiewicz};
pub use driver::Integral;
pub use segments::{SegmentIntegrands, SEGMENT_NAMES};

use crate::compliance::{check_admissible, AdmissibilityError, Compliance, SlopeChange};
use crate::cycle::{CycleError, CycleKind, LoadCycle};
use crate::real::Real;
use driver::{converge, Converged};

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
    /// The Gauss–Legendre rule each piece of the four-segment integrals ended with (for a
    /// piece tanh–sinh finished, the largest rule); empty for the closed forms.
    pub piece_points: Vec<usize>,
    /// Which formula produced it.
    pub method: Method,
}

impl<R: Real> Dissipation<R> {
    /// The significant digits of `value` that the error estimate vouches for, at most
    /// `most`: where W is a small difference of large segments (near in phase with
    /// Q1 < fP1, say) this is far fewer than the working precision carries. 0 when the
    /// estimate is as large as the value.
    pub fn resolved_digits(&self, value: &R, most: u32) -> u32 {
        let (magnitude, error) = (value.abs().to_f64_lossy(), self.error_estimate.to_f64_lossy());
        if error <= 0.0 {
            return most;
        }
        if !magnitude.is_finite() || magnitude <= error {
            return 0;
        }
        ((magnitude / error).log10().floor() as u32).min(most)
    }
}

/// Accuracy and checking controls.
#[derive(Clone, Debug)]
pub struct Options<R> {
    /// Target relative accuracy; `None` is 256 ulps of the working precision.
    pub relative_tolerance: Option<R>,
    /// The smallest Gauss–Legendre rule per segment (the first of the doubling sequence);
    /// 0 chooses (16 points).
    pub min_points: usize,
    /// Integrate every piece once with this Gauss–Legendre rule, no refinement; the error
    /// estimate is the change from the rule of a quarter of the points. For checking a
    /// converged result with another rule.
    pub fixed_points: Option<usize>,
    /// With `fixed_points`, size the error by the rule of a quarter of the points (on by
    /// default). Off where the value is only compared with an independent one, as the
    /// verification's check run is: the estimate would cost a fifth more and go unused.
    pub fixed_rule_error: bool,
    /// With `fixed_points`, the rule of each piece in turn (as [`Dissipation::piece_points`]
    /// gives them for the same case); where the count differs, `fixed_points` for all.
    pub fixed_points_per_piece: Option<Vec<usize>>,
    /// The largest Gauss–Legendre rule per segment before giving up.
    pub max_points: usize,
    /// Integrate with v'(x) − v'(P0) in place of v'(x) (exact, and free of cancellation).
    pub remove_constant_slope: bool,
    /// With `remove_constant_slope`, also take the linear part v''(P0)·(P − P0) out of
    /// v' and add its contribution v''(P0)·W[P − P0] from a separate integral
    /// (four-segment path only). Exact by linearity; see proofs/stability.md for what
    /// it changes (measured: nothing beyond rounding — off by default).
    pub remove_linear_slope: bool,
    /// Refuse cycles whose loads alone, rounded at the working precision, would move W
    /// by more than this relative amount (ε × `LoadCycle::rounding_amplification`):
    /// in f64 that is a cycle within about P0/4500 of separation or of gross slip.
    pub rounding_limit: f64,
    /// Give up with [`DissipationError::OutOfTime`] once this instant has passed
    /// (checked between refinements).
    pub deadline: Option<std::time::Instant>,
    /// Refuse compliances with v' ≤ 0 or v'' > 0 over the loads the cycle reaches.
    /// The dissipation functional is linear in v' and defined for any v'; turn this
    /// off to apply it to non-physical v' (as the small-amplitude coefficient does).
    pub check_compliance: bool,
}

impl<R> Default for Options<R> {
    fn default() -> Self {
        Options {
            relative_tolerance: None,
            min_points: 0,
            fixed_points: None,
            fixed_rule_error: true,
            fixed_points_per_piece: None,
            max_points: 512,
            remove_constant_slope: true,
            remove_linear_slope: false,
            rounding_limit: 1e-12,
            deadline: None,
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
    #[error("{0} = [P_T, P0 + P1]: the slip loads of the cycle reach down to the permanent-stick load P_T")]
    Compliance(#[from] AdmissibilityError),
    /// The quadrature did not reach the tolerance.
    #[error("the integrals did not converge: relative change {relative_error:.2e} at {points} points per segment, {requested:.2e} requested; the case is too stiff for this working precision (more precision may converge)")]
    NotConverged {
        points: usize,
        relative_error: f64,
        requested: f64,
    },
    /// The working precision cannot resolve the cycle: rounding alone moves W too much.
    #[error("the case is ill-conditioned at {bits} bits: {cause}, so rounding alone can change W by ~{expected:.1e} relative (limit {limit:.0e}); it needs more working precision")]
    IllConditioned {
        bits: u32,
        /// What amplifies the rounding, with its size.
        cause: String,
        expected: f64,
        limit: f64,
    },
    /// The segment values are so small that f64 would hold them with fewer digits.
    #[error("the segment contributions ({scale:e}) fall below the range the working precision holds in full; rescale the loads (W scales with the load scale) or compute with a wider exponent range (MPFR)")]
    OutOfRange { scale: f64 },
    /// W came out negative beyond its error estimate (a physical compliance dissipates).
    #[error("W = {total:e} is negative beyond its error estimate {error:e}; the compliance may violate v'' ≤ 0 between the sampled loads")]
    Negative { total: f64, error: f64 },
    /// The deadline passed before the integrals converged.
    #[error("the time budget ran out before the integrals converged")]
    OutOfTime,
    /// An integrand produced NaN or infinity (compliance undefined at some load).
    #[error("the {segment} integral is not finite: the compliance is undefined at some load the cycle reaches")]
    NotFinite { segment: &'static str },
    /// A magnitude of the case lies where products of it would overflow or underflow.
    #[error("{quantity} = {value:e} is outside what {bits}-bit arithmetic carries through the integrals without overflow or underflow (magnitudes {low:.0e} to {high:.0e}); compute with more precision, whose exponent range is far wider")]
    OutsideRange {
        quantity: String,
        value: f64,
        bits: u32,
        low: f64,
        high: f64,
    },
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
            let nothing = Converged::combined(vec![], cycle.mean_normal_load.int(0), 0, 0);
            scaled_result(cycle, nothing, Method::NoTangentialOscillation, options)
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
    let amplification = cycle.rounding_amplification();
    check_conditioning(
        &amplification,
        options,
        format!("min(P0 − P1, P_T) = P0/{:.3e}", amplification.to_f64_lossy()),
    )?;
    let low = (cycle.mean_normal_load.clone() - &cycle.normal_amplitude).min_of(&cycle.permanent_stick_load());
    let high = cycle.mean_normal_load.clone() + &cycle.normal_amplitude;
    range::check_magnitudes(cycle, compliance, options, &low, &high)?;
    if options.check_compliance {
        check_admissible(compliance, &low, &high)?;
    }
    Ok(())
}

/// Refuses a cycle whose rounding amplification times ε exceeds `rounding_limit`.
fn check_conditioning<R: Real>(amplification: &R, options: &Options<R>, cause: String) -> Result<(), DissipationError> {
    let expected = (amplification.clone() * &amplification.epsilon_like()).to_f64_lossy();
    if expected > options.rounding_limit {
        return Err(DissipationError::IllConditioned {
            bits: amplification.precision().in_bits(),
            cause,
            expected,
            limit: options.rounding_limit,
        });
    }
    Ok(())
}

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

fn integrate_segments<R: Real>(
    cycle: &LoadCycle<R>,
    compliance: &dyn Compliance<R>,
    options: &Options<R>,
) -> Result<Dissipation<R>, DissipationError> {
    let geometry = cycle.geometry()?;
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
    let (pieces, curvature) = if options.remove_linear_slope {
        // W[v'] = W[v' − v'(P0) − v''(P0)·x] + v''(P0)·W[x]: the remainder and the
        // linear part as two sets of pieces, the second weighted by v''(P0) below.
        let curvature = compliance.curvature(&geometry.mean_normal_load);
        let reduced = integrands.prepared_slope();
        let linear = curvature.clone();
        let mut pieces = integrands.pieces_with_slope(Box::new(move |x: &R| reduced(x) - &(linear.clone() * x)));
        let remainder_count = pieces.len();
        pieces.extend(integrands.pieces_with_slope(Box::new(|x: &R| x.clone())));
        (pieces, Some((curvature, remainder_count)))
    } else {
        (integrands.pieces(), None)
    };
    let mut converged = converge(&pieces, &options.tolerance_for(&zero), options)?;
    if let Some((curvature, remainder_count)) = &curvature {
        for value in converged.values.iter_mut().skip(*remainder_count) {
            *value *= curvature;
        }
    }
    let mut values = vec![zero.clone(); 4];
    for (value, piece) in converged.values.iter().zip(&pieces) {
        values[piece.segment] += value;
    }
    let mut combined = Converged::combined(values, converged.error, converged.evaluations, converged.points);
    combined.piece_points = converged.piece_points;
    scaled_result(cycle, combined, Method::FourSegment, options)
}

/// Multiplies the per-unit-λ segment integrals by λ and assembles the result.
///
/// The error estimate adds to the quadrature's what rounding can do: of the loads
/// (ε × `rounding_amplification` × |W|), inside the four-segment integrands
/// (ε × `cancellation_amplification` × |W|) and of the segment sum (64ε × Σ|segment|).
/// A W that overflowed, or whose segments fell below the full-precision range, is
/// refused; for a physical compliance (`check_compliance`) a W below zero within ten
/// times its error estimate is reported as 0 (with the estimate raised to cover it),
/// and one below by more is refused.
pub(crate) fn scaled_result<R: Real>(
    cycle: &LoadCycle<R>,
    converged: Converged<R>,
    method: Method,
    options: &Options<R>,
) -> Result<Dissipation<R>, DissipationError> {
    let lambda = &cycle.compliance_ratio;
    let mut scaled = converged.values.into_iter().map(|v| v * lambda);
    let mut next = || scaled.next().unwrap_or_else(|| lambda.int(0));
    let segments = Segments {
        eb: next(),
        bc: next(),
        ch: next(),
        he: next(),
    };
    let mut total = segments.total();
    let eps = total.epsilon_like();
    let scale = segments.named().iter().fold(total.int(0), |acc, (_, v)| acc + &v.abs());
    // The four-segment integrands also cancel internally when Q1 ≪ fP1.
    let mut amplification = cycle.rounding_amplification();
    if method == Method::FourSegment {
        amplification += &cycle.cancellation_amplification();
    }
    let rounding = total.abs() * &(amplification * &eps) + &(scale.clone() * &eps * &eps.int(64));
    let mut error_estimate = converged.error * lambda + &rounding;
    if !total.is_finite() || !error_estimate.is_finite() {
        return Err(DissipationError::NotFinite { segment: "total" });
    }
    let zero = total.int(0);
    if scale > zero && scale < R::smallest_full_precision(total.precision()) {
        return Err(DissipationError::OutOfRange {
            scale: scale.to_f64_lossy(),
        });
    }
    if options.check_compliance && total < zero {
        // Rounding can leave a W that vanishes slightly negative; ten times the estimate
        // is beyond rounding, and a sign that a compliance is not physical after all.
        if -total.clone() > error_estimate.clone() * &zero.int(10) {
            return Err(DissipationError::Negative {
                total: total.to_f64_lossy(),
                error: error_estimate.to_f64_lossy(),
            });
        }
        error_estimate = error_estimate.max_of(&-total);
        total = zero;
    }
    Ok(Dissipation {
        total,
        segments,
        error_estimate,
        evaluations: converged.evaluations,
        points: converged.points,
        piece_points: converged.piece_points,
        method,
    })
}
