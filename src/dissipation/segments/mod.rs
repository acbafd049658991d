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
//!
//! By job: [`angles`] forms θ and the segment's other angles at a point (in s, or through
//! the bottom map near separation); [`low_loads`] the loads far below P0 from the lowest
//! load and the slip terms with their two loads apart, for f64 intervals; [`breaks`] the
//! break points and narrow peaks of each segment; [`plans`] the pieces they make and how
//! each is mapped. This module puts them together into the integrand of each piece.

use std::rc::Rc;

use super::segment::{Segment, Segments};
use super::slope::slope_at;
use crate::compliance::{Compliance, SlopeChange};
use crate::cycle::EllipseGeometry;
use crate::quad::Piece;
use crate::real::Real;

mod angles;
mod breaks;
mod low_loads;
mod plans;

use angles::SegmentAngle;
#[cfg(feature = "certified")]
pub(crate) use low_loads::SlopeBetween;
pub(crate) use low_loads::{Slopes, SlopesAtLoads};
use plans::PieceMap;
#[cfg(feature = "certified")]
pub(crate) use plans::NEAR_SEPARATION;

/// The pieces of the four segment integrals, with the segment each belongs to.
pub struct SegmentPieces<'a, R> {
    /// The pieces, segment by segment in cycle order.
    pub pieces: Vec<Piece<'a, R>>,
    /// The segment of each piece.
    pub segments: Vec<Segment>,
}

impl<'a, R: Real> SegmentPieces<'a, R> {
    /// Appends `other`'s pieces.
    pub fn extend(&mut self, other: SegmentPieces<'a, R>) {
        self.pieces.extend(other.pieces);
        self.segments.extend(other.segments);
    }

    /// The sum of the pieces' `values` per segment, starting from `zero`.
    pub fn sum_by_segment<'v>(&self, values: impl Iterator<Item = &'v R>, zero: &R) -> Segments<R> {
        let mut sums = Segments::from_fn(|_| zero.clone());
        for (value, segment) in values.zip(&self.segments) {
            *sums.get_mut(*segment) += value;
        }
        sums
    }
}

/// The slope change at the load a bottom map is centred on, formed by the caller from
/// that load as a product (δ cosh²u, [`Compliance::slope_at_scaled_square`]) rather than
/// from its offset P1 cos θ: on a complex ball the product's factors keep away from 0
/// where the offset's sum does not.
struct CentredChange<R> {
    load: LowLoad,
    change: R,
}

/// The slope change at `load`: the centred one where it is that load, else `otherwise`.
#[inline(always)]
fn change_at<R>(load: LowLoad, centred: &mut Option<CentredChange<R>>, otherwise: impl FnOnce() -> R) -> R {
    match centred.take_if(|centred| centred.load == load) {
        Some(centred) => centred.change,
        None => otherwise(),
    }
}

/// A load the integrand of a segment takes v' at, where it is least.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum LowLoad {
    /// P at θ ≡ π.
    Normal,
    /// P_Y of CH at θ_C − s ≡ π.
    Mirror,
    /// The slip load P_S of EB or P_K of HE at the segment's end.
    Slip,
}

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
    /// The slope function the integrands use, prepared about P0.
    pub(crate) fn prepared_slope(&self) -> SlopeChange<'a, R> {
        slope_at(
            self.compliance,
            &self.geometry.mean_normal_load,
            self.remove_constant_slope,
        )
    }

    /// Q − Q0 and f v'(P) dP/dθ at an angle with the given (sin, cos): the factor and the
    /// term shared by EB (with the opposite sign), CH and HE.
    fn loads_and_normal_term(
        &self,
        sin_cos: &(R, R),
        rise: &Option<R>,
        slopes: Slopes<'_, R>,
        centred: &mut Option<CentredChange<R>>,
    ) -> (R, R) {
        let g = self.geometry;
        let loads = g.loads_at(sin_cos);
        let change = change_at(LowLoad::Normal, centred, || {
            self.normal_change(slopes, rise.as_ref(), || loads.normal_offset())
        });
        let term = change * &g.friction * &loads.normal_rate();
        (loads.tangential_offset(), term)
    }

    /// The integrand of `segment` at angle `s` from its start.
    /// (For many evaluations use [`Self::pieces`], which prepares the slope once.)
    pub fn integrand(&self, segment: Segment, s: &R) -> R {
        self.integrand_with(segment, s, &self.prepared_slope())
    }

    pub(crate) fn integrand_with(&self, segment: Segment, s: &R, slope: &dyn Fn(&R) -> R) -> R {
        let slopes = Slopes {
            offset: slope,
            at_loads: None,
        };
        self.integrand_at(segment, self.angle_at(segment, s, false), slopes, None)
    }

    /// The integrand of `segment` at the angles `angle`.
    #[inline(always)]
    fn integrand_at(
        &self,
        segment: Segment,
        angle: SegmentAngle<R>,
        slopes: Slopes<'_, R>,
        mut centred: Option<CentredChange<R>>,
    ) -> R {
        let g = self.geometry;
        if let (Some(at_loads), None) = (slopes.at_loads, &centred) {
            if let Some(value) = self.integrand_with_loads_apart(segment, &angle, slopes, at_loads) {
                return value;
            }
        }
        match angle {
            SegmentAngle::Slip {
                theta,
                rise,
                half_sin,
                double_sin,
                ..
            } => {
                let (tangential_offset, normal) = self.loads_and_normal_term(&theta, &rise, slopes, &mut centred);
                if segment == Segment::EB {
                    let reverse =
                        self.slip_change(slopes, &g.sum_amplitude, &half_sin) * &g.sum_amplitude * &double_sin;
                    tangential_offset * &(reverse - &normal)
                } else {
                    let forward = self.slip_change(slopes, &g.difference_amplitude, &half_sin)
                        * &g.difference_amplitude
                        * &double_sin;
                    tangential_offset * &(normal - &forward)
                }
            }
            SegmentAngle::Stick { theta, rise } => {
                let loads = g.loads_at(&theta);
                let change = change_at(LowLoad::Normal, &mut centred, || {
                    self.normal_change(slopes, rise.as_ref(), || loads.normal_offset())
                });
                loads.tangential_offset() * &change * &loads.tangential_rate()
            }
            SegmentAngle::Mirrored {
                theta,
                rise,
                mirror_cos,
                mirror_rise,
                from_c_sin,
            } => {
                let (tangential_offset, normal) = self.loads_and_normal_term(&theta, &rise, slopes, &mut centred);
                let change = change_at(LowLoad::Mirror, &mut centred, || {
                    self.normal_change(slopes, mirror_rise.as_ref(), || {
                        g.normal_amplitude.clone() * &mirror_cos
                    })
                });
                let forward = change * &g.difference_amplitude * &from_c_sin;
                tangential_offset * &(normal + &forward)
            }
        }
    }

    /// Where `segment` starts (in θ) and how long it is.
    pub fn extent(&self, segment: Segment) -> (&'a R, &'a R) {
        let g = self.geometry;
        match segment {
            Segment::EB => (&g.theta_e, &g.slip_angle),
            Segment::BC => (&g.theta_b, &g.stick_angle),
            Segment::CH => (&g.theta_c, &g.stick_angle),
            Segment::HE => (&g.theta_h, &g.slip_angle),
        }
    }

    /// The integrals whose sum times λ is W: each segment split at its lowest-load points.
    pub fn pieces(&self) -> SegmentPieces<'a, R> {
        self.pieces_with_slope(self.prepared_slope())
    }

    /// The same pieces with the compliance's slope replaced by `slope` (a function of
    /// the offset x = P − P0): W is linear in v', so parts of v' can be integrated apart.
    pub fn pieces_with_slope(&self, slope: SlopeChange<'a, R>) -> SegmentPieces<'a, R> {
        let slope = Rc::new(slope);
        let plans = self.plans();
        let mut pieces = Vec::with_capacity(plans.len());
        let mut segments = Vec::with_capacity(plans.len());
        for plan in plans {
            let slope = Rc::clone(&slope);
            pieces.push(Piece {
                label: plan.segment.name(),
                integrand: self.plan_integrand(plan.segment, plan.map, move |x: &R| (*slope)(x)),
                start: plan.start,
                end: plan.end,
            });
            segments.push(plan.segment);
        }
        SegmentPieces { pieces, segments }
    }

    /// The integrand of one piece of `segment` in the variable of `map`, with `slope`.
    pub(crate) fn plan_integrand<S>(&self, segment: Segment, map: PieceMap<R>, slope: S) -> Box<dyn Fn(&R) -> R + 'a>
    where
        S: Fn(&R) -> R + 'a,
    {
        self.plan_integrand_at_bottom(segment, map, slope, None::<fn(&R) -> R>, None)
    }

    /// [`Self::plan_integrand`], with the slope change at the load a bottom map is centred
    /// on, δ cosh²u, taken from `at_bottom(cosh u)` where given (the same function; on
    /// complex balls a far narrower enclosure), and at loads far below P0 from
    /// `at_loads` where given ([`Slopes::at_loads`]).
    pub(crate) fn plan_integrand_at_bottom<S, B>(
        &self,
        segment: Segment,
        map: PieceMap<R>,
        slope: S,
        at_bottom: Option<B>,
        at_loads: Option<&'a SlopesAtLoads<'a, R>>,
    ) -> Box<dyn Fn(&R) -> R + 'a>
    where
        S: Fn(&R) -> R + 'a,
        B: Fn(&R) -> R + 'a,
    {
        let integrands = *self;
        match map {
            PieceMap::Plain => Box::new(move |s: &R| {
                let angle = integrands.angle_at(segment, s, at_loads.is_some());
                integrands.integrand_at(segment, angle, Slopes::of(&slope, at_loads), None)
            }),
            PieceMap::Sinh(map) => Box::new(move |u: &R| {
                let (s, rate) = map.point_and_rate(u);
                let angle = integrands.angle_at(segment, &s, at_loads.is_some());
                integrands.integrand_at(segment, angle, Slopes::of(&slope, at_loads), None) * &rate
            }),
            PieceMap::Bottom(bottom) => Box::new(move |u: &R| {
                let point = bottom.map.point(u);
                let angle = integrands.angle_near_bottom(segment, &bottom, &point);
                let centred = at_bottom.as_ref().map(|change| CentredChange {
                    load: if bottom.mirror {
                        LowLoad::Mirror
                    } else {
                        LowLoad::Normal
                    },
                    change: change(&point.load_root),
                });
                integrands.integrand_at(segment, angle, Slopes::of(&slope, at_loads), centred) * &point.rate
            }),
        }
    }
}

/// A cycle clear of separation and gross slip (P0 = 1, P1 = 0.6, Q1 = 0.3, f = 0.8), for
/// the tests of the segments' parts.
#[cfg(test)]
fn cycle_at(phase: f64) -> crate::cycle::LoadCycle<f64> {
    crate::cycle::LoadCycle {
        mean_normal_load: 1.0,
        normal_amplitude: 0.6,
        mean_tangential_load: 0.0,
        tangential_amplitude: 0.3,
        phase,
        friction: 0.8,
        compliance_ratio: 1.0,
    }
}
