//! An independent check of W: a brute-force simulation of the contact through its
//! loading history, using none of the four-segment formulas.
//!
//! The contact is a bed of independent spring elements indexed by the normal load s
//! at which each enters contact (the method-of-dimensionality-reduction picture).
//! With contact stiffness K(P) = 1/v'(P), element s has normal stiffness
//! dK = K'(s) ds and tangential stiffness dK/λ (plus, where K(0) > 0, a base element
//! of stiffness K(0) always in contact). For P > s its normal force is
//! dK·(v(P) − v(s)) — the normal forces sum to P — and its tangential force
//! (dK/λ)(u − w_s) is limited by Coulomb, |t_s| ≤ f·n_s, the slip offset w_s moving
//! when the limit is reached. An element entering contact carries no tangential
//! force; one leaving contact forgets its state. The rigid tangential displacement u
//! is found at every step from Σ t_s(u) = Q. proofs/independent-simulation.md shows
//! why this realises the paper's constitutive assumption u = λf[v(P) − v(P*)].
//!
//! Both grids — entry loads and cycle angles — have nodes where the dissipation is not
//! smooth (the lowest slipping load, P0 − P1, the path's turning points), so that the
//! errors in the element spacing and in the step are smooth O(h²) and three runs at
//! doubling resolution extrapolate them away (order 2 measured in both).

use std::time::Instant;

use crate::compliance::{check_admissible, AdmissibilityError, Compliance};
use crate::cycle::{CycleError, LoadCycle};

/// How the contact is brought from unloaded to the start of the cycle (θ = 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InitialPath {
    /// Normal load first (to P(0)), then tangential load (to Q(0)).
    NormalThenTangential,
    /// Both loads together, in proportion.
    Proportional,
}

/// Resolution and history of a simulation.
#[derive(Clone, Debug)]
pub struct SimulationOptions {
    /// Elements in the coarsest bed (doubled twice for the extrapolation); default 400.
    pub elements: Option<usize>,
    /// Load steps per cycle in the coarsest run (doubled twice); default 1200.
    pub steps: Option<usize>,
    /// The path from the unloaded state.
    pub initial_path: InitialPath,
    /// Extrapolate from three resolutions (Richardson); otherwise one run at the given resolution.
    pub extrapolate: bool,
    /// Stop with [`SimulationError::OutOfTime`] once this instant has passed (checked every step).
    pub deadline: Option<Instant>,
    /// The most memory, in bytes, the runs may need (estimated before anything is allocated);
    /// default 1 GiB.
    pub memory_limit: f64,
    /// Fail with [`SimulationError::ToleranceNotReached`] when the estimated relative error
    /// exceeds this; `None` returns every result with its estimate.
    pub tolerance: Option<f64>,
}

impl Default for SimulationOptions {
    fn default() -> Self {
        SimulationOptions {
            elements: None,
            steps: None,
            initial_path: InitialPath::NormalThenTangential,
            extrapolate: true,
            deadline: None,
            memory_limit: DEFAULT_MEMORY_LIMIT,
            tolerance: None,
        }
    }
}

/// The default [`SimulationOptions::memory_limit`]: 1 GiB.
pub const DEFAULT_MEMORY_LIMIT: f64 = 1024.0 * 1024.0 * 1024.0;

/// One sample of the steady loop.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopSample {
    /// The cycle angle θ.
    pub theta: f64,
    /// P(θ).
    pub normal_load: f64,
    /// Q(θ).
    pub tangential_load: f64,
    /// The rigid tangential displacement u.
    pub displacement: f64,
}

/// The dissipation per cycle of the steady state, measured two ways.
#[non_exhaustive]
#[derive(Clone, Debug)]
pub struct SimulationResult {
    /// ∮ Q du over the last cycle (extrapolated when asked).
    pub w_work: f64,
    /// Σ f n_s |Δw_s| over the last cycle: the frictional work of the elements.
    pub w_friction: f64,
    /// 2(|W − W'| + |W_work − W_friction|) / |W|, W' the extrapolation from the two coarser
    /// runs; without extrapolation, the two measures' difference only. How well it bounds
    /// the true error is measured in proofs/independent-simulation.md.
    pub estimated_rel_error: f64,
    /// The steady loop of the finest run.
    pub steady_loop: Vec<LoopSample>,
    /// Elements of the finest run.
    pub elements: usize,
    /// Steps per cycle of the finest run.
    pub steps: usize,
}

impl SimulationResult {
    /// The significant digits of W that the error estimate vouches for (at most 15, 0 when
    /// the estimate is 100 % or more).
    pub fn vouched_digits(&self) -> u32 {
        let error = self.estimated_rel_error;
        if error <= 0.0 {
            return 15;
        }
        if error >= 1.0 || error.is_nan() {
            return 0;
        }
        ((-error.log10()).floor() as u32).min(15)
    }
}

/// Why a simulation could not run.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SimulationError {
    /// The cycle is outside the theory.
    #[error(transparent)]
    Cycle(#[from] CycleError),
    /// The compliance is not physical over the loads the simulated bed covers.
    #[error("{0} = [0.9 P_T, P0 + P1]: the simulated bed reaches below the permanent-stick load P_T")]
    Compliance(#[from] AdmissibilityError),
    /// Too few elements or steps to mean anything.
    #[error("the simulation needs at least 20 elements and 40 steps per cycle (got {elements} and {steps})")]
    Resolution {
        /// Elements of the coarsest bed asked for.
        elements: usize,
        /// Load steps per cycle asked for.
        steps: usize,
    },
    /// The runs would need more memory than allowed.
    #[error(
        "{elements} elements and {steps} steps per cycle (times 4 in the finest of the three runs) need about {bytes:.1e} bytes of memory, more than the {limit:.1e} allowed"
    )]
    TooLarge {
        /// Elements of the coarsest bed asked for.
        elements: usize,
        /// Load steps per cycle asked for.
        steps: usize,
        /// The memory the three runs would need, estimated before allocating.
        bytes: f64,
        /// The memory allowed.
        limit: f64,
    },
    /// The deadline passed before the simulation finished.
    #[error("the time budget ran out during the run with {elements} elements and {steps} steps per cycle")]
    OutOfTime {
        /// Elements of the run that was under way.
        elements: usize,
        /// Load steps per cycle of that run.
        steps: usize,
    },
    /// The estimated error exceeds the tolerance asked for.
    #[error(
        "the simulation's estimated relative error {estimated:.1e} exceeds the tolerance {tolerance:.0e} (W = {w_work:.3e} as the work of the load, {w_friction:.3e} as frictional work)"
    )]
    ToleranceNotReached {
        /// The estimated relative error of W.
        estimated: f64,
        /// The relative tolerance asked for.
        tolerance: f64,
        /// W as the work of the load (extrapolated).
        w_work: f64,
        /// W as the frictional work (extrapolated).
        w_friction: f64,
    },
    /// Elements below the load P_T that the grid takes as the lowest to slip did slip.
    #[error(
        "elements below the predicted lowest slipping load P_T = {load:.6e} slipped ({share:.1e} of the frictional work): the simulation's grid premise failed"
    )]
    SlipBelowLowestSlip {
        /// The predicted lowest slipping load P_T.
        load: f64,
        /// The share of the frictional work done below it.
        share: f64,
    },
    /// The force balance had no solution (every element slipping) or a number went bad.
    #[error(
        "the simulated contact lost equilibrium at θ = {theta:.4}: the tangential load exceeds what friction holds"
    )]
    Equilibrium {
        /// The cycle angle where it was lost.
        theta: f64,
    },
}

/// The bed of elements: entry loads, stiffnesses, and v at each entry load; element 0
/// is the base (entry 0, always in contact). Elements `1..never_slipping` lie below the
/// lowest slipping load P_T: if one of them slips in the steady cycle, the grid's premise
/// failed and the run says so.
struct Bed {
    entry: Vec<f64>,
    stiffness: Vec<f64>,
    approach_at_entry: Vec<f64>,
    never_slipping: usize,
}

/// The share of the slipping elements kept at least for the loads that stay in contact,
/// [P_T, P0 − P1]: their dissipation rises steeply from zero at P_T. The share with the
/// smallest worst error among those tried (proofs/independent-simulation.md).
const KEPT_SHARE: f64 = 0.25;

impl Bed {
    /// A base element that stands for every contact below 0.9 P_T, then `count` elements,
    /// each with the stiffness K(b) − K(a) of its interval [a, b], placed at the interval's
    /// middle in the grading variable. The grid has a node wherever an element's
    /// dissipation per unit stiffness is not smooth in its entry load s, so that the error
    /// of the bed is a smooth O(h²) that extrapolation removes: at P_T (nothing slips below,
    /// and above it the dissipation rises steeply), at the loads of the path's turning points
    /// (kinks), and at P0 − P1 (above it elements leave and re-enter contact each cycle;
    /// there the grid is uniform in the angle α of s = P0 − P1 cos α, in which leaving and
    /// re-entering are smooth, where in s they go like a square root).
    fn new(compliance: &dyn Compliance<f64>, cycle: &LoadCycle<f64>, lowest_slip: f64, count: usize) -> Bed {
        let (mean, amplitude) = (cycle.mean_normal_load, cycle.normal_amplitude);
        let (lowest, highest) = (mean - amplitude, mean + amplitude);
        let lowest_slip = lowest_slip.min(lowest);
        let low = 0.9 * lowest_slip;
        let turning = turning_point_loads(cycle);
        // A few never-slipping elements [0.9 P_T, P_T], as a check; the loads kept in
        // contact [P_T, P0 − P1], in proportion to their range but at least KEPT_SHARE of
        // the rest; the loads leaving contact [P0 − P1, P0 + P1] (none when P1 = 0).
        let stuck = (count / 50).max(2);
        let slipping = count - stuck;
        let leaving_range = if amplitude > 0.0 { highest - lowest } else { 0.0 };
        let kept = if leaving_range == 0.0 {
            slipping
        } else if lowest > lowest_slip {
            ((slipping as f64 * (lowest - lowest_slip) / (highest - lowest_slip)).round() as usize)
                .max((slipping as f64 * KEPT_SHARE) as usize)
                .clamp(1, slipping / 2)
        } else {
            0
        };
        let between = |a: f64, b: f64| -> Vec<f64> {
            let mut nodes = vec![a];
            nodes.extend(turning.iter().copied().filter(|&t| t > a && t < b));
            nodes.push(b);
            nodes.sort_by(f64::total_cmp);
            nodes
        };
        let angle_of = |s: f64| ((mean - s) / amplitude).clamp(-1.0, 1.0).acos();
        let load_of = |angle: f64| mean - amplitude * angle.cos();
        let mut bed = Bed {
            entry: vec![0.0],
            stiffness: vec![1.0 / compliance.slope(&low)],
            approach_at_entry: vec![f64::NAN],
            never_slipping: 1,
        };
        bed.add_elements(compliance, &[low, lowest_slip], stuck, &|s| s);
        bed.never_slipping = bed.entry.len();
        bed.add_elements(compliance, &between(lowest_slip, lowest), kept, &|s| s);
        if leaving_range > 0.0 {
            let angles: Vec<f64> = between(lowest, highest).into_iter().map(angle_of).collect();
            bed.add_elements(compliance, &angles, slipping - kept, &load_of);
        }
        bed
    }

    /// `total` elements over the pieces between `nodes` (in a grading variable, which `at`
    /// maps to a load), in proportion to each piece's length, at least one each.
    fn add_elements(&mut self, compliance: &dyn Compliance<f64>, nodes: &[f64], total: usize, at: &dyn Fn(f64) -> f64) {
        let length = nodes[nodes.len() - 1] - nodes[0];
        if total == 0 || length.is_nan() || length <= 0.0 {
            return;
        }
        let stiffness_at = |s: f64| 1.0 / compliance.slope(&s);
        for piece in nodes.windows(2) {
            let n = ((total as f64 * (piece[1] - piece[0]) / length).round() as usize).max(1);
            for i in 0..n {
                let x = |k: f64| piece[0] + (piece[1] - piece[0]) * k / n as f64;
                let (a, b, middle) = (at(x(i as f64)), at(x(i as f64 + 1.0)), at(x(i as f64 + 0.5)));
                self.entry.push(middle);
                self.stiffness.push((stiffness_at(b) - stiffness_at(a)).max(0.0));
                self.approach_at_entry.push(compliance.approach(&middle));
            }
        }
    }
}

/// The cycle angles of the path's turning points in [0, 2π): the extremes of Q + fP
/// and Q − fP, where the path's direction in the (P, Q) plane crosses the friction cone
/// |dQ| = f|dP|, so that slip starts or stops (Q ± fP are sinusoids in θ: the extremes of
/// Re[(Q1 e^{−iφ} ± fP1) e^{iθ}] are at θ = −arg(Q1 e^{−iφ} ± fP1) and that + π).
fn turning_angles(cycle: &LoadCycle<f64>) -> Vec<f64> {
    let (f, p1, q1, phi) = (
        cycle.friction,
        cycle.normal_amplitude,
        cycle.tangential_amplitude,
        cycle.phase,
    );
    let tau = 2.0 * std::f64::consts::PI;
    let mut angles = Vec::new();
    for sign in [1.0, -1.0] {
        let (re, im) = (q1 * phi.cos() + sign * f * p1, -q1 * phi.sin());
        let angle = -im.atan2(re);
        angles.push(angle.rem_euclid(tau));
        angles.push((angle + std::f64::consts::PI).rem_euclid(tau));
    }
    angles
}

/// The normal loads at the path's turning points.
fn turning_point_loads(cycle: &LoadCycle<f64>) -> Vec<f64> {
    turning_angles(cycle)
        .into_iter()
        .map(|theta| cycle.mean_normal_load + cycle.normal_amplitude * theta.cos())
        .collect()
}

/// Exactly `steps` angles over one cycle, ending at 2π, with a node at each turning point
/// (where slip starts or stops, the state's error jumps by an amount that depends on
/// where the event falls in its step; on a node it does not) and uniform between them.
fn cycle_angles(cycle: &LoadCycle<f64>, steps: usize) -> Vec<f64> {
    let tau = 2.0 * std::f64::consts::PI;
    let mut nodes = vec![0.0, tau];
    nodes.extend(turning_angles(cycle).into_iter().filter(|&t| t > 0.0 && t < tau));
    nodes.sort_by(f64::total_cmp);
    nodes.dedup();
    // Steps per piece in proportion to its length, at least one, exactly `steps` in all
    // (largest remainders get the spare steps).
    let ideal: Vec<f64> = nodes.windows(2).map(|p| steps as f64 * (p[1] - p[0]) / tau).collect();
    let mut counts: Vec<usize> = ideal.iter().map(|&x| (x.floor() as usize).max(1)).collect();
    let shortfall = |counts: &[usize], i: usize| ideal[i] - counts[i] as f64;
    while counts.iter().sum::<usize>() < steps {
        let i = (0..counts.len())
            .max_by(|&a, &b| shortfall(&counts, a).total_cmp(&shortfall(&counts, b)))
            .unwrap_or(0);
        counts[i] += 1;
    }
    while counts.iter().sum::<usize>() > steps {
        let Some(i) = (0..counts.len())
            .filter(|&i| counts[i] > 1)
            .min_by(|&a, &b| shortfall(&counts, a).total_cmp(&shortfall(&counts, b)))
        else {
            break;
        };
        counts[i] -= 1;
    }
    let mut angles = Vec::with_capacity(steps);
    for (piece, &n) in nodes.windows(2).zip(&counts) {
        angles.extend((1..=n).map(|i| piece[0] + (piece[1] - piece[0]) * i as f64 / n as f64));
    }
    angles
}

/// The lowest load at which any element slips in the steady cycle: the apex of the
/// narrowest friction wedge |Q − Q_c| ≤ f(P − P_c) that holds the whole load path,
/// ½[min(Q + fP) − max(Q − fP)]/f (Q ± fP are sinusoids in θ, so their extremes are
/// their means ∓ their amplitudes). The grid is built on it; were it wrong, the
/// never-slipping elements below it would slip and the run would fail
/// ([`SimulationError::SlipBelowLowestSlip`]).
fn lowest_slipping_load(cycle: &LoadCycle<f64>) -> f64 {
    let (f, p1, q1, phi) = (
        cycle.friction,
        cycle.normal_amplitude,
        cycle.tangential_amplitude,
        cycle.phase,
    );
    // Q1 cos(θ − φ) ± f P1 cos θ has amplitude |Q1 e^{−iφ} ± f P1|.
    let amplitude = |sign: f64| (q1 * phi.cos() + sign * f * p1).hypot(q1 * phi.sin());
    cycle.mean_normal_load - (amplitude(1.0) + amplitude(-1.0)) / (2.0 * f)
}

/// The state of every element: in contact or not, and its slip offset.
struct Contact<'a> {
    bed: &'a Bed,
    /// Frictional work of the elements below P_T since it was last reset.
    work_below_lowest_slip: f64,
    in_contact: Vec<bool>,
    offset: Vec<f64>,
    /// The share of this step's displacement increment each element feels (1, or less
    /// for an element that entered contact during the step).
    engagement: Vec<f64>,
    displacement: f64,
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
    fn new(bed: &'a Bed, friction: f64, ratio: f64) -> Self {
        Contact {
            bed,
            work_below_lowest_slip: 0.0,
            in_contact: vec![false; bed.entry.len()],
            offset: vec![0.0; bed.entry.len()],
            engagement: vec![1.0; bed.entry.len()],
            displacement: 0.0,
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

    /// Moves to loads (P, Q): updates contact, solves Σ t_s(u) = Q, and returns the
    /// frictional work of the step, Σ f n_s |Δw_s|.
    fn step(&mut self, compliance: &dyn Compliance<f64>, load: f64, tangential: f64) -> Option<f64> {
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
        let target = self.ratio * tangential;
        let u = self.solve(approach, target)?;
        // A leaving element's limit falls to zero: it slips back to no force, releasing
        // its elastic displacement through friction at (on average) half its starting limit.
        let mut work = 0.0;
        for (j, elastic, start_limit, share) in leaving {
            let slip = (elastic + share * (u - self.displacement)).abs();
            work += self.bed.stiffness[j] * 0.5 * start_limit / self.ratio * slip;
        }
        // Return mapping: the offsets of slipping elements follow u.
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

/// The measures of one run: W as the work of the load, W as frictional work, the loop.
type Run = (f64, f64, Vec<LoopSample>);

/// One run at a given resolution, on a grid built for the given lowest slipping load (a
/// wrong one is caught): the initial path, then cycles until the loop closes.
fn run(
    cycle: &LoadCycle<f64>,
    compliance: &dyn Compliance<f64>,
    lowest_slip: f64,
    elements: usize,
    steps: usize,
    path: InitialPath,
    deadline: Option<Instant>,
) -> Result<Run, SimulationError> {
    let bed = Bed::new(compliance, cycle, lowest_slip, elements);
    let mut contact = Contact::new(&bed, cycle.friction, cycle.compliance_ratio);
    let equilibrium = |theta: f64| SimulationError::Equilibrium { theta };
    let in_time = || match deadline {
        Some(deadline) if Instant::now() > deadline => Err(SimulationError::OutOfTime { elements, steps }),
        _ => Ok(()),
    };
    let (p_start, q_start) = (cycle.normal_load(&0.0), cycle.tangential_load(&0.0));
    let ramp = steps.max(100);
    for i in 1..=ramp {
        let t = i as f64 / ramp as f64;
        let (p, q) = match path {
            InitialPath::NormalThenTangential => (p_start * (2.0 * t).min(1.0), q_start * (2.0 * t - 1.0).max(0.0)),
            InitialPath::Proportional => (p_start * t, q_start * t),
        };
        in_time()?;
        contact.step(compliance, p, q).ok_or_else(|| equilibrium(0.0))?;
    }
    let angles = cycle_angles(cycle, steps);
    let mut previous_start = f64::NAN;
    let mut last = (0.0, 0.0, Vec::new());
    for _ in 0..8 {
        let mut samples = vec![LoopSample {
            theta: 0.0,
            normal_load: p_start,
            tangential_load: q_start,
            displacement: contact.displacement,
        }];
        let mut friction_work = 0.0;
        let mut work = 0.0;
        contact.work_below_lowest_slip = 0.0;
        for &theta in &angles {
            let (p, q) = (cycle.normal_load(&theta), cycle.tangential_load(&theta));
            let before = *samples.last().unwrap_or(&samples[0]);
            in_time()?;
            friction_work += contact.step(compliance, p, q).ok_or_else(|| equilibrium(theta))?;
            work += 0.5 * (before.tangential_load + q) * (contact.displacement - before.displacement);

            samples.push(LoopSample {
                theta,
                normal_load: p,
                tangential_load: q,
                displacement: contact.displacement,
            });
        }
        let start = samples[0].displacement;

        let closed = (start - previous_start).abs() <= 1e-13 * (start.abs() + work.abs() + 1e-300);
        last = (work, friction_work, samples);
        if closed {
            break;
        }
        previous_start = start;
    }
    // Elements below P_T carry rounding-level slip at most (≤ 1e−14 of W measured).
    let below = contact.work_below_lowest_slip / last.1.abs().max(f64::MIN_POSITIVE);
    if below > 1e-9 {
        return Err(SimulationError::SlipBelowLowestSlip {
            load: lowest_slip,
            share: below,
        });
    }
    Ok(last)
}

/// W of the steady cycle by simulation (f64), extrapolated from three resolutions.
///
/// ```
/// use microslip::compliance::Persson;
/// use microslip::cycle::LoadCycle;
/// use microslip::dissipation::{dissipation, Options};
/// use microslip::simulate::{simulate, SimulationOptions};
///
/// let cycle = LoadCycle {
///     mean_normal_load: 1.0,
///     normal_amplitude: 0.4,
///     mean_tangential_load: 0.0,
///     tangential_amplitude: 0.5,
///     phase: 0.4 * std::f64::consts::PI,
///     friction: 1.0,
///     compliance_ratio: 1.0,
/// };
/// let persson = Persson { gamma: 1.0, sigma: 1.0 };
/// let coarse = SimulationOptions { elements: Some(100), steps: Some(400), ..SimulationOptions::default() };
/// let simulated = simulate(&cycle, &persson, &coarse)?;
/// let integrated = dissipation(&cycle, &persson, &Options::default())?.total;
/// assert!((simulated.w_work / integrated - 1.0).abs() < 1e-3);
/// assert!((simulated.w_friction / integrated - 1.0).abs() < 1e-3);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn simulate(
    cycle: &LoadCycle<f64>,
    compliance: &dyn Compliance<f64>,
    options: &SimulationOptions,
) -> Result<SimulationResult, SimulationError> {
    cycle.validate()?;
    // The bed reaches down to 0.9 P_T (never-slipping elements that check the grid).
    let lowest_slip = lowest_slipping_load(cycle);
    let low = 0.9 * lowest_slip.min(cycle.mean_normal_load - cycle.normal_amplitude);
    check_admissible(compliance, &low, &(cycle.mean_normal_load + cycle.normal_amplitude))?;
    let elements = options.elements.unwrap_or(400);
    let steps = options.steps.unwrap_or(1200);
    if elements < 20 || steps < 40 {
        return Err(SimulationError::Resolution { elements, steps });
    }
    let bytes = memory_needed(elements, steps, options.extrapolate);
    if bytes > options.memory_limit || bytes.is_nan() {
        return Err(SimulationError::TooLarge {
            elements,
            steps,
            bytes,
            limit: options.memory_limit,
        });
    }
    let result = simulate_at(cycle, compliance, options, lowest_slip, elements, steps)?;
    match options.tolerance {
        Some(tolerance) if result.estimated_rel_error > tolerance || result.estimated_rel_error.is_nan() => {
            Err(SimulationError::ToleranceNotReached {
                estimated: result.estimated_rel_error,
                tolerance,
                w_work: result.w_work,
                w_friction: result.w_friction,
            })
        }
        _ => Ok(result),
    }
}

/// An upper estimate of the bytes the runs need: per element its entry load, stiffness,
/// v at entry, slip offset, engagement and contact flag, per step a loop sample and an
/// angle; the extrapolation keeps the loops of all three runs (1 + 2 + 4 times the steps)
/// and the finest bed has four times the elements.
fn memory_needed(elements: usize, steps: usize, extrapolate: bool) -> f64 {
    let (finest, loops) = if extrapolate { (4.0, 7.0) } else { (1.0, 1.0) };
    let per_element = (5 * std::mem::size_of::<f64>() + 1) as f64;
    let per_step = (std::mem::size_of::<LoopSample>() + std::mem::size_of::<f64>()) as f64;
    // A bed has a few more elements than asked (at least one per piece between nodes).
    per_element * (finest * elements as f64 * 1.05 + 64.0) + per_step * (loops * steps as f64 + 3.0 * loops)
}

/// The runs at the given resolution, extrapolated when asked.
fn simulate_at(
    cycle: &LoadCycle<f64>,
    compliance: &dyn Compliance<f64>,
    options: &SimulationOptions,
    lowest_slip: f64,
    elements: usize,
    steps: usize,
) -> Result<SimulationResult, SimulationError> {
    if !options.extrapolate {
        let (w_work, w_friction, steady_loop) = run(
            cycle,
            compliance,
            lowest_slip,
            elements,
            steps,
            options.initial_path,
            options.deadline,
        )?;
        if w_friction == 0.0 {
            return Ok(stuck_throughout(steady_loop, elements, steps));
        }
        return Ok(SimulationResult {
            estimated_rel_error: (w_work - w_friction).abs() / w_work.abs().max(f64::MIN_POSITIVE),
            w_work,
            w_friction,
            steady_loop,
            elements,
            steps,
        });
    }
    // Three resolutions, each doubling elements and steps: with the grids aligned to where
    // the dissipation is not smooth, both errors are O(h²) with smooth coefficients, so
    // Richardson with order 2 removes them; the two extrapolations (from the coarser and
    // from the finer pair) differ by about the error of the coarser one.
    let runs = [1usize, 2, 4]
        .iter()
        .map(|&m| {
            run(
                cycle,
                compliance,
                lowest_slip,
                elements * m,
                steps * m,
                options.initial_path,
                options.deadline,
            )
        })
        .collect::<Result<Vec<_>, _>>()?;
    if runs.iter().all(|(_, friction, _)| *friction == 0.0) {
        let (_, _, steady_loop) = runs.into_iter().last().unwrap_or_default();
        return Ok(stuck_throughout(steady_loop, elements * 4, steps * 4));
    }
    let richardson = |coarse: f64, fine: f64| (4.0 * fine - coarse) / 3.0;
    let work = richardson(runs[1].0, runs[2].0);
    let friction = richardson(runs[1].1, runs[2].1);
    let coarser_work = richardson(runs[0].0, runs[1].0);
    let scale = work.abs().max(f64::MIN_POSITIVE);
    // Twice the two discrepancies: at the 1e−8 level their sum alone fell short of the
    // true error in 2 of 140 random cases (by up to 1.6 times).
    let estimated_rel_error = 2.0 * ((work - coarser_work).abs() + (work - friction).abs()) / scale;
    let (_, _, steady_loop) = runs.into_iter().last().unwrap_or_default();
    Ok(SimulationResult {
        w_work: work,
        w_friction: friction,
        estimated_rel_error,
        steady_loop,
        elements: elements * 4,
        steps: steps * 4,
    })
}

/// The result where no element slipped: the frictional work, a sum of non-negative terms
/// f n_s |Δw_s|, is exactly 0, so the contact stuck throughout and W = 0 exactly (a constant
/// v', say), whatever rounding left in ∮ Q du.
fn stuck_throughout(steady_loop: Vec<LoopSample>, elements: usize, steps: usize) -> SimulationResult {
    SimulationResult {
        w_work: 0.0,
        w_friction: 0.0,
        estimated_rel_error: 0.0,
        steady_loop,
        elements,
        steps,
    }
}

/// The steady loop as CSV: a header `theta,P,Q,u`, then one line per sample.
pub fn loop_csv(result: &SimulationResult) -> Result<String, csv::Error> {
    let rows = result
        .steady_loop
        .iter()
        .map(|s| [s.theta, s.normal_load, s.tangential_load, s.displacement].map(|value| value.to_string()));
    crate::files::csv_text(&["theta", "P", "Q", "u"], rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compliance::parse_spec;
    use crate::real::Precision;

    fn cycle(phase: f64, mean_tangential_load: f64) -> LoadCycle<f64> {
        LoadCycle {
            mean_normal_load: 1.0,
            normal_amplitude: 0.4,
            mean_tangential_load,
            tangential_amplitude: 0.5,
            phase,
            friction: 1.0,
            compliance_ratio: 1.0,
        }
    }

    #[test]
    fn a_grid_built_on_a_wrong_lowest_slipping_load_is_caught() {
        let compliance = parse_spec::<f64>("persson:gamma=1,sigma=1", Precision::DOUBLE).unwrap();
        let cycle = cycle(0.4 * std::f64::consts::PI, 0.0);
        let path = InitialPath::NormalThenTangential;
        let right = lowest_slipping_load(&cycle);
        assert!(run(&cycle, compliance.as_ref(), right, 200, 600, path, None).is_ok());
        // Halfway between P_T and P0 − P1: the never-slipping elements then slip.
        let wrong = 0.5 * (right + 0.6);
        match run(&cycle, compliance.as_ref(), wrong, 200, 600, path, None) {
            Err(SimulationError::SlipBelowLowestSlip { load, share }) => {
                assert_eq!(load, wrong);
                assert!(share > 1e-6, "{share}");
            }
            other => panic!("expected the premise to fail, got {:?}", other.map(|run| run.0)),
        }
    }

    #[test]
    fn the_lowest_slipping_load_is_the_cycles_permanent_stick_load() {
        // Two derivations: the wedge apex from the sinusoids Q ± fP here, and σ₊, σ₋ in cycle.rs.
        for k in 0..40 {
            let phase = -7.0 + 0.37 * f64::from(k);
            let cycle = cycle(phase, 0.1);
            let (here, there) = (lowest_slipping_load(&cycle), cycle.permanent_stick_load());
            assert!((here - there).abs() < 1e-14, "φ = {phase}: {here} vs {there}");
        }
    }

    #[test]
    fn turning_angles_are_where_q_plus_or_minus_fp_is_stationary() {
        for k in 0..40 {
            let cycle = cycle(-7.0 + 0.37 * f64::from(k), 0.0);
            let angles = turning_angles(&cycle);
            assert_eq!(angles.len(), 4);
            for theta in angles {
                assert!((0.0..2.0 * std::f64::consts::PI).contains(&theta));
                let rate = |sign: f64| {
                    -cycle.tangential_amplitude * (theta - cycle.phase).sin()
                        - sign * cycle.friction * cycle.normal_amplitude * theta.sin()
                };
                assert!(rate(1.0).abs().min(rate(-1.0).abs()) < 1e-14, "θ = {theta}");
            }
        }
    }

    #[test]
    fn the_cycle_angles_are_exactly_the_steps_asked_with_every_turning_point_a_node() {
        let cycle = cycle(0.4 * std::f64::consts::PI, 0.0);
        for steps in [40, 41, 300, 1201] {
            let angles = cycle_angles(&cycle, steps);
            assert_eq!(angles.len(), steps);
            assert!(angles.windows(2).all(|w| w[0] < w[1]));
            assert_eq!(angles[steps - 1], 2.0 * std::f64::consts::PI);
            for turning in turning_angles(&cycle) {
                assert!(angles.iter().any(|&a| (a - turning).abs() < 1e-15), "{turning}");
            }
        }
    }
}
