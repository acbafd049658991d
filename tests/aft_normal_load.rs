//! The harmonic-balance friction element under a varying normal load: its Jacobian against
//! central differences, its agreement with Masing's element at a nearly constant load and
//! with the independent simulation's W, gross slip, and its refusals.

use microslip::aft::{
    aft, aft_with_normal_load, AftForce, FrictionElement, NormalLoad, VaryingLoadElement, DEFAULT_ELEMENTS,
};
use microslip::compliance::parse_spec;
use microslip::path::{Contact, LoadPath, TrigPoly};
use microslip::real::Precision;
use microslip::simulate::{simulate_displacement_path, SimulationOptions};

const HERTZ: &str = "hertz:r=1,estar=100";
const HARMONICS: [usize; 3] = [0, 1, 3];

/// f = 0.5, λ = 1.2 under P = 1 + the load's harmonics (in the layout of [`HARMONICS`]).
fn element(spec: &str, normal: &[f64], time_points: usize, elements: usize) -> VaryingLoadElement {
    let load = NormalLoad {
        mean: 1.0,
        harmonics: &HARMONICS,
        coefficients: normal,
        time_points,
    };
    VaryingLoadElement::from_spec(&load, 0.5, 1.2, spec, elements).unwrap()
}

/// The displacement with fundamental `amplitude`, a phase-shifted part and a third harmonic.
fn displacement(amplitude: f64) -> [f64; 5] {
    [
        0.1 * amplitude,
        amplitude,
        0.4 * amplitude,
        0.15 * amplitude,
        -0.1 * amplitude,
    ]
}

fn largest(values: &[f64]) -> f64 {
    values.iter().fold(0.0f64, |m, x| m.max(x.abs()))
}

#[test]
fn jacobian_matches_central_differences_under_a_varying_load() {
    for spec in [HERTZ, "persson:gamma=0.01,sigma=1", "exp:a=0.02,c=1,d=0.01"] {
        for normal in [[0.0, 0.3, 0.1, 0.0, 0.05], [0.0, 0.0, 0.8, 0.1, 0.0]] {
            let element = element(spec, &normal, 128, DEFAULT_ELEMENTS);
            // From deep microslip to gross slip under the lowest load (g(fP) ≈ 0.023 at P = 1
            // for the Hertz contact, about a third of it at P = 0.2).
            for amplitude in [1e-3, 5e-3, 1e-2, 2e-2, 6e-2] {
                let u = displacement(amplitude);
                let force = aft_with_normal_load(&element, &u).unwrap();
                let scale = largest(&force.jacobian);
                assert!(scale > 0.0, "{spec}: the Jacobian vanishes at {u:?}");
                let mut worst = 0.0f64;
                for j in 0..5 {
                    let step = 1e-7 * amplitude;
                    let moved = |by: f64| {
                        let mut moved = u;
                        moved[j] += by;
                        aft_with_normal_load(&element, &moved).unwrap().force
                    };
                    let (up, down) = (moved(step), moved(-step));
                    for i in 0..5 {
                        let difference = (up[i] - down[i]) / (2.0 * step);
                        worst = worst.max((difference - force.jacobian_entry(i, j)).abs() / scale);
                    }
                }
                println!("{spec}, P = {normal:?}, u1 = {amplitude}: worst {worst:.1e}");
                assert!(worst <= 1e-6, "{spec}, P = {normal:?}, u1 = {amplitude}: {worst:e}");
            }
        }
    }
}

/// At a normal amplitude of 1e−7 P the bed's force is Masing's to the bed's accuracy, from
/// deep microslip to beyond gross slip: measured (F as the largest difference over the
/// largest |F|) below 5.2e−5 with 256 elements and 2.3e−6 with 1024; W within 3.1e−3 and
/// 1.3e−4 (the deepest microslip, whose slip annulus the fewest elements span).
#[test]
fn a_tiny_normal_amplitude_gives_masings_force() {
    let masing = FrictionElement::from_spec(1.0, 0.5, 1.2, HERTZ).unwrap();
    let normal = [0.0, 1e-7, 0.0, 0.0, 0.0];
    for (elements, force_tolerance, work_tolerance) in [(DEFAULT_ELEMENTS, 1e-4, 5e-3), (1024, 5e-6, 3e-4)] {
        let element = element(HERTZ, &normal, 128, elements);
        for amplitude in [1e-4, 1e-3, 5e-3, 1.5e-2, 3e-2] {
            let u = [0.0, amplitude, 0.3 * amplitude, 0.1 * amplitude, 0.0];
            let exact = aft(&masing, &HARMONICS, &u, 128).unwrap();
            let bed = aft_with_normal_load(&element, &u).unwrap();
            let worst = bed
                .force
                .iter()
                .zip(&exact.force)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
                / largest(&exact.force);
            let work = bed.work_per_cycle() / exact.work_per_cycle() - 1.0;
            println!("{elements} elements, u1 = {amplitude}: F {worst:.1e}, W {work:.1e}");
            assert!(
                worst <= force_tolerance,
                "{elements} elements, u1 = {amplitude}: F off by {worst:e}"
            );
            assert!(
                work.abs() <= work_tolerance,
                "{elements} elements, u1 = {amplitude}: W off by {work:e}"
            );
        }
    }
}

/// Without normal harmonics (or with C_0 alone, a shift of the mean) the element is
/// Masing's, value for value.
#[test]
fn a_constant_normal_load_is_masings_element() {
    let u = displacement(1e-2);
    let masing = aft(
        &FrictionElement::from_spec(1.25, 0.5, 1.2, HERTZ).unwrap(),
        &HARMONICS,
        &u,
        128,
    )
    .unwrap();
    let load = NormalLoad {
        mean: 1.0,
        harmonics: &HARMONICS,
        coefficients: &[0.25, 0.0, 0.0, 0.0, 0.0],
        time_points: 128,
    };
    let constant = VaryingLoadElement::from_spec(&load, 0.5, 1.2, HERTZ, DEFAULT_ELEMENTS).unwrap();
    assert_eq!(constant.elements(), 0);
    assert_eq!(aft_with_normal_load(&constant, &u).unwrap(), masing);
}

/// The harmonics of `coefficients` (in the layout of [`HARMONICS`]) plus `mean` as a
/// trigonometric polynomial.
fn polynomial(coefficients: &[f64], mean: f64) -> TrigPoly<f64> {
    let mut cos = vec![mean + coefficients[0], coefficients[1], 0.0, coefficients[3]];
    let mut sin = vec![0.0, coefficients[2], 0.0, coefficients[4]];
    cos.truncate(4);
    sin.truncate(4);
    TrigPoly { cos, sin }
}

/// W from the force's harmonics is the independent simulation's (extrapolated, estimated
/// error ≤ 1.1e−5) on the same path: with 1024 elements and 1024 time points within 6.6e−5
/// measured, at the defaults (256 elements, 128 time points) within 7.5e−4.
#[test]
fn the_work_per_cycle_is_the_simulations() {
    let compliance = parse_spec::<f64>(HERTZ, Precision::DOUBLE).unwrap();
    let contact = Contact {
        friction: 0.5,
        compliance_ratio: 1.2,
    };
    let options = SimulationOptions {
        elements: Some(400),
        steps: Some(1200),
        ..SimulationOptions::default()
    };
    for (amplitude, swing) in [(2e-3, 0.3), (1e-2, 0.3), (3e-2, 0.5), (1e-2, 0.8)] {
        let u = displacement(amplitude);
        let normal = [0.0, swing, 0.0, 0.0, 0.05];
        let path = LoadPath {
            normal: polynomial(&normal, 1.0),
            tangential: polynomial(&u, 0.0),
        };
        let simulated = simulate_displacement_path(&path, &contact, compliance.as_ref(), &options).unwrap();
        assert!(
            simulated.estimated_rel_error < 2e-5,
            "{}",
            simulated.estimated_rel_error
        );
        for (elements, time_points, tolerance) in [(DEFAULT_ELEMENTS, 128, 2e-3), (1024, 1024, 2e-4)] {
            let force = aft_with_normal_load(&element(HERTZ, &normal, time_points, elements), &u).unwrap();
            let error = force.work_per_cycle() / simulated.w_work - 1.0;
            println!("u1 = {amplitude}, P1 = {swing}, {elements} elements, N = {time_points}: {error:.1e}");
            assert!(
                error.abs() <= tolerance,
                "u1 = {amplitude}, P1 = {swing}: W off by {error:e}"
            );
        }
    }
}

/// Far beyond gross slip every element slides wherever u moves: Q = ±f P(t) there, to the
/// bed's share of the normal load (measured within 1.1e−4 with 256 elements).
#[test]
fn beyond_gross_slip_the_force_follows_the_friction_limit() {
    let normal = [0.0, 0.0, 0.8, 0.1, 0.0];
    let element = element(HERTZ, &normal, 256, DEFAULT_ELEMENTS);
    let force: AftForce = aft_with_normal_load(&element, &[0.0, 100.0, 0.0, 0.0, 0.0]).unwrap();
    let loads = element.normal_load_samples();
    let mut sliding = 0;
    let mut worst = 0.0f64;
    let samples = force.displacement_samples.iter().zip(&force.load_samples).zip(loads);
    for (n, ((u, q), load)) in samples.enumerate() {
        // u = 100 cos t moves down for t in (0, π): the load is then −fP, up again after.
        let expected = if n > 0 && n < 128 { -0.5 } else { 0.5 } * load;
        if n % 128 > 4 {
            sliding += 1;
            worst = worst.max((q / expected - 1.0).abs());
            assert!(
                (q / expected - 1.0).abs() < 1e-3,
                "sample {n}: u = {u}, Q = {q}, fP = {expected}"
            );
        }
    }
    println!("gross slip: worst {worst:.1e}");
    assert!(sliding > 200);
}

#[test]
fn bad_normal_loads_are_refused_with_the_reason() {
    let refused = |mean: f64, coefficients: &[f64], elements: usize| {
        let load = NormalLoad {
            mean,
            harmonics: &HARMONICS,
            coefficients,
            time_points: 128,
        };
        VaryingLoadElement::from_spec(&load, 0.5, 1.2, HERTZ, elements)
            .unwrap_err()
            .to_string()
    };
    // P = 1 − 1.2 cos t is −0.2 at t = 0.
    let message = refused(1.0, &[0.0, -1.2, 0.0, 0.0, 0.0], DEFAULT_ELEMENTS);
    assert!(
        message.contains("P = -0.19999999999999996 at time point 0 is not positive"),
        "{message}"
    );
    assert!(refused(0.0, &[0.0, 0.1, 0.0, 0.0, 0.0], DEFAULT_ELEMENTS).contains("at time point"));
    assert!(refused(1.0, &[0.0, 0.1, 0.0], DEFAULT_ELEMENTS).contains("the normal load has 3 harmonic coefficients"));
    assert!(
        refused(1.0, &[0.0, f64::NAN, 0.0, 0.0, 0.0], DEFAULT_ELEMENTS).contains("normal-load coefficient 1 is NaN")
    );
    assert!(refused(1.0, &[0.0, 0.1, 0.0, 0.0, 0.0], 8).contains("the number of elements = 8"));
    let at_zero = refused(0.0, &[0.0; 5], DEFAULT_ELEMENTS);
    assert!(at_zero.contains("normal load P = 0"), "{at_zero}");
    let element = element(HERTZ, &[0.0, 0.1, 0.0, 0.0, 0.0], 128, DEFAULT_ELEMENTS);
    let error = aft_with_normal_load(&element, &[0.0, 1e-3]).unwrap_err().to_string();
    assert!(
        error.contains("the displacement has 2 harmonic coefficients"),
        "{error}"
    );
}
