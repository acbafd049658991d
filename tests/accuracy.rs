//! The accuracy-against-cost report: the measurements, the Pareto front, the
//! cheapest configuration per target, and the files the command writes.

mod common;
use common::Scratch;

use microslip::accuracy::{
    cheapest_for, measure_case, pareto_front, reference_value, standard_cases, to_csv, Measurement,
};
use microslip::plot::{accuracy_picture, Format};

fn synthetic(rule: &'static str, seconds: f64, rel_error: f64) -> Measurement {
    Measurement {
        rule,
        precision_bits: 53,
        parameter: 1.0,
        evaluations: 1,
        seconds,
        rel_error,
        case: "x".into(),
    }
}

#[test]
fn pareto_front_keeps_only_undominated_points_and_the_cheapest_meets_the_target() {
    let points = vec![
        synthetic("a", 1.0, 1e-3),
        synthetic("b", 2.0, 1e-2),
        synthetic("c", 3.0, 1e-9),
        synthetic("d", 0.5, 1e-1),
        synthetic("e", 4.0, 1e-9),
    ];
    let front: Vec<&str> = pareto_front(&points).iter().map(|m| m.rule).collect();
    assert_eq!(front, ["d", "a", "c"]);
    assert_eq!(cheapest_for(&points, 1e-2).map(|m| m.rule), Some("a"));
    assert_eq!(cheapest_for(&points, 1e-9).map(|m| m.rule), Some("c"));
    assert!(cheapest_for(&points, 1e-12).is_none());
}

#[test]
fn gauss_legendre_in_theta_converges_geometrically_where_the_load_integral_does_not() {
    let case = &standard_cases(true)[0];
    let reference = reference_value(&case.text).unwrap();
    let measured = measure_case(case, &reference, true, |_| {});
    let error_of = |rule: &str, bits: u32, parameter: f64| {
        measured
            .iter()
            .find(|m| m.rule == rule && m.precision_bits == bits && m.parameter == parameter)
            .map(|m| m.rel_error)
            .unwrap()
    };
    // Gauss–Legendre: each doubling of the points gains digits, to f64's limit by 32 points.
    assert!(error_of("gauss-legendre", 53, 8.0) < 1e-6);
    assert!(error_of("gauss-legendre", 53, 16.0) < error_of("gauss-legendre", 53, 8.0) / 100.0);
    assert!(error_of("gauss-legendre", 53, 32.0) < 1e-14);
    assert!(error_of("gauss-legendre", 256, 64.0) < 1e-50);
    // The naive integral in P with square-root end points: slow algebraic convergence.
    assert!(error_of("naive-midpoint-in-P", 53, 256.0) > 1e-8);
    assert!(error_of("naive-midpoint-in-P", 53, 4096.0) < error_of("naive-midpoint-in-P", 53, 256.0));
    let csv = to_csv(&measured).unwrap();
    assert!(csv.starts_with("rule,precision_bits,parameter,evaluations,seconds,rel_error,case\n"));
    assert_eq!(csv.lines().count(), measured.len() + 1);
    assert!(measured
        .iter()
        .all(|m| m.seconds > 0.0 && m.rel_error > 0.0 && m.rel_error <= 1.0));
}

#[test]
fn accuracy_command_writes_the_csv_and_both_plots() {
    let scratch = Scratch::new("out");
    let dir = scratch.join("accuracy");
    let output = common::run(["accuracy", "--quick", "--out"]).arg(&dir).output();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        stdout.contains("1e-13") && stdout.contains("gauss-legendre"),
        "{stdout}"
    );
    for name in ["accuracy.csv", "accuracy.svg", "accuracy.png"] {
        let size = std::fs::metadata(dir.join(name)).map(|m| m.len()).unwrap_or(0);
        assert!(size > 1000, "{name}: {size} bytes");
    }
    let svg = std::fs::read_to_string(dir.join("accuracy.svg")).unwrap();
    assert!(svg.contains("Pareto front") && svg.contains("tanh-sinh"));
}

#[test]
fn accuracy_writes_all_three_files_or_none() {
    let dir = Scratch::new("full");
    // File size limited to 64 KiB, as a full disk would stop it: the CSV and the SVG fit,
    // the PNG does not (a write beyond the limit fails with "File too large").
    let output = common::run(["accuracy", "--quick", "--out"])
        .arg(&dir)
        .file_size_limit_kib(64)
        .output();
    let stderr = common::failed_with_one(&output);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("accuracy.png") && stderr.contains("no file of this run was kept"),
        "{stderr}"
    );
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert!(left.is_empty(), "{left:?}");
}

/// The measurements of a CSV written by `to_csv`.
fn read_measurements(text: &str) -> Vec<Measurement> {
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    reader
        .records()
        .map(|record| {
            let r = record.unwrap();
            Measurement {
                rule: Box::leak(r[0].to_string().into_boxed_str()),
                precision_bits: r[1].parse().unwrap(),
                parameter: r[2].parse().unwrap(),
                evaluations: r[3].parse().unwrap(),
                seconds: r[4].parse().unwrap(),
                rel_error: r[5].parse().unwrap(),
                case: r[6].to_string(),
            }
        })
        .collect()
}

#[test]
fn the_committed_accuracy_chart_is_the_drawing_of_the_committed_measurements() {
    // With MICROSLIP_REDRAW=1 the pictures are redrawn from benches/accuracy.csv instead.
    let benches = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("benches");
    let csv = std::fs::read_to_string(benches.join("accuracy.csv")).unwrap();
    let measurements = read_measurements(&csv);
    assert_eq!(to_csv(&measurements).unwrap(), csv, "the CSV reads back as written");
    let picture = accuracy_picture(&measurements).unwrap();
    let svg = picture.encode(Format::Svg).unwrap();
    let png = picture.encode(Format::Png).unwrap();
    if std::env::var_os("MICROSLIP_REDRAW").is_some() {
        std::fs::write(benches.join("accuracy.svg"), &svg).unwrap();
        std::fs::write(benches.join("accuracy.png"), &png).unwrap();
    }
    assert!(
        std::fs::read(benches.join("accuracy.svg")).unwrap() == svg,
        "accuracy.svg is stale"
    );
    assert!(
        std::fs::read(benches.join("accuracy.png")).unwrap() == png,
        "accuracy.png is stale"
    );
}
