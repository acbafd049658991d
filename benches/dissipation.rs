//! W for an ordinary case (v' = 1/P, P0 = 1, P1 = 0.4, Q1 = 0.5, φ = 0.4π) in f64 and at
//! increasing precision, and the Gauss–Legendre node tables cold and cached.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use microslip::dissipation::{dissipation, Options};
use microslip::inputs::{Case, CaseText};
use microslip::quad::gauss_legendre::{clear_node_cache, compute_node_table, node_table};
use microslip::real::{Precision, Real};
use rug::Float;

fn ordinary_case() -> CaseText {
    CaseText {
        p0: "1".into(),
        p1: "0.4".into(),
        q0: "0".into(),
        q1: "0.5".into(),
        phi: "0.4pi".into(),
        friction: "1".into(),
        lambda: Some("1".into()),
        nu: None,
        compliance: "power:c=1,beta=-1".into(),
    }
}

fn bench_dissipation(c: &mut Criterion) {
    let mut group = c.benchmark_group("dissipation/ordinary");
    let Case { cycle, compliance } = ordinary_case().read::<f64>(Precision::DOUBLE).unwrap();
    group.bench_function("f64", |b| {
        b.iter(|| {
            dissipation(&cycle, compliance.as_ref(), &Options::default())
                .unwrap()
                .total
        })
    });
    for bits in [128u32, 256, 512, 1024] {
        let Case { cycle, compliance } = ordinary_case().read::<Float>(Precision::bits(bits)).unwrap();
        group.bench_with_input(BenchmarkId::new("bits", bits), &bits, |b, _| {
            b.iter(|| {
                dissipation(&cycle, compliance.as_ref(), &Options::default())
                    .unwrap()
                    .total
            })
        });
    }
    group.finish();
}

fn bench_node_tables(c: &mut Criterion) {
    let mut group = c.benchmark_group("gauss_legendre_nodes");
    for (points, bits) in [(64usize, 256u32), (128, 512)] {
        let precision = Precision::bits(bits);
        group.bench_function(format!("cold/{points}pt/{bits}bits"), |b| {
            b.iter(|| compute_node_table::<Float>(points, precision).nodes.len())
        });
        node_table::<Float>(points, precision);
        group.bench_function(format!("cached/{points}pt/{bits}bits"), |b| {
            b.iter(|| node_table::<Float>(points, precision).points())
        });
    }
    clear_node_cache();
    group.bench_function("cold/64pt/f64", |b| {
        b.iter(|| compute_node_table::<f64>(64, Precision::DOUBLE).nodes[0].to_f64_lossy())
    });
    group.finish();
}

criterion_group!(benches, bench_dissipation, bench_node_tables);
criterion_main!(benches);
