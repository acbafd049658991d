//! The four segment integrands in the cycle angle (proofs/four-segment.md).
//!
//! Each integrand takes s, the angle from the start of its segment, and returns
//! (Q − Q0)·ψ(θ) with du/dθ = λψ, so that W = λ Σ ∫ (Q − Q0) ψ ds:
//!
//! ```text
//! EB  ψ = −f v'(P) P' + v'(P_S) σ₊ sin(θ − θ_B)
//! BC  ψ = v'(P) Q'
//! CH  ψ =  f v'(P) P' − v'(P_Y) σ₋ sin(θ − θ_E)
//! HE  ψ =  f v'(P) P' − v'(P_K) σ₋ sin(θ − θ_E)
//! ```

use super::driver::Integral;
use super::slope_at;
use crate::compliance::Compliance;
use crate::cycle::EllipseGeometry;
use crate::real::Real;

/// The segment names in cycle order; a piece's `segment` indexes this.
pub const SEGMENT_NAMES: [&str; 4] = ["EB", "BC", "CH", "HE"];

/// The integrands of one cycle on one compliance.
pub struct SegmentIntegrands<'a, R> {
    /// The cycle's ellipse.
    pub geometry: &'a EllipseGeometry<R>,
    /// The compliance.
    pub compliance: &'a dyn Compliance<R>,
    /// Use v'(x) − v'(P0) in place of v'(x).
    pub remove_constant_slope: bool,
}

// Only references and a flag: copyable whatever R is.
impl<R> Clone for SegmentIntegrands<'_, R> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<R> Copy for SegmentIntegrands<'_, R> {}

impl<'a, R: Real> SegmentIntegrands<'a, R> {
    fn slope(&self, offset: &R) -> R {
        slope_at(
            self.compliance,
            &self.geometry.mean_normal_load,
            self.remove_constant_slope,
        )(offset)
    }

    /// f v'(P) dP/dθ, shared by EB (with the opposite sign), CH and HE.
    fn normal_term(&self, theta: &R) -> R {
        let g = self.geometry;
        g.friction.clone() * &self.slope(&g.normal_offset(theta)) * &g.normal_rate(theta)
    }

    /// The integrand of segment `index` (0 EB, 1 BC, 2 CH, 3 HE) at angle `s` from its start.
    pub fn integrand(&self, index: usize, s: &R) -> R {
        let g = self.geometry;
        match index {
            0 => {
                let theta = g.theta_e.clone() + s;
                let from_b = s.clone() - &g.slip_angle;
                let reverse = self.slope(&g.reverse_slip_offset(&from_b)) * &g.sum_amplitude * &from_b.sin();
                g.tangential_offset(&theta) * &(reverse - &self.normal_term(&theta))
            }
            1 => {
                let theta = g.theta_b.clone() + s;
                g.tangential_offset(&theta) * &self.slope(&g.normal_offset(&theta)) * &g.tangential_rate(&theta)
            }
            2 => {
                let theta = g.theta_c.clone() + s;
                let mirror = g.theta_c.clone() - s;
                // sin(θ − θ_E) = sin(π + s) = −sin s.
                let forward = self.slope(&g.normal_offset(&mirror)) * &g.difference_amplitude * &s.sin();
                g.tangential_offset(&theta) * &(self.normal_term(&theta) + &forward)
            }
            _ => {
                let theta = g.theta_h.clone() + s;
                let from_e = s.clone() - &g.slip_angle;
                let forward = self.slope(&g.forward_slip_offset(&from_e)) * &g.difference_amplitude * &from_e.sin();
                g.tangential_offset(&theta) * &(self.normal_term(&theta) - &forward)
            }
        }
    }

    /// Where segment `index` starts (in θ) and how long it is.
    pub fn extent(&self, index: usize) -> (&'a R, &'a R) {
        let g = self.geometry;
        match index {
            0 => (&g.theta_e, &g.slip_angle),
            1 => (&g.theta_b, &g.stick_angle),
            2 => (&g.theta_c, &g.stick_angle),
            _ => (&g.theta_h, &g.slip_angle),
        }
    }

    /// The integrals whose sum times λ is W: each segment split at its lowest-load points.
    pub fn pieces(&self) -> Vec<Integral<'a, R>> {
        let mut pieces = Vec::new();
        for (index, name) in SEGMENT_NAMES.iter().enumerate() {
            let breaks = self.lowest_load_points(index);
            for window in breaks.windows(2) {
                let integrands = *self;
                pieces.push(Integral {
                    name,
                    segment: index,
                    integrand: Box::new(move |s: &R| integrands.integrand(index, s)),
                    start: window[0].clone(),
                    end: window[1].clone(),
                });
            }
        }
        pieces
    }

    /// The break points 0 = s₀ < s₁ < … < L of a segment: the angles where P (and,
    /// for CH, P at the mirror point θ_C − s) is least, θ ≡ π (mod 2π). A compliance
    /// singular at P → 0 is nearly singular there when the cycle nears separation,
    /// and a break puts the trouble at an end of a piece.
    fn lowest_load_points(&self, index: usize) -> Vec<R> {
        let (start, length) = self.extent(index);
        let zero = length.int(0);
        let pi = length.pi_like();
        let mut breaks = vec![zero.clone()];
        for k in -2..=3i64 {
            let lowest = pi.clone() * &pi.int(2 * k + 1);
            let mut candidates = vec![lowest.clone() - start];
            if index == 2 {
                candidates.push(self.geometry.theta_c.clone() - &lowest);
            }
            breaks.extend(candidates.into_iter().filter(|s| *s > zero && s < length));
        }
        breaks.push(length.clone());
        breaks.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        breaks
    }
}
