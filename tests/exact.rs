//! The exact (quadrature-free) methods against the four-segment quadrature:
//! W for polynomial compliances and the closed-form coefficient I(ρ, φ).

use microslip::compliance::Polynomial;
use microslip::compliance::{Compliance, Hertz};
use microslip::cycle::{LoadCycle, ValidCycle};
use microslip::dissipation::{four_segment, in_phase, HertzConfiguration, MindlinDeresiewicz, Options};
use microslip::exact::{closed_form_coefficient, polynomial_dissipation};
use microslip::real::{Precision, Real};
use microslip::verify::small_amplitude::coefficient_with_error;
use rug::Float;

/// A small deterministic generator (xorshift), uniform in [0, 1).
struct Draws(u64);

impl Draws {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn between(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * self.next()
    }
}

fn at(x: f64, bits: u32) -> Float {
    Float::from_f64(x, Precision::bits(bits))
}

/// −log10 of |a − b| / scale.
fn digits(a: &Float, b: &Float, scale: &Float) -> f64 {
    let difference = (a.clone() - b).abs();
    if difference == 0 {
        return f64::INFINITY;
    }
    -(difference / scale).log10().to_f64()
}

#[test]
fn polynomial_w_equals_the_quadrature_to_100_digits() {
    let bits = 400;
    let mut draws = Draws(0x5eed_1234_abcd);
    for case in 0..4 {
        let friction = draws.between(0.3, 1.0);
        let p1 = draws.between(0.1, 0.4);
        let rho = draws.between(0.2, 1.5);
        let cycle = LoadCycle {
            mean_normal_load: at(1.0, bits),
            normal_amplitude: at(p1, bits),
            mean_tangential_load: at(draws.between(-0.1, 0.1) * friction, bits),
            tangential_amplitude: at(rho * friction * p1, bits),
            phase: at(draws.between(0.05, 3.1), bits),
            friction: at(friction, bits),
            compliance_ratio: at(draws.between(1.0, 2.0), bits),
        };
        let degree = 2 + case;
        let polynomial = Polynomial {
            reference: at(draws.between(0.5, 1.5), bits),
            coefficients: (0..=degree).map(|_| at(draws.between(-2.0, 2.0), bits)).collect(),
        };
        let exact = polynomial_dissipation(&cycle, &polynomial).unwrap();
        let options = Options {
            check_compliance: false,
            ..Options::default()
        };
        let quadrature = four_segment(&cycle, &polynomial, &options).unwrap();
        let scale = exact.named().iter().fold(at(0.0, bits), |acc, (_, v)| acc + &v.abs());
        let agreed = digits(&exact.total(), &quadrature.total, &scale);
        println!("polynomial case {case} (degree {degree}): W agrees to {agreed:.1} digits");
        assert!(agreed >= 100.0, "case {case}: {agreed:.1} digits");
        for ((name, a), (_, b)) in exact.named().iter().zip(quadrature.segments.named()) {
            let agreed = digits(a, b, &scale);
            assert!(agreed >= 100.0, "case {case} segment {name}: {agreed:.1} digits");
        }
    }
}

/// The grid of the issue: ρ from 0.001 to 1000 (with ρ = 1), φ near 0, π/2 and π.
fn grid() -> Vec<(&'static str, &'static str)> {
    let mut cases = Vec::new();
    for rho in ["0.001", "0.3", "1", "2.5", "1000"] {
        for phi in ["0.01", "0.5pi", "pi-0.01", "0.3pi"] {
            cases.push((rho, phi));
        }
    }
    cases
}

#[test]
fn closed_form_coefficient_equals_the_quadrature_to_100_digits() {
    let precision = Precision::bits(420);
    for (rho_text, phi_text) in grid() {
        let rho = Float::parse_decimal(rho_text, precision).unwrap();
        let (phi, _) = microslip::case::parse_phase::<Float>(phi_text, precision).unwrap();
        let closed = closed_form_coefficient(&rho, &phi);
        let (quadrature, error) = coefficient_with_error(&rho, &phi, Options::default()).unwrap();
        let agreed = digits(&closed, &quadrature, &closed.clone().abs());
        println!("ρ = {rho_text}, φ = {phi_text}: {agreed:.1} digits");
        assert!(
            agreed >= 100.0,
            "ρ = {rho_text}, φ = {phi_text}: {agreed:.1} digits (estimate {})",
            error.to_scientific(3)
        );
    }
}

fn closed(rho: &str, phi: &str, bits: u32) -> Float {
    let precision = Precision::bits(bits);
    let rho = Float::parse_decimal(rho, precision).unwrap();
    let (phi, _) = microslip::case::parse_phase::<Float>(phi, precision).unwrap();
    closed_form_coefficient(&rho, &phi)
}

#[test]
fn closed_form_limits_in_rho() {
    let bits = 200;
    let pi = Float::pi(Precision::bits(bits));
    for phi in ["0.3", "1.2", "2.8"] {
        let phase = Float::parse_decimal(phi, Precision::bits(bits)).unwrap();
        let (sin, cos) = phase.clone().sin_cos(Float::new(bits));
        // ρ → 0: I = −(8/3)ρ² sin²φ (1 + ρ cos φ) + O(ρ⁴).
        let rho = Float::parse_decimal("1e-6", Precision::bits(bits)).unwrap();
        let small = -(rho.clone() * &rho * &sin * &sin * 8i32 / 3i32) * (rho.clone() * &cos + 1i32);
        let relative = ((closed("1e-6", phi, bits) - &small) / &small).abs().to_f64();
        assert!(relative < 1e-11, "φ = {phi}: {relative:e}");
        // ρ → ∞: I = −(2/3)ρ³ + (7cos²φ/3 − 5/3 − (π/2) sin φ cos φ)ρ + O(1).
        let rho = Float::parse_decimal("1e8", Precision::bits(bits)).unwrap();
        let second =
            cos.clone() * &cos * 7i32 / 3i32 - Float::with_val(bits, 5) / 3i32 - pi.clone() * &sin * &cos / 2i32;
        let large = -(rho.clone() * &rho * &rho * 2i32 / 3i32) + second * &rho;
        let remainder = (closed("1e8", phi, bits) - &large).abs().to_f64();
        assert!(remainder < 10.0, "φ = {phi}: O(1) remainder {remainder}");
    }
}

#[test]
fn closed_form_limits_in_phase() {
    let bits = 200;
    // ρ < 1: I ≈ −(8/3)ρ²φ²/(1 − ρ); ρ = 1: I ≈ −(13/6 + π/4)φ; ρ > 1: I ≈ −(2/3)ρ(ρ² − 1) − (π/2)ρφ.
    let phi = 1e-12;
    let below = closed("0.6", "1e-12", bits).to_f64();
    assert!(
        (below / (-8.0 / 3.0 * 0.36 * phi * phi / 0.4) - 1.0).abs() < 1e-9,
        "{below}"
    );
    let at_one = closed("1", "1e-12", bits).to_f64();
    let slope = -(13.0 / 6.0 + std::f64::consts::FRAC_PI_4);
    assert!((at_one / (slope * phi) - 1.0).abs() < 1e-9, "{at_one}");
    let above = closed("2.5", "1e-12", bits).to_f64();
    let expected = -2.0 / 3.0 * 2.5 * (2.5 * 2.5 - 1.0) - std::f64::consts::FRAC_PI_2 * 2.5 * phi;
    assert!((above - expected).abs() < 1e-20, "{above} against {expected}");
    // Exactly in phase the closed form equals the paper's in-phase closed form (ρ > 1) and 0 (ρ ≤ 1).
    let precision = Precision::bits(bits);
    for rho in ["0.4", "1", "1.7", "30"] {
        let one = Float::with_val(bits, 1);
        let amplitude = Float::parse_decimal("0.01", precision).unwrap();
        let cycle = microslip::cycle::LoadCycle {
            mean_normal_load: one.clone(),
            normal_amplitude: amplitude.clone(),
            mean_tangential_load: Float::with_val(bits, 0),
            tangential_amplitude: Float::parse_decimal(rho, precision).unwrap() * &amplitude,
            phase: Float::with_val(bits, 0),
            friction: one.clone(),
            compliance_ratio: one.clone(),
        };
        let linear = Polynomial {
            reference: one.clone(),
            coefficients: vec![Float::with_val(bits, 0), one.clone()],
        };
        let options = Options {
            check_compliance: false,
            ..Options::default()
        };
        let w = in_phase(&ValidCycle::new(cycle.clone()).unwrap(), &linear, &options)
            .unwrap()
            .total;
        let from_closed_form = closed(rho, "0", bits) * &amplitude * &amplitude * &amplitude;
        let difference = (w - &from_closed_form).abs().to_f64();
        assert!(difference < 1e-50, "ρ = {rho}: {difference:e}");
    }
}

#[test]
fn closed_form_large_rho_is_the_cubic_term_of_mindlin_deresiewicz() {
    // P1 → 0 at fixed Q1 is ρ → ∞: λ f² P1³ v''(P0) I → −(2/3) λ v''(P0) Q1³/f, which for a Hertz
    // sphere on a rigid flat is the cubic term (2 − ν) Q1³/(36 G a f P0) of Mindlin–Deresiewicz.
    let bits = 200;
    let p = Precision::bits(bits);
    let number = |text: &str| Float::parse_decimal(text, p).unwrap();
    let md = MindlinDeresiewicz {
        shear_modulus: number("1"),
        poisson_ratio: number("0.3"),
        configuration: HertzConfiguration::SphereOnRigidFlat,
    };
    let hertz = Hertz {
        radius: number("1"),
        contact_modulus: md.contact_modulus(),
    };
    let (p0, f, lambda) = (number("1"), number("0.5"), number("1.7") / number("1.4"));
    for q in ["1e-3", "1e-5"] {
        let q1 = number(q) * &f * &p0;
        let exact = md.dissipation(&f, &p0, &q1, &hertz.contact_radius(&p0));
        let rho = number("1e9");
        let p1 = q1.clone() / (f.clone() * &rho);
        let coefficient = closed_form_coefficient(&rho, &number("0.7"));
        let series = lambda.clone() * &f * &f * &p1 * &p1 * &p1 * &hertz.curvature(&p0) * &coefficient;
        let relative = ((series / &exact) - 1i32).abs().to_f64();
        // The cubic term is exact up to O(q) (the bracket's next term).
        assert!(relative < 2.0 * q.parse::<f64>().unwrap(), "q = {q}: {relative:e}");
    }
}

/// The φ in (0, π) where I(ρ, ·) is most negative, by golden-section search in f64.
fn most_dissipative_phase(rho: f64) -> f64 {
    let golden = (5f64.sqrt() - 1.0) / 2.0;
    let (mut low, mut high) = (0.05, std::f64::consts::PI - 0.05);
    for _ in 0..200 {
        let (a, b) = (high - golden * (high - low), low + golden * (high - low));
        if closed_form_coefficient(&rho, &a) < closed_form_coefficient(&rho, &b) {
            high = b;
        } else {
            low = a;
        }
    }
    (low + high) / 2.0
}

#[test]
fn i_is_largest_near_half_pi_for_small_rho_and_near_0_406_pi_for_large_rho() {
    use std::f64::consts::PI;
    // ρ → 0: φ* ≈ π/2 − ρ/2 (from −(8/3)ρ² sin²φ (1 + ρ cos φ)).
    let small = most_dissipative_phase(1e-3);
    assert!((small - (PI / 2.0 - 5e-4)).abs() < 1e-5, "{small}");
    // ρ → ∞: φ* → π/2 − atan(3π/14)/2 = 0.405699π (the ρ¹ term of the expansion).
    let limit = PI / 2.0 - (3.0 * PI / 14.0).atan() / 2.0;
    let large = most_dissipative_phase(1e4);
    assert!((large - limit).abs() < 1e-4, "{} against {}", large / PI, limit / PI);
    // In between φ* dips to about 0.394π near ρ = 1 (proofs/small-amplitude-coefficient.md).
    let middle = most_dissipative_phase(1.0) / PI;
    assert!((middle - 0.3944).abs() < 1e-3, "{middle}");
}
