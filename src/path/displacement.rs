//! Displacement driving at constant normal load: Q(θ) from a prescribed u(θ), and W.
//!
//! At constant P the contact is a Masing element. From the unloaded state the tangential
//! load Q follows the initial loading curve u = g(Q) = λf (v(P) − v(P − Q/f)) (Cattaneo–Mindlin
//! for any compliance, what the path module's dU gives at constant P); from a reversal
//! (u_r, Q_r) it follows u = u_r ± 2 g(|Q − Q_r|/2), and a branch that meets an older one
//! continues it (Masing's memory). |Q| never exceeds fP: there the contact slides at
//! Q = ±fP, which wipes the memory.
//!
//! Convention (shared with the f64 harmonic-balance friction element): the contact starts
//! unloaded, is loaded monotonically along the initial curve to the extreme
//! u* of u of largest magnitude, and the steady loop is the period that starts there. Every
//! inner loop then closes, and W is the sum over the rainflow cycles of u of the loop
//! dissipation of each: the constant-P force-driven W at the cycle's Q amplitude, plus
//! 2fP times the sliding per direction when the cycle reaches gross slip
//! (proofs/periodic-loading.md).

use std::time::Instant;

use crate::compliance::{check_admissible, Compliance};
use crate::doubts::if_decided;
use crate::quad::gauss_legendre::node_table;
use crate::quad::{tanh_sinh, QuadError};
use crate::real::{Precision, Real};

use super::dissipation::PathDissipation;
use super::events::{sign_changes, solve};
use super::input::{LoadPath, PathError, TrigPoly};
use super::outputs::{LoopPoint, PathHarmonic, PathOutputs};
use super::Contact;

/// The deepest tanh–sinh level of a loop's integral.
const MAX_LEVEL: u32 = 18;

/// The Masing element of a contact at constant normal load P.
#[derive(Debug)]
pub struct MasingLaw<'a, R> {
    normal_load: R,
    friction: R,
    compliance_ratio: R,
    compliance: &'a dyn Compliance<R>,
    /// g(fP), the displacement of the initial curve at gross slip; `None` where v(0) is
    /// infinite (the contact never slides as a whole).
    gross_slip_displacement: Option<R>,
}

impl<'a, R: Real> MasingLaw<'a, R> {
    /// The element at normal load P (> 0) on a contact with compliance v.
    pub fn new(normal_load: &R, contact: &Contact<R>, compliance: &'a dyn Compliance<R>) -> Self {
        let mut law = MasingLaw {
            normal_load: normal_load.clone(),
            friction: contact.friction.clone(),
            compliance_ratio: contact.compliance_ratio.clone(),
            compliance,
            gross_slip_displacement: None,
        };
        let gross = law.scale() * &(compliance.approach(normal_load) - &compliance.approach(&normal_load.int(0)));
        law.gross_slip_displacement = (gross.is_finite() && gross > normal_load.int(0)).then_some(gross);
        law
    }

    /// λf: u = λf U.
    fn scale(&self) -> R {
        self.compliance_ratio.clone() * &self.friction
    }

    /// fP, the largest |Q|.
    pub fn friction_limit(&self) -> R {
        self.friction.clone() * &self.normal_load
    }

    /// g(fP), the displacement of the initial curve at gross slip, if finite.
    pub fn gross_slip_displacement(&self) -> Option<&R> {
        self.gross_slip_displacement.as_ref()
    }

    /// u = g(Q) on the initial loading curve, 0 ≤ Q ≤ fP.
    pub fn initial_displacement(&self, load: &R) -> R {
        let unloaded = (self.normal_load.clone() - &(load.clone() / &self.friction)).max_of(&load.int(0));
        self.scale() * &(self.compliance.approach(&self.normal_load) - &self.compliance.approach(&unloaded))
    }

    /// Q = g⁻¹(u) on the initial loading curve, u ≥ 0, capped at fP.
    pub fn initial_load(&self, displacement: &R) -> R {
        let zero = displacement.int(0);
        if *displacement <= zero {
            return zero;
        }
        if self
            .gross_slip_displacement
            .as_ref()
            .is_some_and(|gross| displacement >= gross)
        {
            return self.friction_limit();
        }
        let p = &self.normal_load;
        let excess = |drop: &R| self.initial_displacement(&(drop.clone() * &self.friction)) - displacement;
        // A drop P(1 − 2⁻ᵏ) of P* = P − Q/f, for the first k where the curve has passed u
        // (below g(fP), some k does), decided on enclosures (one at the root itself is
        // passed over). Not P itself: on enclosures its unloaded load P − (fP)/f
        // straddles 0 unless P and f are exact, where v has no enclosure.
        let mut gap = p.clone() / &p.int(2);
        let mut high = p.clone() - &gap;
        while !if_decided(|| excess(&high) > zero).unwrap_or(false) {
            gap /= &p.int(2);
            let next = p.clone() - &gap;
            if next >= *p {
                return self.friction_limit();
            }
            high = next;
        }
        let drop = solve(
            |d: &R| {
                let rate = self.scale() * &self.compliance.slope(&(p.clone() - d));
                (excess(d), rate)
            },
            &zero,
            &high,
        );
        drop * &self.friction
    }

    /// Q on the branch from the reversal (u_r, Q_r) in direction `direction` (±1) at u,
    /// capped at ±fP: Q_r ± 2 g⁻¹(|u − u_r|/2).
    fn branch_load(&self, reversal: &(R, R), direction: i8, displacement: &R) -> R {
        let travel = (displacement.clone() - &reversal.0).abs() / &displacement.int(2);
        let change = self.initial_load(&travel) * &displacement.int(2 * i64::from(direction));
        let limit = self.friction_limit();
        (reversal.1.clone() + &change).max_of(&(-limit.clone())).min_of(&limit)
    }

    /// u where the branch from (u_r, Q_r) in direction ±1 reaches gross slip, if it can.
    fn branch_slide(&self, reversal: &(R, R), direction: i8) -> Option<R> {
        self.gross_slip_displacement.as_ref()?;
        let sign = reversal.0.int(i64::from(direction));
        let half_change = (self.friction_limit() - &(reversal.1.clone() * &sign)) / &sign.int(2);
        Some(reversal.0.clone() + &(self.initial_displacement(&half_change) * &sign * &sign.int(2)))
    }

    /// W of a closed loop of Q amplitude Q_a ≤ fP at constant P:
    /// 4λf² ∫_{P*}^{P} (P* + P − 2y) (v'(y) − v'(P)) dy, P* = P − Q_a/f (the constant part
    /// of v' integrates to zero against the weight), by tanh–sinh, which the end at P* = 0
    /// that gross slip reaches does not slow; with its error estimate.
    pub fn loop_dissipation(&self, amplitude: &R, deadline: Option<Instant>) -> Result<(R, R), PathError> {
        let q = amplitude.clone() / &self.friction;
        let zero = q.int(0);
        if q <= zero {
            return Ok((zero.clone(), zero));
        }
        let p = &self.normal_load;
        // P* ≥ 0: at Q_a = fP, f(P) / f may round above P.
        let bottom = (p.clone() - &q).max_of(&zero);
        let half_load = p.clone() / &p.int(2);
        let slope = self.compliance.slope_change_about(p);
        let top_slope = self.compliance.slope(p);
        // In the load y: (P* + P − 2y)(v'(y) − v'(P)) on [P*, P], the difference taken
        // about P where it cancels, directly where y is small (down to 0 at gross slip).
        let weight_sum = bottom.clone() + p;
        let integrand = |y: &R| {
            // A node rounded onto the lower end, where v' may be infinite, weighs nothing.
            if *y <= bottom {
                return q.int(0);
            }
            let change = if *y < half_load {
                self.compliance.slope(y) - &top_slope
            } else {
                slope(&(y.clone() - p))
            };
            (weight_sum.clone() - &(y.clone() * &y.int(2))) * &change
        };
        let mut points = vec![bottom.clone()];
        points.extend(
            self.compliance
                .breakpoints(p)
                .into_iter()
                .filter(|y| *y > bottom && *y < *p),
        );
        points.push(p.clone());
        let integrate = |tolerance: &R, level: u32| -> Result<(R, R), PathError> {
            let (mut value, mut error) = (zero.clone(), zero.clone());
            for limits in points.windows(2) {
                let estimate = match deadline {
                    Some(deadline) => {
                        tanh_sinh::integrate_before(integrand, &limits[0], &limits[1], tolerance, level, deadline)
                            .ok_or(PathError::Quadrature(QuadError::OutOfTime))?
                    }
                    None => tanh_sinh::integrate(integrand, &limits[0], &limits[1], tolerance, level),
                };
                value += &estimate.value;
                error += &estimate.error;
            }
            if value.is_finite() {
                Ok((value, error))
            } else {
                Err(PathError::Quadrature(QuadError::NotFinite { piece: "Masing loop" }))
            }
        };
        // A rough value first, for the scale of the relative tolerance.
        let (rough, _) = integrate(&zero, 4)?;
        let tolerance = rough.abs() * &zero.epsilon_like() * &zero.int(256);
        let (value, error) = integrate(&tolerance, MAX_LEVEL)?;
        let factor = self.compliance_ratio.clone() * &self.friction.square() * &zero.int(4);
        let rounding = value.abs() * &zero.epsilon_like() * &zero.int(64);
        Ok((value * &factor, (error + &rounding) * &factor))
    }

    /// W of one rainflow cycle of displacement range Δ: the loop at Q amplitude g⁻¹(Δ/2),
    /// or beyond gross slip (Δ ≥ 2g(fP)) the loop at fP plus 2fP(Δ − 2g(fP)) of sliding.
    pub fn cycle_dissipation(&self, range: &R, deadline: Option<Instant>) -> Result<(R, R), PathError> {
        let two = range.int(2);
        let half = range.clone() / &two;
        match &self.gross_slip_displacement {
            Some(gross) if half >= *gross => {
                let (loop_w, error) = self.loop_dissipation(&self.friction_limit(), deadline)?;
                let sliding = range.clone() - &(gross.clone() * &two);
                Ok((loop_w + &(self.friction_limit() * &two * &sliding), error))
            }
            _ => self.loop_dissipation(&self.initial_load(&half), deadline),
        }
    }
}

/// Where the current branch of a Masing element comes from when no reversal is held.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Base {
    /// The initial loading curve through the unloaded state.
    Initial,
    /// Sliding at Q = ±fP (the sign), which wiped the memory.
    Sliding(i8),
}

/// The state of a Masing element: the reversals it remembers, the current point and the
/// direction of its branch.
#[derive(Clone, Debug)]
pub(crate) struct MasingState<R> {
    reversals: Vec<(R, R)>,
    base: Base,
    displacement: R,
    load: R,
    direction: i8,
}

impl<R: Real> MasingState<R> {
    /// The unloaded state.
    fn unloaded(like: &R) -> Self {
        MasingState {
            reversals: Vec::new(),
            base: Base::Initial,
            displacement: like.int(0),
            load: like.int(0),
            direction: 0,
        }
    }

    /// Q on the current branch at u, moving in direction σ, before any event.
    fn branch(&self, law: &MasingLaw<'_, R>, direction: i8, displacement: &R) -> R {
        match (self.reversals.last(), self.base) {
            (Some(reversal), _) => law.branch_load(reversal, direction, displacement),
            (None, Base::Initial) => {
                let sign = displacement.int(i64::from(direction));
                law.initial_load(&displacement.abs()) * &sign
            }
            (None, Base::Sliding(sign)) => law.friction_limit() * &displacement.int(i64::from(sign)),
        }
    }

    /// Moves monotonically to u, applying the memory; the displacements where the branch
    /// changed on the way (an inner loop closed, gross slip began).
    fn move_to(&mut self, law: &MasingLaw<'_, R>, target: &R) -> Vec<R> {
        let direction = sign_of(&(target.clone() - &self.displacement));
        let mut events = Vec::new();
        if direction == 0 {
            return events;
        }
        if self.direction != 0 && direction != self.direction {
            self.reversals.push((self.displacement.clone(), self.load.clone()));
        }
        self.direction = direction;
        let ahead = |u: &R, from: &R| sign_of(&(u.clone() - from)) == direction;
        let not_past = |u: &R| sign_of(&(target.clone() - u)) != -direction;
        loop {
            if self.reversals.is_empty() && matches!(self.base, Base::Sliding(_)) {
                break;
            }
            // An inner loop closes at the older reversal (for the first one on the initial
            // curve, where the branch meets the opposite initial curve at −u_r).
            let count = self.reversals.len();
            let closing = match (count, self.base) {
                (0, _) => None,
                (1, Base::Initial) => Some(-self.reversals[0].0.clone()),
                (1, Base::Sliding(_)) => None,
                _ => Some(self.reversals[count - 2].0.clone()),
            }
            .filter(|u| ahead(u, &self.displacement) && not_past(u));
            let sliding = match self.reversals.last() {
                Some(reversal) => law.branch_slide(reversal, direction),
                None => law
                    .gross_slip_displacement()
                    .map(|g| g.clone() * &target.int(i64::from(direction))),
            }
            .filter(|u| ahead(u, &self.displacement) && not_past(u));
            // At a tie the loop closes first: its reversal was at gross slip.
            let closes_first = match (&closing, &sliding) {
                (Some(close), Some(slide)) => sign_of(&(slide.clone() - close)) != -direction,
                (Some(_), None) => true,
                (None, _) => false,
            };
            if let (true, Some(close)) = (closes_first, closing) {
                let popped = if count == 1 { 1 } else { 2 };
                self.load = self.reversals[count - popped].1.clone();
                if count == 1 {
                    self.load = -self.load.clone();
                }
                self.reversals.truncate(count - popped);
                self.displacement = close.clone();
                events.push(close);
            } else if let Some(slide) = sliding {
                self.reversals.clear();
                self.base = Base::Sliding(direction);
                self.load = law.friction_limit() * &slide.int(i64::from(direction));
                self.displacement = slide.clone();
                events.push(slide);
            } else {
                break;
            }
        }
        self.load = self.branch(law, direction, target);
        self.displacement = target.clone();
        events
    }
}

/// −1, 0 or 1.
fn sign_of<R: Real>(value: &R) -> i8 {
    let zero = value.int(0);
    if *value > zero {
        1
    } else if *value < zero {
        -1
    } else {
        0
    }
}

/// The ranges of the full cycles a rainflow count finds in turning values that start and
/// end at the extreme of largest magnitude (three-point method: every cycle closes).
///
/// The last value is the first one again: the ranges from the first and back to it are
/// equal exactly, and the cycle they close is counted without comparing them (enclosures
/// of equal values cannot be ordered).
pub fn rainflow_ranges<R: Real>(turning: &[R]) -> Vec<R> {
    let last_index = turning.len().saturating_sub(1);
    let mut stack: Vec<(usize, R)> = Vec::new();
    let mut ranges = Vec::new();
    for (index, value) in turning.iter().enumerate() {
        stack.push((index, value.clone()));
        while stack.len() >= 3 {
            let n = stack.len();
            let newest = (stack[n - 1].1.clone() - &stack[n - 2].1).abs();
            let older = (stack[n - 2].1.clone() - &stack[n - 3].1).abs();
            let closes_on_first = stack[n - 3].0 == 0 && stack[n - 1].0 == last_index;
            if !closes_on_first && newest < older {
                break;
            }
            ranges.push(older);
            let last = stack.swap_remove(n - 1);
            stack.truncate(n - 3);
            stack.push(last);
        }
    }
    ranges
}

/// The steady loop of a displacement-driven contact at constant normal load.
#[derive(Debug)]
pub struct DisplacementCycle<'a, R> {
    law: MasingLaw<'a, R>,
    displacement: TrigPoly<R>,
    /// The turning angles of u over one period from the start u*, the last one 2π after the first.
    turning_angles: Vec<R>,
    /// u at the turning angles.
    turning_values: Vec<R>,
    /// The element's state at each turning angle (before its reversal).
    states: Vec<MasingState<R>>,
}

impl<'a, R: Real> DisplacementCycle<'a, R> {
    /// The steady loop of `path` (whose `tangential` is u): refuses a varying or
    /// non-positive normal load and a u that does not vary.
    pub fn new(path: &LoadPath<R>, contact: &Contact<R>, compliance: &'a dyn Compliance<R>) -> Result<Self, PathError> {
        contact.validate()?;
        let normal = &path.normal;
        let zero = normal.cos[0].int(0);
        let varying = (1..=normal.highest()).find(|&k| normal.cos[k] != zero || normal.sin[k] != zero);
        if let Some(harmonic) = varying {
            return Err(PathError::VaryingNormalLoad { harmonic });
        }
        let load = normal.cos[0].clone();
        if load <= zero {
            return Err(PathError::Separation {
                theta: 0.0,
                load: super::events::quoted(&load),
            });
        }
        let displacement = path.tangential.clone();
        let rate = displacement.derivative();
        let mut angles = sign_changes(&rate);
        if angles.is_empty() {
            return Err(PathError::Malformed(
                "the displacement u does not vary over the period: give u's harmonics k ≥ 1".to_string(),
            ));
        }
        let values: Vec<R> = angles.iter().map(|t| displacement.value(t)).collect();
        // The start: the turning value of largest magnitude (the first, on a tie).
        let start = (0..values.len()).fold(0, |best, i| if values[i].abs() > values[best].abs() { i } else { best });
        angles.rotate_left(start);
        let mut turning_values = values;
        turning_values.rotate_left(start);
        let tau = zero.pi_like() * &zero.int(2);
        let first = angles[0].clone();
        for angle in angles.iter_mut() {
            if *angle < first {
                *angle += &tau;
            }
        }
        angles.push(first + &tau);
        turning_values.push(turning_values[0].clone());
        let law = MasingLaw::new(&load, contact, compliance);
        let mut state = MasingState::unloaded(&zero);
        let mut states = Vec::new();
        for value in &turning_values {
            state.move_to(&law, value);
            states.push(state.clone());
        }
        let (lowest, highest) = slip_load_range(&law, &states);
        check_admissible(compliance, &lowest, &highest)?;
        Ok(DisplacementCycle {
            law,
            displacement,
            turning_angles: angles,
            turning_values,
            states,
        })
    }

    /// The loads the cycle's slip reaches, [P − max|Q|/f, P], its lower end at least P/1024
    /// (in gross slip it reaches 0): where the compliance must be admissible.
    pub fn slip_load_range(&self) -> (R, R) {
        slip_load_range(&self.law, &self.states)
    }

    /// The Masing element.
    pub fn law(&self) -> &MasingLaw<'a, R> {
        &self.law
    }

    /// Q at the turning points of u over the steady period, from the start u*.
    pub fn turning_loads(&self) -> Vec<R> {
        self.states.iter().map(|s| s.load.clone()).collect()
    }

    /// u at the turning points, from the start u* and back to it.
    pub fn turning_displacements(&self) -> &[R] {
        &self.turning_values
    }

    /// W over the rainflow cycles of u.
    pub fn dissipation(&self, deadline: Option<Instant>) -> Result<PathDissipation<R>, PathError> {
        let zero = self.law.normal_load.int(0);
        let (mut total, mut error) = (zero.clone(), zero);
        let ranges = rainflow_ranges(&self.turning_values);
        for range in &ranges {
            let (w, e) = self.law.cycle_dissipation(range, deadline)?;
            total += &w;
            error += &e;
        }
        Ok(PathDissipation {
            total,
            error_estimate: error,
            segments: self.turning_values.len() - 1,
            evaluations: ranges.len(),
        })
    }

    /// Q at θ in the steady period [start, start + 2π].
    fn load_at(&self, theta: &R) -> R {
        let leg = self.leg_of(theta);
        let mut state = self.states[leg].clone();
        state.move_to(&self.law, &self.displacement.value(theta));
        state.load
    }

    /// The leg [θᵢ, θᵢ₊₁] holding θ.
    fn leg_of(&self, theta: &R) -> usize {
        let legs = self.turning_angles.len() - 1;
        (0..legs)
            .find(|&i| *theta <= self.turning_angles[i + 1])
            .unwrap_or(legs - 1)
    }

    /// The angles over the steady period where Q(θ) is not smooth: the turning points and
    /// where an inner loop closes or gross slip begins.
    pub(crate) fn smooth_pieces(&self) -> Vec<(R, R)> {
        let mut pieces = Vec::new();
        for i in 0..self.turning_angles.len() - 1 {
            let (a, b) = (&self.turning_angles[i], &self.turning_angles[i + 1]);
            let mut state = self.states[i].clone();
            let mut cuts = vec![a.clone()];
            for value in state.move_to(&self.law, &self.turning_values[i + 1]) {
                let rate = self.displacement.derivative();
                cuts.push(solve(
                    |t: &R| (self.displacement.value(t) - &value, rate.value(t)),
                    a,
                    b,
                ));
            }
            cuts.push(b.clone());
            pieces.extend(
                cuts.windows(2)
                    .filter(|w| w[1] > w[0])
                    .map(|w| (w[0].clone(), w[1].clone())),
            );
        }
        pieces
    }
}

/// [`DisplacementCycle::slip_load_range`] of a law and its states at the turning points.
fn slip_load_range<R: Real>(law: &MasingLaw<'_, R>, states: &[MasingState<R>]) -> (R, R) {
    let load = &law.normal_load;
    let lowest = load.clone() - &(state_extreme_load(states) / &law.friction);
    let floor = load.clone() / &load.int(1024);
    (lowest.max_of(&floor), load.clone())
}

/// The largest |Q| the element reaches at a turning point.
fn state_extreme_load<R: Real>(states: &[MasingState<R>]) -> R {
    states
        .iter()
        .map(|s| s.load.abs())
        .fold(states[0].load.int(0), |a, b| a.max_of(&b))
}

/// W of a displacement-driven path (its `tangential` is u) at constant normal load.
///
/// ```
/// use microslip::compliance::Persson;
/// use microslip::path::displacement::displacement_dissipation;
/// use microslip::path::{Contact, LoadPath};
///
/// // u = 0.3 cos θ at P = 1.
/// let path = LoadPath::harmonic(&1.0, &0.0, &0.0, &0.3, &0.0);
/// let contact = Contact { friction: 1.0, compliance_ratio: 1.0 };
/// let w = displacement_dissipation(&path, &contact, &Persson { gamma: 1.0, sigma: 1.0 }, None)?;
/// assert!(w.total > 0.0 && w.error_estimate < 1e-12 * w.total);
/// # Ok::<(), microslip::path::PathError>(())
/// ```
pub fn displacement_dissipation<R: Real>(
    path: &LoadPath<R>,
    contact: &Contact<R>,
    compliance: &dyn Compliance<R>,
    deadline: Option<Instant>,
) -> Result<PathDissipation<R>, PathError> {
    DisplacementCycle::new(path, contact, compliance)?.dissipation(deadline)
}

/// Gauss–Legendre points per smooth piece of the loop (each at most 2π/256 long).
const LOOP_RULE: usize = 20;

/// The longest piece of the loop integrated with one rule, as a fraction of the period.
const PIECES_PER_PERIOD: usize = 256;

impl DisplacementCycle<'_, f64> {
    /// ∮ Q du along the steady loop by quadrature on its smooth pieces: an independent
    /// check on the rainflow W.
    pub fn loop_work(&self) -> f64 {
        let rate = self.displacement.derivative();
        self.quadrature(|theta, q| q * rate.value(&theta), 0)
            .first()
            .copied()
            .unwrap_or(0.0)
    }

    /// ∫ h(θ, Q(θ)) dθ over the period, and ∫ Q cos kθ, ∫ Q sin kθ for k = 1 … `harmonics`
    /// (after the first, in pairs).
    fn quadrature(&self, h: impl Fn(f64, f64) -> f64, harmonics: usize) -> Vec<f64> {
        let rule = node_table::<f64>(LOOP_RULE, Precision::DOUBLE);
        let longest = std::f64::consts::TAU / PIECES_PER_PERIOD as f64;
        let mut sums = vec![0.0; 1 + 2 * harmonics];
        for (a, b) in self.smooth_pieces() {
            let parts = ((b - a) / longest).ceil().max(1.0) as usize;
            let width = (b - a) / parts as f64;
            for part in 0..parts {
                let (low, high) = (a + width * part as f64, a + width * (part + 1) as f64);
                let (half, middle) = (0.5 * (high - low), 0.5 * (high + low));
                for (x, w) in rule.nodes.iter().zip(&rule.weights) {
                    let theta = middle + half * x;
                    let q = self.load_at(&theta);
                    let weight = w * half;
                    sums[0] += weight * h(theta, q);
                    for k in 1..=harmonics {
                        let (s, c) = (k as f64 * theta).sin_cos();
                        sums[2 * k - 1] += weight * q * c;
                        sums[2 * k] += weight * q * s;
                    }
                }
            }
        }
        sums
    }
}

/// The outputs of a displacement-driven steady loop whose W is `w`: as for force driving,
/// with u the prescribed displacement (its mean kept) and Q's harmonics by quadrature on
/// the loop's smooth pieces.
pub fn displacement_outputs(
    cycle: &DisplacementCycle<'_, f64>,
    w: f64,
    harmonics_out: usize,
    loop_points: usize,
) -> PathOutputs {
    let pi = std::f64::consts::PI;
    let loads = cycle.turning_loads();
    let spread = |values: &[f64]| {
        let high = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let low = values.iter().copied().fold(f64::INFINITY, f64::min);
        0.5 * (high - low)
    };
    let q_amplitude = spread(&loads);
    let u_amplitude = spread(&cycle.turning_values);
    let sums = cycle.quadrature(|_, q| q, harmonics_out);
    let u = &cycle.displacement;
    let harmonics = (0..=harmonics_out)
        .map(|k| {
            let coefficient = |poly: &[f64]| poly.get(k).copied().unwrap_or(0.0);
            if k == 0 {
                PathHarmonic {
                    k,
                    q_cos: sums[0] / (2.0 * pi),
                    q_sin: 0.0,
                    u_cos: coefficient(&u.cos),
                    u_sin: 0.0,
                }
            } else {
                PathHarmonic {
                    k,
                    q_cos: sums[2 * k - 1] / pi,
                    q_sin: sums[2 * k] / pi,
                    u_cos: coefficient(&u.cos),
                    u_sin: coefficient(&u.sin),
                }
            }
        })
        .collect();
    let tau = std::f64::consts::TAU;
    let start = cycle.turning_angles[0];
    let count = loop_points.max(1);
    let steady_loop = (0..count)
        .map(|j| {
            let theta = tau * j as f64 / count as f64;
            let within = if theta < start { theta + tau } else { theta };
            LoopPoint {
                theta,
                normal_load: cycle.law.normal_load,
                tangential_load: cycle.load_at(&within),
                displacement: u.value(&theta),
            }
        })
        .collect();
    PathOutputs::of_loop(w, q_amplitude, u_amplitude, harmonics, steady_loop)
}
