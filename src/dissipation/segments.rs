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

use std::rc::Rc;

use super::segment::{Segment, Segments};
use super::slope::{knot_offsets, slope_at};
use crate::compliance::{Compliance, SlopeChange};
use crate::cycle::{EllipseGeometry, LoadsAt};
use crate::quad::bottom_map::{BottomMap, BottomPoint};
use crate::quad::sinh_map::{acosh_one_plus, asinh, resolve_peaks, Peak, SinhMap};
use crate::quad::Piece;
use crate::real::{Precision, Real};

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

/// The angles one evaluation of a segment's integrand takes, with θ through its sine
/// and cosine, and 1 + cos θ, the rise P1(1 + cos θ) of P above P0 − P1 per unit P1.
enum SegmentAngle<R> {
    /// BC.
    Stick {
        /// (sin θ, cos θ).
        theta: (R, R),
        /// 1 + cos θ.
        rise: R,
    },
    /// CH.
    Mirrored {
        /// (sin θ, cos θ).
        theta: (R, R),
        /// 1 + cos θ.
        rise: R,
        /// cos θ_Y at the mirror angle θ_Y = 2θ_C − θ.
        mirror_cos: R,
        /// 1 + cos θ_Y.
        mirror_rise: R,
        /// sin(θ − θ_C).
        from_c_sin: R,
    },
    /// EB and HE, with h half the angle to the segment's end.
    Slip {
        /// (sin θ, cos θ).
        theta: (R, R),
        /// 1 + cos θ.
        rise: R,
        /// sin h.
        half_sin: R,
        /// cos h (with sin h, up to a sign common to both).
        half_cos: R,
        /// sin 2h.
        double_sin: R,
    },
}

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
    /// has a form for it ([`Compliance::slope_change`]).
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
    fn of<S: Fn(&R) -> R>(offset: &'s S, at_loads: Option<&'s SlopesAtLoads<'s, R>>) -> Self {
        Slopes { offset, at_loads }
    }
}

/// 1 + cos θ from (sin θ, cos θ): as sin²θ/(1 − cos θ) where cos θ < 0 (a double
/// decides), which near θ ≡ π keeps the relative accuracy of sin θ where 1 + cos θ cancels.
fn rise_of<R: Real>((sin, cos): &(R, R)) -> R {
    if cos.to_f64_lossy() < 0.0 {
        sin.square() / &(cos.int(1) - cos)
    } else {
        cos.int(1) + cos
    }
}

/// A point of `s` to split an integral at: any point splits it exactly, and at double
/// precision the middle of an enclosure of s (a double) gives the pieces on either side
/// an exact common limit where s itself, an angle of the cycle near π formed from other
/// angles, would widen both by its width; other precisions keep s.
fn split_point<R: Real>(s: R) -> R {
    match s.real_span() {
        Some((lo, hi)) if s.precision() == Precision::DOUBLE && lo < hi => {
            R::from_f64(lo * 0.5 + hi * 0.5, Precision::DOUBLE)
        }
        _ => s,
    }
}

/// How far (in rad, by doubles) a segment's end must lie from a bottom map's centre for
/// the sign of the angle between them to be taken from doubles: far beyond the rounding of
/// angles of a few turns.
const END_SIGN_MARGIN: f64 = 1e-12;

/// The loads, as a fraction of P0, below which [`SlopesAtLoads::at_load`] is taken: there the
/// offset's sum P0 + x would lose more than two bits of the load to the rounding of P0.
const SMALL_LOAD: f64 = 0.25;

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

/// Below this lowest load δ = P0 − P1, as a fraction of P1, the bottom of the cycle is
/// integrated through the bottom map (proofs/certified-digits.md, "Near separation").
pub(crate) const NEAR_SEPARATION: i64 = 1 << 10;

/// How far from the lowest load, in θ, a bottom map reaches: 1/[`BOTTOM_REACH`] rad, so
/// that sin α ≤ sin(1/8) keeps the branch points of cos α (t sinh u = ±1) ln 8 beyond the
/// piece in u; the rest is integrated in s, where 1 + cos θ ≥ 1 − cos(1/4) no longer
/// cancels much (measured: proofs/certified-digits.md, "Near separation").
const BOTTOM_REACH: i64 = 4;

/// A bottom map in one segment, with what the segment's integrand needs besides.
#[derive(Clone, Debug)]
pub(crate) struct Bottom<R> {
    map: BottomMap<R>,
    /// Centred on the mirror load of CH rather than on P.
    mirror: bool,
    /// (sin, cos) of half the angle of the slip segment's end (B for EB, E for HE).
    end_half: (R, R),
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
        rise: &R,
        slopes: Slopes<'_, R>,
        centred: &mut Option<CentredChange<R>>,
    ) -> (R, R) {
        let g = self.geometry;
        let loads = g.loads_at(sin_cos);
        let change = change_at(LowLoad::Normal, centred, || {
            self.normal_change(slopes, rise, || loads.normal_offset())
        });
        let term = change * &g.friction * &loads.normal_rate();
        (loads.tangential_offset(), term)
    }

    /// The slope change at the normal load P = (P0 − P1) + P1·`rise` (the load at an angle
    /// with 1 + cos θ = `rise`), whose offset P1 cos θ is `offset()`.
    fn normal_change(&self, slopes: Slopes<'_, R>, rise: &R, offset: impl FnOnce() -> R) -> R {
        match slopes.at_loads {
            Some(_) => self.change_at_load(slopes, &self.normal_load(rise), offset),
            None => (slopes.offset)(&offset()),
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
        let g = self.geometry;
        let lift = amplitude.clone() * &half_sin.square() / &g.friction;
        (
            g.permanent_stick_load() + &lift,
            g.permanent_stick_offset.clone() + &lift,
        )
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
        self.integrand_at(segment, self.angle_at(segment, s), slopes, None)
    }

    /// The angles of `segment` at angle `s` from its start.
    // Inlined into each piece's integrand, as `integrand_at` is: as calls they cost an f64
    // run about 15 % (proofs/certified-digits.md, "The f64 default in process").
    #[inline(always)]
    fn angle_at(&self, segment: Segment, s: &R) -> SegmentAngle<R> {
        let g = self.geometry;
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
                    rise: rise_of(&theta),
                    theta,
                    half_sin,
                    half_cos,
                    double_sin,
                }
            }
            Segment::BC => {
                let theta = (g.theta_b.clone() + s).sin_cos();
                SegmentAngle::Stick {
                    rise: rise_of(&theta),
                    theta,
                }
            }
            Segment::CH => {
                // θ = θ_C + s, the mirror point θ_C − s; sin(θ − θ_E) = sin(π + s) = −sin s.
                let s_sin_cos = s.sin_cos();
                let (theta, mirror) = self.around_c(&s_sin_cos);
                SegmentAngle::Mirrored {
                    rise: rise_of(&theta),
                    mirror_rise: rise_of(&mirror),
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
    fn angle_near_bottom(&self, segment: Segment, bottom: &Bottom<R>, point: &BottomPoint<R>) -> SegmentAngle<R> {
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
            Segment::BC => SegmentAngle::Stick { theta, rise },
            Segment::CH => {
                let mirror_sin = mirror_half.map_or_else(|| half_sin.int(0), |(sin, _)| sin);
                let mirror_rise = mirror_sin.square().times_power_of_two(1);
                let mirror_cos = mirror_rise.clone() - &half_sin.int(1);
                let (c_sin, c_cos) = &g.theta_c_sin_cos;
                let from_c_sin = theta.0.clone() * c_cos - &(theta.1.clone() * c_sin);
                SegmentAngle::Mirrored {
                    theta,
                    rise,
                    mirror_cos,
                    mirror_rise,
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
                    rise,
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
                    self.normal_change(slopes, &rise, || loads.normal_offset())
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
                    self.normal_change(slopes, &mirror_rise, || g.normal_amplitude.clone() * &mirror_cos)
                });
                let forward = change * &g.difference_amplitude * &from_c_sin;
                tangential_offset * &(normal + &forward)
            }
        }
    }

    /// The slope change at the slip load P_T + σ sin²h/f of EB (σ = σ₊, P_S) or HE (σ = σ₋,
    /// P_K), given sin h.
    fn slip_change(&self, slopes: Slopes<'_, R>, amplitude: &R, half_sin: &R) -> R {
        let (load, offset) = self.slip_load(amplitude, half_sin);
        match slopes.at_loads {
            Some(_) => self.change_at_load(slopes, &load, || offset),
            None => (slopes.offset)(&offset),
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

    /// [`Self::slip_loads_apart`] for the slip segments' angles; `None` for BC's.
    fn integrand_with_loads_apart(
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
                (theta, rise, load, offset)
            }
            SegmentAngle::Mirrored {
                theta,
                rise,
                mirror_cos,
                mirror_rise,
                ..
            } => (
                theta,
                rise,
                self.normal_load(mirror_rise),
                g.normal_amplitude.clone() * mirror_cos,
            ),
        };
        let gap = self.slip_gap(segment, angle);
        let change = self.change_at_load(slopes, &slip_load, || offset);
        let loads = g.loads_at(theta);
        let between = (segment, &at_loads.between);
        Some(self.slip_loads_apart(between, &loads, (&slip_load, change), gap, &self.normal_load(rise)))
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

    /// The windows of `segment` in s, between its break points (lowest loads and
    /// knot crossings), before narrow peaks are mapped: for rules that integrate in s
    /// or in the load themselves.
    pub fn windows(&self, segment: Segment) -> Vec<(R, R)> {
        let mut breaks = self.lowest_load_points(segment);
        let knots = knot_offsets(self.compliance, &self.geometry.mean_normal_load);
        if !knots.is_empty() {
            breaks.extend(self.knot_crossings(segment, &knots));
            breaks.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
            breaks.dedup();
        }
        breaks.windows(2).map(|w| (w[0].clone(), w[1].clone())).collect()
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
    fn normal_margin(&self) -> Option<R> {
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
    fn bottom(&self, segment: Segment, center: R, low: LowLoad, margin: &R) -> Bottom<R> {
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
                let angle = integrands.angle_at(segment, s);
                integrands.integrand_at(segment, angle, Slopes::of(&slope, at_loads), None)
            }),
            PieceMap::Sinh(map) => Box::new(move |u: &R| {
                let (s, rate) = map.point_and_rate(u);
                let angle = integrands.angle_at(segment, &s);
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

    /// The narrow peaks of segment `index` (in s), where a load that v' is taken at is
    /// least: P at θ ≡ π (mod 2π), and for CH P_Y at the mirror angle θ_C − s ≡ π, each
    /// of half-width acosh(P0/P1) (where P0 + P1 cos θ vanishes, off the real axis);
    /// for EB P_S = P_T + σ₊ sin²h/f at B, of half-width 2 asinh(√(fP_T/σ₊)), and for HE
    /// P_K likewise at E with σ₋. A compliance singular at P = 0 makes these peaks as
    /// narrow as √((P0 − P1)/P0) near separation and √(P_T/P0) near gross slip; one with a
    /// decay load c shorter than those loads ([`Compliance::decay_load`]) as narrow as
    /// √(2c/P1), the load itself replaced by c in each width.
    fn low_loads(&self, segment: Segment) -> Vec<(Peak<R>, LowLoad)> {
        let g = self.geometry;
        let (start, length) = self.extent(segment);
        let zero = length.int(0);
        let pi = length.pi_like();
        // Six turns, twice for CH, and the slip load's peak.
        let mut peaks = Vec::with_capacity(13);
        // A v' singular at P = 0 peaks over the load itself, one with a decay load of its
        // own over that where it is shorter.
        let decay_load = self.compliance.decay_load();
        let within_decay = |load: R| match &decay_load {
            Some(scale) => load.min_of(scale),
            None => load,
        };
        if let Some(margin) = self.normal_margin() {
            let margin = match &decay_load {
                Some(scale) => margin.min_of(&(scale.clone() / &g.normal_amplitude)),
                None => margin,
            };
            let width = acosh_one_plus(&margin);
            // A centre more than the segment's length outside it is farther than its length
            // from every window in it, which `resolve_peaks` skips: it is not formed in R.
            for (k, normal, mirror) in self.nearby_turns(segment, 1.0) {
                let lowest = pi.clone() * &pi.int(2 * k + 1);
                if normal {
                    let center = lowest.clone() - start;
                    peaks.push((
                        Peak {
                            center,
                            width: width.clone(),
                        },
                        LowLoad::Normal,
                    ));
                }
                if mirror {
                    let center = g.theta_c.clone() - &lowest;
                    peaks.push((
                        Peak {
                            center,
                            width: width.clone(),
                        },
                        LowLoad::Mirror,
                    ));
                }
            }
        }
        if let Some(amplitude) = self.slip_amplitude(segment).filter(|a| **a > zero) {
            let ratio = within_decay(g.permanent_stick_load()) * &g.friction / amplitude;
            let width = asinh(&ratio.max_of(&zero).sqrt()) * &zero.int(2);
            peaks.push((
                Peak {
                    center: length.clone(),
                    width,
                },
                LowLoad::Slip,
            ));
        }
        peaks
    }

    /// σ₊ for EB (P_S), σ₋ for HE (P_K): the amplitude of the slip load a slip segment
    /// takes v' at besides P; none for BC and CH.
    fn slip_amplitude(&self, segment: Segment) -> Option<&'a R> {
        match segment {
            Segment::EB => Some(&self.geometry.sum_amplitude),
            Segment::HE => Some(&self.geometry.difference_amplitude),
            Segment::BC | Segment::CH => None,
        }
    }

    /// The angles s strictly inside segment `index` where a load that v' is taken at
    /// crosses a knot (given as offsets x = P − P0), so that between two of them (and
    /// the lowest-load points) every v' in the integrand is one analytic piece:
    ///
    /// ```text
    /// P    = P0 + P1 cos θ                 θ = ±acos(x/P1) + 2πm          (all segments)
    /// P_Y  = P0 + P1 cos(θ_C − s)          s = θ_C ∓ acos(x/P1) − 2πm     (CH)
    /// P_S  = P_T + σ₊ sin²h/f, h = (s − L)/2 ∈ [−π/2, 0]:
    ///                                      s = L − 2 asin(√((P − P_T) f/σ₊))   (EB; HE with P_K, σ₋)
    /// ```
    fn knot_crossings(&self, segment: Segment, knots: &[R]) -> Vec<R> {
        let g = self.geometry;
        let (start, length) = self.extent(segment);
        let zero = length.int(0);
        let one = length.int(1);
        let two_pi = length.pi_like() * &length.int(2);
        let mut crossings = Vec::new();
        let slip_amplitude = self.slip_amplitude(segment);
        for knot in knots {
            if g.normal_amplitude > zero {
                let cosine = knot.clone() / &g.normal_amplitude;
                if cosine > -one.clone() && cosine < one {
                    // acos c = atan2(√((1 − c)(1 + c)), c), free of cancellation near c = ±1.
                    let sine = ((one.clone() - &cosine) * &(one.clone() + &cosine)).sqrt();
                    let angle = sine.atan2(&cosine);
                    for m in -2..=3i64 {
                        let turn = two_pi.clone() * &length.int(m);
                        for theta in [turn.clone() + &angle, turn.clone() - &angle] {
                            crossings.push(theta.clone() - start);
                            if segment == Segment::CH {
                                crossings.push(g.theta_c.clone() - &theta);
                            }
                        }
                    }
                }
            }
            if let Some(amplitude) = slip_amplitude.filter(|a| **a > zero) {
                let fraction = (knot.clone() - &g.permanent_stick_offset) * &g.friction / amplitude;
                if fraction > zero && fraction < one {
                    let half = fraction.sqrt().atan2(&(one.clone() - &fraction).sqrt());
                    crossings.push(length.clone() - &(half * &length.int(2)));
                }
            }
        }
        crossings.retain(|s| *s > zero && s < length);
        crossings
    }

    /// The six turns around the cycle (k = −2..=3) whose lowest loads can lie within
    /// `slack` lengths of `segment`'s [0, length], by a double's reckoning: k, and whether
    /// P's, at (2k + 1)π − start, and in CH the mirror load's, at θ_C − (2k + 1)π, can. The
    /// margin, 10⁻⁹·(1 + |s| + length), is far beyond a double's rounding of these angles
    /// or a ball's radius around them, so a turn skipped here is outside in every type; the
    /// callers skip it without the arithmetic of R (on balls, a product and comparisons of
    /// about 1 200 instructions each). A NaN skips nothing.
    fn nearby_turns(&self, segment: Segment, slack: f64) -> impl Iterator<Item = (i64, bool, bool)> {
        let (start, length) = self.extent(segment);
        let (start, length) = (start.to_f64_lossy(), length.to_f64_lossy());
        let theta_c = self.geometry.theta_c.to_f64_lossy();
        let near = move |s: f64| {
            let margin = 1e-9 * (1.0 + s.abs() + length.abs());
            !(s < -slack * length - margin || s > (1.0 + slack) * length + margin)
        };
        (-2..=3i64).filter_map(move |k| {
            let lowest = std::f64::consts::PI * (2 * k + 1) as f64;
            let normal = near(lowest - start);
            let mirror = segment == Segment::CH && near(theta_c - lowest);
            (normal || mirror).then_some((k, normal, mirror))
        })
    }

    /// The break points 0 = s₀ < s₁ < … < L of a segment: the angles where P (and,
    /// for CH, P at the mirror point θ_C − s) is least, θ ≡ π (mod 2π). A compliance
    /// singular at P → 0 is nearly singular there when the cycle nears separation,
    /// and a break puts the trouble at an end of a piece.
    fn lowest_load_points(&self, segment: Segment) -> Vec<R> {
        let (start, length) = self.extent(segment);
        let zero = length.int(0);
        let pi = length.pi_like();
        // At most two candidates for each of the six turns, and the two ends.
        let mut breaks = Vec::with_capacity(14);
        breaks.push(zero.clone());
        // A candidate outside [0, length] is not a break point: it is not formed in R.
        for (k, normal, mirror) in self.nearby_turns(segment, 0.0) {
            let lowest = pi.clone() * &pi.int(2 * k + 1);
            let mirror = mirror.then(|| self.geometry.theta_c.clone() - &lowest);
            let candidates = normal.then(|| lowest.clone() - start).into_iter().chain(mirror);
            breaks.extend(candidates.filter(|s| *s > zero && s < length).map(split_point));
        }
        breaks.push(length.clone());
        breaks.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
        breaks
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compliance::Persson;
    use crate::cycle::LoadCycle;

    /// Persson's v' = 1/P with knots declared at given loads (v' itself stays analytic).
    #[derive(Debug)]
    struct WithKnots {
        inner: Persson<f64>,
        knots: Vec<f64>,
    }

    impl Compliance<f64> for WithKnots {
        fn approach(&self, load: &f64) -> f64 {
            self.inner.approach(load)
        }
        fn slope(&self, load: &f64) -> f64 {
            self.inner.slope(load)
        }
        fn curvature(&self, load: &f64) -> f64 {
            self.inner.curvature(load)
        }
        fn breakpoints(&self, _: &f64) -> Vec<f64> {
            self.knots.clone()
        }
        fn describe(&self) -> String {
            "Persson with knots".into()
        }
    }

    /// A cycle clear of separation and gross slip (P0 = 1, P1 = 0.6, Q1 = 0.3, f = 0.8).
    fn cycle_at(phase: f64) -> LoadCycle<f64> {
        LoadCycle {
            mean_normal_load: 1.0,
            normal_amplitude: 0.6,
            mean_tangential_load: 0.0,
            tangential_amplitude: 0.3,
            phase,
            friction: 0.8,
            compliance_ratio: 1.0,
        }
    }

    #[test]
    fn knot_crossings_are_where_a_load_of_the_integrand_meets_a_knot() {
        let knots: Vec<f64> = (0..40).map(|i| 0.3 + 0.04 * i as f64).collect();
        let compliance = WithKnots {
            inner: Persson { gamma: 1.0, sigma: 1.0 },
            knots: knots.clone(),
        };
        for phase in [0.1, 0.4, 0.7, 0.95].map(|x| x * std::f64::consts::PI) {
            let g = cycle_at(phase).geometry().expect("valid cycle");
            let integrands = SegmentIntegrands {
                geometry: &g,
                compliance: &compliance,
                remove_constant_slope: true,
            };
            let offsets = knot_offsets(integrands.compliance, &g.mean_normal_load);
            let on_knot = |offset: f64| offsets.iter().any(|x| (x - offset).abs() < 1e-12);
            let mut normal_crossings = 0;
            for segment in Segment::ALL {
                let (start, length) = integrands.extent(segment);
                for s in integrands.knot_crossings(segment, &offsets) {
                    assert!(s > 0.0 && s < *length);
                    let half_sin = ((s - length) / 2.0).sin();
                    let normal = on_knot(g.normal_offset(&(start + s)));
                    let other = match segment {
                        Segment::EB => on_knot(g.reverse_slip_offset(&half_sin)),
                        Segment::CH => on_knot(g.normal_offset(&(g.theta_c - s))),
                        Segment::HE => on_knot(g.forward_slip_offset(&half_sin)),
                        Segment::BC => false,
                    };
                    assert!(normal || other, "segment {segment}, s = {s}: no load on a knot");
                    normal_crossings += usize::from(normal);
                }
            }
            // P = P0 + P1 cos θ meets each knot strictly inside (P0 − P1, P0 + P1) twice a cycle.
            let inside = knots.iter().filter(|&&k| (k - 1.0).abs() < 0.6).count();
            assert_eq!(normal_crossings, 2 * inside, "phase {phase}");
        }
    }

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

    /// The break points at the lowest loads, with far turns skipped by doubles, are every
    /// angle strictly inside the segment where P (or CH's mirror load) is least, in f64 and
    /// at 200 bits, for phases that put the segments' ends on all sides of those angles.
    #[test]
    fn lowest_load_points_are_every_lowest_load_inside_the_segment() {
        use crate::real::Precision;
        use rug::Float;
        let p = Precision::bits(200);
        let compliance = Persson { gamma: 1.0, sigma: 1.0 };
        let precise_compliance = Persson {
            gamma: Float::from_i64(1, p),
            sigma: Float::from_i64(1, p),
        };
        for phase in [0.05, 0.3, 1.0, 1.6, 2.5, 3.1] {
            let cycle = cycle_at(phase);
            let g = cycle.geometry().expect("valid cycle");
            let precise_cycle = LoadCycle {
                mean_normal_load: Float::from_f64(cycle.mean_normal_load, p),
                normal_amplitude: Float::from_f64(cycle.normal_amplitude, p),
                mean_tangential_load: Float::from_f64(cycle.mean_tangential_load, p),
                tangential_amplitude: Float::from_f64(cycle.tangential_amplitude, p),
                phase: Float::from_f64(phase, p),
                friction: Float::from_f64(cycle.friction, p),
                compliance_ratio: Float::from_i64(1, p),
            };
            let precise_g = precise_cycle.geometry().expect("valid cycle");
            let integrands = SegmentIntegrands {
                geometry: &g,
                compliance: &compliance,
                remove_constant_slope: true,
            };
            let precise = SegmentIntegrands {
                geometry: &precise_g,
                compliance: &precise_compliance,
                remove_constant_slope: true,
            };
            for segment in Segment::ALL {
                let (start, length) = integrands.extent(segment);
                let pi = std::f64::consts::PI;
                let mut expected: Vec<f64> = (-4..=6i64)
                    .flat_map(|k| {
                        let lowest = (2 * k + 1) as f64 * pi;
                        let mirror = (segment == Segment::CH).then_some(g.theta_c - lowest);
                        std::iter::once(lowest - start).chain(mirror)
                    })
                    .filter(|s| *s > 0.0 && s < length)
                    .collect();
                expected.push(0.0);
                expected.push(*length);
                expected.sort_by(f64::total_cmp);
                assert_eq!(
                    integrands.lowest_load_points(segment),
                    expected,
                    "{segment}, φ = {phase}"
                );
                let found: Vec<f64> = precise.lowest_load_points(segment).iter().map(Float::to_f64).collect();
                assert_eq!(found.len(), expected.len(), "{segment}, φ = {phase}: {found:?}");
                for (found, expected) in found.iter().zip(&expected) {
                    assert!(
                        (found - expected).abs() < 1e-12,
                        "{segment}, φ = {phase}: {found} {expected}"
                    );
                }
            }
        }
    }

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

    #[test]
    fn an_analytic_compliance_gets_no_extra_pieces() {
        let cycle = LoadCycle {
            mean_normal_load: 1.0,
            normal_amplitude: 0.6,
            mean_tangential_load: 0.0,
            tangential_amplitude: 0.3,
            phase: 1.0,
            friction: 0.8,
            compliance_ratio: 1.0,
        };
        let g = cycle.geometry().expect("valid cycle");
        let plain = Persson { gamma: 1.0, sigma: 1.0 };
        let knotted = WithKnots {
            inner: plain.clone(),
            knots: vec![0.7, 1.2],
        };
        let count = |compliance: &dyn Compliance<f64>| {
            SegmentIntegrands {
                geometry: &g,
                compliance,
                remove_constant_slope: true,
            }
            .pieces()
            .pieces
            .len()
        };
        assert!(count(&knotted) > count(&plain));
        let lowest: usize = Segment::ALL
            .into_iter()
            .map(|segment| {
                let integrands = SegmentIntegrands {
                    geometry: &g,
                    compliance: &plain,
                    remove_constant_slope: true,
                };
                integrands.lowest_load_points(segment).len() - 1
            })
            .sum();
        assert!(count(&plain) >= lowest && count(&plain) <= 2 * lowest);
    }
}
