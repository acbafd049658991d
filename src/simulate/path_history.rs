//! Any periodic path as a load history (the quantities of a force path P(θ), Q(θ) here,
//! those of a displacement-driven one in `displacement_history`); a force path's found from its
//! harmonics (the extremes of P, of Q + fP and of Q − fP), its lowest slipping load and
//! the loads where its slip fronts stop from the path module's steady cycle, which also
//! refuses a path outside the theory. They only place the grids' nodes: W is the bed's.

use crate::path::events::{extreme, sign_changes};
use crate::path::input::padded;
use crate::path::{Contact, Drive, LoadPath, PathError, SteadyCycle, TrigPoly};

use super::history::{LoadHistory, LoadNodes};

/// How close to a turning angle a segment of the steady cycle must end to end there.
const STOP_ANGLE: f64 = 1e-12;

/// A path on a contact, driven by force or by displacement, with what the grids are built on.
pub(super) struct PathHistory {
    pub(super) normal: TrigPoly<f64>,
    /// Q, or u under displacement driving.
    pub(super) tangential: TrigPoly<f64>,
    pub(super) drive: Drive,
    pub(super) start_angle: f64,
    pub(super) friction: f64,
    pub(super) compliance_ratio: f64,
    pub(super) lowest_slip: f64,
    pub(super) lowest: f64,
    pub(super) highest: f64,
    pub(super) turning_angles: Vec<f64>,
    pub(super) kinked_loads: Vec<f64>,
    pub(super) normal_extremes: Vec<f64>,
}

impl PathHistory {
    /// The history of `path` on `contact`; refused where the path separates or slips
    /// grossly (naming the angle) or the contact is out of range.
    pub(super) fn new(path: &LoadPath<f64>, contact: &Contact<f64>) -> Result<Self, PathError> {
        let steady = SteadyCycle::new(path, contact)?;
        let LoadPath { normal, tangential } = padded(path);
        let friction = contact.friction;
        let lowest = extreme(&normal, false).1;
        let highest = steady.highest_load;
        // Slip starts or stops where Q − fP (forward slip) or Q + fP (backward slip) is
        // stationary.
        let tau = 2.0 * std::f64::consts::PI;
        let rate_of_normal = normal.derivative().scaled(&friction);
        let rate_of_tangential = tangential.derivative();
        let stationary = |sign: i64| -> Vec<f64> {
            sign_changes(&rate_of_tangential.combined(&rate_of_normal, sign))
                .into_iter()
                .map(|theta| theta.rem_euclid(tau))
                .collect()
        };
        let (forward_turns, backward_turns) = (stationary(-1), stationary(1));
        let turning_angles: Vec<f64> = forward_turns.iter().chain(&backward_turns).copied().collect();
        let mut nodes = LoadNodes::new(steady.lowest_slip, lowest, highest);
        let mut new_node = |load: f64| nodes.admit(load);
        let normal_extremes = interior_extremes(&normal, &mut new_node);
        let mut kinked_loads: Vec<f64> = turning_angles
            .iter()
            .map(|theta| normal.value(theta))
            .filter(|&load| new_node(load))
            .collect();
        kinked_loads.extend(
            stopped_fronts(&steady, &forward_turns, &backward_turns)
                .into_iter()
                .filter(|&load| new_node(load)),
        );
        Ok(PathHistory {
            normal,
            tangential,
            drive: Drive::Force,
            start_angle: 0.0,
            friction,
            compliance_ratio: contact.compliance_ratio,
            lowest_slip: steady.lowest_slip,
            lowest,
            highest,
            turning_angles,
            kinked_loads,
            normal_extremes,
        })
    }
}

/// P's local extremes that `new_node` admits as new nodes of the bed.
pub(super) fn interior_extremes(normal: &TrigPoly<f64>, new_node: &mut impl FnMut(f64) -> bool) -> Vec<f64> {
    sign_changes(&normal.derivative())
        .iter()
        .map(|theta| normal.value(theta))
        .filter(|&load| new_node(load))
        .collect()
}

/// The loads the slip fronts have reached where slip stops (at the turning angles of
/// Q − fP for forward slip, of Q + fP for backward slip): the elements on either side of
/// such a load slipped in different events, so their dissipation has a kink there.
fn stopped_fronts(steady: &SteadyCycle<f64>, forward_turns: &[f64], backward_turns: &[f64]) -> Vec<f64> {
    let tau = 2.0 * std::f64::consts::PI;
    let at = |theta: f64, angles: &[f64]| {
        angles.iter().any(|angle| {
            let gap = (theta - angle).rem_euclid(tau);
            gap.min(tau - gap) <= STOP_ANGLE
        })
    };
    let mut loads = Vec::new();
    for segment in &steady.segments {
        let fronts = steady.fronts(segment, &steady.point(&segment.end));
        if at(segment.end, forward_turns) {
            loads.push(fronts.forward);
        }
        if at(segment.end, backward_turns) {
            loads.push(fronts.backward);
        }
    }
    loads
}

impl LoadHistory for PathHistory {
    fn loads(&self, theta: f64) -> (f64, f64) {
        (self.normal.value(&theta), self.tangential.value(&theta))
    }

    fn drive(&self) -> Drive {
        self.drive
    }

    fn start_angle(&self) -> f64 {
        self.start_angle
    }

    fn friction(&self) -> f64 {
        self.friction
    }

    fn compliance_ratio(&self) -> f64 {
        self.compliance_ratio
    }

    fn normal_span(&self) -> (f64, f64) {
        (0.5 * (self.lowest + self.highest), 0.5 * (self.highest - self.lowest))
    }

    fn lowest_slip(&self) -> f64 {
        self.lowest_slip
    }

    fn turning_angles(&self) -> Vec<f64> {
        self.turning_angles.clone()
    }

    fn kinked_loads(&self) -> Vec<f64> {
        self.kinked_loads.clone()
    }

    fn normal_extremes(&self) -> Vec<f64> {
        self.normal_extremes.clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_local_extreme_of_p_inside_its_range_is_named() {
        // P = 1 + 0.3 cos θ + 0.2 cos 2θ: its maximum 1.5 at θ = 0, its minimum 0.74375
        // where cos θ = −0.375, and a local maximum 0.9 at θ = π.
        let path = LoadPath {
            normal: TrigPoly {
                cos: vec![1.0, 0.3, 0.2],
                sin: vec![0.0; 3],
            },
            tangential: TrigPoly {
                cos: vec![0.0; 3],
                sin: vec![0.0; 3],
            },
        };
        let contact = Contact {
            friction: 1.0,
            compliance_ratio: 1.0,
        };
        let history = PathHistory::new(&path, &contact).unwrap();
        let (lowest, highest) = history.normal_range();
        assert!((lowest - 0.74375).abs() < 1e-14 && (highest - 1.5).abs() < 1e-14);
        assert_eq!(history.normal_extremes().len(), 1);
        assert!((history.normal_extremes()[0] - 0.9).abs() < 1e-14);
    }
}
