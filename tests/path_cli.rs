//! `microslip path`: its JSON against docs/schema/path.schema.json, the loop file, the
//! proven W where P varies too, and one-line refusals that leave nothing behind.

mod common;

use common::{microslip, samples_text, Scratch, PERSSON};
use microslip::compliance::parse_spec;
use microslip::path::input::{read_driven_harmonics, read_harmonics};
use microslip::path::{displacement_dissipation, path_dissipation, Contact, Drive};
use microslip::real::Precision;
use serde_json::Value;

const TWO_HARMONICS: &str = "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0.05,0\n1,0.25,0.05,0.2,-0.3\n2,0.08,-0.04,0.1,0.06\n";

/// `microslip path --harmonics FILE --friction 0.8 --lambda 1.2 --compliance persson extra…`
/// with `contents` in FILE.
fn path_run(directory: &std::path::Path, contents: &str, extra: &[&str]) -> (i32, String, String) {
    path_file_run(directory, "--harmonics", contents, extra)
}

/// [`path_run`] with the file given as `kind` (`--harmonics` or `--samples`).
fn path_file_run(directory: &std::path::Path, kind: &str, contents: &str, extra: &[&str]) -> (i32, String, String) {
    let file = directory.join("path.csv");
    std::fs::write(&file, contents).unwrap();
    let mut args: Vec<String> = ["path", kind, file.to_str().unwrap()]
        .iter()
        .chain(&["--friction", "0.8", "--lambda", "1.2", "--compliance", PERSSON])
        .map(|s| s.to_string())
        .collect();
    args.extend(extra.iter().map(|s| s.to_string()));
    microslip(&args)
}

fn schema() -> jsonschema::Validator {
    let path = format!("{}/docs/schema/path.schema.json", env!("CARGO_MANIFEST_DIR"));
    let schema: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    jsonschema::meta::validate(&schema).unwrap_or_else(|e| panic!("{path}: {e}"));
    jsonschema::draft202012::new(&schema).unwrap()
}

fn library_w() -> f64 {
    let path = read_harmonics::<f64>(TWO_HARMONICS, Precision::DOUBLE).unwrap();
    let contact = Contact {
        friction: 0.8,
        compliance_ratio: 1.2,
    };
    let compliance = parse_spec::<f64>(PERSSON, Precision::DOUBLE).unwrap();
    path_dissipation(&path, &contact, compliance.as_ref(), None)
        .unwrap()
        .total
}

#[test]
fn the_json_conforms_to_its_schema_and_carries_the_library_w() {
    let directory = Scratch::new("json");
    let validator = schema();
    for extra in [
        &["--json"][..],
        &["--json", "--digits", "20", "--harmonics-out", "5"][..],
    ] {
        let (code, stdout, stderr) = path_run(&directory, TWO_HARMONICS, extra);
        assert_eq!(code, 0, "{stderr}");
        let document: Value = serde_json::from_str(stdout.trim()).unwrap();
        let problems: Vec<String> = validator.iter_errors(&document).map(|e| e.to_string()).collect();
        assert!(problems.is_empty(), "{problems:?}\n{document}");
        let w = document["W_f64"].as_f64().unwrap();
        assert!((w / library_w() - 1.0).abs() < 1e-15, "{w}");
        let printed: f64 = document["W"].as_str().unwrap().parse().unwrap();
        assert!((printed / w - 1.0).abs() < 1e-12);
        let eta = document["loss_factor"].as_f64().unwrap();
        let (qa, ua) = (
            document["q_amplitude"].as_f64().unwrap(),
            document["u_amplitude"].as_f64().unwrap(),
        );
        assert!((eta * std::f64::consts::PI * qa * ua / w - 1.0).abs() < 1e-14);
    }
    let (_, stdout, _) = path_run(&directory, TWO_HARMONICS, &["--json", "--digits", "20"]);
    let document: Value = serde_json::from_str(stdout.trim()).unwrap();
    assert_eq!(document["provenance"], "certified", "{document}");
    assert_eq!(document["digits_certified"], 20, "{document}");
    assert_eq!(
        document["W"]
            .as_str()
            .unwrap()
            .trim_start_matches('-')
            .replace('.', "")
            .split('e')
            .next()
            .unwrap()
            .len(),
        20
    );
    assert_eq!(document["harmonics"].as_array().unwrap().len(), 4);
}

#[test]
fn samples_of_the_path_give_the_same_w_as_its_harmonics() {
    let directory = Scratch::new("samples");
    let path = read_harmonics::<f64>(TWO_HARMONICS, Precision::DOUBLE).unwrap();
    let samples = samples_text(&path, 16);
    let file = directory.join("samples.csv");
    std::fs::write(&file, samples).unwrap();
    let (code, stdout, stderr) = microslip(&[
        "path",
        "--samples",
        file.to_str().unwrap(),
        "--friction",
        "0.8",
        "--nu",
        "0.3333333333333333",
        "--compliance",
        PERSSON,
        "--json",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let from_samples = serde_json::from_str::<Value>(stdout.trim()).unwrap()["W_f64"]
        .as_f64()
        .unwrap();
    // ν = 1/3 is λ = 1.25.
    assert!(
        (from_samples * 1.2 / 1.25 / library_w() - 1.0).abs() < 1e-12,
        "{from_samples}"
    );
}

#[test]
fn the_loop_is_written_whole_to_a_file_or_to_standard_output() {
    let directory = Scratch::new("loop");
    let out = directory.join("loop.csv");
    let (code, stdout, stderr) = path_run(&directory, TWO_HARMONICS, &["--loop", out.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.starts_with("W = "), "{stdout}");
    let text = std::fs::read_to_string(&out).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "theta,P,Q,u");
    assert_eq!(lines.len(), 1025);
    let row: Vec<f64> = lines[1].split(',').map(|c| c.parse().unwrap()).collect();
    assert_eq!(row[0], 0.0);
    assert!(
        (row[1] - 1.33).abs() < 1e-15 && (row[2] - 0.35).abs() < 1e-15,
        "{row:?}"
    );
    let (code, stdout, stderr) = path_run(&directory, TWO_HARMONICS, &["--loop", "-"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.starts_with("theta,P,Q,u\n"));
    assert!(stderr.contains("W = "), "{stderr}");
}

#[test]
fn bad_paths_are_refused_in_one_line_naming_the_problem_and_leave_no_file() {
    let directory = Scratch::new("refusals");
    let out = directory.join("loop.csv");
    let cases: [(&str, &str); 6] = [
        ("k,P_cos,P_sin,Q_cos\n0,1,0,0\n", "column Q_sin"),
        ("k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,zero\n", "line 2"),
        (
            "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,0\n65,0.1,0,0,0\n",
            "limit of 64 harmonics",
        ),
        (
            "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,0\n1,0.5,0,0,0\n2,0.9,0.3,0,0\n",
            "separates",
        ),
        (
            "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,0\n1,0.2,0,0,0\n2,0,0,0.7,0.3\n",
            "gross slip",
        ),
        ("", "empty"),
    ];
    for (contents, expected) in cases {
        let (code, stdout, stderr) = path_run(&directory, contents, &["--loop", out.to_str().unwrap()]);
        assert_eq!(code, 2, "{contents:?}: {stderr}");
        assert!(stdout.is_empty());
        assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
        assert!(stderr.contains(expected), "{contents:?}: {stderr}");
        assert!(!out.exists());
    }
    // The angle where gross slip is reached is named.
    let (_, _, stderr) = path_run(&directory, cases[4].0, &[]);
    assert!(stderr.contains("at θ = "), "{stderr}");
}

#[test]
fn displacement_driving_prints_the_library_w_and_names_its_drive() {
    let directory = Scratch::new("displacement");
    let validator = schema();
    let text = "k,P_cos,P_sin,u_cos,u_sin\n0,1.2,0,0.01,0\n1,0,0,0.2,-0.1\n2,0,0,0.04,0.05\n";
    let (code, stdout, stderr) = path_run(&directory, text, &["--drive", "displacement", "--json"]);
    assert_eq!(code, 0, "{stderr}");
    let document: Value = serde_json::from_str(stdout.trim()).unwrap();
    let problems: Vec<String> = validator.iter_errors(&document).map(|e| e.to_string()).collect();
    assert!(problems.is_empty(), "{problems:?}\n{document}");
    assert_eq!(document["drive"], "displacement");
    let path = read_driven_harmonics::<f64>(text, Precision::DOUBLE, Drive::Displacement).unwrap();
    let contact = Contact {
        friction: 0.8,
        compliance_ratio: 1.2,
    };
    let compliance = parse_spec::<f64>(PERSSON, Precision::DOUBLE).unwrap();
    let library = displacement_dissipation(&path, &contact, compliance.as_ref(), None)
        .unwrap()
        .total;
    let w = document["W_f64"].as_f64().unwrap();
    assert!((w / library - 1.0).abs() < 1e-14, "{w} against {library}");
    let (qa, ua, eta) = (
        document["q_amplitude"].as_f64().unwrap(),
        document["u_amplitude"].as_f64().unwrap(),
        document["loss_factor"].as_f64().unwrap(),
    );
    assert!((eta * std::f64::consts::PI * qa * ua / w - 1.0).abs() < 1e-14);
    assert!(qa < 0.8 * 1.2);
    // The prescribed u comes back as u's harmonics.
    assert_eq!(document["harmonics"][2]["u_sin"].as_f64(), Some(0.05));
    // Force driving says so too.
    let (_, stdout, _) = path_run(&directory, TWO_HARMONICS, &["--json"]);
    assert_eq!(serde_json::from_str::<Value>(stdout.trim()).unwrap()["drive"], "force");
}

#[test]
fn displacement_driving_refuses_a_varying_normal_load_and_force_columns() {
    let directory = Scratch::new("displacement-refusals");
    let out = directory.join("loop.csv");
    let cases = [
        (
            "k,P_cos,P_sin,u_cos,u_sin\n0,1,0,0,0\n1,0.1,0,0.2,0\n",
            "constant normal load",
        ),
        (TWO_HARMONICS, "column u_cos"),
    ];
    for (contents, expected) in cases {
        let (code, stdout, stderr) = path_run(
            &directory,
            contents,
            &["--drive", "displacement", "--loop", out.to_str().unwrap()],
        );
        assert_eq!(code, 2, "{stderr}");
        assert!(stdout.is_empty());
        assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
        assert!(stderr.contains(expected), "{stderr}");
        assert!(!out.exists());
    }
}

/// A force-driven path whose Q is constant dissipates nothing, whatever P does: W = Q ∮ du
/// = 0 over the closed loop. It is printed as exactly 0 (JSON provenance `exact`, every
/// digit asked), from harmonics and from samples, where agreement of two precisions could
/// never settle a digit of 0; the library's W is 0 in f64 and in MPFR. A Q harmonic that is
/// not exactly 0 is not taken for one.
#[test]
fn a_constant_q_under_a_varying_normal_load_dissipates_exactly_nothing() {
    let directory = Scratch::new("constant-q");
    let validator = schema();
    let constant_q = "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0.1,0\n1,0.3,0.1,0,0\n2,0.05,0,0.0000,0\n";
    for (extra, digits) in [(&["--json"][..], 15), (&["--json", "--digits", "30"][..], 30)] {
        let (code, stdout, stderr) = path_run(&directory, constant_q, extra);
        assert_eq!(code, 0, "{stderr}");
        let document: Value = serde_json::from_str(stdout.trim()).unwrap();
        let problems: Vec<String> = validator.iter_errors(&document).map(|e| e.to_string()).collect();
        assert!(problems.is_empty(), "{problems:?}\n{document}");
        assert_eq!(document["W"], "0", "{document}");
        assert_eq!(document["provenance"], "exact", "{document}");
        assert_eq!(document["digits_certified"], digits, "{document}");
        assert_eq!(document["W_f64"], 0.0, "{document}");
    }
    let (code, stdout, stderr) = path_run(&directory, constant_q, &[]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.starts_with("W = 0 (exact: Q is constant"), "{stdout}");
    let samples = "P,Q\n1.3,0.1\n1,0.1\n0.7,0.1\n1,0.1\n";
    let (code, stdout, stderr) = path_file_run(&directory, "--samples", samples, &["--json"]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(
        serde_json::from_str::<Value>(stdout.trim()).unwrap()["provenance"],
        "exact"
    );
    let contact = Contact {
        friction: 0.8,
        compliance_ratio: 1.2,
    };
    let compliance = parse_spec::<f64>(PERSSON, Precision::DOUBLE).unwrap();
    let path = read_harmonics::<f64>(constant_q, Precision::DOUBLE).unwrap();
    let w = path_dissipation(&path, &contact, compliance.as_ref(), None).unwrap();
    assert_eq!(w.total, 0.0);
    let precision = Precision::bits(128);
    let read = |text: &str| rug::Float::with_val(128, rug::Float::parse(text).unwrap());
    let path = read_harmonics::<rug::Float>(constant_q, precision).unwrap();
    let contact = Contact {
        friction: read("0.8"),
        compliance_ratio: read("1.2"),
    };
    let compliance = parse_spec::<rug::Float>(PERSSON, precision).unwrap();
    let w = path_dissipation(&path, &contact, compliance.as_ref(), None).unwrap();
    assert!(w.total.is_zero(), "{}", w.total);
    // Q's first harmonic 1e-6, not 0: W by agreement, and positive.
    let nearly = "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0.1,0\n1,0.3,0.1,1e-6,0\n";
    let (code, stdout, stderr) = path_run(&directory, nearly, &["--json"]);
    assert_eq!(code, 0, "{stderr}");
    let document: Value = serde_json::from_str(stdout.trim()).unwrap();
    assert_eq!(document["provenance"], "agreement", "{document}");
    assert!(document["W_f64"].as_f64().unwrap() > 0.0, "{document}");
}
