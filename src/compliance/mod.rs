//! Normal compliance v(P): the rigid-body approach of the two bodies as a function
//! of the normal load, the only property of the rough contact the dissipation needs.
//!
//! The dissipation depends on v only through v'(P) (and, at small amplitude,
//! v''(P0)). Physical compliances have v' > 0 and v'' ≤ 0 (the contact stiffens
//! as it is pressed); [`check_admissible`] tests that over a load range. The
//! dissipation functional itself is linear in v' and accepts any smooth v', which
//! the verification suite uses (e.g. v' = P − P0 for the small-amplitude coefficient).
//!
//! A compliance is a family's struct (generic over the number type), a combination of
//! them, or the SPEC text the command line reads, at any precision:
//!
//! ```
//! use microslip::compliance::{parse_spec, Compliance};
//! use microslip::real::Precision;
//!
//! // v' = 2·(1/P) + ½: at P = 2, v' = 3/2 and v'' = −2/P² = −½.
//! let v = parse_spec::<f64>("2*persson:gamma=1,sigma=1+const:c=0.5", Precision::DOUBLE)?;
//! assert_eq!(v.slope(&2.0), 1.5);
//! assert_eq!(v.curvature(&2.0), -0.5);
//! # Ok::<(), microslip::compliance::SpecError>(())
//! ```

mod combinators;
mod derivative_bounds;
pub(crate) use derivative_bounds::scaled_range;
mod families;
mod slope_form;
mod spec;
mod table;

pub use combinators::{LoadScaled, Scaled, Shifted, Sum};
pub use families::{Exponential, Hertz, Persson, Polynomial, PowerLaw, Rational};
pub use spec::{family_names, parse_spec, spec_help, spec_summary, ComplianceSpec, Family, SpecError, FAMILIES};
pub(crate) use table::column_name;
pub use table::{
    cached_table, ComplianceTable, Coordinates, TableColumn, TableCompliance, TableError, TableInterpolant, TABLE_ORDER,
};

use std::fmt::Debug;

use crate::real::Real;

/// x ↦ v'(P0 + x) − v'(P0) about a fixed P0 (see [`Compliance::slope_change_about`]).
pub type SlopeChange<'a, R> = Box<dyn Fn(&R) -> R + Send + Sync + 'a>;

/// x ↦ v(P0 + x) − v(P0) about a fixed P0 (see [`Compliance::approach_change_about`]).
pub type ApproachChange<'a, R> = Box<dyn Fn(&R) -> R + Send + Sync + 'a>;

/// A normal compliance function v(P) with its first two derivatives.
pub trait Compliance<R: Real>: Debug + Send + Sync {
    /// v(P), the normal approach under load P (defined up to an additive constant).
    fn approach(&self, load: &R) -> R;
    /// v'(P), the incremental normal compliance (inverse of the contact stiffness).
    fn slope(&self, load: &R) -> R;
    /// v''(P).
    fn curvature(&self, load: &R) -> R;
    /// v'(reference + offset) − v'(reference).
    ///
    /// The dissipation integrals use this difference: a constant part of v' does
    /// not dissipate, and removing it before integrating keeps small-amplitude
    /// results from cancelling away. Families with a closed form override it to
    /// compute the difference without cancellation.
    fn slope_change(&self, reference: &R, offset: &R) -> R {
        self.slope(&(reference.clone() + offset)) - self.slope(reference)
    }
    /// x ↦ v'(reference + x) − v'(reference), prepared once for many offsets x
    /// (the dissipation integrals evaluate it thousands of times about one P0).
    /// Families override it to hoist what does not depend on x.
    fn slope_change_about<'a>(&'a self, reference: &R) -> SlopeChange<'a, R> {
        let reference = reference.clone();
        Box::new(move |offset: &R| self.slope_change(&reference, offset))
    }
    /// x ↦ v(reference + x) − v(reference) in a form free of cancellation at small x,
    /// prepared once for many offsets x (the harmonic-balance element evaluates its virgin
    /// curve, such a difference, hundreds of times per call about one P). `None` for a
    /// compliance without one: a caller then differences v where x is large and integrates
    /// v' where it is small.
    fn approach_change_about<'a>(&'a self, reference: &R) -> Option<ApproachChange<'a, R>> {
        let _ = reference;
        None
    }
    /// v'(scale·root²): v' at a load given as a positive scale times a square, as the
    /// bottom of a cycle near separation gives it (the lowest load δ times cosh²u).
    /// On a complex ball the enclosure of root² may hold 0 where root's does not, so a
    /// family singular at P = 0 divides by root itself (or raises it to a power), which
    /// keeps its enclosure finite wherever root's keeps away from 0 (and, for a power,
    /// from its branch cut).
    fn slope_at_scaled_square(&self, scale: &R, root: &R) -> R {
        self.slope(&(root.square() * scale))
    }
    /// The load over which v' decays by a factor e, for a compliance with a load scale
    /// of its own (the exponential's c); `None` for one whose only load scale is the
    /// load itself (the power laws, Persson's, a polynomial). Where it is shorter than
    /// the cycle's lowest load, the integrands of W peak within about √(2c/P1) rad of
    /// every lowest load, and the quadrature maps peaks of that width.
    fn decay_load(&self) -> Option<R> {
        None
    }
    /// The loads where v' is not analytic (the knots of an interpolant, where its
    /// derivatives jump), at the precision of `like`, increasing; none for the analytic
    /// families. The dissipation integrals split at the angles where a load crosses
    /// one, since a quadrature rule converges geometrically only on smooth pieces.
    fn breakpoints(&self, like: &R) -> Vec<R> {
        let _ = like;
        Vec::new()
    }
    /// A short human-readable description, e.g. `power law v' = 1·P^-1`.
    fn describe(&self) -> String;
    /// Whether v' > 0 and v'' ≤ 0 at every load of [low, high] (0 < low ≤ high) follow from
    /// the family's form and parameters, v' and v'' being finite at both ends and monotone
    /// in between. `false` means "not known from the form": [`check_admissible`] then
    /// samples the range.
    fn admissible_by_form(&self, low: &R, high: &R) -> bool {
        let _ = (low, high);
        false
    }
    /// The derivative of v of order `order` at `load` (0: v, 1: v', 2: v'', …), from a
    /// closed form exact at the working precision, for the small-amplitude series at
    /// every order. `None` for a compliance that cannot give it.
    fn derivative(&self, order: usize, load: &R) -> Option<R> {
        match order {
            0 => Some(self.approach(load)),
            n => self.slope_derivative(n - 1, load),
        }
    }
    /// The derivative of v' of order `order` at `load` (0: v', 1: v'', …): what a family
    /// with closed-form derivatives gives [`Compliance::derivative`] beyond v itself.
    /// `None` for a compliance that cannot give it.
    fn slope_derivative(&self, order: usize, load: &R) -> Option<R> {
        let _ = (order, load);
        None
    }
    /// The least and the greatest value of v⁽ᵒʳᵈᵉʳ⁾ over [low, high] (order ≥ 2, as for
    /// [`Compliance::derivative`]), for the proven remainder of the small-amplitude series:
    /// on Arb balls every value lies between the lower end of the first and the upper end of
    /// the second. `None` where the form gives none (a table's interpolant, a range that
    /// reaches a singularity, an order below 2).
    fn derivative_range(&self, order: usize, low: &R, high: &R) -> Option<(R, R)> {
        let _ = (order, low, high);
        None
    }
    /// An upper bound on |v⁽ᵒʳᵈᵉʳ⁾| over [low, high], from [`Compliance::derivative_range`]:
    /// on Arb balls the upper end of the ball bounds it.
    fn derivative_bound(&self, order: usize, low: &R, high: &R) -> Option<R> {
        let (least, greatest) = self.derivative_range(order, low, high)?;
        Some(least.abs().max_of(&greatest.abs()))
    }
}

/// v' positive and finite and v'' finite at both ends of [low, high], with low > 0: for a
/// form whose v' and v'' are monotone, so throughout (v' does not underflow to 0 or
/// overflow in between).
pub(crate) fn regular_at_ends<R: Real>(compliance: &dyn Compliance<R>, low: &R, high: &R) -> bool {
    let zero = low.int(0);
    *low > zero
        && [low, high].into_iter().all(|load| {
            let slope = compliance.slope(load);
            slope.is_finite() && slope > zero && compliance.curvature(load).is_finite()
        })
}

/// The falling factorial β(β − 1)…(β − k + 1) at the precision of `beta`:
/// the k-th derivative of P^β is that times P^(β − k).
pub(crate) fn falling_factorial<R: Real>(beta: &R, k: usize) -> R {
    (0..k).fold(beta.int(1), |acc, j| acc * &(beta.clone() - &beta.int(j as i64)))
}

/// The breakpoints of several compliances together, increasing and without repeats.
pub(crate) fn merged_breakpoints<R: Real>(lists: impl IntoIterator<Item = Vec<R>>) -> Vec<R> {
    let mut all: Vec<R> = lists.into_iter().flatten().collect();
    all.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
    all.dedup();
    all
}

/// Why a compliance is not physical over a load range.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AdmissibilityError {
    /// v' ≤ 0 somewhere: the contact would not resist the load.
    #[error("the compliance has v'(P) = {slope:.4e} ≤ 0 at P = {load:.4e}: the contact would not resist the load; v' > 0 is needed on [{low:.4e}, {high:.4e}]")]
    NonPositiveSlope {
        /// The load where it happens.
        load: f64,
        /// v' there.
        slope: f64,
        /// The lower end of the load range that needs it.
        low: f64,
        /// The upper end of that range.
        high: f64,
    },
    /// v'' > 0 somewhere: the contact would soften as it is pressed.
    #[error("the compliance has v''(P) = {curvature:.4e} > 0 at P = {load:.4e}: the contact would soften as it is pressed; v'' ≤ 0 is needed on [{low:.4e}, {high:.4e}]")]
    PositiveCurvature {
        /// The load where it happens.
        load: f64,
        /// v'' there.
        curvature: f64,
        /// The lower end of the load range that needs it.
        low: f64,
        /// The upper end of that range.
        high: f64,
    },
    /// Neither admissibility nor its failure is settled near `load` by ball enclosures
    /// over up to `intervals` subintervals of the range.
    #[error("undecidable at this precision: whether v' > 0 and v'' ≤ 0 is not settled near P = {load:.4e} by ball enclosures over up to {intervals} subintervals of [{low:.4e}, {high:.4e}] (v'' or v' may touch 0 there); the theory needs both on that range")]
    Undecidable {
        /// A load near which it is not settled.
        load: f64,
        /// The lower end of the load range that needs it.
        low: f64,
        /// The upper end of that range.
        high: f64,
        /// The subintervals tried.
        intervals: usize,
    },
    /// v' or v'' is not a finite number somewhere.
    #[error("the compliance is not finite at P = {load:.4e} (v' = {slope:e}, v'' = {curvature:e}); finite v' and v'' are needed on [{low:.4e}, {high:.4e}]")]
    NotFinite {
        /// The load where it happens.
        load: f64,
        /// v' there.
        slope: f64,
        /// v'' there.
        curvature: f64,
        /// The lower end of the load range that needs it.
        low: f64,
        /// The upper end of that range.
        high: f64,
    },
}

/// Checks v' > 0 and v'' ≤ 0 over [low, high]: from the family's form where it decides
/// ([`Compliance::admissible_by_form`]), otherwise at 65 evenly spaced loads (both ends
/// included). There v'' is allowed a rounding-level excess over 0 so that a linear v
/// (v'' = 0 exactly) computed with rounding error still passes.
///
/// ```
/// use microslip::compliance::{check_admissible, AdmissibilityError, Persson, PowerLaw};
///
/// assert!(check_admissible(&Persson { gamma: 1.0, sigma: 1.0 }, &0.5, &1.5).is_ok());
/// // v' = P softens as it is pressed (v'' = 1 > 0).
/// let softening = PowerLaw { coefficient: 1.0, exponent: 1.0 };
/// let refused = check_admissible(&softening, &0.5, &1.5);
/// assert!(matches!(refused, Err(AdmissibilityError::PositiveCurvature { .. })));
/// ```
pub fn check_admissible<R: Real>(compliance: &dyn Compliance<R>, low: &R, high: &R) -> Result<(), AdmissibilityError> {
    const SAMPLES: i64 = 64;
    if compliance.admissible_by_form(low, high) {
        return Ok(());
    }
    let (low_f, high_f) = (low.to_f64_lossy(), high.to_f64_lossy());
    for i in 0..=SAMPLES {
        let load = low.clone() + &((high.clone() - low) * low.ratio(i, SAMPLES));
        let slope = compliance.slope(&load);
        let curvature = compliance.curvature(&load);
        let (load_f, slope_f, curvature_f) = (load.to_f64_lossy(), slope.to_f64_lossy(), curvature.to_f64_lossy());
        if !slope.is_finite() || !curvature.is_finite() {
            return Err(AdmissibilityError::NotFinite {
                load: load_f,
                slope: slope_f,
                curvature: curvature_f,
                low: low_f,
                high: high_f,
            });
        }
        if slope <= load.int(0) {
            return Err(AdmissibilityError::NonPositiveSlope {
                load: load_f,
                slope: slope_f,
                low: low_f,
                high: high_f,
            });
        }
        let tolerance = slope.abs() / load.abs().max_of(&load.epsilon_like()) * load.epsilon_like() * load.int(64);
        if curvature > tolerance {
            return Err(AdmissibilityError::PositiveCurvature {
                load: load_f,
                curvature: curvature_f,
                low: low_f,
                high: high_f,
            });
        }
    }
    Ok(())
}
