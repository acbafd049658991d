//! W for an ordinary catalogue case and two stiff ones in f64 and at increasing
//! precision, verified digits (50 and 100) with node tables warm, the
//! Gauss–Legendre node tables cold and cached, and the history simulation at its
//! default resolution (goal: ≤ 1 s a case on one core), and cycles near separation.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use microslip::accuracy::standard_cases;
use microslip::admissibility::prove_admissible;
use microslip::answer::agreed::verified_dissipation;
use microslip::answer::dissipation::dissipation_answer;
use microslip::case::Case;
#[cfg(feature = "certified")]
use microslip::digits::enclosure::{enclose_dissipation_with_lowest_load, INTERVAL_GOAL_BITS};
use microslip::dissipation::{dissipation, Options};
#[cfg(feature = "certified")]
use microslip::interval::Interval;
use microslip::quad::gauss_legendre::{clear_node_cache, compute_node_table, node_table};
use microslip::real::{Precision, Real};
use microslip::simulate::{simulate, SimulationOptions};
use rug::Float;
use std::time::Duration;

// The test builder of cases, shared with the tests.
#[path = "../tests/common/mod.rs"]
mod common;

fn bench_dissipation(c: &mut Criterion) {
    for case in standard_cases(false) {
        let mut group = c.benchmark_group(format!("dissipation/{}", case.name));
        group.sample_size(10);
        // The stiff cases are refused in f64 by default (rounding alone exceeds 1e-12); time them anyway.
        let options = Options::<f64> {
            rounding_limit: 1.0,
            ..Options::default()
        };
        let Case { cycle, compliance } = case.text.read::<f64>(Precision::DOUBLE).unwrap();
        group.bench_function("f64", |b| {
            b.iter(|| dissipation(&cycle, compliance.as_ref(), &options).unwrap().total)
        });
        // Near gross slip at 1024 bits the pieces need more than the default 512-point cap
        // (the library refuses with NotConverged there; verified digits raise the cap).
        let wide = Options::<Float>::default().with_max_points(4096);
        for bits in [128u32, 256, 512, 1024] {
            let Case { cycle, compliance } = case.text.read::<Float>(Precision::bits(bits)).unwrap();
            group.bench_with_input(BenchmarkId::new("bits", bits), &bits, |b, _| {
                b.iter(|| dissipation(&cycle, compliance.as_ref(), &wide).unwrap().total)
            });
        }
        group.finish();
    }
}

/// The acceptance case with the general power law v' = P⁻¹ (`power:c=1,beta=-1`, the same
/// compliance as Persson's with γσ = 1) in f64 with its error estimate. Goal: ≤ 10 µs.
fn bench_power_law_f64(c: &mut Criterion) {
    let text = common::case().compliance("power:c=1,beta=-1").text();
    let Case { cycle, compliance } = text.read::<f64>(Precision::DOUBLE).unwrap();
    c.bench_function("dissipation/power-law-acceptance/f64", |b| {
        b.iter(|| {
            let result = dissipation(&cycle, compliance.as_ref(), &Options::default()).unwrap();
            (result.total, result.error_estimate)
        })
    });
}

/// One run at a fixed precision with its error estimate (no verifying run), node tables
/// warm, for the three cases of `benches/mpmath_side_by_side.py`, which runs this group
/// (`cargo bench --bench dissipation -- single_run`) and reads the `single-run` lines:
/// case, digits, W, error estimate. Precision: the digits plus 10; tolerance 10^−(digits+1).
/// Goal: ≥ 20× faster than one mpmath tanh–sinh run at 50 and 100 digits.
fn bench_single_runs(c: &mut Criterion) {
    let mut group = c.benchmark_group("single_run");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(300));
    group.measurement_time(Duration::from_secs(1));
    // Each case as it differs from the acceptance case.
    let cases = [
        ("persson", common::case()),
        ("power", common::case().compliance("power:c=0.5,beta=-0.5")),
        (
            "hertz",
            common::case()
                .q0("0.1")
                .q1("0.3")
                .phi("0.3pi")
                .friction("0.5")
                .lambda("1.2")
                .compliance("hertz:r=1,estar=1"),
        ),
    ];
    for (name, case) in cases {
        let text = case.text();
        for digits in [15u32, 30, 50, 100] {
            let precision = Precision::decimal_digits(digits + 10);
            let Case { cycle, compliance } = text.read::<Float>(precision).unwrap();
            let options = Options {
                relative_tolerance: Some(Float::with_val(precision.in_bits(), 10).powi(-(digits as i32 + 1))),
                ..Options::default()
            };
            let result = dissipation(&cycle, compliance.as_ref(), &options).unwrap();
            println!(
                "single-run {name} {digits} {} {:.3e}",
                result.total.to_scientific(digits as usize + 5),
                result.error_estimate.to_f64_lossy()
            );
            group.bench_function(format!("{name}/{digits}"), |b| {
                b.iter(|| {
                    let result = dissipation(&cycle, compliance.as_ref(), &options).unwrap();
                    (result.total, result.error_estimate)
                })
            });
        }
    }
    group.finish();
}

fn bench_verified_digits(c: &mut Criterion) {
    let mut group = c.benchmark_group("verified_digits/persson-ordinary");
    group.sample_size(10);
    let case = &standard_cases(true)[0];
    for digits in [50u32, 100] {
        verified_dissipation(&case.text, digits, Duration::from_secs(60)).unwrap();
        group.bench_with_input(BenchmarkId::new("digits", digits), &digits, |b, &digits| {
            b.iter(|| {
                verified_dissipation(&case.text, digits, Duration::from_secs(60))
                    .unwrap()
                    .answer
                    .digits()
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

fn bench_simulation(c: &mut Criterion) {
    let mut group = c.benchmark_group("simulate");
    group.sample_size(10);
    // The acceptance case, and the steep power law near separation that was the worst of
    // 40 random cases before the grids followed the slip fronts.
    let cases = [
        ("acceptance-persson", common::case()),
        (
            "steep-power-law",
            common::case()
                .p1("0.8257076")
                .q1("0.117891")
                .phi("0.6973478pi")
                .friction("0.5950675")
                .lambda("1.213117")
                .compliance("power:c=2.589146,beta=-0.4994542 + power:c=0.2205953,beta=-1.971846"),
        ),
    ];
    for (name, case) in cases {
        let text = case.text();
        let Case { cycle, compliance } = text.read::<f64>(Precision::DOUBLE).unwrap();
        group.bench_function(name, |b| {
            b.iter(|| {
                simulate(&cycle, compliance.as_ref(), &SimulationOptions::default())
                    .unwrap()
                    .w_work
            })
        });
    }
    group.finish();
}

/// The slow case (φ = 1.1, v' = 1/P, Q1 = 0.03 (P0 − P1) as there) at 1e−6,
/// 1e−10 and 1e−15 of separation: the command-line policy without a digit count (f64 refuses these as
/// ill-conditioned and computes 15 verified digits in MPFR) and 20 verified digits.
/// Goals: ≤ 50 ms and ≤ 200 ms (proofs/stability.md, "Near separation").
fn bench_near_separation(c: &mut Criterion) {
    let mut group = c.benchmark_group("near_separation");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(3));
    for (distance, p1, q1) in [
        ("1e-6", "0.999999", "3e-8"),
        ("1e-10", "0.9999999999", "3e-12"),
        ("1e-15", "0.999999999999999", "3e-17"),
    ] {
        let text = common::case()
            .p1(p1)
            .q1(q1)
            .phi("1.1")
            .compliance("power:c=1,beta=-1")
            .text();
        let budget = Duration::from_secs(60);
        group.bench_function(format!("{distance}/command"), |b| {
            b.iter(|| dissipation_answer(&text, None, budget).unwrap().digits())
        });
        group.bench_function(format!("{distance}/digits20"), |b| {
            b.iter(|| verified_dissipation(&text, 20, budget).unwrap().answer.digits())
        });
    }
    group.finish();
}

/// The answer printed without `--digits` (proven: an enclosure in f64 intervals of 12 to
/// 15 digits, Arb's balls where they prove fewer) beside the f64 run with its error
/// estimate that printed before and the Arb ladder to 15 digits that printed after it
/// (`--digits 15`), in one run, for the three families of the proven default's speed
/// target (Persson, power −1.5, Hertz). Goal: ≤ 3× f64.
fn bench_default_answer(c: &mut Criterion) {
    let mut group = c.benchmark_group("default_answer");
    group.sample_size(20);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(2));
    for (name, spec) in [
        ("persson", common::PERSSON),
        ("power-1.5", "power:c=1,beta=-1.5"),
        ("hertz", "hertz:r=1,estar=1"),
    ] {
        let text = common::case().compliance(spec).text();
        let Case { cycle, compliance } = text.read::<f64>(Precision::DOUBLE).unwrap();
        group.bench_function(format!("{name}/f64-estimate"), |b| {
            b.iter(|| {
                let result = dissipation(&cycle, compliance.as_ref(), &Options::default()).unwrap();
                (result.total, result.error_estimate)
            })
        });
        let budget = Duration::from_secs(60);
        group.bench_function(format!("{name}/proven"), |b| {
            b.iter(|| dissipation_answer(&text, None, budget).unwrap().digits())
        });
        // The previous default: the Arb ladder to 15 digits, as `--digits 15` still runs.
        group.bench_function(format!("{name}/arb-15"), |b| {
            b.iter(|| dissipation_answer(&text, Some(15), budget).unwrap().digits())
        });
        // The proven default's parts: what the exact reading of the decimals (every boundary
        // decided on them) and the proof of admissibility cost before any quadrature, and
        // the enclosure in f64 intervals alone.
        group.bench_function(format!("{name}/parts/read-decimals"), |b| {
            b.iter(|| text.spec().unwrap())
        });
        let spec = text.spec().unwrap();
        group.bench_function(format!("{name}/parts/prove-admissible"), |b| {
            b.iter(|| prove_admissible(&spec).unwrap())
        });
        #[cfg(feature = "certified")]
        group.bench_function(format!("{name}/parts/interval-enclosure"), |b| {
            b.iter(|| {
                let Case { cycle, compliance } = spec.at::<Interval>(Precision::DOUBLE).unwrap();
                let lowest = spec.lowest_normal_load::<Interval>(Precision::DOUBLE).unwrap();
                let goal = INTERVAL_GOAL_BITS;
                enclose_dissipation_with_lowest_load(&cycle, Some(&lowest), compliance.as_ref(), goal)
                    .unwrap()
                    .total
            })
        });
    }
    group.finish();
}

criterion_group!(
    benches,
    bench_default_answer,
    bench_dissipation,
    bench_power_law_f64,
    bench_single_runs,
    bench_verified_digits,
    bench_node_tables,
    bench_simulation,
    bench_near_separation
);
criterion_main!(benches);
