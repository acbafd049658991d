//! A rigorous Gauss–Legendre integral in f64 intervals against the plain f64 sum of the
//! same degree and against Arb balls at 53 bits, on the four segment integrals of the
//! acceptance case (Persson, P0 = 1, P1 = 0.4, Q1 = 0.5, φ = 0.4π, f = λ = 1):
//!
//! - `intervals, proven`: `interval::gauss::integrate` on every piece (its Bernstein-ellipse
//!   bound on a complex rectangle, the rule, the error added);
//! - `f64, same degrees`: the f64 rule of the degree the intervals chose, per piece;
//! - `balls 53 bits, same degrees`: that rule's sum on balls at 53 bits (real points
//!   only, no bound: a lower bound of a ball rule's cost).
//!
//! Before timing, prints per piece the degree, the width of the enclosure and the f64
//! value.

use std::cell::Cell;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use microslip::ball::Ball;
use microslip::case::Case;
use microslip::cycle::ValidCycle;
use microslip::dissipation::SegmentIntegrands;
use microslip::doubts::{watch, with_analytic};
use microslip::interval::gauss::integrate;
use microslip::interval::Interval;
use microslip::quad::gauss_legendre::node_table;
use microslip::quad::Piece;
use microslip::real::{Precision, Real};

#[path = "../tests/common/mod.rs"]
mod common;

/// The absolute error each interval rule may have.
const TOLERANCE: f64 = 1e-17;

/// The most points of one interval rule.
const DEGREE_LIMIT: u64 = 256;

/// The segment pieces of the acceptance case in `R`, passed to `use_them`.
fn with_pieces<R: Real, T>(precision: Precision, use_them: impl FnOnce(&[Piece<'_, R>]) -> T) -> T {
    let Case { cycle, compliance } = common::case().text().read::<R>(precision).expect("the case");
    let geometry = ValidCycle::new(cycle).expect("a valid cycle").geometry();
    let integrands = SegmentIntegrands {
        geometry: &geometry,
        compliance: compliance.as_ref(),
        remove_constant_slope: true,
    };
    let pieces = integrands.pieces();
    let outcome = use_them(&pieces.pieces);
    drop(pieces);
    outcome
}

/// Each piece's integral on intervals with the real points it took (`None` where the
/// rule gave up).
fn proven(pieces: &[Piece<'_, Interval>]) -> Vec<(Option<Interval>, u64)> {
    pieces
        .iter()
        .map(|piece| {
            let points = Cell::new(0);
            let integrand = |x: &Interval, analytic: bool| {
                points.set(points.get() + u64::from(!analytic));
                let (value, doubts) = watch(|| with_analytic(analytic, || (piece.integrand)(x)));
                doubts.none().then_some(value)
            };
            let value = integrate(&integrand, &piece.start, &piece.end, TOLERANCE, DEGREE_LIMIT);
            (value, points.get())
        })
        .collect()
}

/// Σ over pieces of the rule of `degrees[i]` points on piece i.
fn same_degrees<R: Real>(pieces: &[Piece<'_, R>], degrees: &[usize], precision: Precision) -> R {
    let mut total = pieces[0].start.int(0);
    for (piece, &points) in pieces.iter().zip(degrees) {
        total += node_table::<R>(points, precision).integrate(&piece.integrand, &piece.start, &piece.end);
    }
    total
}

fn bench_interval_rule(c: &mut Criterion) {
    let ball_bits = Precision::bits(53);
    let degrees: Vec<usize> = with_pieces::<Interval, _>(Precision::DOUBLE, |pieces| {
        let results = proven(pieces);
        with_pieces::<f64, _>(Precision::DOUBLE, |plain| {
            for ((piece, (value, points)), f64_piece) in pieces.iter().zip(&results).zip(plain) {
                let table = node_table::<f64>((*points).max(1) as usize, Precision::DOUBLE);
                let reference = table.integrate(&f64_piece.integrand, &f64_piece.start, &f64_piece.end);
                match value {
                    Some(value) => println!(
                        "{}: {points} points, {value:?}, width {:.2e}, f64 {reference:e}",
                        piece.label,
                        value.width()
                    ),
                    None => println!("{}: no enclosure", piece.label),
                }
            }
        });
        results.iter().map(|(_, points)| (*points).max(1) as usize).collect()
    });
    let mut group = c.benchmark_group("interval/persson segments");
    group.bench_function("intervals, proven", |b| {
        with_pieces::<Interval, _>(Precision::DOUBLE, |pieces| b.iter(|| black_box(proven(pieces))))
    });
    group.bench_function("f64, same degrees", |b| {
        with_pieces::<f64, _>(Precision::DOUBLE, |pieces| {
            b.iter(|| black_box(same_degrees(pieces, &degrees, Precision::DOUBLE)))
        })
    });
    group.bench_function("balls 53 bits, same degrees", |b| {
        with_pieces::<Ball, _>(ball_bits, |pieces| {
            b.iter(|| black_box(same_degrees(pieces, &degrees, ball_bits)))
        })
    });
    group.finish();
}

criterion_group!(benches, bench_interval_rule);
criterion_main!(benches);
