//! A displacement-driven path P(θ), u(θ) as a load history: the bed is moved to u directly
//! at every step and Q = Σ t_s follows. The normal load may vary (the elements enter and
//! leave contact with it) but must stay positive. What the grids are built on comes from
//! u ∓ λf v(P), whose extremes bound the band every element's slip offset must keep to
//! (as Q ∓ fP do under force driving), and at constant P from the path module's Masing
//! loop; they only place the grids' nodes: W is the bed's.

use crate::compliance::Compliance;
use crate::path::displacement::{rainflow_ranges, DisplacementCycle};
use crate::path::events::extreme;
use crate::path::input::padded;
use crate::path::{Contact, Drive, LoadPath, PathError, TrigPoly};

use super::history::LoadNodes;
use super::path_history::{interior_extremes, PathHistory};

/// Samples per harmonic of u ∓ λf v(P)'s rate, searched for its sign changes.
const SAMPLES_PER_HARMONIC: usize = 256;

impl PathHistory {
    /// The history of `path` (whose `tangential` is u) on `contact`: refused where P ≤ 0
    /// (naming the angle), u does not vary, or the contact is out of range; at constant P as
    /// `microslip path --drive displacement` refuses it.
    pub(super) fn driven_by_displacement(
        path: &LoadPath<f64>,
        contact: &Contact<f64>,
        compliance: &dyn Compliance<f64>,
    ) -> Result<Self, PathError> {
        let constant_load = path.normal.is_constant();
        let masing = if constant_load {
            Some(DisplacementCycle::new(path, contact, compliance)?)
        } else {
            contact.validate()?;
            None
        };
        let LoadPath {
            normal,
            tangential: displacement,
        } = padded(path);
        let (theta, lowest) = extreme(&normal, false);
        if lowest <= 0.0 {
            return Err(PathError::Separation { theta, load: lowest });
        }
        if displacement.is_constant() {
            return Err(PathError::Malformed(
                "the displacement u does not vary over the period: give u's harmonics k ≥ 1".to_string(),
            ));
        }
        let highest = extreme(&normal, true).1;
        let band = Band {
            normal: &normal,
            normal_rate: normal.derivative(),
            displacement: &displacement,
            displacement_rate: displacement.derivative(),
            compliance,
            scale: contact.compliance_ratio * contact.friction,
        };
        let (forward_turns, backward_turns) = (band.stationary(-1.0), band.stationary(1.0));
        let lowest_slip = band.lowest_slip(lowest, &forward_turns, &backward_turns);
        let mut nodes = LoadNodes::new(lowest_slip, lowest, highest);
        let mut new_node = |load: f64| nodes.admit(load);
        let normal_extremes = interior_extremes(&normal, &mut new_node);
        let (turning_angles, kinked_loads) = turning_angles_and_kinks(
            masing.as_ref(),
            (&forward_turns, &backward_turns),
            &normal,
            lowest,
            contact.friction,
            &mut new_node,
        );
        let (top, bottom) = (extreme(&displacement, true), extreme(&displacement, false));
        let start_angle = if top.1.abs() >= bottom.1.abs() { top.0 } else { bottom.0 };
        Ok(PathHistory {
            normal,
            tangential: displacement,
            drive: Drive::Displacement,
            start_angle,
            friction: contact.friction,
            compliance_ratio: contact.compliance_ratio,
            lowest_slip,
            lowest,
            highest,
            turning_angles,
            kinked_loads,
            normal_extremes,
        })
    }
}

/// The functions u ∓ λf v(P(θ)): an element entered at s keeps its slip offset w_s in
/// u − λf v(P) + λf v(s) ≤ w_s ≤ u + λf v(P) − λf v(s) while in contact.
struct Band<'a> {
    normal: &'a TrigPoly<f64>,
    normal_rate: TrigPoly<f64>,
    displacement: &'a TrigPoly<f64>,
    displacement_rate: TrigPoly<f64>,
    compliance: &'a dyn Compliance<f64>,
    /// λf.
    scale: f64,
}

impl Band<'_> {
    /// u + sign·λf v(P) at θ.
    fn value(&self, sign: f64, theta: f64) -> f64 {
        self.displacement.value(&theta) + sign * self.scale * self.compliance.approach(&self.normal.value(&theta))
    }

    /// Its rate at θ.
    fn rate(&self, sign: f64, theta: f64) -> f64 {
        let load = self.normal.value(&theta);
        self.displacement_rate.value(&theta)
            + sign * self.scale * self.compliance.slope(&load) * self.normal_rate.value(&theta)
    }

    /// The angles in [0, 2π) where u + sign·λf v(P) is stationary, increasing: sign changes
    /// of its rate on a fine sampling, refined by bisection (a pair of them closer than the
    /// sampling is missed, which only costs the grids a node).
    fn stationary(&self, sign: f64) -> Vec<f64> {
        let count = SAMPLES_PER_HARMONIC * self.displacement.highest().max(1);
        let step = std::f64::consts::TAU / count as f64;
        let rate = |theta: f64| self.rate(sign, theta);
        let mut roots = Vec::new();
        let mut before = rate(0.0);
        for j in 0..count {
            let (a, b) = (step * j as f64, step * (j + 1) as f64);
            let after = rate(b);
            if before == 0.0 {
                roots.push(a);
            } else if before * after < 0.0 {
                roots.push(bisect(&rate, a, b));
            }
            before = after;
        }
        roots
    }

    /// The smallest (sign −1: largest) value of u + sign·λf v(P) over the cycle, given
    /// where it is stationary.
    fn extreme(&self, sign: f64, stationary: &[f64]) -> f64 {
        let values = stationary.iter().chain(&[0.0]).map(|&theta| self.value(sign, theta));
        if sign > 0.0 {
            values.fold(f64::INFINITY, f64::min)
        } else {
            values.fold(f64::NEG_INFINITY, f64::max)
        }
    }

    /// The lowest entry load of an element that slips in the steady cycle, P_T (at most the
    /// lowest P): below it a constant offset fits the band throughout,
    /// λf v(P_T) = ½[min(u + λf v(P)) − max(u − λf v(P))]; 0 where even s = 0 slips.
    fn lowest_slip(&self, lowest: f64, forward_turns: &[f64], backward_turns: &[f64]) -> f64 {
        let target = 0.5 * (self.extreme(1.0, backward_turns) - self.extreme(-1.0, forward_turns)) / self.scale;
        if target >= self.compliance.approach(&lowest) {
            return lowest;
        }
        if target <= self.compliance.approach(&0.0) {
            return 0.0;
        }
        bisect(&|s: f64| self.compliance.approach(&s) - target, 0.0, lowest)
    }
}

/// The point of [a, b] where `f` changes sign, by bisection to the last bit.
fn bisect(f: &dyn Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let (mut low, mut high) = (a, b);
    let low_sign = f(low).signum();
    loop {
        let middle = 0.5 * (low + high);
        if middle <= low || middle >= high {
            return middle;
        }
        if f(middle).signum() == low_sign {
            low = middle;
        } else {
            high = middle;
        }
    }
}

/// Where the history's smooth pieces start and the loads at which its dissipation has a
/// kink, admitted as grid nodes by `new_node`. At constant P (`masing`) the pieces start
/// at the turning points of u and where an inner loop closes or sliding begins (dQ/du
/// jumps); each rainflow cycle of range Δ slips the elements whose limit is below Δ/2, so
/// their dissipation has a kink at the element whose limit is Δ/2. Otherwise they start
/// at the turning points of u ∓ λf v(P), the loads there the kinks.
fn turning_angles_and_kinks(
    masing: Option<&DisplacementCycle<'_, f64>>,
    (forward_turns, backward_turns): (&[f64], &[f64]),
    normal: &TrigPoly<f64>,
    lowest: f64,
    friction: f64,
    new_node: &mut dyn FnMut(f64) -> bool,
) -> (Vec<f64>, Vec<f64>) {
    match masing {
        // At constant P the loop's smooth pieces start at the turning points of u and
        // where an inner loop closes or sliding begins (dQ/du jumps); each rainflow cycle
        // of range Δ slips the elements whose limit is below Δ/2, so their dissipation
        // has a kink at the element whose limit is Δ/2.
        Some(cycle) => {
            let tau = std::f64::consts::TAU;
            let angles = cycle
                .smooth_pieces()
                .iter()
                .map(|piece| piece.0.rem_euclid(tau))
                .collect();
            let law = cycle.law();
            let fronts = rainflow_ranges(cycle.turning_displacements())
                .iter()
                .map(|range| lowest - law.initial_load(&(0.5 * range)) / friction)
                .filter(|&load| new_node(load))
                .collect();
            (angles, fronts)
        }
        None => {
            let angles: Vec<f64> = forward_turns.iter().chain(backward_turns).copied().collect();
            let loads = angles
                .iter()
                .map(|theta| normal.value(theta))
                .filter(|&load| new_node(load))
                .collect();
            (angles, loads)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compliance::parse_spec;
    use crate::path::input::read_driven_harmonics;
    use crate::real::Precision;
    use crate::simulate::history::LoadHistory;

    const CONTACT: Contact<f64> = Contact {
        friction: 0.8,
        compliance_ratio: 1.2,
    };

    fn history(text: &str, spec: &str) -> (PathHistory, LoadPath<f64>, Box<dyn Compliance<f64>>) {
        let compliance = parse_spec::<f64>(spec, Precision::DOUBLE).unwrap();
        let path = read_driven_harmonics::<f64>(text, Precision::DOUBLE, Drive::Displacement).unwrap();
        (
            PathHistory::driven_by_displacement(&path, &CONTACT, compliance.as_ref()).unwrap(),
            path,
            compliance,
        )
    }

    #[test]
    fn at_constant_load_the_lowest_slipping_load_is_the_front_of_the_widest_rainflow_cycle() {
        // Two derivations: the band of u ∓ λf v(P) here, Masing's initial curve g⁻¹ there.
        let text = "k,P_cos,P_sin,u_cos,u_sin\n0,1.2,0,0.01,0\n1,0,0,0.2,-0.1\n2,0,0,0.08,0.05\n";
        for spec in ["persson:gamma=1,sigma=1", "hertz:r=1,estar=1", "exp:a=1,c=1,d=0.1"] {
            let (history, path, compliance) = history(text, spec);
            let cycle = DisplacementCycle::new(&path, &CONTACT, compliance.as_ref()).unwrap();
            let turning = cycle.turning_displacements();
            let spread = |pick: fn(f64, f64) -> f64| turning.iter().copied().reduce(pick).unwrap();
            let range = spread(f64::max) - spread(f64::min);
            let front = 1.2 - cycle.law().initial_load(&(0.5 * range)) / CONTACT.friction;
            assert!(
                (history.lowest_slip() - front).abs() < 1e-12,
                "{spec}: {} vs {front}",
                history.lowest_slip()
            );
            // The cycle starts at the extreme of u of largest magnitude, a node of the steps.
            let start = history.start_angle();
            assert!((path.tangential.value(&start).abs() - spread(f64::max).max(-spread(f64::min))).abs() < 1e-15);
            assert!(history
                .turning_angles()
                .iter()
                .any(|&angle| (angle - start).abs() < 1e-12));
            assert_eq!(history.normal_span(), (1.2, 0.0));
        }
    }

    #[test]
    fn beyond_gross_slip_every_element_slips() {
        let text = "k,P_cos,P_sin,u_cos,u_sin\n0,1.2,0,0.01,0\n1,0,0,1.2,-0.5\n2,0,0,0.3,0.3\n";
        assert_eq!(history(text, "hertz:r=1,estar=1").0.lowest_slip(), 0.0);
        // Persson's contact never slides as a whole: v(0) = −∞.
        assert!(history(text, "persson:gamma=1,sigma=1").0.lowest_slip() > 0.0);
    }

    #[test]
    fn a_varying_load_has_the_extremes_of_u_minus_and_plus_lambda_f_v_as_turning_points() {
        let text = "k,P_cos,P_sin,u_cos,u_sin\n0,1.2,0,0.01,0\n1,0.3,0.1,0.2,-0.1\n2,0.1,-0.05,0.08,0.06\n";
        let (history, path, compliance) = history(text, "persson:gamma=1,sigma=1");
        let band = |theta: f64, sign: f64| {
            path.tangential.value(&theta) + sign * 0.96 * compliance.approach(&path.normal.value(&theta))
        };
        for theta in history.turning_angles() {
            // Stationary: a step of 1e−6 either way changes it by second order only.
            let flat = [1.0, -1.0].iter().any(|&sign| {
                let (before, here, after) = (band(theta - 1e-6, sign), band(theta, sign), band(theta + 1e-6, sign));
                (before - here).abs() < 1e-10 && (after - here).abs() < 1e-10
            });
            assert!(flat, "θ = {theta}");
        }
        let (lowest, highest) = history.normal_range();
        assert!(lowest < 1.2 && highest > 1.2 && history.lowest_slip() < lowest);
    }
}
