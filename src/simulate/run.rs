//! The one stepping loop: the contact from unloaded to the history's start angle and on
//! to the end of that cycle, then cycles of the load history until the loop closes,
//! whichever tangential quantity the history prescribes.

use std::time::Instant;

use crate::compliance::Compliance;

use super::bed::Bed;
use super::elements::Contact;
use super::history::{cycle_angles, LoadHistory};
use super::{InitialPath, LoopSample, SimulationError};

/// The measures of one run: W as the work of the load, W as frictional work, the loop.
pub(super) type Run = (f64, f64, Vec<LoopSample>);

/// One run at a given resolution, on a grid built for the given lowest slipping load (a
/// wrong one is caught): the initial path, then cycles until the loop closes.
pub(super) fn run(
    history: &dyn LoadHistory,
    compliance: &dyn Compliance<f64>,
    lowest_slip: f64,
    elements: usize,
    steps: usize,
    path: InitialPath,
    deadline: Option<Instant>,
) -> Result<Run, SimulationError> {
    let bed = Bed::new(compliance, history, lowest_slip, elements);
    let mut contact = Contact::new(&bed, history.friction(), history.compliance_ratio());
    let in_time = || match deadline {
        Some(deadline) if Instant::now() > deadline => Err(SimulationError::OutOfTime { elements, steps }),
        _ => Ok(()),
    };
    let angles = cycle_angles(history, steps);
    load_to_start(&mut contact, history, compliance, &angles, steps, path, &in_time)?;
    let mut previous_start = (f64::NAN, f64::NAN);
    let mut last = (0.0, 0.0, Vec::new());
    for _ in 0..8 {
        let (work, friction_work, samples) = one_cycle(&mut contact, history, compliance, &angles, &in_time)?;
        // The loop closes when the state at its start repeats: u under force driving,
        // Q under displacement driving (the prescribed one repeats by itself).
        let start = (samples[0].displacement, samples[0].tangential_load);
        let normal_at_zero = samples[0].normal_load;
        let closed = (start.0 - previous_start.0).abs() <= 1e-13 * (start.0.abs() + work.abs() + 1e-300)
            && (start.1 - previous_start.1).abs()
                <= 1e-13 * (start.1.abs() + history.friction() * normal_at_zero.abs() + 1e-300);
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

/// Steps the contact from the unloaded state to the history's start angle along `path`,
/// then on to the end of that cycle.
fn load_to_start(
    contact: &mut Contact<'_>,
    history: &dyn LoadHistory,
    compliance: &dyn Compliance<f64>,
    angles: &[f64],
    steps: usize,
    path: InitialPath,
    in_time: &dyn Fn() -> Result<(), SimulationError>,
) -> Result<(), SimulationError> {
    let drive = history.drive();
    let equilibrium = |theta: f64| SimulationError::Equilibrium { theta };
    let start_angle = history.start_angle();
    let (p_start, x_start) = history.loads(start_angle);
    let ramp = steps.max(100);
    for i in 1..=ramp {
        let t = i as f64 / ramp as f64;
        let (p, x) = match path {
            InitialPath::NormalThenTangential => (p_start * (2.0 * t).min(1.0), x_start * (2.0 * t - 1.0).max(0.0)),
            InitialPath::Proportional => (p_start * t, x_start * t),
        };
        in_time()?;
        contact
            .step(compliance, p, x, drive)
            .ok_or_else(|| equilibrium(start_angle))?;
    }
    if start_angle > 0.0 {
        for &theta in angles.iter().filter(|&&theta| theta > start_angle) {
            let (p, x) = history.loads(theta);
            in_time()?;
            contact
                .step(compliance, p, x, drive)
                .ok_or_else(|| equilibrium(theta))?;
        }
    }
    Ok(())
}

/// One cycle of the history from θ = 0: W as the work of the load, W as frictional work,
/// and the loop's samples.
fn one_cycle(
    contact: &mut Contact<'_>,
    history: &dyn LoadHistory,
    compliance: &dyn Compliance<f64>,
    angles: &[f64],
    in_time: &dyn Fn() -> Result<(), SimulationError>,
) -> Result<Run, SimulationError> {
    let drive = history.drive();
    let mut samples = vec![LoopSample {
        theta: 0.0,
        normal_load: history.loads(0.0).0,
        tangential_load: contact.tangential_load,
        displacement: contact.displacement,
    }];
    let (mut work, mut friction_work) = (0.0, 0.0);
    contact.work_below_lowest_slip = 0.0;
    for &theta in angles {
        let (p, x) = history.loads(theta);
        let before = *samples.last().unwrap_or(&samples[0]);
        in_time()?;
        friction_work += contact
            .step(compliance, p, x, drive)
            .ok_or(SimulationError::Equilibrium { theta })?;
        work += 0.5 * (before.tangential_load + contact.tangential_load) * (contact.displacement - before.displacement);
        samples.push(LoopSample {
            theta,
            normal_load: p,
            tangential_load: contact.tangential_load,
            displacement: contact.displacement,
        });
    }
    Ok((work, friction_work, samples))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::compliance::parse_spec;
    use crate::cycle::LoadCycle;
    use crate::real::Precision;

    #[test]
    fn a_grid_built_on_a_wrong_lowest_slipping_load_is_caught() {
        let compliance = parse_spec::<f64>("persson:gamma=1,sigma=1", Precision::DOUBLE).unwrap();
        let cycle = LoadCycle {
            mean_normal_load: 1.0,
            normal_amplitude: 0.4,
            mean_tangential_load: 0.0,
            tangential_amplitude: 0.5,
            phase: 0.4 * std::f64::consts::PI,
            friction: 1.0,
            compliance_ratio: 1.0,
        };
        let path = InitialPath::NormalThenTangential;
        let right = cycle.lowest_slip();
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
}
