//! Accuracy against cost: every quadrature rule, at several precisions, on the
//! same segment integrands, measured against a 100-digit reference.
//!
//! Each configuration (rule, precision, parameter) computes W of a case with that
//! rule applied once to every piece (no adaptivity), and is timed as the median of
//! repeated runs. Rules: our Gauss–Legendre (n points per piece) and tanh–sinh (a
//! level), the `quadrature` crate's double-exponential and Clenshaw–Curtis (f64,
//! by target error), and, for contrast, the naive integral in P with the midpoint
//! rule, whose integrand has square-root end points.

use std::time::{Duration, Instant};

use rug::Float;
use serde::Serialize;

use crate::answer::agreed::verified_dissipation;
use crate::case::{Case, CaseSpec, CaseText};
use crate::dissipation::{Segment, SegmentIntegrands};
use crate::files::csv_text;
use crate::quad::{gauss_legendre, tanh_sinh, Piece};
use crate::real::{Precision, Real};

/// One measured configuration.
#[derive(Clone, Debug, Serialize)]
pub struct Measurement {
    /// The rule.
    pub rule: &'static str,
    /// Working precision in bits (53 for f64).
    pub precision_bits: u32,
    /// Points per piece, level, target error or panels.
    pub parameter: f64,
    /// Integrand evaluations per W.
    pub evaluations: usize,
    /// Median seconds per W.
    pub seconds: f64,
    /// |W − reference| / |reference| (1 when the rule failed to give a number).
    pub rel_error: f64,
    /// The catalogue case.
    pub case: String,
}

/// A case to measure on.
pub struct BenchCase {
    /// Its name.
    pub name: String,
    /// Its text.
    pub text: CaseText,
}

/// The cases measured: an ordinary one and two stiff ones from the catalogue
/// (`tests/data/catalogue.json` holds the same texts under the same names).
pub fn standard_cases(quick: bool) -> Vec<BenchCase> {
    let case = |name: &str, p0: &str, p1: &str, q1: &str, phi: &str, compliance: &str| BenchCase {
        name: name.to_string(),
        text: CaseText {
            p0: p0.into(),
            p1: p1.into(),
            q0: "0".into(),
            q1: q1.into(),
            phi: phi.into(),
            friction: "1".into(),
            lambda: Some("1".into()),
            nu: None,
            compliance: compliance.into(),
        },
    };
    let mut cases = vec![
        case(
            "persson-ordinary",
            "1",
            "0.4",
            "0.5",
            "0.4pi",
            "persson:gamma=1,sigma=1",
        ),
        case("steep-compliance", "1", "0.4", "0.5", "0.4pi", "power:c=1,beta=-3"),
    ];
    if !quick {
        cases.push(case(
            "permanent-stick-near-zero",
            "1.000001",
            "0.6",
            "0.8",
            "0.5pi",
            "persson:gamma=1,sigma=1",
        ));
    }
    cases
}

/// The 100-digit reference value of a case (computed, verified).
pub fn reference_value(case: &CaseText) -> Result<Float, crate::answer::DissipationAnswerError> {
    Ok(verified_dissipation(case, 100, Duration::from_secs(300))?.value.total)
}

/// The median time of `run` over repeats that add up to at least `budget` (and 3 runs).
fn median_seconds<T>(budget: Duration, mut run: impl FnMut() -> T) -> (f64, T) {
    let mut times = Vec::new();
    let started = Instant::now();
    let mut last;
    loop {
        let t = Instant::now();
        last = run();
        times.push(t.elapsed().as_secs_f64());
        if times.len() >= 3 && (started.elapsed() >= budget || times.len() >= 1000) {
            break;
        }
    }
    times.sort_by(f64::total_cmp);
    (times[times.len() / 2], last)
}

/// A rule applied once to a piece: the value and the integrand evaluations it took.
type RuleOnce<'r, R> = dyn Fn(&Piece<'_, R>, Precision) -> (R, usize) + 'r;

/// W of `case` at `precision`, each piece integrated by `rule`, with the evaluations it took.
fn fixed_rule_w<R: Real>(case: Option<&CaseSpec>, precision: Precision, rule: &RuleOnce<'_, R>) -> Option<(R, usize)> {
    let Case { cycle, compliance } = case?.at::<R>(precision).ok()?;
    let geometry = cycle.geometry().ok()?;
    let integrands = SegmentIntegrands {
        geometry: &geometry,
        compliance: compliance.as_ref(),
        remove_constant_slope: true,
    };
    let mut total = R::from_i64(0, precision);
    let mut evaluations = 0;
    for piece in integrands.pieces().pieces {
        let (value, count) = rule(&piece, precision);
        total += value;
        evaluations += count;
    }
    Some((total * &cycle.compliance_ratio, evaluations))
}

/// The naive way: each piece as an integral in P, θ(P) on its monotone branch,
/// midpoint rule with `panels` panels (the end points, where dθ/dP is infinite, are
/// never evaluated).
fn naive_in_load(case: Option<&CaseSpec>, panels: usize) -> Option<(f64, usize)> {
    let Case { cycle, compliance } = case?.at::<f64>(Precision::DOUBLE).ok()?;
    let geometry = cycle.geometry().ok()?;
    let integrands = SegmentIntegrands {
        geometry: &geometry,
        compliance: compliance.as_ref(),
        remove_constant_slope: true,
    };
    let pi = std::f64::consts::PI;
    let (mut total, mut evaluations) = (0.0, 0);
    let slope = integrands.prepared_slope();
    for (index, (piece_start, piece_end)) in Segment::ALL
        .into_iter()
        .flat_map(|index| integrands.windows(index).into_iter().map(move |w| (index, w)))
    {
        let start = integrands.extent(index).0;
        let (theta_a, theta_b) = (start + piece_start, start + piece_end);
        // Split at multiples of π, where P turns.
        let mut cuts = vec![theta_a];
        let mut k = (theta_a / pi).floor() + 1.0;
        while k * pi < theta_b {
            cuts.push(k * pi);
            k += 1.0;
        }
        cuts.push(theta_b);
        for pair in cuts.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let branch = ((0.5 * (a + b)) / pi).floor();
            let (c_a, c_b) = (a.cos(), b.cos());
            let h = (c_b - c_a) / panels as f64;
            for i in 0..panels {
                let c = c_a + h * (i as f64 + 0.5);
                let angle = c.clamp(-1.0, 1.0).acos();
                // θ on this branch: [kπ, (k+1)π] with k even ascends in acos, odd descends.
                let theta = if branch.rem_euclid(2.0) == 0.0 {
                    branch * pi + angle
                } else {
                    (branch + 1.0) * pi - angle
                };
                // Uniform in P is uniform in c = cos θ: dθ = dc / (−sin θ).
                let jacobian = -1.0 / theta.sin();
                total += integrands.integrand_with(index, &(theta - start), slope.as_ref()) * jacobian * h;
                evaluations += 1;
            }
        }
    }
    Some((total * cycle.compliance_ratio, evaluations))
}

fn relative_error(value: &Float, reference: &Float) -> f64 {
    let error = (Float::with_val(reference.prec(), value) - reference).abs() / reference.clone().abs();
    error.to_f64().max(1e-300)
}

/// Every configuration on one case. `quick` measures fewer precisions and parameters.
pub fn measure_case(
    case: &BenchCase,
    reference: &Float,
    quick: bool,
    mut progress: impl FnMut(&str),
) -> Vec<Measurement> {
    let budget = Duration::from_millis(if quick { 5 } else { 40 });
    let mut out = Vec::new();
    let mut record = |rule: &'static str, bits: u32, parameter: f64, seconds: f64, result: Option<(Float, usize)>| {
        let (rel_error, evaluations) = match result {
            Some((value, evaluations)) if value.is_finite() => (relative_error(&value, reference), evaluations),
            _ => (1.0, 0),
        };
        out.push(Measurement {
            rule,
            precision_bits: bits,
            parameter,
            evaluations,
            seconds,
            rel_error: rel_error.min(1.0),
            case: case.name.clone(),
        });
    };
    // Read once; each run below times the computation at its precision, not the reading.
    let spec = case.text.spec().ok();
    progress("f64");
    f64_rules(spec.as_ref(), quick, budget, &mut record);
    multiple_precision_rules(spec.as_ref(), quick, budget, &mut record, &mut progress);
    out
}

/// Records one configuration: its rule, precision, parameter, seconds and result.
type Record<'a> = dyn FnMut(&'static str, u32, f64, f64, Option<(Float, usize)>) + 'a;

/// f64: our rules, the quadrature crate's, and the naive one.
fn f64_rules(text: Option<&CaseSpec>, quick: bool, budget: Duration, record: &mut Record<'_>) {
    let as_float = |r: Option<(f64, usize)>| r.map(|(v, n)| (Float::with_val(53, v), n));
    let gauss_points: Vec<usize> = if quick {
        vec![4, 8, 16, 32, 64]
    } else {
        (1..=8).map(|k| 1usize << k).collect()
    };
    for &n in &gauss_points {
        let rule = |piece: &Piece<'_, f64>, p: Precision| {
            let value = gauss_legendre::node_table::<f64>(n, p).integrate(&piece.integrand, &piece.start, &piece.end);
            (value, n)
        };
        let (seconds, result) = median_seconds(budget, || fixed_rule_w::<f64>(text, Precision::DOUBLE, &rule));
        record("gauss-legendre", 53, n as f64, seconds, as_float(result));
    }
    let levels: Vec<u32> = if quick { vec![2, 4, 6] } else { (1..=10).collect() };
    for &level in &levels {
        let rule = |piece: &Piece<'_, f64>, _: Precision| {
            let estimate = tanh_sinh::integrate(&piece.integrand, &piece.start, &piece.end, &0.0, level);
            (estimate.value, estimate.evaluations)
        };
        let (seconds, result) = median_seconds(budget, || fixed_rule_w::<f64>(text, Precision::DOUBLE, &rule));
        record("tanh-sinh", 53, f64::from(level), seconds, as_float(result));
    }
    let targets: Vec<i32> = if quick { vec![4, 8, 12] } else { (2..=15).collect() };
    for &digits in &targets {
        let target = 10f64.powi(-digits);
        let crate_rule = |which: u8| {
            move |piece: &Piece<'_, f64>, _: Precision| {
                let f = |x: f64| (piece.integrand)(&x);
                let output = if which == 0 {
                    quadrature::double_exponential::integrate(f, piece.start, piece.end, target)
                } else {
                    quadrature::clenshaw_curtis::integrate(f, piece.start, piece.end, target)
                };
                (output.integral, output.num_function_evaluations as usize)
            }
        };
        for (which, name) in [
            (0u8, "quadrature-double-exponential"),
            (1, "quadrature-clenshaw-curtis"),
        ] {
            let rule = crate_rule(which);
            let (seconds, result) = median_seconds(budget, || fixed_rule_w::<f64>(text, Precision::DOUBLE, &rule));
            record(name, 53, target, seconds, as_float(result));
        }
    }
    let panels: Vec<usize> = if quick {
        vec![16, 256, 4096]
    } else {
        (2..=8).map(|k| 4usize.pow(k)).collect()
    };
    for &m in &panels {
        let (seconds, result) = median_seconds(budget, || naive_in_load(text, m));
        record("naive-midpoint-in-P", 53, m as f64, seconds, as_float(result));
    }
}

/// Multiple precision: our two rules.
fn multiple_precision_rules(
    text: Option<&CaseSpec>,
    quick: bool,
    budget: Duration,
    record: &mut Record<'_>,
    progress: &mut impl FnMut(&str),
) {
    let precisions: Vec<u32> = if quick { vec![256] } else { vec![128, 256, 512, 1024] };
    for &bits in &precisions {
        progress(&format!("{bits} bits"));
        let p = Precision::bits(bits);
        let points: Vec<usize> = if quick {
            vec![16, 32, 64]
        } else {
            (2..=8).map(|k| 1usize << k).collect()
        };
        for &n in &points {
            gauss_legendre::node_table::<Float>(n, p);
            let rule = |piece: &Piece<'_, Float>, p: Precision| {
                let value =
                    gauss_legendre::node_table::<Float>(n, p).integrate(&piece.integrand, &piece.start, &piece.end);
                (value, n)
            };
            let (seconds, result) = median_seconds(budget, || fixed_rule_w::<Float>(text, p, &rule));
            record("gauss-legendre", bits, n as f64, seconds, result);
        }
        let levels: Vec<u32> = if quick { vec![4, 6] } else { (1..=10).collect() };
        for &level in &levels {
            let zero = Float::with_val(bits, 0);
            let rule = |piece: &Piece<'_, Float>, _: Precision| {
                let estimate = tanh_sinh::integrate(&piece.integrand, &piece.start, &piece.end, &zero, level);
                (estimate.value, estimate.evaluations)
            };
            let (seconds, result) = median_seconds(budget, || fixed_rule_w::<Float>(text, p, &rule));
            record("tanh-sinh", bits, f64::from(level), seconds, result);
        }
    }
}

/// The measurements no other is both faster and more accurate than, by time.
pub fn pareto_front(measurements: &[Measurement]) -> Vec<&Measurement> {
    let mut sorted: Vec<&Measurement> = measurements.iter().collect();
    sorted.sort_by(|a, b| {
        a.seconds
            .total_cmp(&b.seconds)
            .then(a.rel_error.total_cmp(&b.rel_error))
    });
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for m in sorted {
        if m.rel_error < best {
            best = m.rel_error;
            front.push(m);
        }
    }
    front
}

/// For each target error, the fastest configuration that reaches it (None if none does).
pub fn cheapest_for(measurements: &[Measurement], target: f64) -> Option<&Measurement> {
    measurements
        .iter()
        .filter(|m| m.rel_error <= target)
        .min_by(|a, b| a.seconds.total_cmp(&b.seconds))
}

/// The CSV text: rule,precision_bits,parameter,evaluations,seconds,rel_error,case.
pub fn to_csv(measurements: &[Measurement]) -> Result<String, csv::Error> {
    let header = [
        "rule",
        "precision_bits",
        "parameter",
        "evaluations",
        "seconds",
        "rel_error",
        "case",
    ];
    let rows = measurements.iter().map(|m| {
        [
            m.rule.to_string(),
            m.precision_bits.to_string(),
            m.parameter.to_string(),
            m.evaluations.to_string(),
            format!("{:.6e}", m.seconds),
            format!("{:.3e}", m.rel_error),
            m.case.clone(),
        ]
    });
    csv_text(&header, rows)
}
