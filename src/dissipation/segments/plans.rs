//! The pieces each segment is integrated in: its windows between break points, split
//! where a narrow peak needs its own map (sinh), and near separation the bottom of the
//! cycle through the bottom map, with limits in u formed from the sines of the angles
//! at the segment's ends.

use super::{LowLoad, Segment, SegmentIntegrands};
use crate::quad::bottom_map::BottomMap;
use crate::quad::sinh_map::{resolve_peaks, Peak, SinhMap};
use crate::real::Real;

/// Below this lowest load δ = P0 − P1, as a fraction of P1, the bottom of the cycle is
/// integrated through the bottom map (proofs/certified-digits.md, "Near separation").
pub(crate) const NEAR_SEPARATION: i64 = 1 << 10;

/// How far from the lowest load, in θ, a bottom map reaches: 1/[`BOTTOM_REACH`] rad, so
/// that sin α ≤ sin(1/8) keeps the branch points of cos α (t sinh u = ±1) ln 8 beyond the
/// piece in u; the rest is integrated in s, where 1 + cos θ ≥ 1 − cos(1/4) no longer
/// cancels much (measured: proofs/certified-digits.md, "Near separation").
const BOTTOM_REACH: i64 = 4;

/// 1 + cos θ from (sin θ, cos θ): as sin²θ/(1 − cos θ) where cos θ < 0 (a double
/// decides), which near θ ≡ π keeps the relative accuracy of sin θ where 1 + cos θ cancels.
pub(super) fn rise_of<R: Real>((sin, cos): &(R, R)) -> R {
    if cos.to_f64_lossy() < 0.0 {
        sin.square() / &(cos.int(1) - cos)
    } else {
        cos.int(1) + cos
    }
}

/// A bottom map in one segment, with what the segment's integrand needs besides.
#[derive(Clone, Debug)]
pub(crate) struct Bottom<R> {
    /// The map about the lowest load.
    pub(super) map: BottomMap<R>,
    /// Centred on the mirror load of CH rather than on P.
    pub(super) mirror: bool,
    /// (sin, cos) of half the angle of the slip segment's end (B for EB, E for HE).
    pub(super) end_half: (R, R),
}

/// How one piece of a segment is integrated.
#[derive(Clone, Debug)]
pub(crate) enum PieceMap<R> {
    /// In s.
    Plain,
    /// In u, through s = c + w sinh u.
    Sinh(SinhMap<R>),
    /// In u, through the bottom map.
    Bottom(Bottom<R>),
}

/// One piece of a segment integral: its limits (in the variable of its map) and map.
#[derive(Clone, Debug)]
pub(crate) struct PiecePlan<R> {
    pub segment: Segment,
    pub start: R,
    pub end: R,
    pub map: PieceMap<R>,
}

/// How far (in rad, by doubles) a segment's end must lie from a bottom map's centre for
/// the sign of the angle between them to be taken from doubles: far beyond the rounding of
/// angles of a few turns.
const END_SIGN_MARGIN: f64 = 1e-12;

impl<R: Real> SegmentIntegrands<'_, R> {
    /// The pieces of the four segment integrals, segment by segment in cycle order:
    /// each window split where a narrow peak needs its own map, and near separation
    /// the bottom of the cycle (within 1/[`BOTTOM_REACH`] rad of θ ≡ π) through the
    /// bottom map.
    pub(crate) fn plans(&self) -> Vec<PiecePlan<R>> {
        // Usually one or two pieces a segment.
        let mut plans = Vec::with_capacity(2 * Segment::ALL.len());
        let margin = self.separation_margin();
        for segment in Segment::ALL {
            let lows = self.low_loads(segment);
            let peaks: Vec<Peak<R>> = lows.iter().map(|(peak, _)| peak.clone()).collect();
            let windows = self.windows(segment);
            let last_window = windows.len().saturating_sub(1);
            for (index, (start, end)) in windows.into_iter().enumerate() {
                let parts = resolve_peaks(&start, &end, &peaks);
                let last_part = parts.len().saturating_sub(1);
                for (part_index, part) in parts.into_iter().enumerate() {
                    let chosen = part.peak.map(|index| &lows[index]);
                    // Which of the part's ends are the segment's own.
                    let ends = (
                        index == 0 && part_index == 0,
                        index == last_window && part_index == last_part,
                    );
                    match (part.map, chosen, &margin) {
                        (Some(_), Some((peak, low @ (LowLoad::Normal | LowLoad::Mirror))), Some(margin)) => {
                            let bottom = self.bottom(segment, peak.center.clone(), *low, margin);
                            self.push_bottom(&mut plans, segment, (part.window, ends), bottom);
                        }
                        (map, ..) => plans.push(PiecePlan {
                            segment,
                            start: part.start,
                            end: part.end,
                            map: map.map_or(PieceMap::Plain, PieceMap::Sinh),
                        }),
                    }
                }
            }
        }
        plans
    }

    /// δ/P1 = (P0 − P1)/P1, the lowest load relative to the amplitude, where P1 > 0.
    pub(super) fn normal_margin(&self) -> Option<R> {
        let g = self.geometry;
        let zero = g.normal_amplitude.int(0);
        (g.normal_amplitude > zero).then(|| g.lowest_normal_load.clone() / &g.normal_amplitude)
    }

    /// [`Self::normal_margin`] where it is below 1/[`NEAR_SEPARATION`].
    fn separation_margin(&self) -> Option<R> {
        self.normal_margin()
            .filter(|margin| *margin < margin.ratio(1, NEAR_SEPARATION))
    }

    /// The window (a, b) of `segment` with its lowest load toward one end: the bottom
    /// map `bottom` within [`BOTTOM_REACH`] of it, and beyond in s itself (there the
    /// load's zeros, about w = acosh(P0/P1) off the real axis at the lowest load, lie
    /// at least 1/[`BOTTOM_REACH`] rad from the piece).
    fn push_bottom(
        &self,
        plans: &mut Vec<PiecePlan<R>>,
        segment: Segment,
        ((a, b), (at_start, at_end)): ((R, R), (bool, bool)),
        bottom: Bottom<R>,
    ) {
        let center = bottom.map.center().clone();
        let reach = center.ratio(1, BOTTOM_REACH);
        let toward_start = center.clone() * &center.int(2) < a.clone() + &b;
        // The limits in u, and whether each is the segment's own end.
        let (mapped, beyond) = if toward_start {
            let cut = center + &reach;
            if cut < b {
                (((a, at_start), (cut.clone(), false)), Some((cut, b)))
            } else {
                (((a, at_start), (b, at_end)), None)
            }
        } else {
            let cut = center - &reach;
            if cut > a {
                (((cut.clone(), false), (b, at_end)), Some((a, cut)))
            } else {
                (((a, at_start), (b, at_end)), None)
            }
        };
        let ((start, start_is_end), (end, end_is_end)) = mapped;
        plans.push(PiecePlan {
            segment,
            start: self.limit_in_u(segment, &bottom, &start, start_is_end.then_some(false)),
            end: self.limit_in_u(segment, &bottom, &end, end_is_end.then_some(true)),
            map: PieceMap::Bottom(bottom),
        });
        if let Some((start, end)) = beyond {
            plans.push(PiecePlan {
                segment,
                start,
                end,
                map: PieceMap::Plain,
            });
        }
    }

    /// The point `s` of `segment` in the variable u of `bottom`; on enclosures, at the
    /// segment's start (`segment_end` false) or end (true), from the sine and cosine of the angle there,
    /// α = ±√((1 + cos θ)/2), free of the rounding of s − c, which for an end near the
    /// lowest load is large against α. The sign of α comes from doubles where they decide
    /// it by a wide margin; elsewhere s − c itself is taken.
    fn limit_in_u(&self, segment: Segment, bottom: &Bottom<R>, s: &R, segment_end: Option<bool>) -> R {
        let g = self.geometry;
        let from_center = s.to_f64_lossy() - bottom.map.center().to_f64_lossy();
        // A number (f64, MPFR) stands for itself: s − c is the end's own value, as the
        // neighbouring piece's limit is; only an enclosure's width is at stake.
        let enclosed = s.real_span().is_some();
        let Some(at_end) = segment_end.filter(|_| enclosed && from_center.abs() > END_SIGN_MARGIN) else {
            return bottom.map.to_u(s);
        };
        // θ at the end, or for a map about CH's mirror load θ_Y = θ_C − s there.
        let angle = match (bottom.mirror, segment, at_end) {
            (true, _, false) | (false, Segment::BC, true) | (false, Segment::CH, false) => &g.theta_c_sin_cos,
            (true, _, true) | (false, Segment::EB, true) | (false, Segment::BC, false) => &g.theta_b_sin_cos,
            (false, Segment::EB, false) | (false, Segment::HE, true) => &g.theta_e_sin_cos,
            (false, Segment::CH, true) | (false, Segment::HE, false) => &g.theta_h_sin_cos,
        };
        let magnitude = rise_of(angle).times_power_of_two(-1).sqrt();
        let half_sin = if from_center < 0.0 { -magnitude } else { magnitude };
        bottom.map.to_u_from_half_sin(&half_sin)
    }

    /// The bottom map of `segment` about the lowest load `low` (P, or CH's mirror load) at
    /// s = `center`, for δ = `margin`·P1.
    pub(super) fn bottom(&self, segment: Segment, center: R, low: LowLoad, margin: &R) -> Bottom<R> {
        let end_half = match segment {
            Segment::EB => self.geometry.theta_b.clone().times_power_of_two(-1).sin_cos(),
            Segment::HE => self.geometry.theta_e.clone().times_power_of_two(-1).sin_cos(),
            Segment::BC | Segment::CH => (center.int(0), center.int(1)),
        };
        Bottom {
            map: BottomMap::new(center, margin),
            mirror: low == LowLoad::Mirror,
            end_half,
        }
    }
}
