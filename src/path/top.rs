//! Where a slip front meets the top of the contact while P falls through elements that
//! entered in stick, proven after the sampling that found it.
//!
//! `events::split` samples such a window near its ends and bisects where the front's
//! place changes. With θ'(t) the angle at which the element at the top, load P(t),
//! entered (P(θ') = P(t), P rising over the piece's angles) and v the front's slip
//! variable (x forward, y backward), the front meets the top where
//! h(t) = v(θ'(t)) − v(t) vanishes. On enclosures h is proven not to vanish between small
//! regions around the window's ends and its cut: by its enclosure on sub-intervals, or by
//! its derivative's sign with both ends' signs alike. Inside a region both formulas of the
//! front (at the top, or inside the piece) may hold in parts; their integrands differ by
//! the front's term q̃·(v'(s) − v'(P))·v', whose size is at most
//! |q̃|·|v'|·(v'(P_T) − v'(P)) (v' falls, and the front's load s lies above the lowest slip
//! load P_T), so the region's length times that bound is added to W as an error
//! (proofs/periodic-loading.md, "Where a front meets the top, proven").

// Without ball arithmetic (feature `certified`) no enclosure asks for this proof.
#![cfg_attr(not(feature = "certified"), allow(dead_code))]

use crate::compliance::Compliance;
use crate::real::Real;

use super::events::{decided_sign, solve_between, Loads, Point, SteadyCycle};
use super::memory::{Piece, Shape};
use crate::doubts::if_decided;

/// A window searched for where a front meets the top of the contact.
#[derive(Clone, Debug)]
pub(crate) struct TopSearch<R> {
    /// The window's ends.
    pub window: (R, R),
    /// Where the sampling found the front meeting the top, if it did.
    pub cut: Option<R>,
    /// Whether the front is the forward one (against x) or the backward one (against y).
    pub forward: bool,
    /// The piece of the memory at the top, whose elements entered in stick.
    pub entered: Piece<R>,
}

/// The halvings a sub-interval may take before h's sign on it is given up.
const MOST_HALVINGS: u32 = 10;

/// The fourfold steps by which a region around an end grows until h's sign is decided
/// beside it, from 2⁸ ε of the window's length.
const REGION_STEPS: i32 = 32;

impl<R: Real> SteadyCycle<R> {
    /// A bound of the error in W/(λf²) that the cuts found by sampling may leave (zero
    /// where no window was searched), or `None` where h's sign is not proven outside the
    /// small regions around the cuts and the windows' ends.
    pub(crate) fn sampled_cut_error(&self, compliance: &dyn Compliance<R>) -> Option<R> {
        let mut error = self.lowest_slip.int(0);
        for search in &self.top_searches {
            error += &search.error(self, compliance)?;
        }
        Some(error)
    }
}

impl<R: Real> TopSearch<R> {
    /// The bound of this window's regions, or `None` where h's sign is not proven
    /// between them.
    fn error(&self, cycle: &SteadyCycle<R>, compliance: &dyn Compliance<R>) -> Option<R> {
        let loads = &cycle.loads;
        let (start, end) = &self.window;
        let mut boundaries = vec![start.clone()];
        boundaries.extend(self.cut.clone());
        boundaries.push(end.clone());
        let length = (end.clone() - start).abs();
        let (mut below, mut above): (Vec<R>, Vec<R>) = boundaries.iter().map(Real::real_ends).unzip();
        for gap in 0..boundaries.len() - 1 {
            let (left, right) = (above[gap].clone(), below[gap + 1].clone());
            let from = self.decided_beside(loads, &left, &right, &length)?;
            let to = self.decided_beside(loads, &right, &left, &length)?;
            if !if_decided(|| from < to).unwrap_or(false) {
                return None;
            }
            self.sign_on(loads, &from, &to, MOST_HALVINGS)?;
            above[gap] = from;
            below[gap + 1] = to;
        }
        // Each segment's front formula was read at its middle: one inside a region could
        // carry that region's other formula into the stretch beyond it, where h keeps the
        // sign proven, so no middle may lie in a region.
        for segment in &cycle.segments {
            let middle = ((segment.start.clone() + &segment.end) / &segment.start.int(2)).midpoint_value();
            for (low, high) in below.iter().zip(&above) {
                let apart = if_decided(|| middle < *low || middle > *high)?;
                if !apart {
                    return None;
                }
            }
        }
        let mut error = start.int(0);
        for (low, high) in below.iter().zip(&above) {
            error += &self.region_bound(cycle, compliance, low, high);
        }
        Some(error)
    }

    /// The first point from `end` towards `toward`, at 2⁸ ε of the window's `length` and
    /// fourfold steps, where h's sign is decided and not zero.
    fn decided_beside(&self, loads: &Loads<R>, end: &R, toward: &R, length: &R) -> Option<R> {
        let rightwards = if_decided(|| toward > end)?;
        let mut step = length.clone() * &length.epsilon_like() * &length.int(256);
        for _ in 0..REGION_STEPS {
            let point = if rightwards {
                end.clone() + &step
            } else {
                end.clone() - &step
            }
            .midpoint_value();
            let inside = if_decided(|| if rightwards { point < *toward } else { point > *toward })?;
            if !inside {
                return None;
            }
            if self
                .gap(loads, &point, &point)
                .as_ref()
                .and_then(nonzero_sign)
                .is_some()
            {
                return Some(point);
            }
            step *= &length.int(4);
        }
        None
    }

    /// h's sign on [u, w] (points, u < w), proven: by h's enclosure there, or by h'
    /// keeping its sign with h at both ends of one sign, or by halves.
    fn sign_on(&self, loads: &Loads<R>, u: &R, w: &R, halvings: u32) -> Option<i8> {
        if let Some(sign) = self.gap(loads, u, w).as_ref().and_then(nonzero_sign) {
            return Some(sign);
        }
        if self.gap_rate(loads, u, w).as_ref().and_then(nonzero_sign).is_some() {
            let at = |t: &R| self.gap(loads, t, t).as_ref().and_then(nonzero_sign);
            if let (Some(first), Some(last)) = (at(u), at(w)) {
                if first == last {
                    return Some(first);
                }
            }
        }
        if halvings == 0 {
            return None;
        }
        let middle = ((u.clone() + w) / &u.int(2)).midpoint_value();
        let left = self.sign_on(loads, u, &middle, halvings - 1)?;
        let right = self.sign_on(loads, &middle, w, halvings - 1)?;
        (left == right).then_some(left)
    }

    /// The angles of entry of the elements at the top over [u, w]: P falls over the
    /// window and rises over the piece's angles, so they lie between those at the ends.
    fn entry_angles(&self, loads: &Loads<R>, u: &R, w: &R) -> Option<R> {
        let Shape::Entry { from, to } = &self.entered.shape else {
            return None;
        };
        let at = |t: &R| {
            let load = loads.p(t);
            let start = loads.start_for(Point::p_and_rate, &load, from, to);
            if_decided(|| {
                let offset = |s: &R| loads.at(s).p_and_rate(&load);
                solve_between(offset, (from, offset(from).0), (to, offset(to).0), start)
            })
        };
        Some(at(u)?.union(&at(w)?))
    }

    /// h = v(θ') − v on [u, w].
    fn gap(&self, loads: &Loads<R>, u: &R, w: &R) -> Option<R> {
        let entry = self.entry_angles(loads, u, w)?;
        let (then, now) = (loads.at(&entry), loads.at(&u.union(w)));
        Some(then.slip_variable(self.forward) - &now.slip_variable(self.forward))
    }

    /// h' = v'(θ')·P'(t)/P'(θ') − v'(t) on [u, w].
    fn gap_rate(&self, loads: &Loads<R>, u: &R, w: &R) -> Option<R> {
        let entry = self.entry_angles(loads, u, w)?;
        let (then, now) = (loads.at(&entry), loads.at(&u.union(w)));
        Some(self.rate(&then) * &now.dp / &then.dp - &self.rate(&now))
    }

    /// v' at a point.
    fn rate(&self, point: &Point<R>) -> R {
        if self.forward {
            point.dx()
        } else {
            point.dy()
        }
    }

    /// The region [low, high]'s length times the size of the front's term there,
    /// q̃·(v'(s) − v'(P))·v' with s the load inside the piece at the slip variable's value
    /// (where the front's place in the piece is enclosed on the region), else its bound
    /// |q̃|·|v'|·(v'(P_T) − v'(P)): a bound of the integral of the difference between the
    /// front's two formulas there.
    fn region_bound(&self, cycle: &SteadyCycle<R>, compliance: &dyn Compliance<R>, low: &R, high: &R) -> R {
        let region = low.union(high);
        let point = cycle.loads.at(&region);
        let tangential = point.q.clone() - &cycle.mean_tangential();
        let inside = if_decided(|| {
            let value = point.slip_variable(self.forward);
            let front = self.entered.front_at(&cycle.loads, &region, &value, self.forward);
            compliance.slope_change(&point.p, &(front - &point.p))
        })
        .filter(Real::is_finite);
        let slopes = inside.unwrap_or_else(|| compliance.slope(&cycle.lowest_slip) - &compliance.slope(&point.p));
        (high.clone() - low).abs() * &tangential.abs() * &self.rate(&point).abs() * &slopes.abs()
    }
}

/// The sign of a value decided and not zero.
fn nonzero_sign<R: Real>(value: &R) -> Option<i8> {
    decided_sign(value).filter(|sign| *sign != 0)
}
