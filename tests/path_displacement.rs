//! Displacement driving at constant normal load: the force-driven W at the resulting Q
//! amplitude, Masing over rainflow cycles, gross slip at fP0, the loss factor, the round
//! trip through the force-driven loop, and the refusals.

use microslip::compliance::{parse_spec, Compliance, Persson};
use microslip::cycle::{LoadCycle, ValidCycle};
use microslip::dissipation::{constant_normal_load, Options};
use microslip::path::input::{read_driven_harmonics, read_driven_samples, read_harmonics};
use microslip::path::{
    displacement_dissipation, displacement_outputs, path_dissipation, path_outputs, Contact, DisplacementCycle, Drive,
    LoadPath, PathError, SteadyCycle, TrigPoly,
};
use microslip::real::Precision;

const CONTACT: Contact<f64> = Contact {
    friction: 0.8,
    compliance_ratio: 1.2,
};

const PERSSON: Persson<f64> = Persson { gamma: 1.0, sigma: 1.0 };

/// P = P0 and u = Σ u_cos,k cos kθ + u_sin,k sin kθ.
fn displacement_path(p0: f64, cos: &[f64], sin: &[f64]) -> LoadPath<f64> {
    let mut normal = TrigPoly::zero(cos.len() - 1, &0.0);
    normal.cos[0] = p0;
    LoadPath {
        normal,
        tangential: TrigPoly {
            cos: cos.to_vec(),
            sin: sin.to_vec(),
        },
    }
}

/// The force-driven W of Q = Qa cos θ at constant P0.
fn force_w(p0: f64, amplitude: f64, compliance: &dyn Compliance<f64>) -> f64 {
    let path = LoadPath::harmonic(&p0, &0.0, &0.0, &amplitude, &0.0);
    path_dissipation(&path, &CONTACT, compliance, None).unwrap().total
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn constant_load_displacement_driving_gives_the_force_driven_w_at_its_q_amplitude() {
    for amplitude in [0.05, 0.3, 1.5] {
        let path = displacement_path(1.0, &[0.0, amplitude], &[0.0, 0.0]);
        let cycle = DisplacementCycle::new(&path, &CONTACT, &PERSSON).unwrap();
        let w = cycle.dissipation(None).unwrap();
        let outputs = displacement_outputs(&cycle, w.total, 3, 64);
        assert!(outputs.q_amplitude > 0.0 && outputs.q_amplitude < 0.8);
        let expected = force_w(1.0, outputs.q_amplitude, &PERSSON);
        assert!(
            relative(w.total, expected) < 1e-11,
            "u_a = {amplitude}: {} against {expected}",
            w.total
        );
        // The closed form of the four segments at P1 = 0 agrees as well.
        let closed = constant_normal_load(
            &ValidCycle::new(LoadCycle {
                mean_normal_load: 1.0,
                normal_amplitude: 0.0,
                mean_tangential_load: 0.0,
                tangential_amplitude: outputs.q_amplitude,
                phase: 0.0,
                friction: CONTACT.friction,
                compliance_ratio: CONTACT.compliance_ratio,
            })
            .unwrap(),
            &PERSSON,
            &Options::default(),
        )
        .unwrap()
        .total;
        assert!(relative(w.total, closed) < 1e-11);
        // The quadrature of ∮ Q du along the loop, independent of the rainflow sum.
        assert!(relative(cycle.loop_work(), w.total) < 1e-9);
        // The loss factor is W/(π Q_a u_a) and u_a the prescribed amplitude.
        assert!(relative(outputs.u_amplitude, amplitude) < 1e-14);
        let eta = w.total / (std::f64::consts::PI * outputs.q_amplitude * outputs.u_amplitude);
        assert!(relative(outputs.loss_factor, eta) < 1e-15);
        assert_eq!(outputs.damping_ratio, 0.5 * outputs.loss_factor);
        // Under u = A cos θ only Q's first harmonic does work: W = −π A Q_sin,1.
        let first = outputs.harmonics[1];
        assert!(relative(-std::f64::consts::PI * amplitude * first.q_sin, w.total) < 1e-9);
        assert!(first.q_cos > 0.0 && first.q_cos <= outputs.q_amplitude);
    }
}

#[test]
fn inner_loops_add_the_masing_w_of_each_rainflow_cycle() {
    // u = cos θ + 0.4 cos 2θ turns at θ = 0 (1.4), π (−0.6) and where cos θ = −5/8, where
    // u = −0.625 + 0.4(2·0.390625 − 1) = −0.7125: an outer cycle from 1.4 to −0.7125 and
    // an inner one of range 0.1125.
    let path = displacement_path(1.0, &[0.0, 0.3, 0.12], &[0.0, 0.0, 0.0]);
    let cycle = DisplacementCycle::new(&path, &CONTACT, &PERSSON).unwrap();
    assert_eq!(cycle.turning_displacements().len(), 5);
    let w = cycle.dissipation(None).unwrap().total;
    let law = cycle.law();
    let (outer, inner) = (0.3 * 1.4 + 0.3 * 0.7125, 0.3 * 0.1125);
    let masing: f64 = [outer, inner]
        .iter()
        .map(|range| force_w(1.0, law.initial_load(&(range / 2.0)), &PERSSON))
        .sum();
    assert!(relative(w, masing) < 1e-11, "{w} against {masing}");
    assert!(relative(cycle.loop_work(), w) < 1e-9);
    // The loop closes: the period ends at the load it started from.
    let loads = cycle.turning_loads();
    assert!((loads[0] - loads[loads.len() - 1]).abs() < 1e-15);
}

#[test]
fn beyond_gross_slip_the_q_amplitude_is_f_p0_and_sliding_dissipates() {
    // v = P^(2/3)/(2/3): finite at P = 0, so the contact slides as a whole beyond g(fP0).
    let compliance = parse_spec::<f64>("power:c=1,beta=-0.3333333333333333", Precision::DOUBLE).unwrap();
    let p0 = 1.5;
    let probe = DisplacementCycle::new(
        &displacement_path(p0, &[0.0, 1e-3], &[0.0, 0.0]),
        &CONTACT,
        compliance.as_ref(),
    )
    .unwrap();
    let gross = *probe.law().gross_slip_displacement().unwrap();
    let amplitude = 3.0 * gross;
    let path = displacement_path(p0, &[0.0, amplitude], &[0.0, 0.0]);
    let cycle = DisplacementCycle::new(&path, &CONTACT, compliance.as_ref()).unwrap();
    let w = cycle.dissipation(None).unwrap().total;
    let outputs = displacement_outputs(&cycle, w, 3, 256);
    let limit = CONTACT.friction * p0;
    assert!(relative(outputs.q_amplitude, limit) < 1e-15);
    assert!(outputs
        .steady_loop
        .iter()
        .all(|point| point.tangential_load.abs() <= limit));
    // W = the loop at fP0 plus fP0 times the sliding in each direction, 2A − 2g(fP0).
    let (loop_w, _) = cycle.law().loop_dissipation(&limit, None).unwrap();
    let sliding = 2.0 * limit * (2.0 * amplitude - 2.0 * gross);
    assert!(relative(w, loop_w + sliding) < 1e-14);
    assert!(sliding > 0.5 * w);
    // The loop's quadrature converges more slowly at the onset of sliding, where
    // dQ/du falls to 0 as a power.
    assert!(
        relative(cycle.loop_work(), w) < 1e-7,
        "{} against {w}",
        cycle.loop_work()
    );
    // The loop at fP0 is the limit of force-driven loops as Q_a → fP0, approached as
    // (fP0 − Q_a)^(2/3) since v' ~ P^(−1/3): a thousandth of the distance, a hundredth of the gap.
    let gap = |distance: f64| loop_w - force_w(p0, limit * (1.0 - distance), compliance.as_ref());
    let (far, near) = (gap(1e-5), gap(1e-8));
    assert!(far > 0.0 && near > 0.0 && near < far / 50.0, "{far} then {near}");
}

#[test]
fn the_force_driven_loop_driven_by_its_displacement_gives_back_its_q() {
    // A Q with only odd harmonics swings symmetrically, so the convention (first loading
    // to the largest |u|) puts the loop where force driving has it.
    let text = "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,0\n1,0,0,0.3,0.1\n3,0,0,0.06,-0.04\n";
    let force = read_harmonics::<f64>(text, Precision::DOUBLE).unwrap();
    let steady = SteadyCycle::new(&force, &CONTACT).unwrap();
    let w_force = path_dissipation(&force, &CONTACT, &PERSSON, None).unwrap().total;
    // u'' jumps where Q turns (the branch's stiffness does), so its harmonics decay as
    // k⁻³: all 64 that a path may carry are passed on.
    let outputs = path_outputs(&force, &steady, &CONTACT, &PERSSON, w_force, 64, 64);
    let rows: String = outputs
        .harmonics
        .iter()
        .map(|h| {
            format!(
                "{},{},0,{:e},{:e}\n",
                h.k,
                if h.k == 0 { 1.0 } else { 0.0 },
                h.u_cos,
                h.u_sin
            )
        })
        .collect();
    let driven = read_driven_harmonics::<f64>(
        &format!("k,P_cos,P_sin,u_cos,u_sin\n{rows}"),
        Precision::DOUBLE,
        Drive::Displacement,
    )
    .unwrap();
    let cycle = DisplacementCycle::new(&driven, &CONTACT, &PERSSON).unwrap();
    let w = cycle.dissipation(None).unwrap().total;
    assert!(relative(w, w_force) < 1e-4, "{w} against {w_force}");
    let back = displacement_outputs(&cycle, w, 3, 64);
    for (k, q_cos, q_sin) in [(0, 0.0, 0.0), (1, 0.3, 0.1), (2, 0.0, 0.0), (3, 0.06, -0.04)] {
        let h = back.harmonics[k];
        assert!(
            (h.q_cos - q_cos).abs() < 1e-5 && (h.q_sin - q_sin).abs() < 1e-5,
            "k = {k}: {h:?}"
        );
    }
    assert!(
        relative(back.q_amplitude, outputs.q_amplitude) < 1e-4,
        "{} against {}",
        back.q_amplitude,
        outputs.q_amplitude
    );
    assert!(
        relative(back.u_amplitude, outputs.u_amplitude) < 1e-4,
        "{} against {}",
        back.u_amplitude,
        outputs.u_amplitude
    );
}

#[test]
fn a_time_shift_and_the_harmonics_file_leave_w_unchanged() {
    let text = "k,P_cos,P_sin,u_cos,u_sin\n0,1.2,0,0.02,0\n1,0,0,0.25,-0.1\n2,0,0,0.05,0.08\n";
    let path = read_driven_harmonics::<f64>(text, Precision::DOUBLE, Drive::Displacement).unwrap();
    let w = displacement_dissipation(&path, &CONTACT, &PERSSON, None).unwrap().total;
    let shifted = LoadPath {
        normal: path.normal.clone(),
        tangential: path.tangential.shifted(&1.1),
    };
    let w_shifted = displacement_dissipation(&shifted, &CONTACT, &PERSSON, None)
        .unwrap()
        .total;
    assert!(relative(w_shifted, w) < 1e-12);
    // The same path at a higher working precision.
    let float = read_driven_harmonics::<rug::Float>(text, Precision::bits(200), Drive::Displacement).unwrap();
    let contact = Contact {
        friction: rug::Float::with_val(200, 0.8),
        compliance_ratio: rug::Float::with_val(200, 1.2),
    };
    let persson = Persson {
        gamma: rug::Float::with_val(200, 1),
        sigma: rug::Float::with_val(200, 1),
    };
    let precise = displacement_dissipation(&float, &contact, &persson, None).unwrap();
    assert!(relative(w, precise.total.to_f64()) < 1e-13);
    assert!(precise.error_estimate < precise.total.clone() * 1e-50);
}

#[test]
fn a_varying_normal_load_and_a_still_displacement_are_refused() {
    let varying = "k,P_cos,P_sin,u_cos,u_sin\n0,1,0,0,0\n1,0,0,0.2,0\n2,0,1e-30,0,0\n";
    let path = read_driven_harmonics::<f64>(varying, Precision::DOUBLE, Drive::Displacement).unwrap();
    let refused = displacement_dissipation(&path, &CONTACT, &PERSSON, None);
    assert_eq!(refused.unwrap_err(), PathError::VaryingNormalLoad { harmonic: 2 });
    let still = displacement_path(1.0, &[0.3, 0.0], &[0.0, 0.0]);
    assert!(matches!(
        displacement_dissipation(&still, &CONTACT, &PERSSON, None),
        Err(PathError::Malformed(m)) if m.contains("does not vary")
    ));
    let separated = displacement_path(0.0, &[0.0, 0.1], &[0.0, 0.0]);
    assert!(matches!(
        displacement_dissipation(&separated, &CONTACT, &PERSSON, None),
        Err(PathError::Separation { .. })
    ));
    // The force columns are not read as displacement.
    let force_columns = "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,0\n";
    assert!(matches!(
        read_driven_harmonics::<f64>(force_columns, Precision::DOUBLE, Drive::Displacement),
        Err(PathError::Malformed(m)) if m.contains("u_cos")
    ));
}

#[test]
fn samples_at_a_constant_load_are_displacement_driven_as_their_harmonics() {
    // 40 samples of P = 1 (written "1.0") and u = 0.2 cos θ + 0.05 sin 3θ.
    let text: String = std::iter::once("P,u\n".to_string())
        .chain((0..40).map(|j| {
            let theta = j as f64 * std::f64::consts::TAU / 40.0;
            format!("1.0,{:e}\n", 0.2 * theta.cos() + 0.05 * (3.0 * theta).sin())
        }))
        .collect();
    let sampled = read_driven_samples::<f64>(&text, Precision::DOUBLE, Drive::Displacement).unwrap();
    assert!(sampled.normal.is_constant());
    let harmonics = displacement_path(1.0, &[0.0, 0.2, 0.0, 0.0], &[0.0, 0.0, 0.0, 0.05]);
    let w = displacement_dissipation(&sampled, &CONTACT, &PERSSON, None)
        .unwrap()
        .total;
    let expected = displacement_dissipation(&harmonics, &CONTACT, &PERSSON, None)
        .unwrap()
        .total;
    assert!(relative(w, expected) < 1e-12, "{w} against {expected}");
}
