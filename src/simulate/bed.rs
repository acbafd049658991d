//! The bed of spring elements, indexed by the normal load at which each enters contact,
//! graded so that its error is smooth in the element spacing.

use crate::compliance::Compliance;

use super::history::LoadHistory;

/// The bed of elements: entry loads, stiffnesses, and v at each entry load; element 0
/// is the base (entry 0, always in contact). Elements `1..never_slipping` lie below the
/// lowest slipping load P_T: if one of them slips in the steady cycle, the grid's premise
/// failed and the run says so.
pub(super) struct Bed {
    pub(super) entry: Vec<f64>,
    pub(super) stiffness: Vec<f64>,
    pub(super) approach_at_entry: Vec<f64>,
    pub(super) never_slipping: usize,
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
    /// (kinks) and P's local extremes inside its range (graded there again), and at the
    /// lowest P, P0 − P1 (above it elements
    /// leave and re-enter contact each cycle; there the grid is uniform in the angle α of
    /// s = P0 − P1 cos α, P0 ± P1 the ends of the range of P, in which leaving and
    /// re-entering at those ends are smooth, where in s they go like a square root).
    pub(super) fn new(
        compliance: &dyn Compliance<f64>,
        history: &dyn LoadHistory,
        lowest_slip: f64,
        count: usize,
    ) -> Bed {
        let (mean, amplitude) = history.normal_span();
        let (lowest, highest) = (mean - amplitude, mean + amplitude);
        let lowest_slip = lowest_slip.min(lowest);
        let low = 0.9 * lowest_slip;
        let turning = history.kinked_loads();
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
        // Where every element slips (gross slip, P_T = 0), K and v may have power-law
        // singularities at s = 0 (Hertz: K ∝ s^(1/3), v ∝ s^(2/3)): the piece from 0 is
        // graded s ∝ τ³, in which they are smooth (Hertz) or vanish fast enough that the
        // bed's error stays O(h²).
        let kept_nodes = between(lowest_slip, lowest);
        let first = kept_nodes.get(1).copied().unwrap_or(lowest);
        let from_zero = |x: f64| {
            if lowest_slip == 0.0 && x < first {
                first * (x / first).powi(3)
            } else {
                x
            }
        };
        bed.add_elements(compliance, &kept_nodes, kept, &from_zero);
        if leaving_range > 0.0 {
            let extremes: Vec<f64> = history
                .normal_extremes()
                .into_iter()
                .filter(|&s| s > lowest && s < highest)
                .collect();
            let mut loads = between(lowest, highest);
            loads.extend(&extremes);
            loads.sort_by(f64::total_cmp);
            let mut angles: Vec<f64> = loads.iter().copied().map(angle_of).collect();
            // The ends are α = 0 and π exactly: near them acos is too steep to take them
            // from the loads, whose rounding it would magnify to the square root.
            let last = angles.len() - 1;
            (angles[0], angles[last]) = (0.0, std::f64::consts::PI);
            if extremes.is_empty() {
                bed.add_elements(compliance, &angles, slipping - kept, &load_of);
            } else {
                bed.add_graded_at_extremes(compliance, &angles, &loads, &extremes, slipping - kept, &load_of);
            }
        }
        bed
    }

    /// [`Bed::add_elements`] over the pieces between `angles` (the angles of `loads`), where
    /// a piece that ends at one of P's local `extremes` inside its range is graded again,
    /// uniform in β of α = a + (b − a)(1 − cos β)/2: elements just past such a load are in
    /// contact for a time that goes like the square root of their distance to it, which
    /// is smooth in β.
    fn add_graded_at_extremes(
        &mut self,
        compliance: &dyn Compliance<f64>,
        angles: &[f64],
        loads: &[f64],
        extremes: &[f64],
        total: usize,
        load_of: &dyn Fn(f64) -> f64,
    ) {
        let length = angles[angles.len() - 1] - angles[0];
        for (piece, ends) in angles.windows(2).zip(loads.windows(2)) {
            let count = ((total as f64 * (piece[1] - piece[0]) / length).round() as usize).max(1);
            if ends.iter().any(|end| extremes.contains(end)) {
                let (a, b) = (piece[0], piece[1]);
                let graded = |beta: f64| load_of(a + (b - a) * 0.5 * (1.0 - beta.cos()));
                self.add_elements(compliance, &[0.0, std::f64::consts::PI], count, &graded);
            } else {
                self.add_elements(compliance, piece, count, load_of);
            }
        }
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
