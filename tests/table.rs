//! Compliance from a table (`table:FILE`): accuracy against analytic compliances, its
//! error estimate, and every refusal of a bad table through the command line.

mod common;
use common::Scratch;

use std::time::Duration;

use microslip::answer::dissipation::dissipation_report;
use microslip::case::{Case, CaseText};
use microslip::dissipation::{dissipation, Options};
use microslip::real::Precision;
use rug::Float;

struct Family {
    name: &'static str,
    spec: &'static str,
    slope: fn(f64) -> f64,
    approach: fn(f64) -> f64,
}

const FAMILIES: [Family; 3] = [
    Family {
        name: "persson",
        spec: "persson:gamma=1,sigma=1",
        slope: |p| 1.0 / p,
        approach: f64::ln,
    },
    Family {
        name: "hertz",
        spec: "hertz:r=1,estar=1",
        slope: |p| (2.0 / 3.0) * (9.0f64 / 16.0).cbrt() * p.powf(-1.0 / 3.0),
        approach: |p| (9.0 * p * p / 16.0).cbrt(),
    },
    Family {
        name: "exponential",
        spec: "exp:a=1,c=0.5,d=0.2",
        slope: |p| (-p / 0.5).exp() + 0.2,
        approach: |p| 0.2 * p - 0.5 * (-p / 0.5).exp(),
    },
];

/// `rows` log-spaced loads over [0.2, 1.5] (the cycle below reaches [0.228, 1.4]).
fn write_table(dir: &std::path::Path, name: &str, column: &str, rows: usize, f: fn(f64) -> f64) -> String {
    let path = dir.join(format!("{name}-{column}-{rows}.csv"));
    let mut text = format!("# {name} sampled at {rows} loads\nload,{column}\n");
    for i in 0..rows {
        let load = 0.2 * (1.5f64 / 0.2).powf(i as f64 / (rows - 1) as f64);
        text.push_str(&format!("{load:e},{:e}\n", f(load)));
    }
    std::fs::write(&path, text).expect("write table");
    path.to_string_lossy().into_owned()
}

/// The acceptance case with compliance `compliance`.
fn case(compliance: &str) -> CaseText {
    common::case().compliance(compliance).text()
}

fn analytic(spec: &str) -> f64 {
    let result = dissipation_report(&case(spec), Some(20), Duration::from_secs(60)).expect("analytic W");
    result.total().parse().expect("W parses")
}

/// (relative error of W, relative table-error estimate) for a sampled table.
fn table_w(path: &str, exact: f64) -> (f64, f64) {
    let result = dissipation_report(&case(&format!("table:{path}")), None, Duration::from_secs(60)).expect("table W");
    let table = result.table.expect("a table estimate");
    ((table.unrounded - exact).abs() / exact, table.error / exact)
}

#[test]
fn table_w_converges_to_the_analytic_w_at_a_measured_order() {
    let dir = Scratch::new("order");
    for family in &FAMILIES {
        let exact = analytic(family.spec);
        for (column, f) in [("slope", family.slope), ("approach", family.approach)] {
            let mut errors = Vec::new();
            for rows in [20, 40, 80, 160] {
                let path = write_table(&dir, family.name, column, rows, f);
                let (error, estimate) = table_w(&path, exact);
                eprintln!(
                    "{:<12} {column:<9} {rows:>4} rows: relative error {error:.2e}, estimate {estimate:.2e}",
                    family.name
                );
                assert!(
                    estimate >= error,
                    "{} {column} {rows}: estimate {estimate:.1e} below the error {error:.1e}",
                    family.name
                );
                errors.push(error);
            }
            assert_accuracy(&format!("{} {column}", family.name), &errors, 3.5);
        }
    }
}

/// Relative errors of W at 20, 40, 80 and 160 rows: within 1e−7 at 80 rows, and
/// converging at an order above `order` from 40 to 160 rows, unless exact (a power law is
/// a line in log–log, exact at any row count).
fn assert_accuracy(name: &str, errors: &[f64], order: f64) {
    assert!(errors[2] <= 1e-7, "{name}: 80 rows give {:.1e}", errors[2]);
    if errors[1] > 1e-12 {
        let measured = (errors[1] / errors[3]).log2() / 2.0;
        eprintln!("{name}: order from 40 to 160 rows {measured:.2}");
        assert!(measured > order, "{name}: order {measured:.2}");
    }
}

/// Runs `microslip dissipation` on the acceptance cycle (with `p1` given) and a compliance.
fn run_cli(p1: &str, compliance: &str, extra: &[&str]) -> std::process::Output {
    let mut args = common::case_args("dissipation", &[("--p1", p1), ("--compliance", compliance)]);
    args.extend(extra.iter().map(|s| s.to_string()));
    common::run(&args).output()
}

/// The one line a refused run prints, after checking exit code 2 and an empty stdout.
fn refusal(output: &std::process::Output) -> String {
    let stderr = String::from_utf8_lossy(&output.stderr).to_string();
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(output.stdout.is_empty(), "{}", String::from_utf8_lossy(&output.stdout));
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    stderr
}

/// Writes `text` as a table file.
fn persson_table(dir: &std::path::Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write table");
    path.to_string_lossy().into_owned()
}

fn good_rows() -> Vec<String> {
    (0..8)
        .map(|i| {
            let load = 0.2 * (1.5f64 / 0.2).powf(f64::from(i) / 7.0);
            format!("{load},{}", 1.0 / load)
        })
        .collect()
}

#[test]
fn bad_tables_are_refused_with_the_line_and_the_problem() {
    let dir = Scratch::new("bad");
    let rows = good_rows();
    let with = |header: &str, rows: &[String]| format!("# measured\n{header}\n{}\n", rows.join("\n"));
    let edited = |line: usize, replacement: &str| {
        let mut rows = rows.clone();
        rows[line - 3] = replacement.to_string();
        with("load,slope", &rows)
    };
    let cases: Vec<(&str, String, Vec<&str>)> = vec![
        (
            "misspelled",
            with("load,slop", &rows),
            vec!["neither an 'approach' nor a 'slope' column", "load,slop"],
        ),
        ("noload", with("laod,slope", &rows), vec!["no 'load' column"]),
        (
            "both",
            with("load,slope,approach", &rows),
            vec!["both an 'approach' and a 'slope'"],
        ),
        (
            "text",
            edited(5, "0.5,abc"),
            vec!["line 5", "slope 'abc' is not a number"],
        ),
        ("infinite", edited(6, "0.7,inf"), vec!["line 6", "is not finite"]),
        ("nan", edited(4, "NaN,2"), vec!["line 4", "load 'NaN' is not finite"]),
        (
            "short",
            with("load,slope", &rows[..3]),
            vec!["has 3 data rows", "at least 4"],
        ),
        (
            "unsorted",
            edited(5, "0.25,4"),
            vec!["line 5", "is below the previous row's", "increase strictly"],
        ),
        ("repeated", edited(4, &rows[0].clone()), vec!["line 4", "repeats"]),
        ("negative", edited(10, "1.5,-0.1"), vec!["line 10", "not positive"]),
    ];
    for (name, text, expected) in cases {
        let path = persson_table(&dir, &format!("{name}.csv"), &text);
        let message = refusal(&run_cli("0.4", &format!("table:{path}"), &[]));
        for part in expected {
            assert!(message.contains(part), "{name}: '{part}' not in {message}");
        }
    }
    // v' that rises between two rows: not concave.
    let mut rows_convex = rows.clone();
    let load: f64 = rows[3].split(',').next().and_then(|x| x.parse().ok()).expect("load");
    rows_convex[3] = format!("{load},{}", 1.2 / load * 1.5);
    let path = persson_table(&dir, "convex.csv", &with("load,slope", &rows_convex));
    let message = refusal(&run_cli("0.4", &format!("table:{path}"), &[]));
    assert!(
        message.contains("line 6") && message.contains("not concave"),
        "{message}"
    );
    assert!(message.contains("smoothing tolerance"), "{message}");
    // An approach that falls.
    let approach: Vec<String> = (0..8)
        .map(|i| {
            let load = 0.2 * (1.5f64 / 0.2).powf(f64::from(i) / 7.0);
            let v = if i == 4 { -5.0 } else { f64::ln(load) };
            format!("{load},{v}")
        })
        .collect();
    let path = persson_table(&dir, "falling.csv", &with("load,approach", &approach));
    let message = refusal(&run_cli("0.4", &format!("table:{path}"), &[]));
    assert!(
        message.contains("line 7") && message.contains("does not increase"),
        "{message}"
    );
    // A file that is not there.
    let message = refusal(&run_cli("0.4", "table:/nonexistent/table.csv", &[]));
    assert!(message.contains("cannot be read"), "{message}");
}

#[test]
fn a_cycle_leaving_the_table_is_refused_with_the_range() {
    let dir = Scratch::new("range");
    let path = persson_table(&dir, "good.csv", &format!("load,slope\n{}\n", good_rows().join("\n")));
    // P1 = 0.6 reaches 1.6 > 1.5 and P_T below 0.2.
    let message = refusal(&run_cli("0.6", &format!("table:{path}"), &[]));
    assert!(
        message.contains("covers loads [2e-1, 1.5e0]") && message.contains("never extrapolated"),
        "{message}"
    );
    let output = common::run(common::case_args(
        "simulate",
        &[("--p1", "0.6"), ("--compliance", &format!("table:{path}"))],
    ))
    .output();
    let message = refusal(&output);
    assert!(message.contains("covers loads [2e-1, 1.5e0]"), "{message}");
}

/// W of the table's interpolant at 300 bits by the library's own Gauss–Legendre
/// quadrature in MPFR (split at the knots like every rule): an integration independent
/// of Arb's.
fn mpfr_w(case: &CaseText) -> Float {
    let precision = Precision::bits(300);
    let Case { cycle, compliance } = case
        .spec()
        .expect("case")
        .at::<Float>(precision)
        .expect("case at 300 bits");
    let options = Options::default()
        .with_tolerance(Float::with_val(300, Float::parse("1e-70").unwrap()))
        .with_max_points(4096);
    dissipation(&cycle, compliance.as_ref(), &options)
        .expect("MPFR W")
        .total
}

/// `digits` certified digits of the interpolant's W for `case`, checked against the
/// MPFR integration and with the table's error stated beside them; the report.
fn assert_certified_table(case: &CaseText, digits: u32) -> microslip::answer::dissipation::DissipationAnswer {
    let report = dissipation_report(case, Some(digits), Duration::from_secs(120)).expect("table W to digits");
    let answer = &report.answer;
    assert_eq!(answer.provenance.key(), "certified", "{case:?}: {report:?}");
    assert!(answer.value.digits() >= digits, "{case:?}: {report:?}");
    let (lower, upper) = answer.value.enclosure.clone().expect("an enclosure");
    let bound = |text: &str| Float::with_val(400, Float::parse(text).expect("a decimal"));
    let exact = mpfr_w(case);
    assert!(
        bound(&lower) <= exact && exact <= bound(&upper),
        "{case:?}: {} outside [{lower}, {upper}]",
        exact.to_string_radix(10, Some(50))
    );
    let table = report.table.as_ref().expect("the table's error beside the digits");
    assert!(table.error > 0.0 && table.error.is_finite(), "{table:?}");
    report
}

/// A table of `slope` at the loads `step`·k for k in `rows`: every load a dyadic
/// rational, so that a knot can sit exactly at a load of the cycle.
fn dyadic_table(
    dir: &std::path::Path,
    name: &str,
    step: f64,
    rows: std::ops::RangeInclusive<i32>,
    slope: fn(f64) -> f64,
) -> String {
    let text: String = rows
        .map(|k| step * f64::from(k))
        .map(|p| format!("{p:e},{:e}\n", slope(p)))
        .collect();
    persson_table(dir, name, &format!("load,slope\n{text}"))
}

#[test]
fn digits_of_a_table_are_proven_for_its_interpolant_with_the_table_error_beside() {
    let example = format!("table:{}/tests/data/rough-surface.csv", env!("CARGO_MANIFEST_DIR"));
    assert_certified_table(&case(&example), 30);
    // Loads ≤ 0 in the table: v' as a cubic in P itself.
    let dir = Scratch::new("certified");
    let quadratic = dyadic_table(&dir, "quadratic.csv", 0.25, -2..=10, |p| {
        3.0 - 0.1 * (p + 1.0) * (p + 1.0)
    });
    assert_certified_table(&case(&format!("table:{quadratic}")), 40);
    // The half tables give the model error; each is an interpolant of its own.
    let report = assert_certified_table(&case(&example), 20);
    assert!(report.table.expect("table").error < 1e-6);
}

#[test]
fn knots_exactly_at_the_extreme_loads_and_the_permanent_stick_load_are_enclosed() {
    let dir = Scratch::new("knots");
    // Knots at 0.5, 1 and 1.5 = P0 − P1, P0 and P0 + P1, exactly, in log–log and in P.
    let log_log = dyadic_table(&dir, "persson.csv", 0.125, 1..=16, |p| 1.0 / p);
    let linear = dyadic_table(&dir, "quadratic.csv", 0.25, -2..=10, |p| {
        3.0 - 0.1 * (p + 1.0) * (p + 1.0)
    });
    for table in [&log_log, &linear] {
        let at_extremes = common::case().p1("0.5").compliance(format!("table:{table}")).text();
        assert_certified_table(&at_extremes, 30);
        // In phase, P_T = P0 − (σ₊ + σ₋)/2f = 1 − (0.75 + 0.25)/2 = 0.5: a knot.
        let at_stick = common::case()
            .p1("0.25")
            .phi("0")
            .compliance(format!("table:{table}"))
            .text();
        assert_certified_table(&at_stick, 30);
        // At φ = π/2, P_T = 1 − √(Q1² + f²P1²) = 0.5 too, but only as a limit of balls
        // around cos φ: whether the slip load crosses the knot is a tie no precision
        // decides, and two precisions agreeing answer, saying so.
        let tie = common::case()
            .q1("0.3")
            .phi("0.5pi")
            .compliance(format!("table:{table}"))
            .text();
        let report = dissipation_report(&tie, Some(20), Duration::from_secs(120)).expect("W");
        assert_eq!(report.answer.provenance.key(), "agreement", "{report:?}");
        assert!(report
            .no_enclosure
            .as_ref()
            .expect("why")
            .to_string()
            .contains("overlap"));
        let exact = mpfr_w(&tie);
        let printed = Float::with_val(300, Float::parse(report.total()).expect("W"));
        assert!(Float::with_val(300, &printed - &exact).abs() <= Float::with_val(300, &exact * 1e-19));
    }
}

#[test]
fn a_table_of_constant_slope_is_exactly_zero_at_any_digits() {
    let dir = Scratch::new("constant");
    // v = 3P: v' ≡ 3 between and beyond the rows' rounding.
    let text: String = (0..12)
        .map(|i| 0.1 + 1.9 * f64::from(i) / 11.0)
        .map(|p| format!("{p:e},{:e}\n", 3.0 * p))
        .collect();
    let path = persson_table(&dir, "v3p.csv", &format!("load,approach\n{text}"));
    let report = dissipation_report(&case(&format!("table:{path}")), Some(40), Duration::from_secs(60)).expect("W");
    assert_eq!(report.answer.provenance.key(), "exact", "{report:?}");
    assert_eq!(report.total(), "0");
    assert!(report.table.is_some());
}

#[test]
fn digits_of_a_table_on_the_command_line_say_what_is_proven_and_what_is_not() {
    let example = format!("table:{}/tests/data/rough-surface.csv", env!("CARGO_MANIFEST_DIR"));
    let output = run_cli("0.4", &example, &["--digits", "25"]);
    let text = String::from_utf8_lossy(&output.stdout);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let first = text.lines().next().expect("W's line");
    assert!(
        first.contains("25 significant digits, proven") && first.contains("for the table's interpolant"),
        "{text}"
    );
    assert!(
        text.contains("model error: the table itself is accurate to about"),
        "{text}"
    );
    let output = run_cli("0.4", &example, &["--digits", "25", "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("JSON");
    assert_eq!(json["provenance"], "certified");
    assert_eq!(json["digits_certified"], 25);
    assert!(
        json["enclosure"].is_array() && json["table_error"].as_f64().is_some_and(|e| e > 0.0),
        "{json}"
    );
    assert!(json["error_estimate"].is_null(), "{json}");
}

/// v' = 1/P with relative noise of ±`size` at every other row.
fn noisy_table(dir: &std::path::Path, size: f64) -> String {
    let rows: Vec<String> = (0..80)
        .map(|i| {
            let load = 0.2 * (1.5f64 / 0.2).powf(f64::from(i) / 79.0);
            let noise = if i % 2 == 0 { 1.0 + size } else { 1.0 - size };
            format!("{load},{}", noise / load)
        })
        .collect();
    persson_table(
        dir,
        &format!("noisy-{size}.csv"),
        &format!("load,slope\n{}\n", rows.join("\n")),
    )
}

#[test]
fn noisy_data_are_fitted_within_the_smoothing_tolerance_and_the_residual_reported() {
    let dir = Scratch::new("noisy");
    let path = noisy_table(&dir, 2e-2);
    // Without smoothing the noise is a violation of v'' ≤ 0.
    let message = refusal(&run_cli("0.4", &format!("table:{path}"), &[]));
    assert!(message.contains("not concave"), "{message}");
    let output = run_cli("0.4", &format!("table:{path},smoothing=0.05"), &["--json"]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).expect("json");
    let residual = json["smoothing_residual"].as_f64().expect("residual");
    assert!(residual > 1e-3 && residual <= 0.05, "residual {residual}");
    let exact = analytic("persson:gamma=1,sigma=1");
    let (error, estimate) = table_w(&format!("{path},smoothing=0.05"), exact);
    eprintln!("±2% noise, smoothing=0.05: relative error of W {error:.2e}, table estimate {estimate:.2e}, fit residual {residual:.2e}");
    // The fit averages the ±2% noise: W within a few tenths of a per cent.
    assert!(error < 5e-3, "relative error {error:.2e}");
}

#[test]
fn the_interpolant_keeps_the_physics_between_the_rows() {
    use microslip::compliance::{cached_table, Compliance, TableCompliance, TableInterpolant};
    let dir = Scratch::new("shape");
    for (name, column, rows, f) in [
        ("hertz", "approach", 6, FAMILIES[1].approach),
        ("exponential", "slope", 5, FAMILIES[2].slope),
        ("persson", "approach", 12, FAMILIES[0].approach),
    ] {
        let path = write_table(&dir, name, column, rows, f);
        let table = cached_table(&path, 0.0).expect("table");
        for interpolant in [TableInterpolant::Cubic, TableInterpolant::HalfTable] {
            let compliance = TableCompliance {
                table: table.clone(),
                interpolant,
            };
            let (first, last) = table.range();
            let mut previous = f64::INFINITY;
            for i in 0..=2000 {
                let load = first + (last - first) * f64::from(i) / 2000.0;
                let slope: f64 = compliance.slope(&load);
                let curvature: f64 = compliance.curvature(&load);
                assert!(
                    slope > 0.0 && slope <= previous * (1.0 + 1e-15),
                    "{name} {interpolant:?} at {load}"
                );
                assert!(
                    curvature <= 1e-12 * slope,
                    "{name} {interpolant:?}: v'' = {curvature} at {load}"
                );
                previous = slope;
            }
            // Outside the table: not a number, never an extrapolation.
            assert!(Compliance::<f64>::slope(&compliance, &(last * 1.01)).is_nan());
            assert!(Compliance::<f64>::slope(&compliance, &(first * 0.99)).is_nan());
        }
    }
}

#[test]
fn the_quadrature_estimate_holds_on_the_piecewise_cubic() {
    use microslip::compliance::{cached_table, TableCompliance, TableInterpolant};
    use microslip::dissipation::{dissipation, Options};
    use microslip::quad::RuleError;
    let dir = Scratch::new("quadrature");
    let path = write_table(&dir, "persson", "slope", 40, FAMILIES[0].slope);
    let compliance = TableCompliance {
        table: cached_table(&path, 0.0).expect("table"),
        interpolant: TableInterpolant::Cubic,
    };
    let cycle = common::acceptance_cycle(0.4 * std::f64::consts::PI);
    let options = Options {
        relative_tolerance: Some(microslip::batch::TABLE_QUADRATURE_TOLERANCE),
        ..Options::default()
    };
    let result = dissipation(&cycle, &compliance, &options).expect("W");
    let fine = dissipation(
        &cycle,
        &compliance,
        &Options::default().with_fixed_rule(4096, RuleError::QuarterRule),
    )
    .expect("W at 4096 points");
    let difference = (result.total - fine.total).abs();
    assert!(
        difference <= result.error_estimate.max(1e-14 * fine.total),
        "difference {difference:e}, estimate {:e}",
        result.error_estimate
    );
}

#[test]
fn the_example_table_gives_w_within_its_estimate() {
    let path = format!("{}/tests/data/rough-surface.csv", env!("CARGO_MANIFEST_DIR"));
    let exact = analytic("persson:gamma=1,sigma=1");
    let (error, estimate) = table_w(&path, exact);
    eprintln!("tests/data/rough-surface.csv: relative error of W {error:.2e}, table estimate {estimate:.2e}");
    assert!(
        error <= estimate && estimate < 1e-4,
        "error {error:.1e}, estimate {estimate:.1e}"
    );
}

#[test]
fn the_closed_form_paths_take_tables_too() {
    // In phase (φ = 0, integrals from P1 down to −Q1/f) and at constant normal load (P1 = 0).
    let dir = Scratch::new("closed-forms");
    let path = write_table(&dir, "persson", "slope", 80, FAMILIES[0].slope);
    for (p1, phi) in [("0.4", "0"), ("0.4", "pi"), ("0", "0.4pi")] {
        let with = |compliance: &str| common::case().p1(p1).phi(phi).compliance(compliance).text();
        let exact = dissipation_report(&with("persson:gamma=1,sigma=1"), Some(20), Duration::from_secs(60))
            .expect("analytic W");
        let exact_w: f64 = exact.total().parse().expect("W");
        let result =
            dissipation_report(&with(&format!("table:{path}")), None, Duration::from_secs(60)).expect("table W");
        let table = result.table.expect("table estimate");
        assert_eq!(result.answer.method, exact.answer.method, "P1 = {p1}, φ = {phi}");
        assert!(
            (table.unrounded - exact_w).abs() <= table.error + table.quadrature_error,
            "P1 = {p1}, φ = {phi}: {} against {exact_w}, table estimate {:e}",
            table.unrounded,
            table.error
        );
    }
}

#[test]
fn a_convex_approach_is_refused_at_the_row_where_its_secants_rise() {
    let dir = Scratch::new("convex-approach");
    // Secants 3, 2, then 7 (rising at the row of load 1.0), then 1.
    let path = persson_table(
        &dir,
        "convex.csv",
        "load,approach\n0.2,0\n0.6,1.2\n1.0,2.0\n1.4,4.8\n1.6,5.0\n",
    );
    let message = refusal(&run_cli("0.4", &format!("table:{path}"), &[]));
    assert!(
        message.contains("line 4") && message.contains("secant slope of the approach rises from 2.0000e0 to 7.0000e0"),
        "{message}"
    );
}

/// The example table (v' = 1/P from 60 rows of the approach) over cycles of every kind:
/// each converges under the default rules, and its quadrature estimate bounds the
/// difference from a dense fixed rule (4096 points on every piece between knot crossings).
#[test]
fn table_w_converges_with_an_estimate_that_bounds_a_dense_rule_between_knots() {
    use microslip::compliance::{cached_table, TableCompliance, TableInterpolant};
    use microslip::cycle::LoadCycle;
    use microslip::dissipation::{dissipation, Options};
    use microslip::quad::RuleError;
    let path = format!("{}/tests/data/rough-surface.csv", env!("CARGO_MANIFEST_DIR"));
    let pi = std::f64::consts::PI;
    // (P1, Q1, φ, f): ordinary phases, in phase, constant normal load, near separation
    // (P0 − P1 = 0.15) and near gross slip.
    let cycles = [
        (0.4, 0.5, 0.4 * pi, 1.0),
        (0.4, 0.5, 0.1 * pi, 1.0),
        (0.4, 0.5, 0.9 * pi, 1.0),
        (0.4, 0.5, 0.0, 1.0),
        (0.0, 0.5, 0.4 * pi, 1.0),
        (0.85, 0.1, 0.5 * pi, 1.0),
        (0.3, 0.6, 0.5 * pi, 0.9),
    ];
    for interpolant in [TableInterpolant::Cubic, TableInterpolant::HalfTable] {
        let compliance = TableCompliance {
            table: cached_table(&path, 0.0).expect("table"),
            interpolant,
        };
        for (p1, q1, phase, friction) in cycles {
            let cycle = LoadCycle {
                normal_amplitude: p1,
                tangential_amplitude: q1,
                friction,
                ..common::acceptance_cycle(phase)
            };
            let result = dissipation(&cycle, &compliance, &Options::default())
                .unwrap_or_else(|e| panic!("P1 {p1}, Q1 {q1}, φ {phase}, f {friction}, {interpolant:?}: {e}"));
            let dense = dissipation(
                &cycle,
                &compliance,
                &Options::default().with_fixed_rule(4096, RuleError::QuarterRule),
            )
            .expect("W at 4096 points");
            let difference = (result.total - dense.total).abs();
            eprintln!(
                "P1 {p1}, Q1 {q1}, φ {:.2}π, f {friction}, {interpolant:?}: W {:.6e}, |W − dense| {difference:.1e}, estimate {:.1e}, {} evaluations",
                phase / pi,
                result.total,
                result.error_estimate,
                result.evaluations
            );
            assert!(
                difference <= result.error_estimate.max(1e-14 * dense.total.abs()),
                "P1 {p1}, Q1 {q1}, φ {phase}: difference {difference:e}, estimate {:e}",
                result.error_estimate
            );
            assert!(result.error_estimate <= 1e-12 * result.total.abs());
        }
    }
}

/// A table that reaches load 0 is interpolated in the load itself (log–log needs
/// positive loads), where a quadratic v' is reproduced exactly (its node derivatives are
/// exact for quadratics), so its W is the analytic W of the polynomial, across every knot
/// crossing.
#[test]
fn a_table_of_a_quadratic_slope_gives_the_analytic_w() {
    use microslip::compliance::{cached_table, Polynomial, TableCompliance, TableInterpolant};
    use microslip::dissipation::{dissipation, Options};
    let dir = Scratch::new("quadratic");
    let rows: String = (0..30)
        .map(|i| {
            let load = 1.5 * f64::from(i) / 29.0;
            format!("{load:e},{:e}\n", 3.0 - load - 0.5 * load * load)
        })
        .collect();
    let path = persson_table(&dir, "quadratic.csv", &format!("load,slope\n{rows}"));
    let data = cached_table(&path, 0.0).expect("table");
    assert_eq!(data.coordinates, microslip::compliance::Coordinates::Linear);
    let table = TableCompliance {
        table: data,
        interpolant: TableInterpolant::Cubic,
    };
    let polynomial = Polynomial {
        reference: 0.0,
        coefficients: vec![3.0, -1.0, -0.5],
    };
    for phase in [0.0, 0.2, 0.4, 0.6, 0.8].map(|x| x * std::f64::consts::PI) {
        let cycle = common::acceptance_cycle(phase);
        let from_table = dissipation(&cycle, &table, &Options::default()).expect("table W");
        let exact = dissipation(&cycle, &polynomial, &Options::default()).expect("polynomial W");
        let difference = (from_table.total - exact.total).abs();
        eprintln!(
            "φ {:.1}π: |W_table − W| {difference:.1e}, estimates {:.1e} + {:.1e}",
            phase / std::f64::consts::PI,
            from_table.error_estimate,
            exact.error_estimate
        );
        assert!(
            difference <= from_table.error_estimate + exact.error_estimate + 1e-14 * exact.total.abs(),
            "φ {phase}: W from the table {:e}, analytic {:e}",
            from_table.total,
            exact.total
        );
    }
}

/// A table declares its interior loads as breakpoints, combinators forward them, and
/// the analytic families declare none.
#[test]
fn breakpoints_are_the_table_knots_through_combinators() {
    use microslip::compliance::{
        cached_table, Compliance, LoadScaled, Persson, Sum, TableCompliance, TableInterpolant,
    };
    let path = format!("{}/tests/data/rough-surface.csv", env!("CARGO_MANIFEST_DIR"));
    let data = cached_table(&path, 0.0).expect("table");
    let interior = data.loads[1..data.loads.len() - 1].to_vec();
    let table = |interpolant| TableCompliance {
        table: data.clone(),
        interpolant,
    };
    let persson = || Persson { gamma: 1.0, sigma: 1.0 };
    assert_eq!(table(TableInterpolant::Cubic).breakpoints(&1.0), interior);
    let half = table(TableInterpolant::HalfTable).breakpoints(&1.0);
    assert!(half.len() < interior.len() && half.iter().all(|k| interior.contains(k)));
    assert!(Compliance::<f64>::breakpoints(&persson(), &1.0).is_empty());
    let sum = Sum::<f64> {
        terms: vec![Box::new(persson()), Box::new(table(TableInterpolant::Cubic))],
    };
    assert_eq!(sum.breakpoints(&1.0), interior);
    let scaled = LoadScaled::<f64> {
        factor: 2.0,
        inner: Box::new(table(TableInterpolant::Cubic)),
    };
    let doubled: Vec<f64> = interior.iter().map(|k| 2.0 * k).collect();
    assert_eq!(scaled.breakpoints(&1.0), doubled);
}

/// Writes a table of `rows` loads from `first` to `last` (log spacing) of `f`.
fn sampled_table(
    dir: &std::path::Path,
    name: &str,
    header: &str,
    loads: (f64, f64, usize),
    f: fn(f64) -> f64,
) -> String {
    let (first, last, rows) = loads;
    let text: String = (0..rows)
        .map(|i| {
            let load = first * (last / first).powf(i as f64 / (rows - 1) as f64);
            format!("{load:e},{:e}\n", f(load))
        })
        .collect();
    persson_table(dir, name, &format!("{header}\n{text}"))
}

/// The flags of a cycle: P0, P1, Q1, φ, f, λ.
fn cycle_flags(values: [&'static str; 6]) -> Vec<&'static str> {
    ["--p0", "--p1", "--q1", "--phi", "--friction", "--lambda"]
        .into_iter()
        .zip(values)
        .flat_map(|(flag, value)| [flag, value])
        .collect()
}

/// W from `microslip dissipation … --json` on a cycle given as flags.
fn json_w(flags: &[&str]) -> Result<serde_json::Value, String> {
    let mut args = vec!["dissipation", "--json"];
    args.extend_from_slice(flags);
    let (code, stdout, stderr) = common::microslip(&args);
    if code != 0 {
        return Err(stderr);
    }
    serde_json::from_str(&stdout).map_err(|e| e.to_string())
}

/// The analytic W of a SPEC on the cycle of `flags`, to 20 verified digits.
fn analytic_w(flags: &[&str], spec: &str) -> f64 {
    let mut args = flags.to_vec();
    args.extend(["--compliance", spec, "--digits", "20"]);
    let json = json_w(&args).expect("analytic W");
    json["W"].as_str().and_then(|w| w.parse().ok()).expect("W")
}

#[test]
fn a_cycle_below_a_wide_table_is_refused_not_extrapolated() {
    // Loads 1e-2 … 1e12: a slack proportional to the largest load let P_T = 2.8e-3 through.
    let dir = Scratch::new("wide");
    let path = sampled_table(&dir, "wide.csv", "load,slope", (1e-2, 1e12, 60), |p| p.powf(-0.5));
    let flags = cycle_flags(["5e-3", "2e-3", "1e-3", "0.4pi", "1", "1"]);
    let mut args = vec!["dissipation"];
    args.extend_from_slice(&flags);
    let compliance = format!("table:{path}");
    args.extend(["--compliance", &compliance]);
    let (code, stdout, stderr) = common::microslip(&args);
    assert_eq!(code, 2, "{stdout}{stderr}");
    assert!(stdout.is_empty() && stderr.contains("never extrapolated"), "{stderr}");
    // The same table and a cycle inside it: W of the power law.
    let inside = cycle_flags(["5e-1", "2e-1", "1e-1", "0.4pi", "1", "1"]);
    let mut args = inside.to_vec();
    args.extend(["--compliance", &compliance]);
    let json = json_w(&args).expect("W inside the table");
    let w = json["W_f64"].as_f64().expect("W");
    let exact = analytic_w(&inside, "power:c=1,beta=-0.5");
    assert!((w - exact).abs() <= 1e-12 * exact, "{w} against {exact}");
}

#[test]
fn exact_tables_of_linear_data_are_accepted() {
    let dir = Scratch::new("exact");
    let flags = cycle_flags(["1", "0.4", "0.3", "1", "1", "1"]);
    // v = 3P (v' = 3, v'' = 0): rounding of the secants is not a violation of v'' ≤ 0.
    let loads: Vec<f64> = (0..12).map(|i| 0.1 + 1.9 * f64::from(i) / 11.0).collect();
    let approach: String = loads.iter().map(|p| format!("{p:e},{:e}\n", 3.0 * p)).collect();
    let linear: String = loads.iter().map(|p| format!("{p:e},{:e}\n", 2.0 - 0.5 * p)).collect();
    for (name, text, spec) in [
        // A constant v' dissipates nothing (W = 0 exactly).
        ("v3p.csv", format!("load,approach\n{approach}"), None),
        ("v3p-smoothed.csv", format!("load,approach\n{approach}"), None),
        (
            "linear.csv",
            format!("load,slope\n{linear}"),
            Some("poly:p0=0,coeffs=2;-0.5"),
        ),
    ] {
        let path = persson_table(&dir, name, &text);
        let smoothing = if name.contains("smoothed") {
            ",smoothing=1e-3"
        } else {
            ""
        };
        let compliance = format!("table:{path}{smoothing}");
        let mut args = flags.to_vec();
        args.extend(["--compliance", &compliance]);
        let json = json_w(&args).unwrap_or_else(|e| panic!("{name}: {e}"));
        if json["provenance"] == "exact" {
            // Equal slopes: W = 0 exactly, by reason, as for any constant slope.
            assert!(spec.is_none() && json["W"] == "0", "{name}: {json}");
            continue;
        }
        let w = json["W_f64"].as_f64().expect("W");
        let bound =
            json["table_error"].as_f64().expect("table error") + json["error_estimate"].as_f64().expect("quadrature");
        let exact = spec.map_or(0.0, |spec| analytic_w(&flags, spec));
        assert!(
            (w - exact).abs() <= bound,
            "{name}: {w} against {exact}, estimate {bound:e}"
        );
        assert!(json["digits"].as_u64().expect("digits") >= 3, "{name}: {json}");
    }
}

#[test]
fn a_table_too_coarse_for_any_digit_prints_none() {
    // Four rows of v' = e^(−2P) + 0.2: its own error estimate exceeds W.
    let dir = Scratch::new("coarse");
    let path = sampled_table(&dir, "coarse.csv", "load,slope", (0.1, 1.5, 4), |p| {
        (-p / 0.5).exp() + 0.2
    });
    let compliance = format!("table:{path}");
    let args = cycle_flags(["0.5", "0.2", "0.3", "2.5", "1", "1.2"]);
    let mut with = args.to_vec();
    with.extend(["--compliance", &compliance]);
    let json = json_w(&with).expect("W");
    let error = json["table_error"].as_f64().expect("table error");
    let w = json["W_f64"].as_f64().expect("W");
    let exact = analytic_w(&args, "exp:a=1,c=0.5,d=0.2");
    assert!((w - exact).abs() <= error, "{w} against {exact}, estimate {error:e}");
    if json["digits"] == 0 {
        assert!(json["W"].is_null(), "{json}");
        let mut plain = vec!["dissipation"];
        plain.extend_from_slice(&with);
        let (code, stdout, _) = common::microslip(&plain);
        assert_eq!(code, 0);
        assert!(stdout.starts_with("W: no digit determined"), "{stdout}");
    } else {
        let digits = json["digits"].as_u64().expect("digits") as usize;
        let printed = json["W"].as_str().expect("W");
        assert_eq!(printed, format!("{:.*e}", digits - 1, exact));
    }
}

#[test]
fn column_names_may_carry_units_in_any_case() {
    let dir = Scratch::new("units");
    let flags = cycle_flags(["1", "0.4", "0.5", "0.4pi", "1", "1"]);
    let exact = analytic_w(&flags, "hertz:r=1,estar=1");
    let approach = |p: f64| (9.0 * p * p / 16.0).cbrt();
    let slope = |p: f64| (2.0 / 3.0) * (9.0f64 / 16.0).cbrt() * p.powf(-1.0 / 3.0);
    for (name, header, f) in [
        ("brackets.csv", "Load [N],Approach [um]", approach as fn(f64) -> f64),
        ("parentheses.csv", "load (N),approach (mm)", approach),
        ("upper.csv", "LOAD,SLOPE", slope),
        ("mixed.csv", "Load(N), Slope [mm/N] ", slope),
    ] {
        let path = sampled_table(&dir, name, header, (0.1, 1.5, 30), f);
        let compliance = format!("table:{path}");
        let mut args = flags.to_vec();
        args.extend(["--compliance", &compliance]);
        let json = json_w(&args).unwrap_or_else(|e| panic!("{header}: {e}"));
        let w = json["W_f64"].as_f64().expect("W");
        assert!((w - exact).abs() <= 1e-12 * exact, "{header}: {w} against {exact}");
    }
    // Two columns that name the same quantity are refused.
    let path = persson_table(
        &dir,
        "twice.csv",
        "load,Load [N],slope\n1,1,1\n2,2,0.5\n3,3,0.3\n4,4,0.25\n",
    );
    let message = refusal(&run_cli("0.4", &format!("table:{path}"), &[]));
    assert!(message.contains("two 'load' columns"), "{message}");
}

#[test]
fn a_cycle_too_close_to_zero_load_for_f64_does_not_suggest_digits() {
    let dir = Scratch::new("tiny");
    let path = sampled_table(&dir, "tiny.csv", "load,slope", (1e-201, 1e-199, 20), |p| p.powf(-0.5));
    let mut args = vec!["dissipation"];
    args.extend(cycle_flags(["1e-200", "4e-201", "5e-201", "0.4pi", "1", "1"]));
    let compliance = format!("table:{path}");
    let mut with = args.to_vec();
    with.extend(["--compliance", &compliance]);
    let (code, stdout, stderr) = common::microslip(&with);
    assert_eq!(code, 2, "{stdout}{stderr}");
    assert!(stdout.is_empty(), "{stdout}");
    assert!(!stderr.contains("--digits"), "{stderr}");
    assert!(stderr.contains("table compliance is computed in f64 only"), "{stderr}");
}

/// 80 log-spaced rows over three decades (loads 0.005 … 5) give W within 1e−7 relative for
/// power-law, Persson, Hertz and exponential tables (slope and approach), and W converges
/// at fourth order where the interpolant is not exact (proofs/table-compliance.md).
#[test]
fn eighty_rows_over_three_decades_give_w_to_a_tenth_of_a_millionth() {
    let dir = Scratch::new("decades");
    let args = cycle_flags(["1", "0.4", "0.3", "1.9", "0.5", "1.2"]);
    let mut flags = args.clone();
    flags.extend(["--q0", "0.05"]);
    let power = Family {
        name: "power",
        spec: "power:c=1,beta=-0.5",
        slope: |p| p.powf(-0.5),
        approach: |p| 2.0 * p.sqrt(),
    };
    for family in FAMILIES.iter().chain([&power]) {
        let exact = analytic_w(&flags, family.spec);
        for (column, f) in [("slope", family.slope), ("approach", family.approach)] {
            let mut errors = Vec::new();
            for rows in [20, 40, 80, 160] {
                let name = format!("{}-{column}-{rows}.csv", family.name);
                let path = sampled_table(&dir, &name, &format!("load,{column}"), (0.005, 5.0, rows), f);
                let compliance = format!("table:{path}");
                let mut with = flags.clone();
                with.extend(["--compliance", &compliance]);
                let json = json_w(&with).unwrap_or_else(|e| panic!("{name}: {e}"));
                let w = json["W_f64"].as_f64().expect("W");
                let estimate = json["table_error"].as_f64().expect("table error");
                let error = (w - exact).abs() / exact;
                eprintln!(
                    "{:<12} {column:<9} {rows:>4} rows: relative error {error:.2e}, estimate {:.2e}",
                    family.name,
                    estimate / exact
                );
                assert!(error <= estimate / exact + 1e-14, "{name}: error {error:e}");
                errors.push(error);
            }
            assert_accuracy(&format!("{} {column}", family.name), &errors, 3.0);
        }
    }
}

/// On evenly spaced rows (in ln P) a half table of an odd number of rows is 2^4 times
/// as coarse as the table (Σ H⁵ / Σ h⁵); where a half drops only rows that sit close to
/// a neighbour, it is hardly coarser at all, and its distance from the table says little
/// of the table's error.
#[test]
fn half_tables_are_as_coarse_as_their_actual_gaps_make_them() {
    use microslip::compliance::ComplianceTable;
    let dir = Scratch::new("refinement");
    let write = |name: &str, loads: &[f64]| {
        let path = dir.join(name);
        let rows: String = loads.iter().map(|p| format!("{p:e},{:e}\n", 1.0 / p)).collect();
        std::fs::write(&path, format!("load,slope\n{rows}")).expect("write table");
        ComplianceTable::read(path.to_str().expect("path"), 0.0).expect("table")
    };
    let even: Vec<f64> = (0..9).map(|i| 0.2 * 1.25f64.powi(i)).collect();
    let refinements = write("even.csv", &even).half_refinements(0.2, 1.0);
    assert!((refinements[0] - 16.0).abs() < 1e-9, "{refinements:?}");
    assert!(refinements[1] > 2.0 && refinements[1] < 16.0, "{refinements:?}");
    // Rows in close pairs: the odd rows are the near partners, and dropping them leaves
    // every wide gap as it was.
    let pairs: Vec<f64> = (0..5).flat_map(|i| [1.0 + i as f64, 1.001 + i as f64]).collect();
    let refinements = write("pairs.csv", &pairs[..9]).half_refinements(1.0, 5.0);
    assert!(refinements[0] < 1.01, "{refinements:?}");
}
