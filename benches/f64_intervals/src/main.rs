//! What would a rigorous f64 bound cost? `sh benches/f64_intervals.sh [BUDGET_MS]` prints,
//! per case, the best time over BUDGET_MS (default 400) of
//!
//! - `f64 run`: the default f64 computation (`dissipation` with default options);
//! - `f64 nodes`: its integrand alone, in f64, at every node the run evaluated (each
//!   piece by every Gauss–Legendre rule of its doubling ladder, 16 points up to its last);
//! - `intervals, last rule`: the same integrand on inari intervals at the nodes of each
//!   piece's last rule only, the least a rigorous quadrature must evaluate;
//! - `intervals, all nodes`: on intervals at every node the f64 run evaluated;
//!
//! with the evaluations counted, the width of the interval sum (rounding alone: the
//! quadrature error of the rule is not in it) against the f64 run's error estimate, and
//! the comparisons the interval run could not decide; and first, the cost of single
//! operations in f64 and on intervals (inari rounds its elementary functions outward
//! through MPFR, two calls per function). A rigorous bound needs at least the
//! last-rule evaluation plus a bound on the rule's error, so `intervals, last rule` over
//! `f64 run` is a lower bound on its cost ratio.

mod interval;

use std::collections::HashMap;
use std::hint::black_box;
use std::time::{Duration, Instant};

use interval::{doubts, Iv};
use microslip::compliance::{parse_spec, Compliance};
use microslip::cycle::{LoadCycle, ValidCycle};
use microslip::dissipation::{dissipation, Options, SegmentIntegrands};
use microslip::quad::gauss_legendre::{node_table, NodeTable};
use microslip::quad::Piece;
use microslip::real::{Precision, Real};
use rug::Float;

/// The cases of `examples/certified_timing.rs`: p0, p1, q1, φ, f, λ, compliance.
const CASES: [(&str, &str); 6] = [
    ("persson", "1,0.4,0.5,0.4pi,1,1,persson:gamma=1,sigma=1"),
    ("power", "1,0.4,0.5,0.4pi,1,1,power:c=0.5,beta=-0.5"),
    ("hertz", "1,0.4,0.5,0.4pi,1,1,hertz:r=1,estar=1"),
    (
        "power-sum",
        "1,0.4,0.5,0.4pi,1,1,power:c=1,beta=-0.5+power:c=0.5,beta=-1.5",
    ),
    ("exponential", "1,0.4,0.5,0.4pi,1,1,exp:a=1,c=0.5,d=1"),
    ("near-gross-slip", "1,0.4,0.8886569,1.5,1,1,persson:gamma=1,sigma=1"),
];

/// The first rule of the engine's doubling ladder.
const FIRST_POINTS: usize = 16;

type RealCase<R> = (LoadCycle<R>, Box<dyn Compliance<R>>);

fn number<R: Real>(text: &str) -> R {
    let parse = |t: &str| R::parse_decimal(t, Precision::DOUBLE).expect("a decimal");
    match text.strip_suffix("pi") {
        Some(multiple) => parse(multiple) * &R::pi(Precision::DOUBLE),
        None => parse(text),
    }
}

fn read<R: Real>(fields: &str) -> RealCase<R> {
    let parts: Vec<&str> = fields.splitn(7, ',').collect();
    let cycle = LoadCycle {
        mean_normal_load: number(parts[0]),
        normal_amplitude: number(parts[1]),
        mean_tangential_load: R::from_i64(0, Precision::DOUBLE),
        tangential_amplitude: number(parts[2]),
        phase: number(parts[3]),
        friction: number(parts[4]),
        compliance_ratio: number(parts[5]),
    };
    (cycle, parse_spec(parts[6], Precision::DOUBLE).expect("a compliance"))
}

/// The best time of `run` over `budget` (at least three runs), and its last outcome.
fn best_of<T>(budget: Duration, mut run: impl FnMut() -> T) -> (Duration, T) {
    let (mut best, started, mut runs) = (Duration::MAX, Instant::now(), 0);
    loop {
        let start = Instant::now();
        let outcome = black_box(run());
        best = best.min(start.elapsed());
        runs += 1;
        if runs >= 3 && started.elapsed() >= budget {
            return (best, outcome);
        }
    }
}

/// The rules 16, 32, … up to `last` (the engine's ladder for a piece that ended at `last`).
fn ladder(last: usize) -> Vec<usize> {
    std::iter::successors(Some(FIRST_POINTS.min(last)), |&n| (n < last).then_some(2 * n)).collect()
}

/// The Gauss–Legendre rules of these sizes in `R`, each node and weight read from the
/// library's MPFR table at 128 bits (on intervals: the f64 interval around it; a table
/// computed by Newton's method on intervals would widen at every step).
fn rules_in<R: Real>(rules: &[Vec<usize>]) -> HashMap<usize, NodeTable<R>> {
    let convert = |values: &[Float]| values.iter().map(|x| R::from_float(x, Precision::DOUBLE)).collect();
    rules
        .iter()
        .flatten()
        .map(|&points| {
            let table = node_table::<Float>(points, Precision::bits(128));
            let (nodes, weights) = (convert(&table.nodes), convert(&table.weights));
            (points, NodeTable { nodes, weights })
        })
        .collect()
}

/// Σ over pieces and their rules of the rule applied to the piece, with Σ |terms|.
fn at_nodes<R: Real>(pieces: &[Piece<'_, R>], rules: &[Vec<usize>], tables: &HashMap<usize, NodeTable<R>>) -> (R, R) {
    let zero = pieces[0].start.int(0);
    let (mut sum, mut magnitude) = (zero.clone(), zero);
    for (piece, rules) in pieces.iter().zip(rules) {
        for points in rules {
            let table = &tables[points];
            let (value, size) = table.integrate_with_magnitude(&piece.integrand, &piece.start, &piece.end);
            sum += value;
            magnitude += size;
        }
    }
    (sum, magnitude)
}

/// The pieces of the four segment integrals of a case, built with `R`, passed to `use_them`.
fn with_pieces<R: Real, T>(fields: &str, use_them: impl FnOnce(&[Piece<'_, R>]) -> T) -> T {
    let (cycle, compliance) = read::<R>(fields);
    let geometry = ValidCycle::new(cycle).expect("a valid cycle").geometry();
    let integrands = SegmentIntegrands {
        geometry: &geometry,
        compliance: compliance.as_ref(),
        remove_constant_slope: true,
    };
    // The pieces borrow `geometry` and `compliance`: they must be dropped first.
    let pieces = integrands.pieces();
    #[allow(clippy::let_and_return)]
    let outcome = use_them(&pieces.pieces);
    outcome
}

fn micros(time: Duration) -> f64 {
    time.as_secs_f64() * 1e6
}

/// ns per call of `operation` over 1000 arguments in [0.3, 1.3), best over `budget`.
fn per_call<R: Real>(budget: Duration, operation: impl Fn(&R) -> R) -> f64 {
    let arguments: Vec<R> = (0..1000)
        .map(|i| R::from_f64(0.3 + f64::from(i) / 1000.0, Precision::DOUBLE))
        .collect();
    let (time, _) = best_of(budget, || {
        black_box(&arguments)
            .iter()
            .map(&operation)
            .map(|x| x.to_f64_lossy())
            .sum::<f64>()
    });
    time.as_secs_f64() * 1e9 / arguments.len() as f64
}

/// The cost of one operation in f64 and on intervals, and their ratio.
fn operation_costs(budget: Duration) {
    println!("| operation | f64 | interval | interval / f64 |");
    println!("|---|---|---|---|");
    let row = |name: &str, f64_ns: f64, interval_ns: f64| {
        println!(
            "| {name} | {f64_ns:.1} ns | {interval_ns:.1} ns | {:.0} |",
            interval_ns / f64_ns
        );
    };
    macro_rules! time_both {
        ($name:expr, |$x:ident| $body:expr) => {
            row(
                $name,
                per_call::<f64>(budget, |$x: &f64| $body),
                per_call::<Iv>(budget, |$x: &Iv| $body),
            )
        };
    }
    time_both!("x·x + x", |x| *x * x + x);
    time_both!("1/x", |x| x.int(1) / x);
    time_both!("sqrt", |x| x.sqrt());
    time_both!("sin_cos", |x| {
        let (sin, cos) = x.sin_cos();
        sin + cos
    });
    time_both!("ln", |x| x.ln());
    time_both!("exp", |x| x.exp());
    time_both!("x^0.7", |x| x.powr(&x.ratio(7, 10)));
    println!();
}

fn main() {
    let budget_ms: u64 = std::env::args()
        .nth(1)
        .map_or(400, |text| text.parse().expect("BUDGET_MS"));
    let budget = Duration::from_millis(budget_ms);
    operation_costs(budget);
    println!(
        "| case | f64 run | f64 nodes | intervals, last rule | intervals, all nodes | last rule / f64 run | all nodes / f64 run | evaluations (run / all / last) | interval width / f64 error estimate | undecided comparisons |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (name, fields) in CASES {
        let (cycle, compliance) = read::<f64>(fields);
        let (run_time, result) = best_of(budget, || dissipation(&cycle, compliance.as_ref(), &Options::default()));
        let w = match result {
            Ok(w) => w,
            Err(error) => {
                println!("| {name} | refused in f64: {error} |");
                continue;
            }
        };
        let last: Vec<Vec<usize>> = w.piece_points.iter().map(|&n| vec![n]).collect();
        let all: Vec<Vec<usize>> = w.piece_points.iter().map(|&n| ladder(n)).collect();
        let count = |rules: &[Vec<usize>]| rules.iter().flatten().sum::<usize>();
        let (f64_nodes_time, pieces_f64) = with_pieces::<f64, _>(fields, |pieces| {
            let tables = rules_in(&all);
            (best_of(budget, || at_nodes(pieces, &all, &tables)).0, pieces.len())
        });
        let before = doubts();
        let (last_time, all_time, interval_sum, pieces_iv) = with_pieces::<Iv, _>(fields, |pieces| {
            let tables = rules_in(&all);
            let (last_time, (sum, _)) = best_of(budget, || at_nodes(pieces, &last, &tables));
            let (all_time, _) = best_of(budget, || at_nodes(pieces, &all, &tables));
            (last_time, all_time, sum, pieces.len())
        });
        let undecided = doubts() - before;
        assert_eq!(pieces_f64, pieces_iv, "{name}: the same pieces in f64 and on intervals");
        // The interval sum is Σ ∫ (Q − Q0) ψ without the factor λ; W's error estimate has it.
        let (lower, upper) = interval_sum.bounds();
        let lambda = cycle.compliance_ratio;
        let width = (upper - lower) * lambda;
        println!(
            "| {name} | {:.1} µs | {:.1} µs | {:.1} µs | {:.1} µs | {:.1} | {:.1} | {} / {} / {} | {:.2e} / {:.2e} | {undecided} |",
            micros(run_time),
            micros(f64_nodes_time),
            micros(last_time),
            micros(all_time),
            last_time.as_secs_f64() / run_time.as_secs_f64(),
            all_time.as_secs_f64() / run_time.as_secs_f64(),
            w.evaluations,
            count(&all),
            count(&last),
            width,
            w.error_estimate,
        );
    }
}
