//! The load cycle P(θ) = P0 + P1 cos θ, Q(θ) = Q0 + Q1 cos(θ − φ): its validation
//! (a [`ValidCycle`] is one the theory covers) and the geometry of its ellipse in the
//! (P, Q) plane.
//!
//! The steady cycle splits into four segments at the points E, B, C, H (paper
//! Section 3.4, located as in errata item 4), taken in the order the angle θ
//! increases, i.e. the ellipse traversed anticlockwise (0 < φ < π):
//!
//! - C minimises Q − fP and E maximises it (θ_E = θ_C − π);
//! - B minimises Q + fP;
//! - H is the mirror image of B about θ_C (θ_H = 2θ_C − θ_B): the line of slope f
//!   through B meets the ellipse again there.
//!
//! With σ₊ and σ₋ the amplitudes of Q + fP and Q − fP, and δ = θ_C − θ_B, the
//! segments EB, BC, CH, HE have lengths π − δ, δ, δ, π − δ in θ.

use std::ops::Deref;

use crate::doubts::if_decided;
use crate::real::Real;

/// The loads of one harmonic cycle, with the friction coefficient and the
/// tangential/normal compliance ratio of the contact.
///
/// Built field by field (every field is a named physical quantity), then validated once
/// into a [`ValidCycle`], with the reason where the theory does not cover it:
///
/// ```
/// use microslip::cycle::{CycleError, CycleKind, LoadCycle, ValidCycle};
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
/// let valid = ValidCycle::try_from(cycle.clone())?;
/// assert_eq!(valid.kind(), CycleKind::Elliptic);
///
/// // |Q| reaches f·P (Q1 = 0.9 > f(P0 − P1) at θ = π): the whole contact slides.
/// let sliding = LoadCycle { tangential_amplitude: 0.9, ..cycle };
/// assert!(matches!(ValidCycle::new(sliding), Err(CycleError::GrossSlip { .. })));
/// # Ok::<(), CycleError>(())
/// ```
#[derive(Clone, Debug)]
pub struct LoadCycle<R> {
    /// P0, the mean normal load (compressive, > 0).
    pub mean_normal_load: R,
    /// P1, the normal load amplitude (≥ 0, < P0).
    pub normal_amplitude: R,
    /// Q0, the mean tangential load.
    pub mean_tangential_load: R,
    /// Q1, the tangential load amplitude (≥ 0).
    pub tangential_amplitude: R,
    /// φ, the phase lag of Q behind P, in radians.
    pub phase: R,
    /// f, the Coulomb friction coefficient (> 0).
    pub friction: R,
    /// λ = (2 − ν)/(2(1 − ν)), the tangential/normal compliance ratio, in [1, 2].
    pub compliance_ratio: R,
}

/// Why a load cycle is not one the theory covers.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CycleError {
    /// An input is NaN or infinite.
    #[error("{quantity} is not a finite number (got {value})")]
    NotFinite {
        /// The input's name, as the message shows it.
        quantity: &'static str,
        /// Its value.
        value: f64,
    },
    /// P0 ≤ 0.
    #[error("the mean normal load P0 = {p0:e} must be positive (the contact is compressed)")]
    NonPositiveMeanLoad {
        /// The mean normal load given.
        p0: f64,
    },
    /// P1 < 0 or Q1 < 0.
    #[error("the amplitude {quantity} = {value:e} must not be negative (a phase of π reverses a load)")]
    NegativeAmplitude {
        /// The amplitude's name (`P1` or `Q1`).
        quantity: &'static str,
        /// Its value.
        value: f64,
    },
    /// P0 − P1 ≤ 0.
    #[error("the contact separates: P0 − P1 = {margin:e} ≤ 0 (P0 = {p0:e}, P1 = {p1:e}); the normal amplitude must stay below the mean load")]
    Separation {
        /// The mean normal load.
        p0: f64,
        /// The normal load amplitude.
        p1: f64,
        /// P0 − P1, the lowest normal load of the cycle.
        margin: f64,
    },
    /// f ≤ 0.
    #[error("the friction coefficient f = {f:e} must be positive")]
    NonPositiveFriction {
        /// The friction coefficient given.
        f: f64,
    },
    /// λ outside [1, 2].
    #[error("the compliance ratio λ = {lambda} lies outside [1, 2] (λ = (2 − ν)/(2(1 − ν)) is 1 for ν = 0 and 1.5 for ν = 0.5)")]
    ComplianceRatioOutOfRange {
        /// The compliance ratio given, as written.
        lambda: String,
    },
    /// Poisson's ratio that gives λ outside [1, 2].
    #[error("Poisson's ratio ν = {nu} gives λ outside [1, 2]; ν must lie in [0, 2/3]")]
    PoissonRatioOutOfRange {
        /// Poisson's ratio given, as written.
        nu: String,
    },
    /// |φ| beyond [`MAX_PHASE`]: reducing it exactly costs working bits in proportion to its exponent.
    #[error("the phase φ = {phi:e} rad is too large: |φ| must be at most 1e100 rad (reducing it modulo 2π exactly needs as many extra bits as its binary exponent)")]
    PhaseTooLarge {
        /// The phase given, in radians.
        phi: f64,
    },
    /// The ellipse reaches |Q| = fP: periods of gross slip (sliding).
    #[error("gross slip: the load ellipse reaches the line Q = {sign}fP (max({sign_word}Q − fP) = {excess:e} ≥ 0, i.e. {relative:.3e} of fP0 beyond it); the theory needs |Q| < fP throughout the cycle: reduce Q1 or |Q0|, or raise P0")]
    GrossSlip {
        /// The side of the friction wedge reached: `+` or `−`.
        sign: &'static str,
        /// The same side in the expression max(±Q − fP): empty or `−`.
        sign_word: &'static str,
        /// max(±Q − fP) over the cycle, ≥ 0.
        excess: f64,
        /// `excess` over fP0.
        relative: f64,
    },
    /// A boundary of the theory that the exact inputs lie on or within 2^(−bits) of, which
    /// no precision up to `bits` settles ([`crate::boundaries`]).
    #[error("undecidable at this precision: whether the cycle reaches {boundary} is not settled at {bits} bits; move the inputs off the boundary")]
    Undecidable {
        /// The boundary, in words.
        boundary: &'static str,
        /// The most bits tried.
        bits: u32,
    },
}

/// The largest |φ| in radians a cycle accepts. Any phase up to it is reduced exactly
/// (see [`LoadCycle::reduced_phase`]); the bound only keeps the cost of an exact
/// reduction at high precision, which grows with the exponent of φ, small.
pub const MAX_PHASE: f64 = 1e100;

/// λ = (2 − ν)/(2(1 − ν)) from Poisson's ratio ν, checked to lie in [1, 2].
pub fn compliance_ratio_from_poisson<R: Real>(nu: &R) -> Result<R, CycleError> {
    let value = nu.to_f64_lossy();
    if !nu.is_finite() {
        return Err(CycleError::NotFinite {
            quantity: "Poisson's ratio ν",
            value,
        });
    }
    if *nu < nu.int(0) || *nu > nu.ratio(2, 3) {
        return Err(CycleError::PoissonRatioOutOfRange { nu: value.to_string() });
    }
    Ok((nu.int(2) - nu) / (nu.int(2) * &(nu.int(1) - nu)))
}

/// Which of the degenerate cases, or the general one, a valid cycle is.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CycleKind {
    /// Q1 = 0: no tangential oscillation, no dissipation.
    NoTangentialOscillation,
    /// P1 = 0: the Cattaneo–Mindlin / Ciavarella–Jäger constant-normal-load case.
    ConstantNormalLoad,
    /// φ ≡ 0 (mod π): the ellipse degenerates to a line (the paper's appendix).
    InPhase,
    /// A true ellipse.
    Elliptic,
}

impl<R> LoadCycle<R> {
    /// The same cycle with every quantity converted by `convert`, e.g. an f64 cycle
    /// carried exactly to a higher precision.
    ///
    /// ```
    /// use microslip::cycle::LoadCycle;
    ///
    /// let cycle = LoadCycle {
    ///     mean_normal_load: 1.0,
    ///     normal_amplitude: 0.4,
    ///     mean_tangential_load: 0.0,
    ///     tangential_amplitude: 0.5,
    ///     phase: 1.25,
    ///     friction: 1.0,
    ///     compliance_ratio: 1.0,
    /// };
    /// let precise = cycle.map(|x| rug::Float::with_val(200, x));
    /// assert_eq!(precise.normal_amplitude, 0.4); // the binary64 0.4, exactly
    /// assert_eq!(precise.phase.prec(), 200);
    /// ```
    pub fn map<S>(self, convert: impl Fn(R) -> S) -> LoadCycle<S> {
        LoadCycle {
            mean_normal_load: convert(self.mean_normal_load),
            normal_amplitude: convert(self.normal_amplitude),
            mean_tangential_load: convert(self.mean_tangential_load),
            tangential_amplitude: convert(self.tangential_amplitude),
            phase: convert(self.phase),
            friction: convert(self.friction),
            compliance_ratio: convert(self.compliance_ratio),
        }
    }
}

impl<R: Real> LoadCycle<R> {
    /// Checks that the cycle is one the theory covers: finite, compressive, within
    /// the friction cone throughout, with physical f and λ.
    pub fn validate(&self) -> Result<(), CycleError> {
        let named = [
            ("P0", &self.mean_normal_load),
            ("P1", &self.normal_amplitude),
            ("Q0", &self.mean_tangential_load),
            ("Q1", &self.tangential_amplitude),
            ("φ", &self.phase),
            ("f", &self.friction),
            ("λ", &self.compliance_ratio),
        ];
        for (quantity, value) in named {
            if !value.is_finite() {
                return Err(CycleError::NotFinite {
                    quantity,
                    value: value.to_f64_lossy(),
                });
            }
        }
        let zero = self.mean_normal_load.int(0);
        if self.mean_normal_load <= zero {
            return Err(CycleError::NonPositiveMeanLoad {
                p0: self.mean_normal_load.to_f64_lossy(),
            });
        }
        for (quantity, value) in [("P1", &self.normal_amplitude), ("Q1", &self.tangential_amplitude)] {
            if *value < zero {
                return Err(CycleError::NegativeAmplitude {
                    quantity,
                    value: value.to_f64_lossy(),
                });
            }
        }
        let margin = self.mean_normal_load.clone() - &self.normal_amplitude;
        if margin <= zero {
            return Err(CycleError::Separation {
                p0: self.mean_normal_load.to_f64_lossy(),
                p1: self.normal_amplitude.to_f64_lossy(),
                margin: margin.to_f64_lossy(),
            });
        }
        if self.friction <= zero {
            return Err(CycleError::NonPositiveFriction {
                f: self.friction.to_f64_lossy(),
            });
        }
        if self.compliance_ratio < zero.int(1) || self.compliance_ratio > zero.int(2) {
            return Err(CycleError::ComplianceRatioOutOfRange {
                lambda: self.compliance_ratio.to_f64_lossy().to_string(),
            });
        }
        if self.phase.abs() > R::from_f64(MAX_PHASE, self.phase.precision()) {
            return Err(CycleError::PhaseTooLarge {
                phi: self.phase.to_f64_lossy(),
            });
        }
        // The actual phase, not the reduced one: with Q0 ≠ 0 the cycle and its mirror image differ here.
        let (sum_amplitude, difference_amplitude) = self.slip_line_amplitudes_at(&self.actual_phase_trig());
        let friction_limit = self.friction.clone() * &self.mean_normal_load;
        // max(Q − fP) = Q0 − fP0 + σ₋ and max(−Q − fP) = −Q0 − fP0 + σ₊.
        let forward = self.mean_tangential_load.clone() - &friction_limit + &difference_amplitude;
        let reverse = -self.mean_tangential_load.clone() - &friction_limit + &sum_amplitude;
        for (excess, sign, sign_word) in [(forward, "+", ""), (reverse, "−", "−")] {
            if excess >= zero {
                return Err(CycleError::GrossSlip {
                    sign,
                    sign_word,
                    excess: excess.to_f64_lossy(),
                    relative: (excess / &friction_limit).to_f64_lossy(),
                });
            }
        }
        Ok(())
    }

    /// Which case the cycle is (for a valid one).
    fn classify(&self) -> CycleKind {
        let zero = self.mean_normal_load.int(0);
        if self.tangential_amplitude == zero {
            CycleKind::NoTangentialOscillation
        } else if self.normal_amplitude == zero {
            CycleKind::ConstantNormalLoad
        } else if self.reduced_phase() == zero {
            CycleKind::InPhase
        } else {
            CycleKind::Elliptic
        }
    }

    /// φ reduced to [0, π), rounded ([`reduced_angle`]). The dissipation has period π in
    /// φ: φ + π is the same cycle with Q − Q0 reversed, its mirror image in the P axis.
    pub fn reduced_phase(&self) -> R {
        reduced_angle(&self.phase)
    }

    /// The sine, cosine and half-angle squares of φ reduced to [0, π) ([`PhaseTrig::reduced`]).
    pub fn phase_trig(&self) -> PhaseTrig<R> {
        PhaseTrig::reduced(&self.phase)
    }

    /// (σ₊, σ₋): the amplitudes of Q + fP and of Q − fP over the cycle (for φ reduced to [0, π)).
    pub fn slip_line_amplitudes(&self) -> (R, R) {
        self.slip_line_amplitudes_at(&self.phase_trig())
    }

    fn slip_line_amplitudes_at(&self, trig: &PhaseTrig<R>) -> (R, R) {
        let q1 = &self.tangential_amplitude;
        let q1_sin = q1.clone() * &trig.sin;
        (
            self.sum_line_offset(trig).hypot(&q1_sin),
            self.difference_line_offset(trig).hypot(&q1_sin),
        )
    }

    /// Q1 cos φ + fP1, written near φ = π as (fP1 − Q1) + 2 Q1 cos²(φ/2) to keep it accurate.
    ///
    /// Both forms are exact and accurate around the switch, which sits at cos φ = −3/5: no
    /// input φ reaches it exactly (a rational multiple of π has cos φ = −3/5 never, by Niven's
    /// theorem; a decimal offset has a transcendental cosine), so an enclosure of φ always
    /// decides the branch at some precision, where a switch at φ = π/2 would not.
    fn sum_line_offset(&self, trig: &PhaseTrig<R>) -> R {
        let q1 = &self.tangential_amplitude;
        let fp1 = self.friction.clone() * &self.normal_amplitude;
        if trig.cos >= trig.cos.ratio(-3, 5) {
            q1.clone() * &trig.cos + &fp1
        } else {
            (fp1 - q1) + &(q1.clone() * &trig.half_cos_squared * &trig.cos.int(2))
        }
    }

    /// Q1 cos φ − fP1, written as (Q1 − fP1) − 2 Q1 sin²(φ/2) to keep it accurate near φ = 0.
    fn difference_line_offset(&self, trig: &PhaseTrig<R>) -> R {
        let q1 = &self.tangential_amplitude;
        let fp1 = self.friction.clone() * &self.normal_amplitude;
        (q1.clone() - &fp1) - &(q1.clone() * &trig.half_sin_squared * &trig.sin.int(2))
    }

    /// P_T, the permanent-stick load: the contact area A(P_T) sticks throughout the
    /// steady cycle. P_T = ½[min(Q + fP) − max(Q − fP)]/f = P0 − (σ₊ + σ₋)/(2f).
    pub fn permanent_stick_load(&self) -> R {
        let (plus, minus) = self.slip_line_amplitudes();
        self.mean_normal_load.clone() - &((plus + &minus) / &(self.friction.clone() * &self.friction.int(2)))
    }

    /// How much the cycle amplifies relative rounding errors of order ε in its loads:
    /// P0 / min(P0 − P1, P_T). Both margins are differences of loads of order P0, so
    /// each carries an absolute error of order εP0, and W is sensitive to them where
    /// v' is steep at low load (near separation, and near gross slip where P_T → 0).
    pub fn rounding_amplification(&self) -> R {
        let separation_margin = self.mean_normal_load.clone() - &self.normal_amplitude;
        let margin = separation_margin.min_of(&self.permanent_stick_load());
        self.mean_normal_load.clone() / &margin
    }

    /// How much the four-segment integrands amplify relative rounding errors when Q1 is
    /// small against fP1: the slip terms f v'(P) P' and v'(P_Y) σ₋ sin(θ − θ_E) of CH (and
    /// their counterparts in EB and HE) are of size fP1·v' and cancel to a difference of
    /// size Q1·v'. Returns 16 fP1/Q1, twice the largest amplification measured
    /// (proofs/stability.md, §1), times [`LoadCycle::in_phase_cancellation`], and 0 when
    /// Q1 = 0, which has no integrals.
    pub fn cancellation_amplification(&self) -> R {
        let zero = self.tangential_amplitude.int(0);
        if self.tangential_amplitude == zero {
            return zero;
        }
        self.friction.clone()
            * &(self.normal_amplitude.clone() / &self.tangential_amplitude)
            * &zero.int(16)
            * &self.in_phase_cancellation()
    }

    /// How far the segments cancel near in phase: with Q1 < fP1 nothing slips at φ ≡ 0, BC
    /// and CH span almost half a cycle each, and their sum W ∝ sin²φ is smaller than |BC|
    /// by up to 1/(8 sin²φ) (proofs/exact-values.md). Returns that where it exceeds 1, and
    /// 1 otherwise (also exactly in phase, which has no integrals).
    pub fn in_phase_cancellation(&self) -> R {
        let one = self.tangential_amplitude.int(1);
        let fp1 = self.friction.clone() * &self.normal_amplitude;
        let sin = self.phase_trig().sin;
        if self.tangential_amplitude >= fp1 || sin == one.int(0) {
            return one;
        }
        (one.clone() / &(sin.square() * &one.int(8))).max_of(&one)
    }

    /// The trigonometry of the phase as given (not reduced), for the validation, which
    /// tells the cycle from its mirror image when Q0 ≠ 0.
    fn actual_phase_trig(&self) -> PhaseTrig<R> {
        PhaseTrig::of(&self.phase)
    }

    /// The ellipse geometry (for φ reduced to [0, π)) of a cycle not yet validated:
    /// validates a copy first ([`ValidCycle::geometry`] for one that is).
    pub fn geometry(&self) -> Result<EllipseGeometry<R>, CycleError> {
        Ok(ValidCycle::new(self.clone())?.geometry())
    }

    /// P(θ).
    pub fn normal_load(&self, theta: &R) -> R {
        self.mean_normal_load.clone() + &(self.normal_amplitude.clone() * &theta.cos())
    }

    /// Q(θ) for the phase as given (not reduced); cos(θ − φ) by the subtraction formula,
    /// since θ − φ at the working precision loses the low bits of θ when |φ| is large.
    pub fn tangential_load(&self, theta: &R) -> R {
        let ((sin_theta, cos_theta), (sin_phi, cos_phi)) = (theta.sin_cos(), self.phase.sin_cos());
        let lag_cos = cos_theta * &cos_phi + &(sin_theta * &sin_phi);
        self.mean_tangential_load.clone() + &(self.tangential_amplitude.clone() * &lag_cos)
    }
}

/// Whether `phase` is an offset ψ ∈ [−π/2, 0) from π: the form in which a case read from
/// text carries a phase just below a multiple of π (see [`crate::phase`]). At ψ = −π/2
/// itself (3π/2 as written) both readings give π + ψ (φ − kπ with k = −1 otherwise), so
/// an enclosure of ψ that straddles −π/2 takes this one without a doubt.
fn below_pi<R: Real>(phase: &R) -> bool {
    let zero = phase.int(0);
    *phase < zero && if_decided(|| -phase.clone() * &zero.int(2) <= phase.pi_like()).unwrap_or(true)
}

/// φ reduced to [0, π), rounded.
///
/// A phase in [0, π) is kept as it is, and one in [−π/2, 0) is read as the offset ψ below
/// π: φ = π + ψ (rounded here; [`PhaseTrig::reduced`] uses ψ itself, so that π − 10⁻¹⁰⁰ is
/// not π). Within two turns of π other phases are reduced modulo π as rounded at the
/// working precision, so that a phase given as the rounded π is exactly in phase. Beyond,
/// φ − kπ at the working precision would lose the bits of kπ below the last of φ (about
/// log2|φ| of them), so the angle is recovered from sin φ and cos φ instead, which both
/// types evaluate with an exact reduction of the argument.
pub fn reduced_angle<R: Real>(phase: &R) -> R {
    let pi = phase.pi_like();
    if below_pi(phase) {
        return phase.clone() + &pi;
    }
    let reduced = if phase.abs() <= pi.clone() * &pi.int(2) {
        let turns = (phase.clone() / &pi).floor();
        phase.clone() - &(turns * &pi)
    } else {
        let (sin, cos) = phase.sin_cos();
        let angle = sin.atan2(&cos);
        if angle < phase.int(0) {
            angle + &pi
        } else {
            angle
        }
    };
    // Guard the rounding of the last step: keep the result inside [0, π).
    if reduced < phase.int(0) || reduced >= pi {
        phase.int(0)
    } else {
        reduced
    }
}

/// sin φ, cos φ, sin²(φ/2) and cos²(φ/2) of an angle, the half-angle squares for
/// 1 ∓ cos φ without cancellation near 0 and π.
#[derive(Clone, Debug)]
pub struct PhaseTrig<R> {
    /// sin φ.
    pub sin: R,
    /// cos φ.
    pub cos: R,
    /// sin²(φ/2) = (1 − cos φ)/2.
    pub half_sin_squared: R,
    /// cos²(φ/2) = (1 + cos φ)/2.
    pub half_cos_squared: R,
}

impl<R: Real> PhaseTrig<R> {
    /// Of the angle φ.
    pub fn of(phi: &R) -> Self {
        let (sin, cos) = phi.sin_cos();
        let (half_sin, half_cos) = (phi.clone() / &phi.int(2)).sin_cos();
        PhaseTrig {
            sin,
            cos,
            half_sin_squared: half_sin.square(),
            half_cos_squared: half_cos.square(),
        }
    }

    /// Of φ reduced to [0, π): for a phase in [−π/2, 0), read as the offset ψ below π,
    /// from ψ itself, so that each is accurate where it is small.
    pub fn reduced(phase: &R) -> Self {
        if below_pi(phase) {
            Self::below_pi(phase)
        } else {
            Self::of(&reduced_angle(phase))
        }
    }

    /// Of π + ψ, from the offset ψ itself (exact where π + ψ would round to π).
    fn below_pi(offset: &R) -> Self {
        let PhaseTrig {
            sin,
            cos,
            half_sin_squared,
            half_cos_squared,
        } = Self::of(offset);
        PhaseTrig {
            sin: -sin,
            cos: -cos,
            half_sin_squared: half_cos_squared,
            half_cos_squared: half_sin_squared,
        }
    }
}

/// A load cycle the theory covers, checked once by [`ValidCycle::new`]; it reads as the
/// [`LoadCycle`] it holds.
#[derive(Clone, Debug)]
pub struct ValidCycle<R> {
    cycle: LoadCycle<R>,
    kind: CycleKind,
}

impl<R: Real> ValidCycle<R> {
    /// The cycle, if it is finite, compressive, within the friction cone throughout, with
    /// physical f and λ ([`LoadCycle::validate`] says which condition fails).
    pub fn new(cycle: LoadCycle<R>) -> Result<Self, CycleError> {
        cycle.validate()?;
        let kind = cycle.classify();
        Ok(ValidCycle { cycle, kind })
    }

    /// Which case the cycle is.
    pub fn kind(&self) -> CycleKind {
        self.kind
    }

    /// The points E, B, C, H of its ellipse (for φ reduced to [0, π)). Defined for every
    /// valid cycle: where P1 = 0 or Q1 = 0, BC and CH have length 0.
    pub fn geometry(&self) -> EllipseGeometry<R> {
        EllipseGeometry::new(&self.cycle)
    }

    /// The loads.
    pub fn into_inner(self) -> LoadCycle<R> {
        self.cycle
    }
}

impl<R: Real> TryFrom<LoadCycle<R>> for ValidCycle<R> {
    type Error = CycleError;

    /// [`ValidCycle::new`].
    fn try_from(cycle: LoadCycle<R>) -> Result<Self, CycleError> {
        ValidCycle::new(cycle)
    }
}

impl<R> Deref for ValidCycle<R> {
    type Target = LoadCycle<R>;

    fn deref(&self) -> &LoadCycle<R> {
        &self.cycle
    }
}

/// The points E, B, C, H of the ellipse and the loads that govern each segment,
/// for the cycle with its phase reduced to [0, π).
#[derive(Clone, Debug)]
pub struct EllipseGeometry<R> {
    /// P0.
    pub mean_normal_load: R,
    /// P1.
    pub normal_amplitude: R,
    /// Q1.
    pub tangential_amplitude: R,
    /// φ reduced to [0, π).
    pub phase: R,
    /// f.
    pub friction: R,
    /// σ₊, the amplitude of Q + fP.
    pub sum_amplitude: R,
    /// σ₋, the amplitude of Q − fP.
    pub difference_amplitude: R,
    /// θ_E ∈ [0, π]: Q − fP is largest.
    pub theta_e: R,
    /// θ_B = θ_C − δ: Q + fP is smallest.
    pub theta_b: R,
    /// θ_C = θ_E + π: Q − fP is smallest.
    pub theta_c: R,
    /// θ_H = θ_C + δ: the mirror of B about C.
    pub theta_h: R,
    /// δ = θ_C − θ_B, the length of BC and of CH in θ.
    pub stick_angle: R,
    /// π − δ, the length of EB and of HE in θ (computed directly, not by subtraction).
    pub slip_angle: R,
    /// P_T − P0 = −(σ₊ + σ₋)/(2f).
    pub permanent_stick_offset: R,
    /// P0 − P1, the lowest normal load: P0 minus P1 as the cycle holds them, or as read
    /// exactly by [`EllipseGeometry::with_lowest_normal_load`]. Near separation the loads
    /// at the bottom of the cycle are formed from it, and keep its relative accuracy.
    pub lowest_normal_load: R,
    /// P0 − P1 − P_T = (σ₊ + σ₋)/(2f) − P1 ≥ 0, how far the permanent-stick load lies
    /// below the lowest normal load, formed without the cancellation of its definition
    /// (`stick_load_depth`), so that P_T ≤ P0 − P1 is as accurate as both near separation.
    pub stick_load_depth: R,
    /// (sin φ, cos φ), for Q at angles whose sine and cosine are known.
    pub phase_sin_cos: (R, R),
    /// (sin θ_C, cos θ_C), for P at θ_C ± s.
    pub theta_c_sin_cos: (R, R),
    /// (sin θ_B, cos θ_B), for the angles of EB measured from B.
    pub theta_b_sin_cos: (R, R),
    /// (sin θ_E, cos θ_E), for the angles of HE measured from E.
    pub theta_e_sin_cos: (R, R),
    /// (sin θ_H, cos θ_H).
    pub theta_h_sin_cos: (R, R),
    /// (sin δ, cos δ) of the stick angle δ = θ_C − θ_B.
    pub stick_sin_cos: (R, R),
    /// (sin, cos) of half the slip angle, (π − δ)/2.
    pub half_slip_sin_cos: (R, R),
}

impl<R: Real> EllipseGeometry<R> {
    fn new(cycle: &LoadCycle<R>) -> Self {
        let phi = cycle.reduced_phase();
        let trig = cycle.phase_trig();
        let (sum_amplitude, difference_amplitude) = cycle.slip_line_amplitudes_at(&trig);
        let q1 = cycle.tangential_amplitude.clone();
        let fp1 = cycle.friction.clone() * &cycle.normal_amplitude;
        let q1_sin = q1.clone() * &trig.sin;
        let pi = phi.pi_like();
        let difference_offset = cycle.difference_line_offset(&trig);
        let theta_e = q1_sin.atan2(&difference_offset);
        // δ = θ_E − θ_A, the angle between (Q1 cos φ + fP1, Q1 sin φ) and (Q1 cos φ − fP1, Q1 sin φ),
        // from their cross and dot products, formed with the loads scaled to at most 1 so
        // that products of loads near the top of the range cannot overflow.
        let largest = q1.max_of(&fp1).max_of(&phi.epsilon_like());
        let (q, p) = (q1.clone() / &largest, fp1.clone() / &largest);
        let cross = q.clone() * &trig.sin * &p * &phi.int(2);
        let dot = (q.clone() - &p) * &(q + &p);
        let stick_angle = cross.atan2(&dot);
        let slip_angle = cross.atan2(&(-dot.clone()));
        let theta_e_sin_cos = direction_sin_cos(&q1_sin, &difference_offset, &theta_e);
        let stick_sin_cos = direction_sin_cos(&cross, &dot, &stick_angle);
        let theta_c = theta_e.clone() + &pi;
        let theta_b = theta_c.clone() - &stick_angle;
        let theta_h = theta_c.clone() + &stick_angle;
        let permanent_stick_offset =
            -((sum_amplitude.clone() + &difference_amplitude) / &(cycle.friction.clone() * &phi.int(2)));
        let lowest_normal_load = cycle.mean_normal_load.clone() - &cycle.normal_amplitude;
        let stick_load_depth =
            stick_load_depth(&sum_amplitude, &difference_amplitude, &q1, &fp1, &trig.sin) / &cycle.friction;
        let phase_sin_cos = (trig.sin, trig.cos);
        // θ_C = θ_E + π and θ_B = θ_C − δ by the addition formulas, free of the rounding
        // of the angles themselves, which near the bottom of the cycle (θ ≈ π) is large
        // against their sines.
        let theta_c_sin_cos = (-theta_e_sin_cos.0.clone(), -theta_e_sin_cos.1.clone());
        let ((c_sin, c_cos), (d_sin, d_cos)) = (&theta_c_sin_cos, &stick_sin_cos);
        let (sin_part, cos_part) = (c_sin.clone() * d_cos, c_cos.clone() * d_sin);
        let (cos_a, sin_b) = (c_cos.clone() * d_cos, c_sin.clone() * d_sin);
        let theta_b_sin_cos = (sin_part.clone() - &cos_part, cos_a.clone() + &sin_b);
        let theta_h_sin_cos = (sin_part + &cos_part, cos_a - &sin_b);
        let half_slip_sin_cos = slip_angle.clone().times_power_of_two(-1).sin_cos();
        EllipseGeometry {
            phase_sin_cos,
            theta_c_sin_cos,
            theta_b_sin_cos,
            theta_e_sin_cos,
            theta_h_sin_cos,
            stick_sin_cos,
            mean_normal_load: cycle.mean_normal_load.clone(),
            normal_amplitude: cycle.normal_amplitude.clone(),
            tangential_amplitude: q1,
            phase: phi,
            friction: cycle.friction.clone(),
            sum_amplitude,
            difference_amplitude,
            theta_e,
            theta_b,
            theta_c,
            theta_h,
            stick_angle,
            slip_angle,
            permanent_stick_offset,
            lowest_normal_load,
            stick_load_depth,
            half_slip_sin_cos,
        }
    }

    /// The same geometry with the lowest normal load P0 − P1 given by the caller: read
    /// exactly from the decimals (enclosed, in intervals, by the two doubles around
    /// it), where P0 − P1 formed from the rounded P0 and P1 would carry their rounding
    /// amplified P0/(P0 − P1)-fold.
    pub fn with_lowest_normal_load(self, lowest_normal_load: R) -> Self {
        EllipseGeometry {
            lowest_normal_load,
            ..self
        }
    }

    /// P_T, the permanent-stick load, as P0 − P1 − [`EllipseGeometry::stick_load_depth`]:
    /// accurate where P_T is small (it is at most P0 − P1).
    pub fn permanent_stick_load(&self) -> R {
        self.lowest_normal_load.clone() - &self.stick_load_depth
    }

    /// P(θ) − P0 = P1 cos θ.
    pub fn normal_offset(&self, theta: &R) -> R {
        self.normal_amplitude.clone() * &theta.cos()
    }

    /// dP/dθ = −P1 sin θ.
    pub fn normal_rate(&self, theta: &R) -> R {
        -(self.normal_amplitude.clone() * &theta.sin())
    }

    /// Q(θ) − Q0 = Q1 cos(θ − φ).
    pub fn tangential_offset(&self, theta: &R) -> R {
        self.tangential_amplitude.clone() * &(theta.clone() - &self.phase).cos()
    }

    /// dQ/dθ = −Q1 sin(θ − φ).
    pub fn tangential_rate(&self, theta: &R) -> R {
        -(self.tangential_amplitude.clone() * &(theta.clone() - &self.phase).sin())
    }

    /// P_S − P0 in segment EB, given sin(h) with h half the angle from B, (θ − θ_B)/2:
    /// P_S = ½(Q/f + P − Q_E/f + P_E) = P_T + σ₊ sin²h/f (errata item 2: no u₀).
    pub fn reverse_slip_offset(&self, half_angle_sin: &R) -> R {
        self.permanent_stick_offset.clone() + &(self.sum_amplitude.clone() * &half_angle_sin.square() / &self.friction)
    }

    /// P_K − P0 in segment HE, given sin(h) with h half the angle from E, (θ − θ_E)/2:
    /// P_K = P_T + ½(P − Q/f − P_E + Q_E/f) = P_T + σ₋ sin²h/f.
    pub fn forward_slip_offset(&self, half_angle_sin: &R) -> R {
        self.permanent_stick_offset.clone()
            + &(self.difference_amplitude.clone() * &half_angle_sin.square() / &self.friction)
    }

    /// The loads at an angle θ given by (sin θ, cos θ): P − P0, dP/dθ, Q − Q0 and dQ/dθ,
    /// each formed when asked.
    pub fn loads_at<'g>(&'g self, sin_cos: &'g (R, R)) -> LoadsAt<'g, R> {
        LoadsAt {
            geometry: self,
            sin: &sin_cos.0,
            cos: &sin_cos.1,
        }
    }

    /// The mirror map Y of Eq. (15): the point of BC with Q_Y − fP_Y = Q − fP,
    /// θ_Y = 2θ_C − θ.
    pub fn mirror(&self, theta: &R) -> R {
        self.theta_c.clone() * &theta.int(2) - theta
    }
}

/// (sin, cos) of `angle` = atan2(y, x), as (y, x)/hypot(x, y): as accurate as y and x,
/// where the sine of the rounded angle is not (a sine near 0 at an angle near π); the
/// angle's own where hypot(x, y) is 0 or below the doubles.
fn direction_sin_cos<R: Real>(y: &R, x: &R, angle: &R) -> (R, R) {
    let radius = x.hypot(y);
    if radius.to_f64_lossy() > 0.0 {
        (y.clone() / &radius, x.clone() / &radius)
    } else {
        angle.sin_cos()
    }
}

/// (σ₊ + σ₋)/2 − fP1 ≥ 0 (with `p` = fP1 and `sin` = sin φ), from
/// ((σ₊ + σ₋)/2)² − p² = (σ₊σ₋ − (p² − Q1²))/2 and, for p > Q1,
/// σ₊σ₋ − (p² − Q1²) = 4Q1²p² sin²φ/(σ₊σ₋ + p² − Q1²) ((σ₊σ₋)² = (Q1² + p²)² − 4Q1²p² cos²φ):
/// sums of terms of one sign, where the definition cancels to a difference of size Q1²/p.
/// Both forms hold wherever they are defined; a double decides which is taken.
fn stick_load_depth<R: Real>(plus: &R, minus: &R, q1: &R, p: &R, sin: &R) -> R {
    let zero = p.int(0);
    let half_sum = (plus.clone() + minus).times_power_of_two(-1);
    if half_sum == zero {
        // σ₊ = σ₋ = 0: Q1 = fP1 = 0.
        return zero;
    }
    let product = plus.clone() * minus;
    let squares = (p.clone() - q1) * &(p.clone() + q1);
    let excess = if p.to_f64_lossy() > q1.to_f64_lossy() {
        (q1.clone() * p * sin).square().times_power_of_two(2) / &(product + &squares)
    } else {
        product - &squares
    };
    excess.times_power_of_two(-1) / &(half_sum + p)
}

/// The loads and their rates at one angle of the cycle, from its sine and cosine. Each is
/// formed only when asked: an integrand on balls pays for every product it forms, and no
/// segment needs all four.
#[derive(Clone, Debug)]
pub struct LoadsAt<'g, R> {
    geometry: &'g EllipseGeometry<R>,
    sin: &'g R,
    cos: &'g R,
}

impl<R: Real> LoadsAt<'_, R> {
    /// P − P0 = P1 cos θ.
    pub fn normal_offset(&self) -> R {
        self.geometry.normal_amplitude.clone() * self.cos
    }

    /// dP/dθ = −P1 sin θ.
    pub fn normal_rate(&self) -> R {
        -(self.geometry.normal_amplitude.clone() * self.sin)
    }

    /// Q − Q0 = Q1 cos(θ − φ), cos(θ − φ) by the subtraction formula.
    pub fn tangential_offset(&self) -> R {
        let (phase_sin, phase_cos) = &self.geometry.phase_sin_cos;
        let lag_cos = self.cos.clone() * phase_cos + &(self.sin.clone() * phase_sin);
        lag_cos * &self.geometry.tangential_amplitude
    }

    /// dQ/dθ = −Q1 sin(θ − φ), sin(θ − φ) by the subtraction formula.
    pub fn tangential_rate(&self) -> R {
        let (phase_sin, phase_cos) = &self.geometry.phase_sin_cos;
        let lag_sin = self.sin.clone() * phase_cos - &(self.cos.clone() * phase_sin);
        -(lag_sin * &self.geometry.tangential_amplitude)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cycle(phase: f64) -> LoadCycle<f64> {
        LoadCycle {
            mean_normal_load: 1.0,
            normal_amplitude: 0.4,
            mean_tangential_load: 0.1,
            tangential_amplitude: 0.5,
            phase,
            friction: 1.0,
            compliance_ratio: 1.0,
        }
    }

    /// The cycle at `phase`, validated, with its geometry.
    fn valid(phase: f64) -> (ValidCycle<f64>, EllipseGeometry<f64>) {
        let valid = ValidCycle::new(cycle(phase)).expect("a valid cycle");
        let geometry = valid.geometry();
        (valid, geometry)
    }

    /// (Q − fP, Q + fP) at θ.
    fn slip_lines(c: &LoadCycle<f64>, theta: f64) -> (f64, f64) {
        let (q, fp) = (c.tangential_load(&theta), c.friction * c.normal_load(&theta));
        (q - fp, q + fp)
    }

    #[test]
    fn tangent_points_are_the_extremes_of_the_slip_line_functions() {
        let (c, g) = valid(0.4 * std::f64::consts::PI);
        let minus = |t: f64| slip_lines(&c, t).0;
        let plus = |t: f64| slip_lines(&c, t).1;
        let h = 1e-4;
        for (theta, func, is_max) in [
            (g.theta_e, &minus as &dyn Fn(f64) -> f64, true),
            (g.theta_c, &minus, false),
            (g.theta_b, &plus, false),
        ] {
            let (l, m, r) = (func(theta - h), func(theta), func(theta + h));
            if is_max {
                assert!(m > l && m > r);
            } else {
                assert!(m < l && m < r);
            }
        }
        // H lies on the line of slope f through B.
        assert!((minus(g.theta_h) - minus(g.theta_b)).abs() < 1e-14);
        assert!(g.theta_e < g.theta_b && g.theta_b < g.theta_c && g.theta_c < g.theta_h);
        assert!(g.theta_h < g.theta_e + 2.0 * std::f64::consts::PI);
        // P_T from the two extremes directly.
        let pt = 0.5 * (plus(g.theta_b) - minus(g.theta_e)) / c.friction;
        assert!((pt - g.permanent_stick_load()).abs() < 1e-14);
        assert!((c.permanent_stick_load() - pt).abs() < 1e-14);
    }

    #[test]
    fn mirror_point_and_slip_loads_satisfy_their_defining_equations() {
        let (c, g) = valid(0.3 * std::f64::consts::PI);
        let minus = |t: f64| slip_lines(&c, t).0;
        let plus = |t: f64| slip_lines(&c, t).1;
        let (p_e, q_e) = (c.normal_load(&g.theta_e), c.tangential_load(&g.theta_e));
        for t in [0.1, 0.5, 0.9] {
            // Y (Eq. 15) for a point of CH.
            let theta = g.theta_c + t * g.stick_angle;
            assert!((minus(g.mirror(&theta)) - minus(theta)).abs() < 1e-14);
            // P_S (Eq. 11 without u0) for a point of EB; P_K (Eq. 18) for a point of HE.
            let theta = g.theta_e + t * g.slip_angle;
            let p_s = 0.5 * (plus(theta) - (q_e - c.friction * p_e)) / c.friction;
            let half = ((theta - g.theta_b) / 2.0).sin();
            assert!((g.mean_normal_load + g.reverse_slip_offset(&half) - p_s).abs() < 1e-14);
            let theta = g.theta_h + t * g.slip_angle;
            let p_k = g.permanent_stick_load() + 0.5 * ((q_e - c.friction * p_e) - minus(theta)) / c.friction;
            let half = ((theta - g.theta_e) / 2.0).sin();
            assert!((g.mean_normal_load + g.forward_slip_offset(&half) - p_k).abs() < 1e-14);
        }
    }

    /// P_T's depth below P0 − P1 and the sines and cosines of E, B, C, H, formed without
    /// cancellation in f64, against their definitions at 300 bits: near separation (P_T and
    /// θ_B − π both small) and on an ordinary cycle.
    #[test]
    fn the_stick_depth_and_the_angles_sines_keep_their_relative_accuracy() {
        use crate::real::Precision;
        use rug::Float;
        let p = Precision::bits(300);
        for (p1, q1, phase) in [(1.0 - 1e-9, 5e-10, 1.2), (0.4, 0.5, 1.25), (0.4, 0.3, 0.3)] {
            let cycle = LoadCycle {
                normal_amplitude: p1,
                tangential_amplitude: q1,
                mean_tangential_load: 0.0,
                ..cycle(phase)
            };
            let g = ValidCycle::new(cycle.clone()).unwrap().geometry();
            let precise = ValidCycle::new(cycle.map(|x| Float::from_f64(x, p)))
                .unwrap()
                .geometry();
            let depth =
                (precise.sum_amplitude.clone() + &precise.difference_amplitude) / 2u32 - &precise.normal_amplitude;
            let close = |name: &str, found: f64, expected: &Float| {
                let error = (Float::with_val(300, found) - expected).abs() / expected.clone().abs();
                assert!(error < 1e-13, "P1 = {p1}, {name}: {found:e} against {expected:e}");
            };
            close("P0 − P1 − P_T", g.stick_load_depth, &depth);
            for (name, (sin, cos), angle) in [
                ("θ_E", &g.theta_e_sin_cos, &precise.theta_e),
                ("θ_B", &g.theta_b_sin_cos, &precise.theta_b),
                ("θ_C", &g.theta_c_sin_cos, &precise.theta_c),
                ("θ_H", &g.theta_h_sin_cos, &precise.theta_h),
            ] {
                let (expected_sin, expected_cos) = angle.clone().sin_cos(Float::new(300));
                close(name, *sin, &expected_sin);
                close(name, *cos, &expected_cos);
            }
        }
    }

    #[test]
    fn phase_reduces_modulo_pi() {
        let c = cycle(0.4 * std::f64::consts::PI + 3.0 * std::f64::consts::PI);
        assert!((c.reduced_phase() - 0.4 * std::f64::consts::PI).abs() < 1e-14);
        let c = cycle(-0.25 * std::f64::consts::PI);
        assert!((c.reduced_phase() - 0.75 * std::f64::consts::PI).abs() < 1e-14);
    }

    #[test]
    fn near_pi_the_geometry_comes_from_the_offset() {
        use crate::real::Precision;
        use rug::Float;
        let cycle_at = |phase: Float| {
            let bits = Precision::bits(phase.prec());
            let number = |x: f64| Float::from_f64(x, bits);
            LoadCycle {
                mean_normal_load: number(1.0),
                normal_amplitude: number(0.5),
                mean_tangential_load: number(0.0),
                // fP1 − Q1 = 2⁻⁷⁰, exact at both precisions: σ₊ ≈ 8.5e−22 comes from the phase alone.
                tangential_amplitude: number(0.5) - number(2f64.powi(-70)),
                phase,
                friction: number(1.0),
                compliance_ratio: number(1.0),
            }
        };
        // The offset ψ = −1e−30 at 200 bits, against φ = π − 1e−30 itself at 600 bits.
        let offset = Float::parse_decimal("-1e-30", Precision::bits(200)).unwrap();
        let near = ValidCycle::new(cycle_at(offset)).unwrap().geometry();
        let p = Precision::bits(600);
        let phase = Float::pi(p) - Float::parse_decimal("1e-30", p).unwrap();
        let exact = ValidCycle::new(cycle_at(phase)).unwrap().geometry();
        for (name, a, b) in [
            ("σ₊", &near.sum_amplitude, &exact.sum_amplitude),
            ("σ₋", &near.difference_amplitude, &exact.difference_amplitude),
            ("θ_E", &near.theta_e, &exact.theta_e),
            ("δ", &near.stick_angle, &exact.stick_angle),
            ("π − δ", &near.slip_angle, &exact.slip_angle),
            ("P_T", &near.permanent_stick_offset, &exact.permanent_stick_offset),
        ] {
            let relative = (Float::with_val(600, a) - b).abs() / b.clone().abs();
            assert!(relative < 1e-55, "{name}: {a} vs {b}");
        }
        // π − δ ≈ 2 Q1 fP1 sin φ/((fP1)² − Q1²) = 5.9e−10: small, but not 0.
        assert!(near.slip_angle < 1e-9 && near.slip_angle > 1e-10, "{}", near.slip_angle);
    }
}
