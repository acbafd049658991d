//! The angles one evaluation of a segment's integrand takes: θ by its sine and cosine,
//! and each segment's own (the mirror point of CH, half the angle to a slip segment's
//! end), at a point in s or at a point of the bottom map, where every sine and cosine
//! is formed from the half-angle α to the lowest load rather than from an angle near π.

use super::plans::{rise_of, Bottom};
use super::{Segment, SegmentIntegrands};
use crate::quad::bottom_map::BottomPoint;
use crate::real::Real;

/// The angles one evaluation of a segment's integrand takes, with θ through its sine
/// and cosine, and 1 + cos θ, the rise P1(1 + cos θ) of P above P0 − P1 per unit P1,
/// where the loads are formed from the lowest load
/// ([`Slopes::at_loads`](super::Slopes::at_loads)) or the bottom map's form gives it
/// free; `None` elsewhere, where no load is formed from it.
pub(super) enum SegmentAngle<R> {
    /// BC.
    Stick {
        /// (sin θ, cos θ).
        theta: (R, R),
        /// 1 + cos θ.
        rise: Option<R>,
    },
    /// CH.
    Mirrored {
        /// (sin θ, cos θ).
        theta: (R, R),
        /// 1 + cos θ.
        rise: Option<R>,
        /// cos θ_Y at the mirror angle θ_Y = 2θ_C − θ.
        mirror_cos: R,
        /// 1 + cos θ_Y.
        mirror_rise: Option<R>,
        /// sin(θ − θ_C).
        from_c_sin: R,
    },
    /// EB and HE, with h half the angle to the segment's end.
    Slip {
        /// (sin θ, cos θ).
        theta: (R, R),
        /// 1 + cos θ.
        rise: Option<R>,
        /// sin h.
        half_sin: R,
        /// cos h (with sin h, up to a sign common to both).
        half_cos: R,
        /// sin 2h.
        double_sin: R,
    },
}

impl<'a, R: Real> SegmentIntegrands<'a, R> {
    /// (sin θ, cos θ) at θ = θ_C + s, and at the mirror point θ_Y = θ_C − s, from
    /// (sin s, cos s) by the addition formulas: one set of four products serves both.
    fn around_c(&self, s_sin_cos: &(R, R)) -> ((R, R), (R, R)) {
        let (c_sin, c_cos) = &self.geometry.theta_c_sin_cos;
        let (s_sin, s_cos) = s_sin_cos;
        let (sin_part, cos_part) = (c_sin.clone() * s_cos, c_cos.clone() * s_sin);
        let (cos_a, sin_b) = (c_cos.clone() * s_cos, c_sin.clone() * s_sin);
        let mirror = (sin_part.clone() - &cos_part, cos_a.clone() + &sin_b);
        ((sin_part + &cos_part, cos_a - &sin_b), mirror)
    }

    /// The angles of `segment` at angle `s` from its start, with 1 + cos θ where `rises`.
    // Inlined into each piece's integrand, as `integrand_at` is: as calls they cost an f64
    // run about 15 % (proofs/certified-digits.md, "The f64 default in process").
    #[inline(always)]
    pub(super) fn angle_at(&self, segment: Segment, s: &R, rises: bool) -> SegmentAngle<R> {
        let g = self.geometry;
        let rise = |theta: &(R, R)| rises.then(|| rise_of(theta));
        match segment {
            Segment::EB | Segment::HE => {
                // EB ends at B and HE at E (+2π): with h half the angle to that end,
                // h = (s − (π − δ))/2, the slip load reads sin²h and sin 2h, and θ is that
                // end plus 2h — one sin_cos serves both.
                let (half_sin, half_cos) = (s.clone() - &g.slip_angle).times_power_of_two(-1).sin_cos();
                let double_sin = (half_sin.clone() * &half_cos).times_power_of_two(1);
                let double_cos = s.int(1) - &half_sin.square().times_power_of_two(1);
                let (end_sin, end_cos) = self.slip_end_sin_cos(segment);
                let theta = (
                    end_sin.clone() * &double_cos + &(end_cos.clone() * &double_sin),
                    end_cos.clone() * &double_cos - &(end_sin.clone() * &double_sin),
                );
                SegmentAngle::Slip {
                    rise: rise(&theta),
                    theta,
                    half_sin,
                    half_cos,
                    double_sin,
                }
            }
            Segment::BC => {
                let theta = (g.theta_b.clone() + s).sin_cos();
                SegmentAngle::Stick {
                    rise: rise(&theta),
                    theta,
                }
            }
            Segment::CH => {
                // θ = θ_C + s, the mirror point θ_C − s; sin(θ − θ_E) = sin(π + s) = −sin s.
                let s_sin_cos = s.sin_cos();
                let (theta, mirror) = self.around_c(&s_sin_cos);
                SegmentAngle::Mirrored {
                    rise: rise(&theta),
                    mirror_rise: rise(&mirror),
                    theta,
                    mirror_cos: mirror.1,
                    from_c_sin: s_sin_cos.0,
                }
            }
        }
    }

    /// (sin, cos) of the end of a slip segment: B for EB, E for HE.
    fn slip_end_sin_cos(&self, segment: Segment) -> &'a (R, R) {
        if segment == Segment::EB {
            &self.geometry.theta_b_sin_cos
        } else {
            &self.geometry.theta_e_sin_cos
        }
    }

    /// The angles of `segment` at a point of a bottom map: θ = (2k + 1)π + 2α for the
    /// load the map is centred on, every sine and cosine formed as sums of products
    /// of sin α and cos α with the geometry's constants, so that the loads near the
    /// bottom never come from the cosine of an angle near π.
    pub(super) fn angle_near_bottom(
        &self,
        segment: Segment,
        bottom: &Bottom<R>,
        point: &BottomPoint<R>,
    ) -> SegmentAngle<R> {
        let g = self.geometry;
        let centred = (point.half_sin.clone(), point.half_cos.clone());
        // The mirror load's θ_Y = θ_C − s = (2k + 1)π − 2α: its half-angle is −α.
        let (half, mirror_half) = if bottom.mirror {
            let mirror = (-centred.0, centred.1);
            (self.reflect(&mirror), Some(mirror))
        } else {
            let mirror = (segment == Segment::CH).then(|| self.reflect(&centred));
            (centred, mirror)
        };
        let (half_sin, half_cos) = &half;
        // sin θ = −sin 2α, cos θ = −cos 2α = −1 + 2 sin²α: 1 + cos θ = 2 sin²α.
        let rise = half_sin.square().times_power_of_two(1);
        let theta = (
            -(half_sin.clone() * half_cos).times_power_of_two(1),
            rise.clone() - &half_sin.int(1),
        );
        match segment {
            Segment::BC => SegmentAngle::Stick {
                theta,
                rise: Some(rise),
            },
            Segment::CH => {
                let mirror_sin = mirror_half.map_or_else(|| half_sin.int(0), |(sin, _)| sin);
                let mirror_rise = mirror_sin.square().times_power_of_two(1);
                let mirror_cos = mirror_rise.clone() - &half_sin.int(1);
                let (c_sin, c_cos) = &g.theta_c_sin_cos;
                let from_c_sin = theta.0.clone() * c_cos - &(theta.1.clone() * c_sin);
                SegmentAngle::Mirrored {
                    theta,
                    rise: Some(rise),
                    mirror_cos,
                    mirror_rise: Some(mirror_rise),
                    from_c_sin,
                }
            }
            Segment::EB | Segment::HE => {
                // h = (θ − θ_end)/2 ≡ π/2 + α − θ_end/2 (mod π): sin h = cos(α − θ_end/2),
                // cos h = −sin(α − θ_end/2); the common sign of both is immaterial.
                let (end_sin, end_cos) = &bottom.end_half;
                let half_slip_sin = half_cos.clone() * end_cos + &(half_sin.clone() * end_sin);
                let half_slip_cos = half_cos.clone() * end_sin - &(half_sin.clone() * end_cos);
                let double_sin = (half_slip_sin.clone() * &half_slip_cos).times_power_of_two(1);
                SegmentAngle::Slip {
                    theta,
                    rise: Some(rise),
                    half_sin: half_slip_sin,
                    half_cos: half_slip_cos,
                    double_sin,
                }
            }
        }
    }

    /// The half-angle of the other load of CH from one's: the normal load's
    /// θ = π + 2α and the mirror load's θ_Y = 2θ_C − θ = π + 2β give β ≡ θ_C − π − α
    /// (mod π), and the same map takes β back to α.
    fn reflect(&self, half: &(R, R)) -> (R, R) {
        let (c_sin, c_cos) = &self.geometry.theta_c_sin_cos;
        let (sin, cos) = half;
        (
            c_cos.clone() * sin - &(c_sin.clone() * cos),
            -(c_cos.clone() * cos + &(c_sin.clone() * sin)),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::super::plans::PieceMap;
    use super::super::{cycle_at, LowLoad};
    use super::*;
    use crate::compliance::Persson;

    /// The bottom map's forms of every segment's angles (P's bottom, and CH's mirror
    /// load's) against the integrand in s, on windows about lowest-load points whether
    /// or not they lie in the segment (the integrands are analytic formulas in s).
    #[test]
    fn bottom_map_angles_are_the_angles_in_s() {
        use crate::quad::gauss_legendre::node_table;
        use crate::real::Precision;
        let table = node_table::<f64>(64, Precision::DOUBLE);
        let compliance = Persson { gamma: 1.0, sigma: 1.0 };
        for phase in [0.3, 1.0, 2.5] {
            let g = cycle_at(phase).geometry().expect("valid cycle");
            let integrands = SegmentIntegrands {
                geometry: &g,
                compliance: &compliance,
                remove_constant_slope: true,
            };
            let margin = (g.mean_normal_load - g.normal_amplitude) / g.normal_amplitude;
            let pi = std::f64::consts::PI;
            for segment in Segment::ALL {
                let (start, _) = integrands.extent(segment);
                let lows = [LowLoad::Normal, LowLoad::Mirror];
                for low in lows.into_iter().take(if segment == Segment::CH { 2 } else { 1 }) {
                    for k in [-1.0, 1.0, 3.0] {
                        let center = match low {
                            LowLoad::Mirror => g.theta_c - k * pi,
                            _ => k * pi - start,
                        };
                        let (a, b) = (center - 1.2, center + 0.9);
                        let plain = integrands.plan_integrand(segment, PieceMap::Plain, integrands.prepared_slope());
                        let bottom = integrands.bottom(segment, center, low, &margin);
                        let (u_a, u_b) = (bottom.map.to_u(&a), bottom.map.to_u(&b));
                        let mapped =
                            integrands.plan_integrand(segment, PieceMap::Bottom(bottom), integrands.prepared_slope());
                        let in_s = table.integrate(|s: &f64| plain(s), &a, &b);
                        let in_u = table.integrate(|u: &f64| mapped(u), &u_a, &u_b);
                        assert!(
                            (in_s - in_u).abs() <= 1e-12 * in_s.abs().max(1e-3),
                            "{segment} {low:?} k = {k}, φ = {phase}: {in_s} in s, {in_u} in u"
                        );
                    }
                }
            }
        }
    }
}
