//! What the stepping loop needs of a load history, and the paper's harmonic cycle
//! P0 + P1 cos θ, Q0 + Q1 cos(θ − φ) as one, its quantities in closed form.

use crate::cycle::LoadCycle;
use crate::path::Drive;

/// A periodic history P(θ) and Q(θ) or u(θ) on a contact, as the simulation follows it:
/// what it prescribes at any angle and what the grids are built on.
pub(super) trait LoadHistory {
    /// P(θ) and the prescribed tangential quantity: Q(θ), or u(θ) under displacement driving.
    fn loads(&self, theta: f64) -> (f64, f64);
    /// Which tangential quantity [`LoadHistory::loads`] prescribes.
    fn drive(&self) -> Drive {
        Drive::Force
    }
    /// The angle in [0, 2π) the contact is loaded to from the unloaded state, where the
    /// cycling starts.
    fn start_angle(&self) -> f64 {
        0.0
    }
    /// The Coulomb friction coefficient f.
    fn friction(&self) -> f64;
    /// The tangential/normal compliance ratio λ.
    fn compliance_ratio(&self) -> f64;
    /// The centre and half-width of the range of P over the cycle: P0 and P1 for the
    /// harmonic cycle.
    fn normal_span(&self) -> (f64, f64);
    /// The lowest load at which any element slips in the steady cycle, P_T.
    fn lowest_slip(&self) -> f64;
    /// The angles in [0, 2π) of the turning points, where slip starts or stops.
    fn turning_angles(&self) -> Vec<f64>;
    /// The normal loads where an element's dissipation has a kink in its entry load,
    /// besides P_T and the ends of the range of P: P at the turning points.
    fn kinked_loads(&self) -> Vec<f64>;
    /// P's local extremes inside its range (none for the harmonic cycle): elements
    /// entering there touch for a time that goes like a square root of their distance.
    fn normal_extremes(&self) -> Vec<f64> {
        Vec::new()
    }

    /// The lowest and highest P over the cycle.
    fn normal_range(&self) -> (f64, f64) {
        let (centre, half_width) = self.normal_span();
        (centre - half_width, centre + half_width)
    }
}

/// How close, relative to the highest load, two loads where the dissipation is not smooth
/// are one node (found two ways, they differ by rounding; two nodes would leave a piece
/// of nothing between them).
const SAME_LOAD: f64 = 1e-9;

/// The loads that are nodes of the bed so far: P_T and the ends of the range of P, then
/// those admitted.
pub(super) struct LoadNodes {
    nodes: Vec<f64>,
    lowest_slip: f64,
    margin: f64,
}

impl LoadNodes {
    pub(super) fn new(lowest_slip: f64, lowest: f64, highest: f64) -> Self {
        LoadNodes {
            nodes: vec![lowest_slip, lowest, highest],
            lowest_slip,
            margin: SAME_LOAD * highest,
        }
    }

    /// Whether `load` is a new node (above P_T, apart from every node so far), kept if so.
    pub(super) fn admit(&mut self, load: f64) -> bool {
        let new = load > self.lowest_slip && !self.nodes.iter().any(|node| (node - load).abs() <= self.margin);
        if new {
            self.nodes.push(load);
        }
        new
    }
}

impl LoadHistory for LoadCycle<f64> {
    fn loads(&self, theta: f64) -> (f64, f64) {
        (self.normal_load(&theta), self.tangential_load(&theta))
    }

    fn friction(&self) -> f64 {
        self.friction
    }

    fn compliance_ratio(&self) -> f64 {
        self.compliance_ratio
    }

    fn normal_span(&self) -> (f64, f64) {
        (self.mean_normal_load, self.normal_amplitude)
    }

    fn lowest_slip(&self) -> f64 {
        lowest_slipping_load(self)
    }

    fn turning_angles(&self) -> Vec<f64> {
        turning_angles(self)
    }

    fn kinked_loads(&self) -> Vec<f64> {
        turning_angles(self)
            .into_iter()
            .map(|theta| self.mean_normal_load + self.normal_amplitude * theta.cos())
            .collect()
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

/// Exactly `steps` angles over one cycle, ending at 2π, with a node at the start angle and each turning point
/// (where slip starts or stops, the state's error jumps by an amount that depends on
/// where the event falls in its step; on a node it does not) and uniform between them.
pub(super) fn cycle_angles(history: &dyn LoadHistory, steps: usize) -> Vec<f64> {
    let tau = 2.0 * std::f64::consts::PI;
    let mut nodes = vec![0.0, tau];
    nodes.extend(
        history
            .turning_angles()
            .into_iter()
            .chain([history.start_angle()])
            .filter(|&t| t > 0.0 && t < tau),
    );
    nodes.sort_by(f64::total_cmp);
    nodes.dedup();
    // Steps per piece in proportion to its length, at least one, exactly `steps` in all
    // (largest remainders get the spare steps). Remainders equal but for rounding (pieces
    // of one length: turning points come in pairs) are told apart by the pieces' order,
    // so that a history given two ways gets one grid.
    let ideal: Vec<f64> = nodes.windows(2).map(|p| steps as f64 * (p[1] - p[0]) / tau).collect();
    let mut counts: Vec<usize> = ideal.iter().map(|&x| (x.floor() as usize).max(1)).collect();
    let shortfall = |counts: &[usize], i: usize| ((ideal[i] - counts[i] as f64) * 1e9).round();
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
/// ([`SimulationError::SlipBelowLowestSlip`](super::SimulationError::SlipBelowLowestSlip)).
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::path::{Contact, LoadPath};
    use crate::simulate::path_history::PathHistory;

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

    #[test]
    fn a_harmonic_path_has_the_harmonic_cycles_quantities() {
        for k in 0..24 {
            let cycle = cycle(-3.0 + 0.29 * f64::from(k), 0.0);
            let path = LoadPath::harmonic(
                &cycle.mean_normal_load,
                &cycle.normal_amplitude,
                &cycle.mean_tangential_load,
                &cycle.tangential_amplitude,
                &cycle.phase,
            );
            let contact = Contact {
                friction: cycle.friction,
                compliance_ratio: cycle.compliance_ratio,
            };
            let history = PathHistory::new(&path, &contact).unwrap();
            let close = |a: f64, b: f64| (a - b).abs() < 1e-13;
            assert!(close(history.lowest_slip(), cycle.lowest_slip()), "φ = {}", cycle.phase);
            let (centre, half_width) = history.normal_span();
            assert!(close(centre, 1.0) && close(half_width, 0.4));
            // The same values, in any order, of those `keep` keeps.
            let same = |mut here: Vec<f64>, mut there: Vec<f64>, keep: &dyn Fn(f64) -> bool| {
                here.retain(|&x| keep(x));
                there.retain(|&x| keep(x));
                here.sort_by(f64::total_cmp);
                there.sort_by(f64::total_cmp);
                here.len() == there.len() && here.iter().zip(&there).all(|(a, b)| close(*a, *b))
            };
            let (angles, its_angles) = (history.turning_angles(), cycle.turning_angles());
            assert!(
                same(angles.clone(), its_angles.clone(), &|_| true),
                "{angles:?} vs {its_angles:?}"
            );
            // No node of its own: the grids are the cycle's.
            let (loads, its_loads) = (history.kinked_loads(), cycle.kinked_loads());
            let inside = |load: f64| load > 0.6 + 1e-9 && load < 1.4 - 1e-9;
            assert!(
                same(loads.clone(), its_loads.clone(), &inside),
                "{loads:?} vs {its_loads:?}"
            );
            assert!(history.normal_extremes().is_empty());
            for theta in [0.3, 2.0, 5.5] {
                let (p, q) = (history.loads(theta), cycle.loads(theta));
                assert!(close(p.0, q.0) && close(p.1, q.1));
            }
        }
    }
}
