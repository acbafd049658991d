//! The loads far below P0 formed from the lowest load, and the slip terms with their two
//! loads apart: what f64 intervals need near separation and where the slip terms
//! cancel (proofs/printing.md, "Near separation in f64 intervals"). With the slopes at
//! loads given ([`Slopes::at_loads`]) a load is the lowest load plus a rise above it, and
//! EB, CH and HE take g(L)·Q' ± fP'·(g(P) − g(L)) in place of their segment formulas.

use super::angles::SegmentAngle;
use super::{Segment, SegmentIntegrands};
use crate::cycle::LoadsAt;
use crate::real::Real;

/// The slope change an integrand takes v' through (v'(P) − v'(P0), or v'(P) itself): as a
/// function of the offset x = P − P0, and, where given, of the load P itself, which loads
/// far below P0 are formed as (their lowest load, P0 − P1 or P_T) + (a rise above it) to
/// keep the relative accuracy of that lowest load, where P0 + x would carry the rounding
/// of P0 amplified P0/P-fold.
pub(crate) struct Slopes<'s, R> {
    /// x ↦ the slope change at P0 + x.
    pub offset: &'s dyn Fn(&R) -> R,
    /// The same at loads given themselves, where the caller has them.
    pub at_loads: Option<&'s SlopesAtLoads<'s, R>>,
}

/// The slope change at loads given themselves rather than by their offsets from P0.
pub(crate) struct SlopesAtLoads<'a, R> {
    /// P ↦ the slope change at P, for loads below P0·[`SMALL_LOAD`].
    pub at_load: Box<dyn Fn(&R) -> R + 'a>,
    /// (L, x) ↦ v'(L + x) − v'(L) for x ≥ 0, free of cancellation where the compliance
    /// has a form for it
    /// ([`Compliance::slope_change`](crate::compliance::Compliance::slope_change)).
    pub between: SlopeBetween<'a, R>,
}

/// (L, x) ↦ v'(L + x) − v'(L) ([`SlopesAtLoads::between`]).
pub(crate) type SlopeBetween<'a, R> = Box<dyn Fn(&R, &R) -> R + 'a>;

// Two references: copyable whatever R is.
impl<R> Clone for Slopes<'_, R> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<R> Copy for Slopes<'_, R> {}

impl<'s, R> Slopes<'s, R> {
    pub(super) fn of<S: Fn(&R) -> R>(offset: &'s S, at_loads: Option<&'s SlopesAtLoads<'s, R>>) -> Self {
        Slopes { offset, at_loads }
    }
}

/// The loads, as a fraction of P0, below which [`SlopesAtLoads::at_load`] is taken: there the
/// offset's sum P0 + x would lose more than two bits of the load to the rounding of P0.
const SMALL_LOAD: f64 = 0.25;

impl<R: Real> SegmentIntegrands<'_, R> {
    /// The slope change at the normal load P = (P0 − P1) + P1·`rise` (the load at an angle
    /// with 1 + cos θ = `rise`) where the loads are formed from the lowest load, else at
    /// its offset P1 cos θ, `offset()`.
    pub(super) fn normal_change(&self, slopes: Slopes<'_, R>, rise: Option<&R>, offset: impl FnOnce() -> R) -> R {
        match (slopes.at_loads, rise) {
            (Some(_), Some(rise)) => self.change_at_load(slopes, &self.normal_load(rise), offset),
            _ => (slopes.offset)(&offset()),
        }
    }

    /// P = (P0 − P1) + P1·`rise` at an angle with 1 + cos θ = `rise`: a sum of two terms
    /// of one sign, as accurate as the lowest load near the bottom of the cycle.
    fn normal_load(&self, rise: &R) -> R {
        let g = self.geometry;
        g.lowest_normal_load.clone() + &(g.normal_amplitude.clone() * rise)
    }

    /// P_T + σ sin²h/f, the slip load of EB (σ = σ₊, P_S) or HE (σ = σ₋, P_K), given sin h,
    /// with its offset from P0.
    fn slip_load(&self, amplitude: &R, half_sin: &R) -> (R, R) {
        let lift = self.slip_lift(amplitude, half_sin);
        (
            self.geometry.permanent_stick_load() + &lift,
            self.geometry.permanent_stick_offset.clone() + &lift,
        )
    }

    /// σ sin²h/f, how far the slip load lies above P_T.
    fn slip_lift(&self, amplitude: &R, half_sin: &R) -> R {
        amplitude.clone() * &half_sin.square() / &self.geometry.friction
    }

    /// The slope change at `load`: from the load itself where it lies below
    /// P0·[`SMALL_LOAD`] and [`Slopes::at_loads`] is given, else from its offset from P0,
    /// `offset()`. A double decides which: both are the same function.
    fn change_at_load(&self, slopes: Slopes<'_, R>, load: &R, offset: impl FnOnce() -> R) -> R {
        if let Some(at_loads) = slopes.at_loads {
            if load.to_f64_lossy() < self.geometry.mean_normal_load.to_f64_lossy() * SMALL_LOAD {
                return (at_loads.at_load)(load);
            }
        }
        (slopes.offset)(&offset())
    }

    /// The slope change at the slip load P_T + σ sin²h/f of EB (σ = σ₊, P_S) or HE (σ = σ₋,
    /// P_K), given sin h.
    pub(super) fn slip_change(&self, slopes: Slopes<'_, R>, amplitude: &R, half_sin: &R) -> R {
        match slopes.at_loads {
            Some(_) => {
                let (load, offset) = self.slip_load(amplitude, half_sin);
                self.change_at_load(slopes, &load, || offset)
            }
            None => {
                let lift = self.slip_lift(amplitude, half_sin);
                (slopes.offset)(&(self.geometry.permanent_stick_offset.clone() + &lift))
            }
        }
    }

    /// The integrand of a slip segment with its two loads' slopes apart (where
    /// [`Slopes::at_loads`] is given). With L the slip load (P_S, P_Y or P_K) and g the slope
    /// change, the derivatives of Q ± fP, σ₊ sin(θ − θ_B) = Q' + fP' and
    /// σ₋ sin(θ − θ_E) = fP' − Q', make CH's and HE's ψ g(L)·Q' + f P'·(g(P) − g(L)) and
    /// EB's g(L)·Q' − f P'·(g(P) − g(L)); P − L is a product of the geometry's sines
    /// ([`Self::slip_gap`]), and v'(P) − v'(L) is [`SlopesAtLoads::between`] the lower load
    /// and the gap: free of the cancellation of two terms of size fP1·v' to one of size
    /// Q1·v' that the segment formulas leave to the arithmetic (proofs/four-segment.md).
    fn slip_loads_apart(
        &self,
        (segment, between): (Segment, &SlopeBetween<'_, R>),
        loads: &LoadsAt<'_, R>,
        (slip_load, slip_change): (&R, R),
        gap: R,
        normal_load: &R,
    ) -> R {
        let g = self.geometry;
        // v'(P) − v'(L) about the lower load, with a gap of one sign.
        let difference = if gap.to_f64_lossy() >= 0.0 {
            between(slip_load, &gap)
        } else {
            -between(normal_load, &(-gap))
        };
        let normal_term = difference * &g.friction * &loads.normal_rate();
        let slip_term = slip_change * &loads.tangential_rate();
        let psi = if segment == Segment::EB {
            slip_term - &normal_term
        } else {
            slip_term + &normal_term
        };
        loads.tangential_offset() * &psi
    }

    /// P − L for the slip load L of `segment`, from the decomposition
    /// P = P_T + σ₊ sin²((θ − θ_B)/2)/f + σ₋ sin²((θ − θ_E)/2)/f (P_T's definition), with
    /// EB's P_S = P_T + σ₊ sin²((θ − θ_B)/2)/f and HE's P_K = P_T + σ₋ sin²((θ − θ_E)/2)/f;
    /// for CH, P − P_Y = −2P1 sin θ_C sin(θ − θ_C); from `angle`'s sin h and cos h for a slip
    /// segment (h = (s − L)/2, L its length), or CH's sin(θ − θ_C).
    fn slip_gap(&self, segment: Segment, angle: &SegmentAngle<R>) -> R {
        let g = self.geometry;
        let (half_sin, half_cos) = match angle {
            SegmentAngle::Slip { half_sin, half_cos, .. } => (half_sin, half_cos),
            SegmentAngle::Mirrored { from_c_sin, .. } => {
                return -(g.normal_amplitude.clone() * &g.theta_c_sin_cos.0 * from_c_sin).times_power_of_two(1);
            }
            SegmentAngle::Stick { .. } => return g.normal_amplitude.int(0),
        };
        let (length_sin, length_cos) = &g.half_slip_sin_cos;
        // s/2 = h + L/2.
        let from_start_sin = half_sin.clone() * length_cos + &(half_cos.clone() * length_sin);
        if segment == Segment::EB {
            // θ − θ_E = s.
            g.difference_amplitude.clone() * &from_start_sin.square() / &g.friction
        } else {
            // θ − θ_B = s + 2δ.
            let from_start_cos = half_cos.clone() * length_cos - &(half_sin.clone() * length_sin);
            let (stick_sin, stick_cos) = &g.stick_sin_cos;
            let from_b_sin = from_start_sin * stick_cos + &(from_start_cos * stick_sin);
            g.sum_amplitude.clone() * &from_b_sin.square() / &g.friction
        }
    }

    /// [`Self::slip_loads_apart`] for the slip segments' angles; `None` for BC's, and for
    /// angles formed without 1 + cos θ.
    // Kept out of line: inlined into `integrand_at`, which every piece's integrand inlines,
    // it costs the segment formulas' evaluations a few per cent where it is not taken.
    #[inline(never)]
    pub(super) fn integrand_with_loads_apart(
        &self,
        segment: Segment,
        angle: &SegmentAngle<R>,
        slopes: Slopes<'_, R>,
        at_loads: &SlopesAtLoads<'_, R>,
    ) -> Option<R> {
        let g = self.geometry;
        let (theta, rise, slip_load, offset) = match angle {
            SegmentAngle::Stick { .. } => return None,
            SegmentAngle::Slip {
                theta, rise, half_sin, ..
            } => {
                let amplitude = if segment == Segment::EB {
                    &g.sum_amplitude
                } else {
                    &g.difference_amplitude
                };
                let (load, offset) = self.slip_load(amplitude, half_sin);
                (theta, rise.as_ref()?, load, offset)
            }
            SegmentAngle::Mirrored {
                theta,
                rise,
                mirror_cos,
                mirror_rise,
                ..
            } => (
                theta,
                rise.as_ref()?,
                self.normal_load(mirror_rise.as_ref()?),
                g.normal_amplitude.clone() * mirror_cos,
            ),
        };
        let gap = self.slip_gap(segment, angle);
        let change = self.change_at_load(slopes, &slip_load, || offset);
        let loads = g.loads_at(theta);
        let between = (segment, &at_loads.between);
        Some(self.slip_loads_apart(between, &loads, (&slip_load, change), gap, &self.normal_load(rise)))
    }
}

#[cfg(test)]
mod tests {
    use super::super::PieceMap;
    use super::*;
    use crate::compliance::{Compliance, Persson};
    use crate::cycle::LoadCycle;

    /// The slip segments with their two loads' slopes apart (P and P_S, P_Y or P_K formed
    /// from the lowest loads, v'(P) − v'(L) about the lower) are the segment formulas: every
    /// piece's integrand, plain, sinh- or bottom-mapped, at 200 bits, on ordinary cycles and
    /// within 1e-6 of separation.
    #[test]
    fn the_slip_loads_apart_are_the_segment_formulas() {
        use crate::real::Precision;
        use rug::Float;
        let p = Precision::bits(200);
        let number = |text: &str| Float::parse_decimal(text, p).expect("a decimal");
        let compliance = Persson {
            gamma: number("1"),
            sigma: number("1"),
        };
        for (p1, q1, phase) in [
            ("0.6", "0.3", "1.0"),
            ("0.6", "0.3", "2.9"),
            ("0.999999", "1e-4", "1.5707963"),
            ("0.999999", "5e-7", "1.2"),
        ] {
            let cycle = LoadCycle {
                mean_normal_load: number("1"),
                normal_amplitude: number(p1),
                mean_tangential_load: number("0"),
                tangential_amplitude: number(q1),
                phase: number(phase),
                friction: number("1"),
                compliance_ratio: number("1"),
            };
            let g = cycle.geometry().expect("valid cycle");
            let integrands = SegmentIntegrands {
                geometry: &g,
                compliance: &compliance,
                remove_constant_slope: true,
            };
            let at_mean = compliance.slope(&g.mean_normal_load);
            let at_loads = SlopesAtLoads {
                at_load: Box::new(|load: &Float| compliance.slope(load) - &at_mean),
                between: Box::new(|load: &Float, gap: &Float| compliance.slope_change(load, gap)),
            };
            let plans = integrands.plans();
            assert!(
                plans.iter().any(|plan| matches!(plan.map, PieceMap::Bottom(_))) == p1.starts_with("0.9999"),
                "P1 = {p1}: bottom maps near separation only"
            );
            for plan in plans {
                let formulas = integrands.plan_integrand(plan.segment, plan.map.clone(), integrands.prepared_slope());
                let apart = integrands.plan_integrand_at_bottom(
                    plan.segment,
                    plan.map,
                    integrands.prepared_slope(),
                    None::<fn(&Float) -> Float>,
                    Some(&at_loads),
                );
                for t in ["0.1", "0.5", "0.9"] {
                    let x = plan.start.clone() + (plan.end.clone() - &plan.start) * number(t);
                    let (expected, found) = (formulas(&x), apart(&x));
                    let error = Float::with_val(200, &found - &expected).abs();
                    assert!(
                        error <= expected.clone().abs() * number("1e-40"),
                        "{} at {x:.6e}, P1 = {p1}, Q1 = {q1}, φ = {phase}: {found:.20e} against {expected:.20e}",
                        plan.segment
                    );
                }
            }
        }
    }
}
