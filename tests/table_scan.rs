//! The table error estimate against the true error, over many tables: six compliance
//! families with closed forms, slope and approach columns, 4 to 160 rows, uniform and
//! logarithmic spacing, two cycles each reaching both ends of its tables. The estimate
//! must bound the error of W from the table, and every digit printed must be a digit
//! of the analytic W (computed by the library from the family's SPEC to 20 digits).

use std::path::Path;
use std::time::Duration;

use microslip::answer::dissipation::dissipation_report;
use microslip::case::CaseText;
use microslip::cycle::LoadCycle;

mod common;
use common::Scratch;

struct Family {
    spec: &'static str,
    slope: fn(f64) -> f64,
    approach: fn(f64) -> f64,
}

const FAMILIES: [Family; 8] = [
    Family {
        spec: "power:c=1,beta=-0.5",
        slope: |p| p.powf(-0.5),
        approach: |p| 2.0 * p.sqrt(),
    },
    Family {
        spec: "power:c=1,beta=-3",
        slope: |p| p.powi(-3),
        approach: |p| -0.5 * p.powi(-2),
    },
    Family {
        spec: "persson:gamma=1,sigma=1",
        slope: |p| 1.0 / p,
        approach: f64::ln,
    },
    Family {
        spec: "hertz:r=1,estar=1",
        slope: |p| (2.0 / 3.0) * (9.0f64 / 16.0).cbrt() * p.powf(-1.0 / 3.0),
        approach: |p| (9.0 * p * p / 16.0).cbrt(),
    },
    Family {
        spec: "exp:a=1,c=0.5,d=0.2",
        slope: |p| (-p / 0.5).exp() + 0.2,
        approach: |p| 0.2 * p - 0.5 * (-p / 0.5).exp(),
    },
    Family {
        spec: "rational:a=0.1,b=1,c=0.3",
        slope: |p| 0.1 + 1.0 / (p + 0.3),
        approach: |p| 0.1 * p + (p + 0.3).ln(),
    },
    Family {
        spec: "rational:a=0.1,b=1,c=0.05",
        slope: |p| 0.1 + 1.0 / (p + 0.05),
        approach: |p| 0.1 * p + (p + 0.05).ln(),
    },
    Family {
        spec: "rational:a=0,b=1,c=-0.05",
        slope: |p| 1.0 / (p - 0.05),
        approach: |p| (p - 0.05).ln(),
    },
];

/// (P0, P1, Q0, Q1, φ, f, λ) as the command line reads them.
const CYCLES: [[&str; 7]; 2] = [
    ["0.5", "0.2", "0", "0.3", "2.5", "1", "1.2"],
    ["1", "0.4", "0.05", "0.3", "1.9", "0.5", "1.2"],
];

fn case(cycle: &[&str; 7], compliance: &str) -> CaseText {
    let [p0, p1, q0, q1, phi, friction, lambda] = *cycle;
    common::case()
        .p0(p0)
        .p1(p1)
        .q0(q0)
        .q1(q1)
        .phi(phi)
        .friction(friction)
        .lambda(lambda)
        .compliance(compliance)
        .text()
}

/// The loads the cycle reaches: min(P_T, P0 − P1) to P0 + P1.
fn reach(cycle: &[&str; 7]) -> (f64, f64) {
    let number = |i: usize| cycle[i].parse::<f64>().expect("number");
    let load_cycle = LoadCycle {
        mean_normal_load: number(0),
        normal_amplitude: number(1),
        mean_tangential_load: number(2),
        tangential_amplitude: number(3),
        phase: number(4),
        friction: number(5),
        compliance_ratio: number(6),
    };
    let low = (number(0) - number(1)).min(load_cycle.permanent_stick_load());
    (low, number(0) + number(1))
}

/// How a table's loads are spaced.
#[derive(Clone, Copy, Debug)]
enum Spacing {
    Logarithmic,
    Uniform,
    /// Loads drawn uniformly at random between the ends, sorted (seeded: every run draws
    /// the same).
    Random(u64),
    /// Their logarithms drawn so.
    RandomLogarithmic(u64),
}

/// Fractions in (0, 1), sorted, from a fixed seed (splitmix64).
fn random_fractions(seed: u64, count: usize) -> Vec<f64> {
    let mut state = seed;
    let mut next = || {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut fractions: Vec<f64> = (0..count).map(|_| next()).collect();
    fractions.sort_by(f64::total_cmp);
    fractions
}

/// A table of `rows` loads from `low` to `high`, each value written to the 17 digits
/// that give back its f64.
fn write_table(path: &Path, column: &str, low: f64, high: f64, rows: usize, spacing: Spacing, f: fn(f64) -> f64) {
    let mut text = format!("load,{column}\n");
    let drawn = match spacing {
        Spacing::Random(seed) | Spacing::RandomLogarithmic(seed) => random_fractions(seed, rows - 2),
        Spacing::Logarithmic | Spacing::Uniform => Vec::new(),
    };
    for i in 0..rows {
        let fraction = i as f64 / (rows - 1) as f64;
        let load = match (i, spacing) {
            (0, _) => low,
            (i, _) if i == rows - 1 => high,
            (_, Spacing::Logarithmic) => low * (high / low).powf(fraction),
            (_, Spacing::Uniform) => low + (high - low) * fraction,
            (_, Spacing::Random(_)) => low + (high - low) * drawn[i - 1],
            (_, Spacing::RandomLogarithmic(_)) => low * (high / low).powf(drawn[i - 1]),
        };
        text.push_str(&format!("{load:e},{:e}\n", f(load)));
    }
    std::fs::write(path, text).expect("write table");
}

/// Runs the scan; returns the number of tables and the smallest ratio estimate/error.
fn scan(name: &str, rows: &[usize]) -> (usize, f64) {
    let spacings = |_| vec![Spacing::Logarithmic, Spacing::Uniform];
    scan_spacings(name, &CYCLES, &FAMILIES, rows, &spacings)
}

/// Uniform and logarithmic spacing, and random spacing drawn from `seed`.
fn every_spacing(seed: u64) -> Vec<Spacing> {
    vec![
        Spacing::Uniform,
        Spacing::Logarithmic,
        Spacing::Random(seed),
        Spacing::RandomLogarithmic(seed),
    ]
}

/// The scan over `cycles`, `families`, slope and approach columns, `rows`, and the
/// spacings `spacings(seed)` gives each (the seed distinct per table); the scratch
/// directory is removed after.
fn scan_spacings(
    name: &str,
    cycles: &[[&str; 7]],
    families: &[Family],
    rows: &[usize],
    spacings: &dyn Fn(u64) -> Vec<Spacing>,
) -> (usize, f64) {
    let dir = Scratch::new(name);
    let (mut tables, mut worst) = (0, f64::INFINITY);
    let mut failures = Vec::new();
    for (c, cycle) in cycles.iter().enumerate() {
        let (low, high) = reach(cycle);
        for (f, family) in families.iter().enumerate() {
            let exact = dissipation_report(&case(cycle, family.spec), Some(20), Duration::from_secs(60))
                .expect("analytic W")
                .total();
            let exact_w: f64 = exact.parse().expect("W");
            for (column, values) in [("slope", family.slope), ("approach", family.approach)] {
                for &n in rows {
                    let seed = ((c * 100 + f) * 1000 + n) as u64 * 2 + u64::from(column == "slope");
                    for spacing in spacings(seed) {
                        let path = dir.join(format!("c{c}-f{f}-{column}-{n}-{spacing:?}.csv"));
                        write_table(&path, column, low, high, n, spacing, values);
                        let label = format!("{} {column} {n} rows {spacing:?} cycle {c}", family.spec);
                        let compliance = format!("table:{}", path.display());
                        let result = match dissipation_report(&case(cycle, &compliance), None, Duration::from_secs(60))
                        {
                            Ok(result) => result,
                            Err(error) => {
                                failures.push(format!("{label}: refused: {error}"));
                                continue;
                            }
                        };
                        tables += 1;
                        let estimate = result.table.as_ref().expect("table estimate");
                        let bound = estimate.error + estimate.quadrature_error;
                        let error = (estimate.unrounded - exact_w).abs();
                        worst = worst.min(bound / error);
                        eprintln!(
                            "{label}: W {:.12e}, relative error {:.1e}, estimate/error {:.1e}, printed '{}' ({} digits)",
                            estimate.unrounded,
                            error / exact_w.abs(),
                            bound / error,
                            result.total(),
                            result.answer.digits()
                        );
                        if error > bound {
                            failures.push(format!("{label}: error {error:.2e} above the estimate {bound:.2e}"));
                        }
                        let digits = result.answer.digits() as usize;
                        let rounded = |value: f64| format!("{:.*e}", digits.max(1) - 1, value);
                        // Where W ± its error straddle a rounding boundary, the digit count is the
                        // printing rule's to lower (decimal::printing::decimal_f64), not the estimate's.
                        let straddles = rounded(estimate.unrounded - bound) != rounded(estimate.unrounded + bound);
                        if digits == 0 {
                            if !result.total().is_empty() {
                                failures.push(format!("{label}: no digit resolved, yet '{}' printed", result.total()));
                            }
                        } else if !straddles {
                            let expected = rounded(exact_w);
                            if result.total() != expected {
                                failures.push(format!(
                                    "{label}: printed {} where the analytic W {exact} rounds to {expected}",
                                    result.total()
                                ));
                            }
                        }
                    }
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of the tables failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
    (tables, worst)
}

#[test]
fn the_table_error_estimate_bounds_the_error_on_every_test_table() {
    let (tables, worst) = scan("quick", &[4, 5, 7, 12, 40, 80]);
    eprintln!("{tables} tables, smallest estimate/error {worst:.2}");
    assert!(tables >= 100, "{tables} tables");
}

/// The full scan (every row count from 4 to 160 in steps): `cargo test --release --test
/// table_scan -- --ignored --nocapture`.
#[test]
#[ignore = "the full scan: run it by name"]
fn the_table_error_estimate_bounds_the_error_on_the_full_scan() {
    let rows: Vec<usize> = (4..=12)
        .chain([16, 20, 24, 32, 40, 48, 64, 80, 100, 120, 160])
        .collect();
    let (tables, worst) = scan("full", &rows);
    eprintln!("{tables} tables, smallest estimate/error {worst:.2}");
}

/// Uniform, logarithmic and random spacing, 20 to 200 rows: 512 tables.
#[test]
fn the_table_error_estimate_bounds_the_error_on_irregular_tables() {
    let (tables, worst) = scan_spacings("irregular", &CYCLES, &FAMILIES, &[20, 50, 110, 200], &every_spacing);
    eprintln!("{tables} tables, smallest estimate/error {worst:.2}");
    assert!(tables >= 500, "{tables} tables");
}

/// The case: 160 rows of `rational:a=0.1,b=1,c=0.05` at random loads, approach
/// column, on the README's cycle (φ = 0.4π written out), where the estimate stated
/// 9.5e−12 against a true error of 1.8e−10; here with 24 draws of the loads.
#[test]
fn a_random_approach_table_of_a_steep_rational_is_bounded() {
    const README_CYCLE: [&str; 7] = ["1", "0.4", "0", "0.5", "1.2566370614359172", "1", "1"];
    let family = Family {
        spec: "rational:a=0.1,b=1,c=0.05",
        slope: |p| 0.1 + 1.0 / (p + 0.05),
        approach: |p| 0.1 * p + (p + 0.05).ln(),
    };
    let draws = |seed: u64| {
        (0..12)
            .flat_map(|k| {
                [
                    Spacing::Random(seed + 7919 * k),
                    Spacing::RandomLogarithmic(seed + 7919 * k),
                ]
            })
            .collect()
    };
    let (tables, worst) = scan_spacings("issue", &[README_CYCLE], &[family], &[160], &draws);
    eprintln!("{tables} tables, smallest estimate/error {worst:.2}");
    assert_eq!(tables, 48);
}

/// The irregular scan at more row counts and draws (`cargo test --release --test
/// table_scan -- --ignored --nocapture`).
#[test]
#[ignore = "the full irregular scan: run it by name"]
fn the_table_error_estimate_bounds_the_error_on_the_full_irregular_scan() {
    let rows: Vec<usize> = (20..=200).step_by(15).collect();
    let draws = |seed: u64| {
        let random = (0..3).flat_map(|k| {
            [
                Spacing::Random(seed + 104_729 * k),
                Spacing::RandomLogarithmic(seed + 104_729 * k),
            ]
        });
        [Spacing::Uniform, Spacing::Logarithmic]
            .into_iter()
            .chain(random)
            .collect()
    };
    let (tables, worst) = scan_spacings("irregular-full", &CYCLES, &FAMILIES, &rows, &draws);
    eprintln!("{tables} tables, smallest estimate/error {worst:.2}");
}
