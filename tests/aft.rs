//! The harmonic-balance friction element: its Jacobian against finite differences, its W
//! against the constant-normal-load cycle, gross slip, time shifts, and the Hertz backbone
//! against Mindlin's formula.

use microslip::aft::{aft, AftError, AftForce, FrictionElement};
use microslip::compliance::Hertz;
use microslip::cycle::{LoadCycle, ValidCycle};
use microslip::dissipation::{constant_normal_load, HertzConfiguration, MindlinDeresiewicz, Options};

const HERTZ: &str = "hertz:r=1,estar=100";

/// P = 1, f = 0.5, λ = 1.2 on `spec`.
fn element(spec: &str) -> FrictionElement {
    FrictionElement::from_spec(1.0, 0.5, 1.2, spec).unwrap()
}

/// A small deterministic generator of uniform numbers in [−1, 1).
struct Uniform(u64);

impl Uniform {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

fn half_range(samples: &[f64]) -> f64 {
    let high = samples.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let low = samples.iter().copied().fold(f64::INFINITY, f64::min);
    0.5 * (high - low)
}

#[test]
fn jacobian_matches_central_differences() {
    let harmonics = [0, 1, 3];
    let mut uniform = Uniform(40);
    for spec in [HERTZ, "persson:gamma=0.01,sigma=1", "exp:a=0.02,c=1,d=0.01"] {
        let element = element(spec);
        // Amplitudes from deep microslip to beyond gross slip (g(fP) ≈ 0.023 for the Hertz contact).
        for scale in [1e-3, 5e-3, 1e-2, 2e-2, 4e-2] {
            let displacement: Vec<f64> = (0..5).map(|_| scale * uniform.next()).collect();
            let force = aft(&element, &harmonics, &displacement, 128).unwrap();
            let largest = force.jacobian.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            assert!(largest > 0.0, "{spec}: the Jacobian vanishes at {displacement:?}");
            for j in 0..5 {
                let step = 1e-6 * scale;
                let shifted = |by: f64| {
                    let mut moved = displacement.clone();
                    moved[j] += by;
                    aft(&element, &harmonics, &moved, 128).unwrap().force
                };
                let (up, down) = (shifted(step), shifted(-step));
                for i in 0..5 {
                    let difference = (up[i] - down[i]) / (2.0 * step);
                    let exact = force.jacobian_entry(i, j);
                    assert!(
                        (difference - exact).abs() <= 1e-6 * largest,
                        "{spec}, U = {displacement:?}: dF{i}/dU{j} = {exact:e}, differences give {difference:e}"
                    );
                }
            }
        }
    }
}

#[test]
fn one_harmonic_loop_dissipates_the_constant_normal_load_w() {
    let hertz = Hertz {
        radius: 1.0,
        contact_modulus: 100.0,
    };
    let element = element(HERTZ);
    for amplitude in [1e-4, 3e-3, 1e-2, 2e-2] {
        let force = aft(&element, &[1], &[amplitude, 0.0], 1024).unwrap();
        let q1 = half_range(&force.load_samples);
        let cycle = LoadCycle {
            mean_normal_load: 1.0,
            normal_amplitude: 0.0,
            mean_tangential_load: 0.0,
            tangential_amplitude: q1,
            phase: 0.0,
            friction: 0.5,
            compliance_ratio: 1.2,
        };
        let expected = constant_normal_load(&ValidCycle::new(cycle).unwrap(), &hertz, &Options::default())
            .unwrap()
            .total;
        let w = force.work_per_cycle();
        assert!(
            (w / expected - 1.0).abs() < 1e-6,
            "u1 = {amplitude}: the loop gives W = {w:e}, the four segments {expected:e} at Q1 = {q1:e}"
        );
    }
}

#[test]
fn beyond_gross_slip_the_load_amplitude_is_the_friction_limit() {
    let element = element(HERTZ);
    let gross = element.gross_slip_displacement();
    for (harmonics, displacement) in [
        (vec![1], vec![1.5 * gross, 0.0]),
        (vec![1, 2], vec![0.0, 3.0 * gross, gross, 0.2 * gross]),
    ] {
        let force = aft(&element, &harmonics, &displacement, 256).unwrap();
        assert_eq!(half_range(&force.load_samples), element.friction_limit());
        let sliding = force.load_samples.iter().filter(|q| q.abs() == 0.5).count();
        assert!(sliding > 0, "no sample slides at U = {displacement:?}");
    }
    // Just short of gross slip the amplitude stays below fP.
    let force = aft(&element, &[1], &[0.999 * gross, 0.0], 256).unwrap();
    assert!(half_range(&force.load_samples) < element.friction_limit());
}

/// The harmonics of u(t + shift) given those of u(t).
fn shifted(harmonics: &[usize], coefficients: &[f64], shift: f64) -> Vec<f64> {
    let mut out = coefficients.to_vec();
    let mut j = 0;
    for &k in harmonics {
        if k == 0 {
            j += 1;
            continue;
        }
        let (c, s) = (coefficients[j], coefficients[j + 1]);
        let (sin, cos) = (k as f64 * shift).sin_cos();
        out[j] = c * cos + s * sin;
        out[j + 1] = s * cos - c * sin;
        j += 2;
    }
    out
}

#[test]
fn a_time_shift_turns_the_force_phases_and_keeps_w() {
    let element = element(HERTZ);
    let harmonics = [0, 1, 3];
    let displacement = [2e-3, 1.2e-2, -4e-3, 3e-3, 2.5e-3];
    let time_points = 128;
    let force = aft(&element, &harmonics, &displacement, time_points).unwrap();
    for samples in [1, 5, 37, 100] {
        let shift = std::f64::consts::TAU * samples as f64 / time_points as f64;
        let moved = aft(
            &element,
            &harmonics,
            &shifted(&harmonics, &displacement, shift),
            time_points,
        )
        .unwrap();
        let expected = shifted(&harmonics, &force.force, shift);
        for (got, want) in moved.force.iter().zip(&expected) {
            assert!(
                (got - want).abs() < 1e-12,
                "shift by {samples} samples: {got:e} against {want:e}"
            );
        }
        let (w, w_moved) = (force.work_per_cycle(), moved.work_per_cycle());
        assert!((w_moved / w - 1.0).abs() < 1e-12, "W = {w:e} becomes {w_moved:e}");
    }
}

#[test]
fn the_hertz_backbone_is_mindlins() {
    let (shear_modulus, nu) = (40.0, 0.3);
    let md = MindlinDeresiewicz {
        shear_modulus,
        poisson_ratio: nu,
        configuration: HertzConfiguration::SphereOnRigidFlat,
    };
    let sphere = Hertz {
        radius: 1.0,
        contact_modulus: md.contact_modulus(),
    };
    let (p, f) = (2.0, 0.3);
    let lambda = (2.0 - nu) / (2.0 * (1.0 - nu));
    let a = sphere.contact_radius(&p);
    let spec = format!("hertz:r=1,estar={:?}", md.contact_modulus());
    let element = FrictionElement::from_spec(p, f, lambda, &spec).unwrap();
    // 1 − (1 − q)^(2/3) as −expm1(⅔ ln(1 − q)), which does not cancel at small q.
    let bracket = |q: f64| -(2.0 / 3.0 * (-q).ln_1p()).exp_m1();
    let mindlin = |q: f64| 3.0 * f * p * (2.0 - nu) / (16.0 * shear_modulus * a) * bracket(q / (f * p));
    for fraction in [1e-9, 1e-4, 0.01, 0.1, 0.3, 0.6, 0.9, 0.999, 1.0] {
        let q = fraction * f * p;
        let (u, formula) = (element.virgin_displacement(q), mindlin(q));
        assert!(
            (u / formula - 1.0).abs() < 1e-13,
            "Q/fP = {fraction}: g = {u:e}, Mindlin {formula:e}"
        );
        if fraction < 1.0 {
            let back = element.virgin_load(u);
            assert!(
                (back / q - 1.0).abs() < 1e-12,
                "Q/fP = {fraction}: g⁻¹(g(Q)) = {back:e}"
            );
            assert_eq!(element.virgin_load(-u), -back);
        }
    }
    assert!((element.gross_slip_displacement() / mindlin(f * p) - 1.0).abs() < 1e-14);
    // The loop's extreme is the virgin curve's load at the largest displacement.
    let u1 = mindlin(0.5 * f * p);
    let force: AftForce = aft(&element, &[1], &[u1, 0.0], 64).unwrap();
    assert!((force.load_samples[0] / (0.5 * f * p) - 1.0).abs() < 1e-12);
}

#[test]
fn bad_input_is_refused_with_the_reason() {
    let refused = |result: Result<FrictionElement, AftError>| result.unwrap_err().to_string();
    assert!(refused(FrictionElement::from_spec(0.0, 0.5, 1.2, HERTZ)).contains("normal load P = 0"));
    assert!(refused(FrictionElement::from_spec(1.0, -1.0, 1.2, HERTZ)).contains("friction coefficient f = -1"));
    assert!(refused(FrictionElement::from_spec(1.0, 0.5, 2.5, HERTZ)).contains("λ = 2.5 lies outside [1, 2]"));
    assert!(refused(FrictionElement::from_spec(1.0, 0.5, 1.2, "hertz:r=1")).contains("estar"));
    // v' = P softens as it is pressed.
    assert!(refused(FrictionElement::from_spec(1.0, 0.5, 1.2, "power:c=1,beta=1")).contains("soften"));
    let element = element(HERTZ);
    let error = |harmonics: &[usize], displacement: &[f64], points| {
        aft(&element, harmonics, displacement, points).unwrap_err().to_string()
    };
    assert!(error(&[], &[], 16).contains("no harmonics"));
    assert!(error(&[1, 1], &[0.0; 4], 16).contains("strictly increasing"));
    assert!(error(&[0, 1], &[0.0; 2], 16).contains("need 3"));
    assert!(error(&[0, 3], &[0.0; 3], 6).contains("more than 6 time points"));
    assert!(error(&[1], &[f64::NAN, 0.0], 16).contains("coefficient 0 is NaN"));
    assert!(error(&[1, 2], &[1e308, 1e308, 1e308, 0.0], 16).contains("overflows at time point"));
}

/// Every sample of a one-harmonic loop is Masing's branch through the anchor, solved afresh
/// from the virgin curve's inverse: the load carried from sample to sample (each solve
/// started from the one before) is the load solved on its own, to a few ulps.
#[test]
fn each_sample_is_the_branch_solved_afresh() {
    for spec in [
        HERTZ,
        "persson:gamma=0.01,sigma=1",
        "power:c=0.02,beta=-0.5",
        "exp:a=0.02,c=1,d=0.01",
    ] {
        let element = element(spec);
        for amplitude in [1e-4, 3e-3, 1.5e-2] {
            let force = aft(&element, &[1], &[amplitude, 0.0], 128).unwrap();
            let (u, q) = (&force.displacement_samples, &force.load_samples);
            let top = element.virgin_load(u[0]);
            assert_eq!(q[0], top, "{spec}, u1 = {amplitude}: the anchor is on the virgin curve");
            for n in 1..u.len() {
                // Down from the anchor to t = π, then up from the lowest sample.
                let (u_r, q_r, sign) = if n <= 64 {
                    (u[0], top, -1.0)
                } else {
                    (u[64], q[64], 1.0)
                };
                let expected = q_r + sign * 2.0 * element.virgin_load(sign * (u[n] - u_r) / 2.0);
                assert!(
                    (q[n] - expected).abs() <= 1e-14 * top.abs(),
                    "{spec}, u1 = {amplitude}, sample {n}: Q = {:e}, the branch gives {expected:e}",
                    q[n]
                );
            }
        }
    }
}

/// The Fourier basis kept for repeated calls is the one of the harmonics and time points
/// asked for: alternating between two layouts gives each its own values, the same on
/// every call.
#[test]
fn alternating_layouts_give_each_its_own_force() {
    let element = element(HERTZ);
    let first = || aft(&element, &[0, 1, 3], &[1e-3, 1e-2, 0.0, 2e-3, 1e-3], 128).unwrap();
    let second = || aft(&element, &[1, 2], &[1e-2, 0.0, 3e-3, 0.0], 64).unwrap();
    let (a, b) = (first(), second());
    assert_eq!(a.coefficients(), 5);
    assert_eq!(b.coefficients(), 4);
    assert_eq!(b.displacement_samples.len(), 64);
    // u(0) = U_0 + U_cos,1 + U_cos,3 and u(0) = U_cos,1 + U_cos,2.
    assert_eq!(a.displacement_samples[0], 1e-3 + 1e-2 + 2e-3);
    assert_eq!(b.displacement_samples[0], 1e-2 + 3e-3);
    for _ in 0..3 {
        assert_eq!(first(), a);
        assert_eq!(second(), b);
    }
    // On another thread, with a cache of its own.
    let (c, d) = std::thread::scope(|scope| scope.spawn(|| (second(), first())).join().unwrap());
    assert_eq!((c, d), (b, a));
}
