//! The exact (quadrature-free) methods against the four-segment quadrature:
//! W for polynomial compliances and the closed-form coefficient I(ρ, φ).

use microslip::compliance::Polynomial;
use microslip::cycle::LoadCycle;
use microslip::dissipation::{four_segment, in_phase, Options};
use microslip::exact::{closed_form_coefficient, polynomial_dissipation, series_coefficients};
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
        let phi = microslip::inputs::parse_phase::<Float>(phi_text, precision).unwrap();
        let closed = closed_form_coefficient(&rho, &phi);
        let (quadrature, error) = coefficient_with_error(&rho, &phi, Options::default()).unwrap();
        let agreed = digits(&closed, &quadrature, &closed.clone().abs());
        assert!(
            agreed >= 100.0,
            "ρ = {rho_text}, φ = {phi_text}: {agreed:.1} digits (estimate {})",
            error.to_scientific(3)
        );
    }
}
