//! The bed of spring elements that stands for the contact under a varying normal load, the
//! picture `microslip simulate` follows (proofs/independent-simulation.md): element s
//! enters contact once P > s, with tangential stiffness dK/λ, dK = K'(s) ds, K = 1/v', and
//! holds at most f times its normal force dK (v(P) − v(s)). Graded once per normal-load
//! history, for any displacement.

use crate::compliance::Compliance;

/// The deepest slip front, below the lowest normal load and relative to it, that the
/// geometric grading resolves: a slip annulus thinner than this falls in one element.
const SHALLOWEST_DEPTH: f64 = 1e-6;

/// The share of the elements on [0, P_min/2], graded s ∝ τ³ where K and v may have
/// power-law singularities at s = 0 (Hertz: K ∝ s^(1/3)).
const DEEP_SHARE: f64 = 0.125;

/// The share of the elements on [P_min, P_max], the entry loads that leave and re-enter
/// contact each period, where the normal load varies.
const LEAVING_SHARE: f64 = 0.25;

/// The elements of the bed, by increasing entry load: entry load, stiffness dK and v at the
/// entry load. Element 0 is the base, of stiffness K(0) (0 where v'(0) is infinite), always
/// in contact, carrying P less what the others carry.
#[derive(Debug)]
pub(super) struct SpringBed {
    pub(super) entry: Vec<f64>,
    pub(super) stiffness: Vec<f64>,
    pub(super) approach_at_entry: Vec<f64>,
}

impl SpringBed {
    /// `count` elements over [0, `highest`]: s ∝ τ³ on [0, P_min/2]; geometric in the depth
    /// P_min − s on [P_min/2, P_min] down to [`SHALLOWEST_DEPTH`], where the slip front of a
    /// small tangential amplitude lies; uniform in α of s = P_mid − P_amp cos α on
    /// [P_min, P_max], where elements leave and re-enter contact (their time in contact
    /// goes like a square root of the distance to either end in s, smoothly in α). Each
    /// element has the stiffness K(b) − K(a) of its interval [a, b] and sits at its middle
    /// in the grading variable.
    pub(super) fn new(compliance: &dyn Compliance<f64>, lowest: f64, highest: f64, count: usize) -> Self {
        let leaving = if highest > lowest {
            (count as f64 * LEAVING_SHARE) as usize
        } else {
            0
        };
        let deep = ((count as f64 * DEEP_SHARE) as usize).max(1);
        let shallow = count - leaving - deep;
        let stiffness_at = |s: f64| {
            let stiffness = 1.0 / compliance.slope(&s);
            if stiffness.is_finite() {
                stiffness.max(0.0)
            } else {
                0.0
            }
        };
        let mut bed = SpringBed {
            entry: vec![f64::NEG_INFINITY],
            stiffness: vec![stiffness_at(0.0)],
            approach_at_entry: vec![f64::NAN],
        };
        let half = 0.5 * lowest;
        bed.add(compliance, &stiffness_at, deep, &|t: f64| half * t * t * t);
        let floor = SHALLOWEST_DEPTH * lowest / half;
        bed.add(compliance, &stiffness_at, shallow, &|t: f64| {
            if t >= 1.0 {
                lowest
            } else {
                lowest - half * floor.powf(t)
            }
        });
        let (middle, amplitude) = (0.5 * (lowest + highest), 0.5 * (highest - lowest));
        // The ends are the lowest and highest loads exactly, not their rounded cosines.
        bed.add(compliance, &stiffness_at, leaving, &|t: f64| {
            if t <= 0.0 {
                lowest
            } else if t >= 1.0 {
                highest
            } else {
                middle - amplitude * (std::f64::consts::PI * t).cos()
            }
        });
        bed
    }

    /// `count` elements uniform in τ ∈ [0, 1], mapped to loads by `at`; the last of the
    /// geometric grading reaches the lowest load itself (τ = 1 maps to it).
    fn add(
        &mut self,
        compliance: &dyn Compliance<f64>,
        stiffness_at: &dyn Fn(f64) -> f64,
        count: usize,
        at: &dyn Fn(f64) -> f64,
    ) {
        for i in 0..count {
            let tau = |k: f64| k / count as f64;
            let (a, b, middle) = (at(tau(i as f64)), at(tau(i as f64 + 1.0)), at(tau(i as f64 + 0.5)));
            if b <= a {
                continue;
            }
            self.entry.push(middle);
            self.stiffness.push((stiffness_at(b) - stiffness_at(a)).max(0.0));
            self.approach_at_entry.push(compliance.approach(&middle));
        }
    }

    /// The base element's stiffness K(0).
    pub(super) fn base_stiffness(&self) -> f64 {
        self.stiffness[0]
    }

    /// The first element that carries anything: the base where K(0) > 0, else the next.
    pub(super) fn first(&self) -> usize {
        usize::from(self.base_stiffness() == 0.0)
    }

    /// How many elements touch at load P (the base among them): those entered below P.
    pub(super) fn touching(&self, load: f64) -> usize {
        self.entry.partition_point(|&entry| entry < load)
    }

    /// The normal load the base element carries at load P with approach v(P): P less what
    /// the other elements in contact carry.
    pub(super) fn base_normal_load(&self, load: f64, approach: f64) -> f64 {
        let touching = self.touching(load);
        let others: f64 = (1..touching)
            .map(|j| self.stiffness[j] * (approach - self.approach_at_entry[j]))
            .sum();
        load - others
    }
}
