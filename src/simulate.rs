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

use std::io::Write;
use std::path::Path;

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
}

impl Default for SimulationOptions {
    fn default() -> Self {
        SimulationOptions {
            elements: None,
            steps: None,
            initial_path: InitialPath::NormalThenTangential,
            extrapolate: true,
        }
    }
}

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
#[derive(Clone, Debug)]
pub struct SimulationResult {
    /// ∮ Q du over the last cycle (extrapolated when asked).
    pub w_work: f64,
    /// Σ f n_s |Δw_s| over the last cycle: the frictional work of the elements.
    pub w_friction: f64,
    /// (2|extrapolated − finest run| + |W_work − W_friction|) / |W|; without extrapolation,
    /// the two measures' difference only.
    pub estimated_rel_error: f64,
    /// The steady loop of the finest run.
    pub steady_loop: Vec<LoopSample>,
    /// Elements of the finest run.
    pub elements: usize,
    /// Steps per cycle of the finest run.
    pub steps: usize,
}

/// Why a simulation could not run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SimulationError {
    /// The cycle is outside the theory.
    #[error(transparent)]
    Cycle(#[from] CycleError),
    /// The compliance is not physical over the cycle's loads.
    #[error(transparent)]
    Compliance(#[from] AdmissibilityError),
    /// Too few elements or steps to mean anything.
    #[error("the simulation needs at least 20 elements and 40 steps per cycle (got {elements} and {steps})")]
    Resolution { elements: usize, steps: usize },
    /// The force balance had no solution (every element slipping) or a number went bad.
    #[error(
        "the simulated contact lost equilibrium at θ = {theta:.4}: the tangential load exceeds what friction holds"
    )]
    Equilibrium { theta: f64 },
}

/// The bed of elements: entry loads, stiffnesses, and v at each entry load; element 0
/// is the base (entry 0, always in contact).
struct Bed {
    entry: Vec<f64>,
    stiffness: Vec<f64>,
    approach_at_entry: Vec<f64>,
}

impl Bed {
    /// A base element that stands for every contact below `low` (always in contact, with
    /// the stiffness K(low) they sum to), then `count` elements uniform in s over
    /// [low, top], each with the stiffness K(b) − K(a) of its interval [a, b], at the
    /// interval's midpoint. `low` lies below every load at which elements slip in the
    /// steady state; it only places nodes, and the base element may still slip (its
    /// limit is f times the normal load the other elements do not carry). Below `low`
    /// the compliance is never evaluated: it need only be physical over the cycle's loads.
    fn new(compliance: &dyn Compliance<f64>, low: f64, top: f64, count: usize) -> Bed {
        let stiffness_at = |s: f64| 1.0 / compliance.slope(&s);
        let mut bed = Bed {
            entry: vec![0.0],
            stiffness: vec![stiffness_at(low)],
            approach_at_entry: vec![f64::NAN],
        };
        for i in 0..count {
            let (a, b) = (
                low + (top - low) * i as f64 / count as f64,
                low + (top - low) * (i + 1) as f64 / count as f64,
            );
            let middle = 0.5 * (a + b);
            bed.entry.push(middle);
            bed.stiffness.push((stiffness_at(b) - stiffness_at(a)).max(0.0));
            bed.approach_at_entry.push(compliance.approach(&middle));
        }
        bed
    }
}

/// The state of every element: in contact or not, and its slip offset.
struct Contact<'a> {
    bed: &'a Bed,
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
        for j in 0..self.bed.entry.len() {
            let entry = self.bed.entry[j];
            let touching = entry < load || j == 0;
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
        // Return mapping: the offsets of slipping elements follow u.
        let mut work = 0.0;
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
                work += self.bed.stiffness[j] * mean_limit / self.ratio * moved.abs();
            }
        }
        self.displacement = u;
        Some(work)
    }

    /// Safeguarded Newton on the monotone piecewise-linear force balance.
    fn solve(&self, approach: f64, target: f64) -> Option<f64> {
        let residual = |u: f64| {
            let (force, slope) = self.force(u, approach);
            (force - target, slope)
        };
        let mut u = self.displacement;
        let (mut r, mut slope) = residual(u);
        if r == 0.0 {
            return Some(u);
        }
        // Bracket the root by stepping outward.
        let scale = approach.abs().max(1e-300) * self.ratio * self.friction + u.abs() + 1e-300;
        let mut step = scale * 1e-3;
        let (mut low, mut high) = (u, u);
        let direction = if r < 0.0 { 1.0 } else { -1.0 };
        let mut far = u;
        for _ in 0..200 {
            far += direction * step;
            step *= 2.0;
            let (value, _) = residual(far);
            if (value > 0.0) == (direction > 0.0) || value == 0.0 {
                break;
            }
            if direction > 0.0 {
                low = far;
            } else {
                high = far;
            }
        }
        if direction > 0.0 {
            high = far;
        } else {
            low = far;
        }
        let (r_low, _) = residual(low);
        let (r_high, _) = residual(high);
        if !(r_low <= 0.0 && r_high >= 0.0) {
            return None;
        }
        for _ in 0..200 {
            let newton = if slope > 0.0 { u - r / slope } else { f64::NAN };
            u = if newton > low && newton < high {
                newton
            } else {
                0.5 * (low + high)
            };
            (r, slope) = residual(u);
            if r.abs() <= 1e-14 * target.abs().max(scale * 1e-3) || high - low <= 1e-15 * scale {
                return Some(u);
            }
            if r < 0.0 {
                low = u;
            } else {
                high = u;
            }
        }
        Some(u)
    }
}

/// One run at a given resolution: the initial path, then cycles until the loop closes.
fn run(
    cycle: &LoadCycle<f64>,
    compliance: &dyn Compliance<f64>,
    elements: usize,
    steps: usize,
    path: InitialPath,
) -> Result<(f64, f64, Vec<LoopSample>), SimulationError> {
    let low = cycle
        .permanent_stick_load()
        .min(cycle.mean_normal_load - cycle.normal_amplitude)
        * 0.9;
    let top = cycle.mean_normal_load + cycle.normal_amplitude;
    let bed = Bed::new(compliance, low, top, elements);
    let mut contact = Contact::new(&bed, cycle.friction, cycle.compliance_ratio);
    let equilibrium = |theta: f64| SimulationError::Equilibrium { theta };
    let (p_start, q_start) = (cycle.normal_load(&0.0), cycle.tangential_load(&0.0));
    let ramp = steps.max(100);
    for i in 1..=ramp {
        let t = i as f64 / ramp as f64;
        let (p, q) = match path {
            InitialPath::NormalThenTangential => (p_start * (2.0 * t).min(1.0), q_start * (2.0 * t - 1.0).max(0.0)),
            InitialPath::Proportional => (p_start * t, q_start * t),
        };
        contact.step(compliance, p, q).ok_or_else(|| equilibrium(0.0))?;
    }
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
        for i in 1..=steps {
            let theta = 2.0 * std::f64::consts::PI * i as f64 / steps as f64;
            let (p, q) = (cycle.normal_load(&theta), cycle.tangential_load(&theta));
            let before = *samples.last().unwrap_or(&samples[0]);
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
    Ok(last)
}

/// W of the steady cycle by simulation (f64), extrapolated from three resolutions.
pub fn simulate(
    cycle: &LoadCycle<f64>,
    compliance: &dyn Compliance<f64>,
    options: &SimulationOptions,
) -> Result<SimulationResult, SimulationError> {
    cycle.validate()?;
    let low = (cycle.mean_normal_load - cycle.normal_amplitude).min(cycle.permanent_stick_load());
    check_admissible(compliance, &low, &(cycle.mean_normal_load + cycle.normal_amplitude))?;
    let elements = options.elements.unwrap_or(400);
    let steps = options.steps.unwrap_or(1200);
    if elements < 20 || steps < 40 {
        return Err(SimulationError::Resolution { elements, steps });
    }
    if !options.extrapolate {
        let (w_work, w_friction, steady_loop) = run(cycle, compliance, elements, steps, options.initial_path)?;
        return Ok(SimulationResult {
            estimated_rel_error: (w_work - w_friction).abs() / w_work.abs().max(f64::MIN_POSITIVE),
            w_work,
            w_friction,
            steady_loop,
            elements,
            steps,
        });
    }
    // Three resolutions, each doubling elements and steps (h ∝ 1/elements ∝ 1/steps).
    let runs = [1usize, 2, 4]
        .iter()
        .map(|&m| run(cycle, compliance, elements * m, steps * m, options.initial_path))
        .collect::<Result<Vec<_>, _>>()?;
    // Richardson with the order observed from the three runs (clamped to [1, 3]).
    let extrapolate = |a: f64, b: f64, c: f64| {
        let order = ((b - a) / (c - b)).abs().log2().clamp(1.0, 3.0);
        c + (c - b) / (2f64.powf(order) - 1.0)
    };
    let work = extrapolate(runs[0].0, runs[1].0, runs[2].0);
    let friction = extrapolate(runs[0].1, runs[1].1, runs[2].1);
    // The error estimate: twice the extrapolation's own correction, plus the gap between
    // the two energy measures.
    let finest = runs[2].0;
    let scale = work.abs().max(f64::MIN_POSITIVE);
    let estimated_rel_error = (2.0 * (work - finest).abs() + (work - friction).abs()) / scale;
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

/// Writes the steady loop as CSV: theta,P,Q,u.
pub fn write_loop_csv(path: &Path, result: &SimulationResult) -> std::io::Result<()> {
    let mut file = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(file, "theta,P,Q,u")?;
    for s in &result.steady_loop {
        writeln!(
            file,
            "{},{},{},{}",
            s.theta, s.normal_load, s.tangential_load, s.displacement
        )?;
    }
    file.flush()
}
