//! The result: the segment integrals per unit λ, scaled by λ and given the error
//! rounding adds.

use super::error::DissipationError;
use super::options::Options;
use super::segment::Segments;
use crate::cycle::{CycleKind, ValidCycle};
use crate::quad::Integrated;
use crate::real::Real;

/// How W was computed.
#[non_exhaustive]
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
    /// W = 0 exactly, for a reason read from the exact input rather than computed.
    Exact(ExactZero),
}

impl From<CycleKind> for Method {
    /// The formula a valid cycle of this kind is computed by.
    fn from(kind: CycleKind) -> Method {
        match kind {
            CycleKind::NoTangentialOscillation => Method::NoTangentialOscillation,
            CycleKind::ConstantNormalLoad => Method::ConstantNormalLoad,
            CycleKind::InPhase => Method::InPhase,
            CycleKind::Elliptic => Method::FourSegment,
        }
    }
}

impl Method {
    /// The formula, as the command line names it after W.
    ///
    /// ```
    /// use microslip::dissipation::Method;
    ///
    /// assert_eq!(Method::InPhase.description(), "in-phase closed form (paper appendix)");
    /// ```
    pub fn description(self) -> &'static str {
        self.names().1
    }

    /// A short machine-readable name (batch rows, JSON).
    ///
    /// ```
    /// use microslip::dissipation::Method;
    ///
    /// assert_eq!(Method::FourSegment.key(), "four-segment");
    /// ```
    pub fn key(self) -> &'static str {
        self.names().0
    }

    /// The one name table: the key and the description.
    fn names(self) -> (&'static str, &'static str) {
        match self {
            Method::FourSegment => (
                "four-segment",
                "four-segment integrals of v' − v'(P0) in the cycle angle",
            ),
            Method::InPhase => ("in-phase", "in-phase closed form (paper appendix)"),
            Method::ConstantNormalLoad => ("constant-normal-load", "constant-normal-load closed form"),
            Method::NoTangentialOscillation => ("no-tangential-oscillation", "no tangential oscillation (W = 0)"),
            Method::Exact(_) => ("exact", "exact"),
        }
    }
}

/// Why W is exactly 0, decided from the exact input (the decimals and the phase as
/// written, the compliance SPEC's structure), never from a rounded value
/// (proofs/exact-values.md).
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExactZero {
    /// v' is constant (v'' ≡ 0): a constant v' dissipates nothing (the constant-term theorem).
    ConstantSlope,
    /// Q1 = 0: nothing oscillates tangentially.
    NoTangentialOscillation,
    /// φ is exactly a multiple of π and Q1 ≤ fP1: the ellipse is a line inside the
    /// friction cone's stick range, and nothing slips.
    InPhaseWithoutSlip,
}

impl ExactZero {
    /// The reason, as printed after `exact:`.
    pub fn reason(self) -> &'static str {
        match self {
            ExactZero::ConstantSlope => "v'' ≡ 0 on [P_T, P0 + P1]",
            ExactZero::NoTangentialOscillation => "Q1 = 0",
            ExactZero::InPhaseWithoutSlip => "in phase, φ = kπ exactly, with Q1 ≤ fP1: nothing slips",
        }
    }

    /// A short machine-readable name.
    pub fn key(self) -> &'static str {
        match self {
            ExactZero::ConstantSlope => "constant-slope",
            ExactZero::NoTangentialOscillation => "no-tangential-oscillation",
            ExactZero::InPhaseWithoutSlip => "in-phase-without-slip",
        }
    }
}

/// The dissipation per cycle and how it was obtained.
#[non_exhaustive]
#[derive(Clone, Debug)]
pub struct Dissipation<R> {
    /// W, the energy dissipated per cycle.
    pub total: R,
    /// Its split over the four segments.
    pub segments: Segments<R>,
    /// An estimate of the absolute error of `total`, of the quadrature and of rounding;
    /// infinite where the rounding is beyond the working precision's range (segments
    /// that cancel near in phase, in f64 at a phase below about 1e-154).
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
    /// W exactly 0 for `reason`, decided from the input: no integral, no error.
    pub fn exact_zero(reason: ExactZero, zero: &R) -> Self {
        Dissipation {
            total: zero.clone(),
            segments: Segments::from_fn(|_| zero.clone()),
            error_estimate: zero.clone(),
            evaluations: 0,
            points: 0,
            piece_points: Vec::new(),
            method: Method::Exact(reason),
        }
    }
}

/// What a formula computed, per unit λ: the four segment values (zero where it has none),
/// the quadrature's error estimate and its cost.
pub(crate) struct Parts<R> {
    pub segments: Segments<R>,
    pub error: R,
    pub evaluations: usize,
    /// The largest Gauss–Legendre rule used on any one piece.
    pub points: usize,
    /// The rule each piece ended with (empty where the formula combined its pieces).
    pub piece_points: Vec<usize>,
}

impl<R: Real> Parts<R> {
    /// Segment values with the error and cost of the integrals they came from.
    pub fn from_integrals(segments: Segments<R>, error: R, integrated: &Integrated<R>) -> Self {
        Parts {
            segments,
            error,
            evaluations: integrated.evaluations,
            points: integrated.largest_rule,
            piece_points: Vec::new(),
        }
    }

    /// No integrals: W = 0 with no error (no tangential oscillation, or no slip).
    pub fn nothing(zero: &R) -> Self {
        Parts {
            segments: Segments::from_fn(|_| zero.clone()),
            error: zero.clone(),
            evaluations: 0,
            points: 0,
            piece_points: Vec::new(),
        }
    }
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
pub(crate) fn assemble<R: Real>(
    cycle: &ValidCycle<R>,
    parts: Parts<R>,
    method: Method,
    options: &Options<R>,
) -> Result<Dissipation<R>, DissipationError> {
    let lambda = &cycle.compliance_ratio;
    let segments = Segments::from_fn(|segment| parts.segments.get(segment).clone() * lambda);
    let mut total = segments.total();
    let eps = total.epsilon_like();
    let scale = segments.iter().fold(total.int(0), |acc, (_, v)| acc + &v.abs());
    // The four-segment integrands also cancel internally when Q1 ≪ fP1.
    let mut amplification = cycle.rounding_amplification();
    if method == Method::FourSegment {
        amplification += &cycle.cancellation_amplification();
    }
    // A W that came out exactly 0 from segments that cancel near in phase is only rounding:
    // the size it is predicted to have stands in for |W|.
    let size = if method == Method::FourSegment && total == total.int(0) {
        scale.clone() / &cycle.in_phase_cancellation()
    } else {
        total.abs()
    };
    if !total.is_finite() || !parts.error.is_finite() {
        return Err(DissipationError::NotFinite { segment: "total" });
    }
    // Where the amplification itself is beyond the precision's range (near in phase, the
    // cancellation 1/(8 sin²φ) once sin²φ underflows), rounding is not bounded at all.
    let rounding = if amplification.is_finite() {
        size * &(amplification * &eps) + &(scale.clone() * &eps * &eps.int(64))
    } else {
        R::from_f64(f64::INFINITY, total.precision())
    };
    let mut error_estimate = parts.error * lambda + &rounding;
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
        evaluations: parts.evaluations,
        points: parts.points,
        piece_points: parts.piece_points,
        method,
    })
}
