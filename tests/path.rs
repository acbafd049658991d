//! W of a periodic load path: against the four segments (one harmonic), Masing's rule over
//! rainflow cycles (constant P), its invariances, and an independent spring-bed simulation.

use microslip::compliance::{parse_spec, Compliance};
use microslip::cycle::LoadCycle;
use microslip::digits::agreement::agreeing_digits;
use microslip::dissipation::{dissipation, Options};
use microslip::path::input::{read_harmonics, read_samples};
use microslip::path::{path_dissipation, path_outputs, Contact, LoadPath, SteadyCycle, TrigPoly};
use microslip::real::{Precision, Real};
use rug::Float;

const PERSSON: &str = "persson:gamma=1,sigma=1";
const HERTZ: &str = "hertz:r=1,estar=1";

fn contact<R: Real>(friction: f64, ratio: f64, precision: Precision) -> Contact<R> {
    Contact {
        friction: R::from_f64(friction, precision),
        compliance_ratio: R::from_f64(ratio, precision),
    }
}

fn w_path<R: Real>(path: &LoadPath<R>, contact: &Contact<R>, compliance: &dyn Compliance<R>) -> R {
    path_dissipation(path, contact, compliance, None)
        .expect("the path computes")
        .total
}

/// The four-segment W of P0 + P1 cos θ, Q0 + Q1 cos(θ − φ).
fn w_harmonic<R: Real>(loads: [R; 5], contact: &Contact<R>, compliance: &dyn Compliance<R>) -> R {
    let [p0, p1, q0, q1, phase] = loads;
    let cycle = LoadCycle {
        mean_normal_load: p0,
        normal_amplitude: p1,
        mean_tangential_load: q0,
        tangential_amplitude: q1,
        phase,
        friction: contact.friction.clone(),
        compliance_ratio: contact.compliance_ratio.clone(),
    };
    dissipation(&cycle, compliance, &Options::default())
        .expect("the cycle computes")
        .total
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn a_harmonic_path_equals_the_four_segment_w_to_12_digits_in_f64() {
    let cases = [
        (PERSSON, 1.0, 0.4, 0.0, 0.5, 0.4, 1.0, 1.0),
        (PERSSON, 1.0, 0.4, 0.1, 0.5, 0.1, 1.0, 1.0),
        (PERSSON, 1.0, 0.3, -0.2, 0.4, 0.7, 0.8, 1.3),
        (HERTZ, 2.0, 0.5, 0.3, 0.9, 1.3, 0.9, 1.5),
        (HERTZ, 1.0, 0.2, 0.0, 0.3, 1.9, 0.6, 1.0),
        (PERSSON, 1.0, 0.6, 0.0, 0.2, 0.5, 0.5, 1.2),
    ];
    for (spec, p0, p1, q0, q1, phase_pi, f, ratio) in cases {
        let compliance = parse_spec::<f64>(spec, Precision::DOUBLE).unwrap();
        let contact = contact::<f64>(f, ratio, Precision::DOUBLE);
        let phase = phase_pi * std::f64::consts::PI;
        let path = LoadPath::harmonic(&p0, &p1, &q0, &q1, &phase);
        let exact = w_harmonic([p0, p1, q0, q1, phase], &contact, compliance.as_ref());
        let computed = w_path(&path, &contact, compliance.as_ref());
        assert!(
            relative(computed, exact) < 1e-12,
            "{spec} P1 = {p1} Q1 = {q1} φ = {phase_pi}π: path {computed:e}, four segments {exact:e}"
        );
    }
}

#[test]
fn a_harmonic_path_equals_the_four_segment_w_to_23_digits_at_25() {
    let precision = Precision::decimal_digits(32);
    let number = |text: &str| Float::parse_decimal(text, precision).unwrap();
    let compliance = parse_spec::<Float>(PERSSON, precision).unwrap();
    let contact = Contact {
        friction: number("0.9"),
        compliance_ratio: number("1.2"),
    };
    let phase = Float::pi(precision) * &number("0.35");
    let (p0, p1, q0, q1) = (number("1"), number("0.4"), number("0.05"), number("0.45"));
    let path = LoadPath::harmonic(&p0, &p1, &q0, &q1, &phase);
    let exact = w_harmonic([p0, p1, q0, q1, phase], &contact, compliance.as_ref());
    let computed = w_path(&path, &contact, compliance.as_ref());
    let digits = agreeing_digits(&computed, &exact);
    assert!(digits >= 23, "{digits} digits: {computed} vs {exact}");
}

/// The turning points of a sampled periodic signal, starting at its largest.
fn reversals(values: &[f64]) -> Vec<f64> {
    let n = values.len();
    let top = (0..n).max_by(|&a, &b| values[a].total_cmp(&values[b])).unwrap_or(0);
    let rotated: Vec<f64> = (0..=n).map(|i| values[(top + i) % n]).collect();
    let mut turning = vec![rotated[0]];
    for i in 1..n {
        let (a, b, c) = (rotated[i - 1], rotated[i], rotated[i + 1]);
        if (b - a) * (c - b) < 0.0 {
            turning.push(b);
        }
    }
    turning.push(rotated[0]);
    turning
}

/// The ranges of the closed rainflow cycles of a periodic sequence of reversals that starts
/// and ends at its largest value (ASTM E1049 three-point rule).
fn rainflow_ranges(reversals: &[f64]) -> Vec<f64> {
    let mut stack: Vec<f64> = Vec::new();
    let mut ranges = Vec::new();
    for &value in reversals {
        stack.push(value);
        while stack.len() >= 3 {
            let k = stack.len();
            let (x, y) = ((stack[k - 1] - stack[k - 2]).abs(), (stack[k - 2] - stack[k - 3]).abs());
            if x < y {
                break;
            }
            ranges.push(y);
            stack.drain(k - 3..k - 1);
        }
    }
    ranges
}

#[test]
fn constant_p_with_two_harmonics_in_q_is_masing_over_rainflow_cycles() {
    let compliance = parse_spec::<f64>(PERSSON, Precision::DOUBLE).unwrap();
    let contact = contact::<f64>(1.0, 1.0, Precision::DOUBLE);
    for (q1, q2, shift) in [(0.3, 0.2, 0.7), (0.25, 0.25, 2.0), (0.4, 0.1, 0.0)] {
        let mut path = LoadPath::harmonic(&1.0, &0.0, &0.0, &q1, &0.0);
        path.normal = TrigPoly {
            cos: vec![1.0, 0.0, 0.0],
            sin: vec![0.0; 3],
        };
        path.tangential = TrigPoly {
            cos: vec![0.0, q1, q2 * f64::cos(shift)],
            sin: vec![0.0, 0.0, -q2 * f64::sin(shift)],
        };
        let samples: Vec<f64> = (0..200_000)
            .map(|j| path.tangential.value(&(j as f64 * std::f64::consts::TAU / 200_000.0)))
            .collect();
        let ranges = rainflow_ranges(&reversals(&samples));
        assert!(ranges.len() >= 2, "{ranges:?}");
        let masing: f64 = ranges
            .iter()
            .map(|range| w_harmonic([1.0, 0.0, 0.0, 0.5 * range, 0.0], &contact, compliance.as_ref()))
            .sum();
        let computed = w_path(&path, &contact, compliance.as_ref());
        // The sampled reversals carry an error of order (2π/200000)², relative.
        assert!(
            relative(computed, masing) < 1e-8,
            "{q1}, {q2}: {computed:e} vs Masing {masing:e} over {ranges:?}"
        );
    }
}

fn two_harmonic_text() -> &'static str {
    "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0.05,0\n1,0.25,0.05,0.2,-0.3\n2,0.08,-0.04,0.1,0.06\n"
}

#[test]
fn w_is_the_same_after_a_time_shift_a_mean_shift_extra_zero_harmonics_and_from_samples() {
    let compliance = parse_spec::<f64>(HERTZ, Precision::DOUBLE).unwrap();
    let contact = contact::<f64>(0.8, 1.2, Precision::DOUBLE);
    let path = read_harmonics::<f64>(two_harmonic_text(), Precision::DOUBLE).unwrap();
    let w = w_path(&path, &contact, compliance.as_ref());
    assert!(w > 0.0);
    let mut shifted = path.clone();
    shifted.normal = path.normal.shifted(&1.234);
    shifted.tangential = path.tangential.shifted(&1.234);
    let mut mean_shift = path.clone();
    mean_shift.tangential.cos[0] += 0.1;
    let padded = read_harmonics::<f64>(
        &format!("{}5,0,0,0,0\n3,0,0,0,0\n", two_harmonic_text()),
        Precision::DOUBLE,
    )
    .unwrap();
    let samples: String = std::iter::once("P,Q\n".to_string())
        .chain((0..9).map(|j| {
            let theta = j as f64 * std::f64::consts::TAU / 9.0;
            format!("{:e},{:e}\n", path.normal.value(&theta), path.tangential.value(&theta))
        }))
        .collect();
    let sampled = read_samples::<f64>(&samples, Precision::DOUBLE).unwrap();
    for (name, other) in [
        ("time shift", shifted),
        ("Q0 shift", mean_shift),
        ("zero harmonics", padded),
        ("samples", sampled),
    ] {
        let value = w_path(&other, &contact, compliance.as_ref());
        assert!(relative(value, w) < 1e-12, "{name}: {value:e} vs {w:e}");
    }
}

#[test]
fn the_steady_loop_closes_and_the_loss_factor_is_w_over_pi_qa_ua() {
    let compliance = parse_spec::<f64>(PERSSON, Precision::DOUBLE).unwrap();
    let contact = contact::<f64>(0.8, 1.2, Precision::DOUBLE);
    let path = read_harmonics::<f64>(two_harmonic_text(), Precision::DOUBLE).unwrap();
    let cycle = SteadyCycle::new(&path, &contact).unwrap();
    let w = w_path(&path, &contact, compliance.as_ref());
    let outputs = path_outputs(&path, &cycle, &contact, compliance.as_ref(), w, 3, 512);
    // ∮ Q du from the loop's own harmonics: π Σ k (Q_cos,k u_sin,k − Q_sin,k u_cos,k) is W.
    let from_harmonics: f64 = outputs
        .harmonics
        .iter()
        .map(|h| std::f64::consts::PI * h.k as f64 * (h.q_cos * h.u_sin - h.q_sin * h.u_cos))
        .sum();
    assert!(relative(from_harmonics, w) < 1e-9, "{from_harmonics:e} vs {w:e}");
    let eta = w / (std::f64::consts::PI * outputs.q_amplitude * outputs.u_amplitude);
    assert!(relative(outputs.loss_factor, eta) < 1e-15);
    assert!((outputs.damping_ratio - 0.5 * outputs.loss_factor).abs() < 1e-18);
    let (low, high) = outputs.steady_loop.iter().fold((f64::MAX, f64::MIN), |(l, h), p| {
        (l.min(p.displacement), h.max(p.displacement))
    });
    assert!(0.5 * (high - low) <= outputs.u_amplitude * (1.0 + 1e-12));
    assert!(0.5 * (high - low) > outputs.u_amplitude * (1.0 - 1e-3));
    assert_eq!(outputs.steady_loop.len(), 512);
    // A loop of fewer samples than the amplitudes use still spans the whole cycle.
    let few = path_outputs(&path, &cycle, &contact, compliance.as_ref(), w, 0, 100);
    assert_eq!(few.steady_loop.len(), 100);
    assert!((few.steady_loop[99].theta - std::f64::consts::TAU * 0.99).abs() < 1e-12);
    assert!(relative(few.u_amplitude, outputs.u_amplitude) < 1e-12);
}

/// W by an independent spring bed: elements at activation loads s with normal stiffness
/// K(b) − K(a) over their interval (K = 1/v'), tangential stiffness that over λ and the
/// Coulomb limit f times their normal force k(v(P) − v(s)); at each step the rigid
/// displacement u balances Q, elements entering carry no force and leaving ones forget.
/// Elements below `floor` (under the lowest slipping load) are one base that sticks.
fn spring_bed_w(
    path: &LoadPath<f64>,
    contact: &Contact<f64>,
    compliance: &dyn Compliance<f64>,
    floor: f64,
    top: f64,
    elements: usize,
    steps: usize,
) -> f64 {
    let (f, ratio) = (contact.friction, contact.compliance_ratio);
    let stiffness = |s: f64| 1.0 / compliance.slope(&s);
    let width = (top - floor) / elements as f64;
    let entry: Vec<f64> = (0..elements).map(|i| floor + width * (i as f64 + 0.5)).collect();
    let spring: Vec<f64> = (0..elements)
        .map(|i| stiffness(floor + width * (i + 1) as f64) - stiffness(floor + width * i as f64))
        .collect();
    let approach_at: Vec<f64> = entry.iter().map(|s| compliance.approach(s)).collect();
    let base = stiffness(floor);
    let mut offset = vec![0.0; elements];
    let mut touching = vec![false; elements];
    let mut u = 0.0;
    let mut step = |p: f64, q: f64, u: &mut f64| {
        let approach = compliance.approach(&p);
        for i in 0..elements {
            let now = entry[i] < p;
            if now && !touching[i] {
                offset[i] = *u;
            }
            touching[i] = now;
        }
        let limit = |i: usize| ratio * f * (approach - approach_at[i]);
        let force = |x: f64| {
            let mut total = base * x;
            for i in (0..elements).filter(|&i| touching[i]) {
                total += spring[i] * (x - offset[i]).clamp(-limit(i), limit(i));
            }
            total / ratio - q
        };
        let (mut low, mut high) = (*u - 1.0, *u + 1.0);
        while force(low) > 0.0 {
            low -= 2.0 * (high - low);
        }
        while force(high) < 0.0 {
            high += 2.0 * (high - low);
        }
        for _ in 0..100 {
            let middle = 0.5 * (low + high);
            if force(middle) < 0.0 {
                low = middle;
            } else {
                high = middle;
            }
        }
        *u = 0.5 * (low + high);
        for i in (0..elements).filter(|&i| touching[i]) {
            offset[i] = offset[i].clamp(*u - limit(i), *u + limit(i));
        }
    };
    let (p0, q0) = (path.normal.value(&0.0), path.tangential.value(&0.0));
    for i in 1..=200 {
        let t = i as f64 / 200.0;
        step(p0 * (2.0 * t).min(1.0), q0 * (2.0 * t - 1.0).max(0.0), &mut u);
    }
    let mut work = 0.0;
    for cycle in 0..3 {
        let (mut q_before, mut u_before) = (q0, u);
        for j in 1..=steps {
            let theta = j as f64 * std::f64::consts::TAU / steps as f64;
            let (p, q) = (path.normal.value(&theta), path.tangential.value(&theta));
            step(p, q, &mut u);
            if cycle == 2 {
                work += 0.5 * (q + q_before) * (u - u_before);
            }
            (q_before, u_before) = (q, u);
        }
    }
    work
}

#[test]
fn two_harmonics_in_p_and_q_agree_with_an_independent_spring_bed_to_1e_4() {
    let compliance = parse_spec::<f64>(PERSSON, Precision::DOUBLE).unwrap();
    let contact = contact::<f64>(0.8, 1.2, Precision::DOUBLE);
    let path = read_harmonics::<f64>(two_harmonic_text(), Precision::DOUBLE).unwrap();
    let cycle = SteadyCycle::new(&path, &contact).unwrap();
    let w = w_path(&path, &contact, compliance.as_ref());
    let floor = 0.9 * cycle.lowest_slip;
    let bed = |n: usize, steps: usize| {
        spring_bed_w(
            &path,
            &contact,
            compliance.as_ref(),
            floor,
            cycle.highest_load,
            n,
            steps,
        )
    };
    let (coarse, fine) = (bed(500, 2000), bed(1000, 4000));
    assert!(relative(fine, w) < 1e-4, "{fine:e} vs {w:e}");
    // The bed converges at first order (entries and exits fall inside steps and elements):
    // measured 8.2e-5 and 4.1e-5, and 6e-7 once extrapolated.
    let extrapolated = 2.0 * fine - coarse;
    assert!(relative(extrapolated, w) < 1e-5, "{extrapolated:e} vs {w:e}");
}

#[test]
fn in_phase_constant_load_and_motionless_paths_meet_their_closed_forms() {
    let compliance = parse_spec::<f64>(PERSSON, Precision::DOUBLE).unwrap();
    let contact = contact::<f64>(1.0, 1.0, Precision::DOUBLE);
    let pi = std::f64::consts::PI;
    // In phase and in anti-phase beyond the friction cone, and at constant P.
    for (p1, q1, phase) in [(0.4, 0.5, 0.0), (0.4, 0.5, pi), (0.2, 0.7, 0.0), (0.0, 0.5, 0.3)] {
        let path = LoadPath::harmonic(&1.0, &p1, &0.05, &q1, &phase);
        // W has period π in φ (the four segments are compared at φ mod π).
        let exact = w_harmonic([1.0, p1, 0.05, q1, phase % pi], &contact, compliance.as_ref());
        let computed = w_path(&path, &contact, compliance.as_ref());
        assert!(
            relative(computed, exact) < 1e-12,
            "P1 = {p1}, Q1 = {q1}, φ = {phase}: {computed:e} vs {exact:e}"
        );
    }
    // In phase inside the cone, P alone, and nothing moving: the contact sticks, W = 0.
    for (p1, q1) in [(0.4, 0.3), (0.4, 0.0), (0.0, 0.0)] {
        let path = LoadPath::harmonic(&1.0, &p1, &0.1, &q1, &0.0);
        let computed = w_path(&path, &contact, compliance.as_ref());
        assert!(computed.abs() < 1e-16, "P1 = {p1}, Q1 = {q1}: {computed:e}");
    }
}

/// A path with harmonics 1 … K of decreasing random size (a fixed linear congruential stream).
fn random_path(harmonics: usize, seed: &mut u64) -> LoadPath<f64> {
    let mut uniform = || {
        *seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((*seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    let mut normal = TrigPoly {
        cos: vec![0.0; harmonics + 1],
        sin: vec![0.0; harmonics + 1],
    };
    let mut tangential = normal.clone();
    normal.cos[0] = 1.0;
    for k in 1..=harmonics {
        let size = 0.25 / k as f64;
        normal.cos[k] = size * uniform();
        normal.sin[k] = size * uniform();
        tangential.cos[k] = 0.7 * size * uniform();
        tangential.sin[k] = 0.7 * size * uniform();
    }
    tangential.cos[0] = 0.05 * uniform();
    LoadPath { normal, tangential }
}

#[test]
fn random_paths_of_two_to_five_harmonics_agree_with_the_spring_bed() {
    let compliance = parse_spec::<f64>(HERTZ, Precision::DOUBLE).unwrap();
    let contact = contact::<f64>(0.7, 1.3, Precision::DOUBLE);
    let mut seed = 12345;
    for harmonics in 2..=5 {
        let path = random_path(harmonics, &mut seed);
        let cycle = SteadyCycle::new(&path, &contact).unwrap();
        let w = w_path(&path, &contact, compliance.as_ref());
        let bed = |n: usize, steps: usize| {
            spring_bed_w(
                &path,
                &contact,
                compliance.as_ref(),
                0.9 * cycle.lowest_slip,
                cycle.highest_load,
                n,
                steps,
            )
        };
        // Measured: 3.5e-6, 2.0e-6, 3.7e-5, 9.3e-7 after extrapolating from 300 and 600 elements.
        let extrapolated = 2.0 * bed(600, 4000) - bed(300, 2000);
        assert!(
            relative(extrapolated, w) < 1e-4,
            "K = {harmonics}, {} segments: bed {extrapolated:e} vs {w:e}",
            cycle.segments.len()
        );
    }
}

#[test]
fn constant_p_with_two_harmonics_in_q_is_masing_to_18_digits_at_20() {
    let precision = Precision::decimal_digits(28);
    let number = |text: &str| Float::parse_decimal(text, precision).unwrap();
    let compliance = parse_spec::<Float>(PERSSON, precision).unwrap();
    let contact = Contact {
        friction: number("0.9"),
        compliance_ratio: number("1.1"),
    };
    let zero = number("0");
    let tangential = TrigPoly {
        cos: vec![zero.clone(), number("0.3"), number("0.15")],
        sin: vec![zero.clone(), number("0.1"), number("-0.13")],
    };
    let path = LoadPath {
        normal: TrigPoly {
            cos: vec![number("1"), zero.clone(), zero.clone()],
            sin: vec![zero.clone(); 3],
        },
        tangential: tangential.clone(),
    };
    // The reversals of Q: sampled in f64, then Newton on Q' = 0 at the working precision.
    let rate = tangential.derivative();
    let curvature = rate.derivative();
    let samples: Vec<f64> = (0..4000)
        .map(|j| {
            rate.value(&Float::with_val(
                precision.in_bits(),
                j as f64 * std::f64::consts::TAU / 4000.0,
            ))
            .to_f64()
        })
        .collect();
    let mut reversals: Vec<(f64, Float)> = Vec::new();
    for j in 0..4000 {
        if samples[j] * samples[(j + 1) % 4000] < 0.0 {
            let mut theta = Float::with_val(precision.in_bits(), (j as f64 + 0.5) * std::f64::consts::TAU / 4000.0);
            for _ in 0..12 {
                theta -= rate.value(&theta) / curvature.value(&theta);
            }
            let value = tangential.value(&theta);
            reversals.push((value.to_f64(), value));
        }
    }
    let top = (0..reversals.len())
        .max_by(|&a, &b| reversals[a].0.total_cmp(&reversals[b].0))
        .unwrap();
    let mut cycle: Vec<Float> = (0..=reversals.len())
        .map(|i| reversals[(top + i) % reversals.len()].1.clone())
        .collect();
    // Rainflow (three-point rule) at the working precision.
    let mut stack: Vec<Float> = Vec::new();
    let mut masing = zero.clone();
    for value in cycle.drain(..) {
        stack.push(value);
        while stack.len() >= 3 {
            let k = stack.len();
            let newer = (stack[k - 1].clone() - &stack[k - 2]).abs();
            let older = (stack[k - 2].clone() - &stack[k - 3]).abs();
            if newer < older {
                break;
            }
            let half = older / &number("2");
            masing += w_harmonic(
                [number("1"), zero.clone(), zero.clone(), half, zero.clone()],
                &contact,
                compliance.as_ref(),
            );
            stack.drain(k - 3..k - 1);
        }
    }
    assert_eq!(reversals.len(), 4, "two rainflow cycles");
    let computed = w_path(&path, &contact, compliance.as_ref());
    let digits = agreeing_digits(&computed, &masing);
    assert!(digits >= 18, "{digits} digits: {computed} vs Masing {masing}");
}
