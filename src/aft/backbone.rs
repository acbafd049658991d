//! The virgin curve u = g(Q) = λ f (v(P) − v(P − Q/f)) and its inverse, the backbone every
//! Masing branch is a copy of (doubled in both directions).

use crate::compliance::{ApproachChange, SlopeChange};

use super::FrictionElement;

/// Gauss–Legendre nodes and weights of 6 points on [0, 1].
const NODES: [f64; 6] = [
    0.033_765_242_898_423_98,
    0.169_395_306_766_867_74,
    0.380_690_406_958_401_55,
    0.619_309_593_041_598_5,
    0.830_604_693_233_132_3,
    0.966_234_757_101_576,
];
const WEIGHTS: [f64; 6] = [
    0.085_662_246_189_585_17,
    0.180_380_786_524_069_3,
    0.233_956_967_286_345_5,
    0.233_956_967_286_345_5,
    0.180_380_786_524_069_3,
    0.085_662_246_189_585_17,
];

/// The longest relief, as a fraction of P, integrated from v' rather than differenced from
/// v: the nearest singularity of v' (at P = 0 for the power laws) then lies at least 15
/// half-lengths from the interval's centre, where 6 Gauss points reach f64's accuracy.
const INTEGRATED_UP_TO: f64 = 0.125;

/// The most steps of the safeguarded Newton iteration.
const MOST_STEPS: usize = 200;

/// A point of the virgin curve: the slip load y = Q (≥ 0) and the tangential stiffness
/// dQ/du = 1/g'(y) there.
#[derive(Clone, Copy, Debug)]
pub(super) struct SlipState {
    pub(super) load: f64,
    pub(super) stiffness: f64,
}

impl FrictionElement {
    /// u = g(Q) for 0 ≤ Q ≤ fP: the tangential displacement of first loading to Q.
    pub fn virgin_displacement(&self, load: f64) -> f64 {
        Backbone::of(self).displacement(load)
    }

    /// Q on the virgin curve at displacement u (of either sign): ±g⁻¹(|u|), or ±fP beyond
    /// gross slip.
    pub fn virgin_load(&self, displacement: f64) -> f64 {
        match Backbone::of(self).slip_state(displacement.abs()) {
            Some(state) => state.load.copysign(displacement),
            None => self.friction_limit().copysign(displacement),
        }
    }
}

/// The virgin curve of an element, with v' prepared about P for the many loads below it
/// that one period evaluates.
pub(super) struct Backbone<'a> {
    element: &'a FrictionElement,
    /// x ↦ v'(P + x) − v'(P).
    slope_change: SlopeChange<'a, f64>,
    /// v'(P).
    slope_at_load: f64,
    /// x ↦ v(P + x) − v(P) free of cancellation, where the compliance has that form.
    approach_change: Option<ApproachChange<'a, f64>>,
}

impl<'a> Backbone<'a> {
    pub(super) fn of(element: &'a FrictionElement) -> Self {
        let load = element.normal_load;
        Backbone {
            element,
            slope_change: element.compliance.slope_change_about(&load),
            slope_at_load: element.compliance.slope(&load),
            approach_change: element.compliance.approach_change_about(&load),
        }
    }

    /// g(y) = λ f (v(P) − v(P − y/f)).
    fn displacement(&self, load: f64) -> f64 {
        let element = self.element;
        element.compliance_ratio * element.friction * self.relief(load / element.friction)
    }

    /// g⁻¹(x) and the stiffness there for x ≥ 0, or `None` at or beyond gross slip
    /// (x ≥ g(fP)): the root of g(y) = x by Newton's method, safeguarded by bisection on
    /// [0, fP], to f64's accuracy.
    pub(super) fn slip_state(&self, displacement: f64) -> Option<SlipState> {
        self.slip_state_from(displacement, None)
    }

    /// [`Backbone::slip_state`] with Newton's method started from `guess` (a load near the
    /// root, such as the previous sample's on the same branch), or from the inverse's
    /// series without one.
    pub(super) fn slip_state_from(&self, displacement: f64, guess: Option<f64>) -> Option<SlipState> {
        if displacement >= self.element.gross_slip_displacement {
            return None;
        }
        let limit = self.element.friction_limit();
        let (mut low, mut high) = (0.0, limit);
        let mut load = match guess {
            Some(guess) if guess.is_finite() => guess.clamp(0.0, limit),
            _ => self.first_guess(displacement),
        };
        // The previous iterate and g' there, for the curvature that bounds the next error.
        let mut previous: Option<(f64, f64)> = None;
        for _ in 0..MOST_STEPS {
            let residual = self.displacement(load) - displacement;
            if residual == 0.0 {
                break;
            }
            if residual > 0.0 {
                high = load;
            } else {
                low = load;
            }
            let compliance = self.compliance_at(load);
            let step = residual / compliance;
            let newton = load - step;
            let next = if newton > low && newton < high {
                newton
            } else {
                low + 0.5 * (high - low)
            };
            // Newton's error after a step s is about |g''|/(2g')·s²: once that is below a
            // quarter of an ulp the step has reached f64's accuracy.
            let converged = previous.is_some_and(|(before, compliance_before): (f64, f64)| {
                let curvature = ((compliance - compliance_before) / (load - before)).abs();
                next == newton && curvature / (2.0 * compliance) * step * step <= 0.25 * f64::EPSILON * next.abs()
            });
            let settled = (next - load).abs() <= f64::EPSILON * load.abs() || high - low <= f64::EPSILON * high;
            previous = Some((load, compliance));
            load = next;
            if converged || settled {
                break;
            }
        }
        Some(SlipState {
            load,
            stiffness: 1.0 / self.compliance_at(load),
        })
    }

    /// The inverse's series to second order, y ≈ x/g'(0) − g''(0) x²/(2 g'(0)³), kept between
    /// the chord of g over [0, fP] (below the root: g is convex) and x/g'(0) (above it).
    fn first_guess(&self, displacement: f64) -> f64 {
        let element = self.element;
        let stiffness = 1.0 / (element.compliance_ratio * self.slope_at_load);
        let linear = displacement * stiffness;
        let curvature = -element.compliance_ratio / element.friction * element.curvature_at_load;
        let series = linear - 0.5 * curvature * stiffness * stiffness * stiffness * displacement * displacement;
        let chord = displacement / element.gross_slip_displacement * element.friction_limit();
        series.max(chord).min(linear).min(element.friction_limit())
    }

    /// g'(y) = λ v'(P − y/f), the tangential compliance of the virgin curve at slip load y.
    fn compliance_at(&self, load: f64) -> f64 {
        let depth = (load / self.element.friction).min(self.element.normal_load);
        self.element.compliance_ratio * self.slope_below(depth)
    }

    /// v'(P − d).
    fn slope_below(&self, depth: f64) -> f64 {
        self.slope_at_load + (self.slope_change)(&-depth)
    }

    /// v(P) − v(P − d) for 0 ≤ d ≤ P: from the compliance's form free of cancellation where
    /// it has one; otherwise integrated from v' for a short relief, where the difference of
    /// v would cancel, and differenced for a long one.
    fn relief(&self, depth: f64) -> f64 {
        let element = self.element;
        let load = element.normal_load;
        if let Some(change) = &self.approach_change {
            -change(&-depth.min(load))
        } else if element.analytic && depth <= INTEGRATED_UP_TO * load {
            let sum: f64 = NODES
                .iter()
                .zip(WEIGHTS)
                .map(|(t, w)| w * self.slope_below(depth * t))
                .sum();
            depth * sum
        } else {
            element.approach_at_load - element.compliance.approach(&(load - depth).max(0.0))
        }
    }
}
