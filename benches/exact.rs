//! The small-amplitude coefficient I(ρ, φ) by its closed form against the four-segment
//! quadrature, in f64 and at 100 digits (goal: closed form ≤ 1 µs in f64, ≤ 100 µs at
//! 100 digits), and the series coefficients I₀ … I₃₀ exactly at 100 digits.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use microslip::exact::{closed_form_coefficient, series_coefficients};
use microslip::real::{Precision, Real};
use microslip::verify::small_amplitude::coefficient;
use rug::Float;

fn bench_coefficient(c: &mut Criterion) {
    let mut group = c.benchmark_group("small-amplitude coefficient");
    let (rho, phase) = (1.25f64, 0.4 * std::f64::consts::PI);
    group.bench_function("closed form f64", |b| {
        b.iter(|| closed_form_coefficient(black_box(&rho), black_box(&phase)))
    });
    group.bench_function("quadrature f64", |b| {
        b.iter(|| coefficient(black_box(&rho), black_box(&phase)).unwrap())
    });
    let precision = Precision::decimal_digits(100);
    let rho_wide = Float::parse_decimal("1.25", precision).unwrap();
    let phase_wide = Float::pi(precision) * Float::parse_decimal("0.4", precision).unwrap();
    group.bench_function("closed form 100 digits", |b| {
        b.iter(|| closed_form_coefficient(black_box(&rho_wide), black_box(&phase_wide)))
    });
    group.sample_size(10);
    group.bench_function("quadrature 100 digits", |b| {
        b.iter(|| coefficient(black_box(&rho_wide), black_box(&phase_wide)).unwrap())
    });
    group.bench_function("series I0..I30 100 digits", |b| {
        b.iter(|| series_coefficients(black_box(&rho_wide), black_box(&phase_wide), 30).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench_coefficient);
criterion_main!(benches);
