//! The state of every element of the bed through the loading, and one load step: which
//! elements touch, the displacement u (prescribed, or solved from the force balance
//! Σ t_s(u) = Q), and the frictional work of the slip.

use crate::compliance::Compliance;
use crate::path::Drive;

use super::bed::Bed;

/// The state of every element: in contact or not, and its slip offset.
pub(super) struct Contact<'a> {
    bed: &'a Bed,
    /// Frictional work of the elements below P_T since it was last reset.
    pub(super) work_below_lowest_slip: f64,
    in_contact: Vec<bool>,
    offset: Vec<f64>,
    /// The share of this step's displacement increment each element feels (1, or less
    /// for an element that entered contact during the step).
    engagement: Vec<f64>,
    pub(super) displacement: f64,
    /// Q at the last step: the one prescribed, or Σ t_s under a prescribed displacement.
    pub(super) tangential_load: f64,
    /// P at the last step.
    load: f64,
    /// v(P) at the last step.
    approach: f64,
    /// The normal load on the base element at the last step.
    base_load: f64,
    friction: f64,
    ratio: f64,
}

impl<'a> Contact<'a> {
    pub(super) fn new(bed: &'a Bed, friction: f64, ratio: f64) -> Self {
        Contact {
            bed,
            work_below_lowest_slip: 0.0,
            in_contact: vec![false; bed.entry.len()],
            offset: vec![0.0; bed.entry.len()],
            engagement: vec![1.0; bed.entry.len()],
            displacement: 0.0,
            tangential_load: 0.0,
            load: 0.0,
            approach: f64::NEG_INFINITY,
            base_load: 0.0,
            friction,
            ratio,
        }
    }

    /// λ·f·n/k: for an element λf(v(P) − v(s)) (with v(P) given), for the base element
    /// λf times its share of the normal load over its stiffness.
    fn slip_limit(&self, j: usize, approach: f64, base_normal: f64) -> f64 {
        // A base element of no stiffness (K(0) = 0) carries nothing.
        if self.bed.stiffness[j] == 0.0 {
            return 0.0;
        }
        let per_stiffness = if j == 0 {
            base_normal / self.bed.stiffness[0]
        } else {
            approach - self.bed.approach_at_entry[j]
        };
        self.ratio * self.friction * per_stiffness.max(0.0)
    }

    /// The normal load the base element carries: P less what the others carry.
    fn base_normal(&self, load: f64, approach: f64) -> f64 {
        let others: f64 = (1..self.bed.entry.len())
            .filter(|&j| self.bed.entry[j] < load)
            .map(|j| self.bed.stiffness[j] * (approach - self.bed.approach_at_entry[j]))
            .sum();
        load - others
    }

    /// λ·Σ t_s at displacement u, and the elastic stiffness there.
    fn force(&self, u: f64, approach: f64) -> (f64, f64) {
        let (mut force, mut slope) = (0.0, 0.0);
        for j in 0..self.bed.entry.len() {
            if !self.in_contact[j] {
                continue;
            }
            let limit = self.slip_limit(j, approach, self.base_load);
            let elastic = self.trial_elastic(j, u);
            let k = self.bed.stiffness[j];
            if elastic.abs() < limit {
                force += k * elastic;
                slope += k * self.engagement[j];
            } else {
                force += k * limit.copysign(elastic);
            }
        }
        (force, slope)
    }

    /// The element's elastic displacement if it sticks through the step to u: an element
    /// that entered contact a fraction t into the step feels only (1 − t) of the step's
    /// displacement increment.
    fn trial_elastic(&self, j: usize, u: f64) -> f64 {
        (self.displacement - self.offset[j]) + self.engagement[j] * (u - self.displacement)
    }

    /// Moves to the normal load P and the prescribed tangential quantity (Q under force
    /// driving, u under displacement driving): updates contact, solves Σ t_s(u) = Q where Q
    /// is prescribed, and returns the frictional work of the step, Σ f n_s |Δw_s|. One
    /// function because its three passes (contact, solve, return mapping) share the
    /// step's loads and approaches and the state of the elements leaving contact.
    pub(super) fn step(
        &mut self,
        compliance: &dyn Compliance<f64>,
        load: f64,
        prescribed: f64,
        drive: Drive,
    ) -> Option<f64> {
        let approach = compliance.approach(&load);
        let (previous_approach, previous_base) = (self.approach, self.base_load);
        self.approach = approach;
        self.base_load = self.base_normal(load, approach);
        // Entering elements start unloaded where P crosses their entry load; leaving ones forget.
        let previous_load = self.load;
        self.load = load;
        // Elements leaving: (index, elastic displacement and limit at the start, share of
        // the step before they leave).
        let mut leaving = Vec::new();
        for j in 0..self.bed.entry.len() {
            let entry = self.bed.entry[j];
            let touching = entry < load || j == 0;
            if self.in_contact[j] && !touching {
                let start_limit = self.slip_limit(j, previous_approach, previous_base);
                let share = (previous_load - entry) / (previous_load - load);
                leaving.push((j, self.displacement - self.offset[j], start_limit, share));
            }
            self.engagement[j] = 1.0;
            if touching && !self.in_contact[j] {
                self.offset[j] = self.displacement;
                if load > previous_load && entry > previous_load {
                    self.engagement[j] = (load - entry) / (load - previous_load);
                }
            }
            self.in_contact[j] = touching;
        }
        let u = match drive {
            Drive::Force => self.solve(approach, self.ratio * prescribed)?,
            Drive::Displacement => prescribed,
        };
        // A leaving element's limit falls to zero: it slips back to no force, releasing
        // its elastic displacement through friction at (on average) half its starting limit.
        let mut work = 0.0;
        for (j, elastic, start_limit, share) in leaving {
            let slip = (elastic + share * (u - self.displacement)).abs();
            work += self.bed.stiffness[j] * 0.5 * start_limit / self.ratio * slip;
        }
        // Return mapping: the offsets of slipping elements follow u.
        let mut force = 0.0;
        for j in 0..self.bed.entry.len() {
            if !self.in_contact[j] {
                continue;
            }
            let limit = self.slip_limit(j, approach, self.base_load);
            let elastic = self.trial_elastic(j, u);
            let held = if elastic.abs() > limit {
                limit.copysign(elastic)
            } else {
                elastic
            };
            self.offset[j] = u - held;
            force += self.bed.stiffness[j] * held;
            if elastic.abs() > limit {
                let moved = elastic - held;
                // |t| = f n = k·limit/λ, times the slip |Δw|, with the limit averaged over
                // the step (trapezoid) so that the work is second-order in the step.
                let mean_limit = 0.5 * (limit + self.slip_limit(j, previous_approach, previous_base));
                let slip_work = self.bed.stiffness[j] * mean_limit / self.ratio * moved.abs();
                work += slip_work;
                if (1..self.bed.never_slipping).contains(&j) {
                    self.work_below_lowest_slip += slip_work;
                }
            }
        }
        self.displacement = u;
        self.tangential_load = match drive {
            Drive::Force => prescribed,
            Drive::Displacement => force / self.ratio,
        };
        if !self.tangential_load.is_finite() {
            return None;
        }
        Some(work)
    }

    /// Safeguarded Newton on the monotone piecewise-linear force balance: Newton from the
    /// last displacement (each element's force saturates, so the iterates usually approach
    /// the root from one side in two or three steps), bisection inside a bracket once the
    /// root is bracketed or Newton stalls, and an outward search if it has no slope.
    fn solve(&self, approach: f64, target: f64) -> Option<f64> {
        let residual = |u: f64| {
            let (force, slope) = self.force(u, approach);
            (force - target, slope)
        };
        let scale = approach.abs().max(1e-300) * self.ratio * self.friction + self.displacement.abs() + 1e-300;
        let tolerance = 1e-14 * target.abs().max(scale * 1e-3);
        let mut u = self.displacement;
        let (mut r, mut slope) = residual(u);
        // [low, high] brackets the root where finite: r(low) < 0 < r(high).
        let (mut low, mut high) = (f64::NEG_INFINITY, f64::INFINITY);
        for _ in 0..200 {
            if r.abs() <= tolerance {
                return Some(u);
            }
            if r < 0.0 {
                low = u;
            } else {
                high = u;
            }
            if high - low <= 1e-15 * scale {
                return Some(u);
            }
            let newton = if slope > 0.0 { u - r / slope } else { f64::NAN };
            u = if newton > low && newton < high {
                newton
            } else if low.is_finite() && high.is_finite() {
                0.5 * (low + high)
            } else {
                // No slope or a Newton step out of the bracket on the open side: step outward.
                let width = if low.is_finite() && high.is_finite() {
                    high - low
                } else {
                    scale * 1e-3
                };
                let reach = width.max((u - self.displacement).abs() * 2.0).max(scale * 1e-3);
                if r < 0.0 {
                    u + reach
                } else {
                    u - reach
                }
            };
            (r, slope) = residual(u);
            if !r.is_finite() {
                return None;
            }
        }
        (low.is_finite() && high.is_finite()).then_some(u)
    }
}
