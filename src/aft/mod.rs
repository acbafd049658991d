//! The friction force of a contact driven by a periodic tangential displacement, in the
//! harmonic-balance form a nonlinear vibration solver needs: the force's harmonics and
//! their exact derivative with respect to the displacement's harmonics (alternating
//! frequency–time, "AFT").
//!
//! At constant normal load P the tangential load–displacement relation of a contact with
//! normal compliance v(P) is Masing's, built on the virgin curve
//! u = g(Q) = λ f (v(P) − v(P − Q/f)), 0 ≤ Q ≤ fP (Cattaneo–Mindlin generalised by Jäger
//! and Ciavarella); a branch from a reversal (u_r, Q_r) is u = u_r ± 2 g(|Q − Q_r|/2),
//! a branch that meets an older one continues it, and |Q| ≤ fP (gross slip wipes the
//! memory). The contact starts unloaded, is loaded along the virgin curve to the sample
//! of largest |u|, and the steady loop is the period that starts there.
//!
//! [`aft`] samples u(t) at equally spaced times of one period, follows the relation
//! sample by sample, and returns the discrete Fourier coefficients of Q with the exact
//! Jacobian of that discrete map (the reversal points and the anchor are samples of u, so
//! the chain rule runs through them): Newton's method on the balance needs no finite
//! differences. proofs/aft.md derives the relation and records the checks.
//!
//! Under a periodic normal load P(t) (its harmonics in the displacement's layout),
//! [`aft_with_normal_load`] steps the spring bed of `microslip simulate` through the samples
//! instead, Masing's rules no longer holding, with the exact Jacobian of that discrete map;
//! a [`VaryingLoadElement`] whose load is constant is Masing's element.
//!
//! ```
//! use microslip::aft::{aft, FrictionElement};
//!
//! // A Hertz contact at P = 1, f = 0.5, λ = 1.2, driven by u = 1e-3·cos t.
//! let element = FrictionElement::from_spec(1.0, 0.5, 1.2, "hertz:r=1,estar=100")?;
//! let force = aft(&element, &[1], &[1e-3, 0.0], 128)?;
//! assert!(force.work_per_cycle() > 0.0);
//! assert_eq!(force.jacobian.len(), 4);
//! # Ok::<(), microslip::aft::AftError>(())
//! ```

mod backbone;
mod fourier;
mod masing;
mod normal_load;
mod spring_bed;
mod varying_load;

use crate::compliance::{check_admissible, parse_spec, AdmissibilityError, Compliance, SpecError};
use crate::real::Precision;

pub use fourier::MAX_TIME_POINTS;
pub use normal_load::{aft_with_normal_load, NormalLoad, VaryingLoadElement, DEFAULT_ELEMENTS};

/// Why an element cannot be built or a displacement not evaluated.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AftError {
    /// A parameter of the element outside its range.
    #[error("{quantity} = {value} {requirement}")]
    Parameter {
        /// The parameter, in words.
        quantity: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        requirement: &'static str,
    },
    /// The compliance SPEC does not parse.
    #[error(transparent)]
    Spec(#[from] SpecError),
    /// The compliance is not physical over the loads the slip zone reaches.
    #[error(transparent)]
    Inadmissible(#[from] AdmissibilityError),
    /// v(0) is not defined, so the displacement at gross slip is not either.
    #[error("the compliance has no approach v(0) at zero load (it gives {approach}); the slip zone reaches P = 0 at gross slip, so v must be defined there (finite or −∞)")]
    UndefinedApproach {
        /// v(0) as computed.
        approach: f64,
    },
    /// The harmonic numbers are not usable.
    #[error("{0}")]
    Harmonics(String),
    /// The displacement's harmonics do not match the harmonic numbers.
    #[error("the displacement has {given} harmonic coefficients but the harmonics {harmonics:?} need {expected} (U_0 for k = 0, then cos and sin for each k)")]
    DisplacementLength {
        /// The coefficients given.
        given: usize,
        /// The coefficients needed.
        expected: usize,
        /// The harmonic numbers.
        harmonics: Vec<usize>,
    },
    /// A displacement coefficient is not a finite number.
    #[error("displacement coefficient {index} is {value}: give finite numbers")]
    NotFinite {
        /// Its position in the displacement's harmonics.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// The displacement's samples overflow f64.
    #[error("the displacement overflows at time point {time_point} (u = {value}): give harmonics whose sum stays within f64's range")]
    Overflow {
        /// The time point where it first does.
        time_point: usize,
        /// The sample there.
        value: f64,
    },
    /// The normal load's harmonics do not match the harmonic numbers.
    #[error("the normal load has {given} harmonic coefficients but the harmonics {harmonics:?} need {expected} (in the displacement's order, added to p0)")]
    NormalLoadLength {
        /// The coefficients given.
        given: usize,
        /// The coefficients needed.
        expected: usize,
        /// The harmonic numbers.
        harmonics: Vec<usize>,
    },
    /// A normal-load coefficient is not a finite number.
    #[error("normal-load coefficient {index} is {value}: give finite numbers")]
    NormalLoadNotFinite {
        /// Its position in the normal load's harmonics.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// The normal load is not positive at a time point: the contact would separate.
    #[error("the normal load P = {load} at time point {time_point} is not positive (the contact separates): give p0 and normal harmonics that keep P above 0 over the whole period")]
    Separation {
        /// The first time point where it is not.
        time_point: usize,
        /// P there.
        load: f64,
    },
    /// Too few or too many time points for the harmonics.
    #[error("time_points = {given}: the harmonics up to k = {highest} need more than {} time points per period (at most {MAX_TIME_POINTS})", 2 * highest)]
    TimePoints {
        /// The time points asked for.
        given: usize,
        /// The highest harmonic number.
        highest: usize,
    },
}

/// A contact at constant normal load P with friction coefficient f, tangential/normal
/// compliance ratio λ and normal compliance v(P): the element whose tangential load
/// follows Masing's relation on the virgin curve g.
#[derive(Debug)]
pub struct FrictionElement {
    normal_load: f64,
    friction: f64,
    compliance_ratio: f64,
    compliance: Box<dyn Compliance<f64>>,
    /// v(P), the reference of every relief v(P) − v(P*) differenced from v.
    approach_at_load: f64,
    /// g(fP): the displacement of the virgin curve at gross slip (∞ where v(0) = −∞).
    gross_slip_displacement: f64,
    /// v''(P), for the curvature of a fresh branch.
    curvature_at_load: f64,
    /// Whether v' is analytic on (0, P] (no knots), so that a short relief is a quadrature.
    analytic: bool,
}

/// The smallest load, as a fraction of P, over which the compliance is checked: the slip
/// zone reaches below it only within a hair of gross slip.
const ADMISSIBLE_FROM: f64 = 1.0 / 1048576.0;

/// f > 0 finite and λ in [1, 2].
fn check_contact(friction: f64, compliance_ratio: f64) -> Result<(), AftError> {
    let refuse = |quantity, value, requirement| {
        Err(AftError::Parameter {
            quantity,
            value,
            requirement,
        })
    };
    if !(friction > 0.0 && friction.is_finite()) {
        return refuse("the friction coefficient f", friction, "must be positive and finite");
    }
    if !(1.0..=2.0).contains(&compliance_ratio) {
        return refuse("the compliance ratio λ", compliance_ratio, "lies outside [1, 2]");
    }
    Ok(())
}

impl FrictionElement {
    /// The element for P = `normal_load` > 0, f = `friction` > 0, λ = `compliance_ratio` in
    /// [1, 2] and a compliance admissible (v' > 0, v'' ≤ 0) on the loads the slip zone
    /// reaches, (0, P].
    pub fn new(
        normal_load: f64,
        friction: f64,
        compliance_ratio: f64,
        compliance: Box<dyn Compliance<f64>>,
    ) -> Result<Self, AftError> {
        if !(normal_load > 0.0 && normal_load.is_finite()) {
            return Err(AftError::Parameter {
                quantity: "the normal load P",
                value: normal_load,
                requirement: "must be positive and finite",
            });
        }
        check_contact(friction, compliance_ratio)?;
        check_admissible(compliance.as_ref(), &(normal_load * ADMISSIBLE_FROM), &normal_load)?;
        let approach_at_load = compliance.approach(&normal_load);
        let approach_at_zero = compliance.approach(&0.0);
        if approach_at_zero.is_nan() || approach_at_zero == f64::INFINITY || !approach_at_load.is_finite() {
            return Err(AftError::UndefinedApproach {
                approach: approach_at_zero,
            });
        }
        let analytic = compliance.breakpoints(&normal_load).is_empty();
        // v(P) − v(0) as the backbone forms its reliefs, so that g reaches it at fP.
        let relief_to_zero = match compliance.approach_change_about(&normal_load) {
            Some(change) => -change(&-normal_load),
            None => approach_at_load - approach_at_zero,
        };
        let gross_slip_displacement = compliance_ratio * friction * relief_to_zero;
        Ok(FrictionElement {
            normal_load,
            friction,
            compliance_ratio,
            approach_at_load,
            gross_slip_displacement,
            curvature_at_load: compliance.curvature(&normal_load),
            analytic,
            compliance,
        })
    }

    /// The element with the compliance given as a SPEC (`hertz:r=1,estar=1`, …).
    pub fn from_spec(normal_load: f64, friction: f64, compliance_ratio: f64, spec: &str) -> Result<Self, AftError> {
        let compliance = parse_spec::<f64>(spec, Precision::DOUBLE)?;
        FrictionElement::new(normal_load, friction, compliance_ratio, compliance)
    }

    /// The normal load P.
    pub fn normal_load(&self) -> f64 {
        self.normal_load
    }

    /// The friction limit fP of |Q|.
    pub fn friction_limit(&self) -> f64 {
        self.friction * self.normal_load
    }

    /// g(fP), the displacement of the virgin curve where gross slip begins (∞ for a
    /// compliance with v(0) = −∞, which never slides as a whole).
    pub fn gross_slip_displacement(&self) -> f64 {
        self.gross_slip_displacement
    }
}

/// The friction force of one displacement: its harmonics, their Jacobian, and the samples
/// of one period they come from.
#[derive(Clone, Debug, PartialEq)]
pub struct AftForce {
    /// The harmonic numbers, as given.
    pub harmonics: Vec<usize>,
    /// The displacement's harmonics, as given.
    pub displacement: Vec<f64>,
    /// The force's harmonics F, in the displacement's order.
    pub force: Vec<f64>,
    /// dF/dU, row-major: entry (i, j) at `i · n + j`, n the number of coefficients.
    pub jacobian: Vec<f64>,
    /// u(t_n) at the time points t_n = 2πn/N.
    pub displacement_samples: Vec<f64>,
    /// Q(t_n) at the time points.
    pub load_samples: Vec<f64>,
}

impl AftForce {
    /// The number of harmonic coefficients n (the side of the Jacobian).
    pub fn coefficients(&self) -> usize {
        self.force.len()
    }

    /// dF_i/dU_j.
    pub fn jacobian_entry(&self, i: usize, j: usize) -> f64 {
        self.jacobian[i * self.coefficients() + j]
    }

    /// W = ∮ Q du over the period, from the harmonics: π Σ_k k (U_sin,k F_cos,k − U_cos,k F_sin,k),
    /// which is the trapezoidal rule of ∫ Q u̇ dt on the samples.
    pub fn work_per_cycle(&self) -> f64 {
        fourier::work_per_cycle(&self.harmonics, &self.displacement, &self.force)
    }
}

/// The friction force's harmonics and their exact Jacobian for the tangential displacement
/// with harmonics `displacement`, ordered [U_0 (if `harmonics` holds 0), U_cos,k₁, U_sin,k₁,
/// U_cos,k₂, U_sin,k₂, …] for the strictly increasing harmonic numbers `harmonics`, on
/// `time_points` equal steps of one period (more than twice the highest harmonic).
pub fn aft(
    element: &FrictionElement,
    harmonics: &[usize],
    displacement: &[f64],
    time_points: usize,
) -> Result<AftForce, AftError> {
    let layout = fourier::Layout::cached(harmonics, time_points)?;
    let samples = sampled_displacement(&layout, harmonics, displacement)?;
    let steady = masing::steady_loop(element, &samples, &layout);
    Ok(AftForce {
        harmonics: harmonics.to_vec(),
        displacement: displacement.to_vec(),
        force: layout.analyze(&steady.load),
        jacobian: layout.analyze_gradients(&steady.gradient),
        displacement_samples: samples,
        load_samples: steady.load,
    })
}

/// u(t_n) at the layout's time points, the displacement's harmonics checked first: as many
/// as the layout has, finite, and samples within f64's range.
fn sampled_displacement(
    layout: &fourier::Layout,
    harmonics: &[usize],
    displacement: &[f64],
) -> Result<Vec<f64>, AftError> {
    if displacement.len() != layout.coefficients() {
        return Err(AftError::DisplacementLength {
            given: displacement.len(),
            expected: layout.coefficients(),
            harmonics: harmonics.to_vec(),
        });
    }
    if let Some((index, &value)) = displacement.iter().enumerate().find(|(_, value)| !value.is_finite()) {
        return Err(AftError::NotFinite { index, value });
    }
    let samples = layout.synthesize(displacement);
    if let Some((time_point, &value)) = samples.iter().enumerate().find(|(_, value)| !value.is_finite()) {
        return Err(AftError::Overflow { time_point, value });
    }
    Ok(samples)
}
