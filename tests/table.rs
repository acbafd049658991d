//! Compliance from a table (`table:FILE`): accuracy against analytic compliances, its
//! error estimate, and every refusal of a bad table through the command line.

mod common;

use std::path::PathBuf;
use std::time::Duration;

use microslip::batch::case_dissipation;
use microslip::inputs::CaseText;

/// A fresh directory for this test's files.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("microslip-table-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

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

fn case(compliance: &str) -> CaseText {
    CaseText {
        p0: "1".into(),
        p1: "0.4".into(),
        q0: "0".into(),
        q1: "0.5".into(),
        phi: "0.4pi".into(),
        friction: "1".into(),
        lambda: Some("1".into()),
        nu: None,
        compliance: compliance.into(),
    }
}

fn analytic(spec: &str) -> f64 {
    let result = case_dissipation(&case(spec), Some(20), Duration::from_secs(60)).expect("analytic W");
    result.printed.total.parse().expect("W parses")
}

/// (relative error of W, relative table-error estimate) for a sampled table.
fn table_w(path: &str, exact: f64) -> (f64, f64) {
    let result = case_dissipation(&case(&format!("table:{path}")), None, Duration::from_secs(60)).expect("table W");
    let table = result.table.expect("a table estimate");
    ((table.unrounded - exact).abs() / exact, table.error / exact)
}

#[test]
fn table_w_converges_to_the_analytic_w_at_a_measured_order() {
    let dir = scratch("order");
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
            assert!(errors[2] < 1e-5, "{} {column}: 80 rows give {:.1e}", family.name, errors[2]);
            let order = (errors[1] / errors[3]).log2() / 2.0;
            eprintln!("{:<12} {column:<9} order from 40 to 160 rows: {order:.2}", family.name);
            assert!(order > 2.5, "{} {column}: order {order:.2}", family.name);
        }
    }
}
