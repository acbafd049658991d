//! W, the hysteresis loop and the damping of a contact under any periodic load path
//! P(θ), Q(θ) given by its harmonics, force-driven, or P and the displacement u(θ) at
//! constant P, displacement-driven.
//!
//! In the spring-bed picture element s (its activation load) is in contact while P > s,
//! and with q = Q/f its memory is a play: Φ_s stays within [q − (P − s), q + (P − s)].
//! Written as F(s) = Φ_s − s, the whole memory is one function of s, clamped between
//! ξ₋/f = q − P and ξ₊/f − 2s = q + P − 2s; it changes only where ξ₋ rises past it
//! (forward slip), where ξ₊ falls past it (backward slip), and where P rises (elements
//! enter at F = ξ₋/f). The displacement follows as
//! dU = v'(P) dq + (v'(s₋) − v'(P)) dξ₋/f + (v'(s₊) − v'(P)) dξ₊/f, s± the slip fronts,
//! and W = λ f² ∮ q dU.
//!
//! proofs/periodic-loading.md derives this and checks it against the four segments,
//! Masing's rule and an independent spring-bed simulation.
//!
//! - [`input`]: the path from harmonics or from equally spaced samples, and its limits;
//! - [`events`]: the turning points of P, ξ₋ and ξ₊ and the steady cycle, split where a
//!   slip front's formula changes, each segment with its fronts' formulas;
//! - `memory`: the memory F(s) as pieces, its update over a monotone interval, and the
//!   fronts it places; values equal by construction carry their origin;
//! - [`dissipation`](mod@dissipation): W by the quadrature engine, in any [`Real`], and
//!   the integrand every segment's enclosure takes, in θ or a racing front's entry angle;
//! - `top`: where a front meets the top of the contact as P falls through elements that
//!   entered in stick, proven after the sampling that finds it;
//! - [`displacement`]: displacement driving at constant P (Masing's rules, rainflow W);
//! - [`outputs`]: amplitudes, loss factor, the harmonics of Q and u, and the loop;
//! - `proven` (feature `certified`, in `answer::path`): W as a rigorous enclosure up the one
//!   ladder: at constant P Masing over the rainflow cycles of Q or u, each cycle's W
//!   certified; where P varies the steady cycle's segments, each enclosed on the rule's
//!   complex boxes (`digits::enclosure::enclose_path_dissipation`);
//! - [`asked`]: a whole request as asked (file text, contact, drive, digits, budget), read
//!   at any precision, and why it may have no answer;
//!
//! The request answered (W proven where `proven` covers the path, else on agreement) is
//! the path's policy, in [`crate::answer::path`].

pub mod asked;
pub mod displacement;
pub mod dissipation;
pub mod events;
pub mod input;
mod memory;
pub mod outputs;
mod top;

pub use asked::{PathFormat, PathRequest, PathRequestError, RatioText};
pub use displacement::{displacement_dissipation, displacement_outputs, DisplacementCycle, MasingLaw};
pub use dissipation::{path_dissipation, PathDissipation};
pub use events::SteadyCycle;
pub use input::{Drive, LoadPath, PathError, TrigPoly, MAX_HARMONICS, MAX_SAMPLES};
pub use outputs::{path_outputs, LoopPoint, PathHarmonic, PathOutputs};

use crate::real::Real;

/// The contact's friction coefficient f and tangential/normal compliance ratio λ.
#[derive(Clone, Debug)]
pub struct Contact<R> {
    /// Coulomb friction coefficient f (> 0).
    pub friction: R,
    /// λ in [1, 2].
    pub compliance_ratio: R,
}

impl<R: Real> Contact<R> {
    /// Checks f > 0 and λ in [1, 2].
    pub fn validate(&self) -> Result<(), PathError> {
        let zero = self.friction.int(0);
        let positive = self.friction > zero;
        if !positive {
            return Err(PathError::Contact(format!(
                "the friction coefficient f = {} must be positive",
                self.friction.to_f64_lossy()
            )));
        }
        let in_range = self.compliance_ratio >= zero.int(1) && self.compliance_ratio <= zero.int(2);
        if !in_range {
            return Err(PathError::Contact(format!(
                "the compliance ratio λ = {} lies outside [1, 2]",
                self.compliance_ratio.to_f64_lossy()
            )));
        }
        Ok(())
    }
}
