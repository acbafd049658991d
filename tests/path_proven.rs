//! Proven W of a periodic path at constant normal load: the certified four-segment W for
//! one harmonic (the same digits, overlapping enclosures), Masing's rule over rainflow
//! cycles for two, invariance under a time shift, a shift of Q0 and zero harmonics, and
//! the enclosures against W at 40 digits by agreement; paths it does not cover say why.
#![cfg(feature = "certified")]

mod common;

use std::time::{Duration, Instant};

use common::{microslip, PERSSON};
use microslip::answer::dissipation::dissipation_of;
use microslip::answer::{path::path_answer, ExitStatus};
use microslip::case::CaseText;
use microslip::compliance::parse_spec;
use microslip::path::displacement::rainflow_ranges;
use microslip::path::input::read_harmonics;
use microslip::path::proven::{proven_w, NotProven, ProvenW};
use microslip::path::{path_dissipation, Contact, Drive, PathFormat, PathRequest, RatioText};
use microslip::real::Precision;
use rug::Float;
use serde_json::Value;

const HERTZ: &str = "hertz:r=1,estar=1";

/// A path file at constant P with Q = Q0 + Σ Qc_k cos kθ + Qs_k sin kθ, k = 1, 2, …
fn constant_p_file(p0: &str, q0: &str, harmonics: &[(&str, &str)]) -> String {
    let mut text = format!("k,P_cos,P_sin,Q_cos,Q_sin\n0,{p0},0,{q0},0\n");
    for (k, (qc, qs)) in harmonics.iter().enumerate() {
        text.push_str(&format!("{},0,0,{qc},{qs}\n", k + 1));
    }
    text
}

fn request(contents: &str, (friction, lambda, spec): (&str, &str, &str), digits: Option<u32>) -> PathRequest {
    PathRequest {
        file: "path.csv".to_string(),
        contents: contents.to_string(),
        format: PathFormat::Harmonics,
        drive: Drive::Force,
        friction: friction.to_string(),
        ratio: RatioText::Lambda(lambda.to_string()),
        compliance: spec.to_string(),
        digits,
        deadline: Instant::now() + Duration::from_secs(120),
        harmonics_out: 3,
        loop_points: 16,
    }
}

fn proven(contents: &str, contact: (&str, &str, &str), digits: Option<u32>) -> ProvenW {
    proven_w(&request(contents, contact, digits)).unwrap_or_else(|why| panic!("{contents}: {why}"))
}

/// The enclosure's ends, read exactly.
fn ends(proven: &ProvenW) -> (Float, Float) {
    let (lower, upper) = proven.value.enclosure.clone().expect("an enclosure");
    let read = |text: &str| Float::with_val(512, Float::parse(text).expect("a decimal"));
    (read(&lower), read(&upper))
}

fn overlap(a: (Float, Float), b: (Float, Float)) -> bool {
    a.0 <= b.1 && b.0 <= a.1
}

#[test]
fn a_harmonic_path_at_constant_p_prints_the_certified_four_segment_digits() {
    let cases = [
        ("1", "0", "0.3", "0", "1", "1", PERSSON),
        ("1", "0.1", "0.25", "0.4", "1", "1.3", PERSSON),
        ("2", "-0.2", "0.9", "1.3", "0.9", "1.5", HERTZ),
    ];
    for (p0, q0, q1, phase, friction, lambda, spec) in cases {
        let phi: f64 = phase.parse().unwrap();
        let (qc, qs) = (
            format!("{:e}", q1.parse::<f64>().unwrap() * phi.cos()),
            format!("{:e}", q1.parse::<f64>().unwrap() * phi.sin()),
        );
        // Q1 cos(θ − φ) as written, its amplitude Q1 to within the decimals' rounding.
        let file = constant_p_file(p0, q0, &[(&qc, &qs)]);
        let amplitude = format!(
            "{}",
            Float::with_val(512, Float::parse(&qc).unwrap()).hypot(&Float::with_val(512, Float::parse(&qs).unwrap()))
        );
        let case = CaseText::builder()
            .p0(p0)
            .p1(0)
            .q0(q0)
            .q1(amplitude.as_str())
            .phi(0)
            .friction(friction)
            .lambda(lambda)
            .compliance(spec)
            .build()
            .unwrap();
        for digits in [None, Some(25)] {
            let path = proven(&file, (friction, lambda, spec), digits);
            let certified = dissipation_of(&case, digits, Duration::from_secs(60)).unwrap();
            assert!(certified.answer.provenance.is_proven() && path.provenance.is_proven());
            assert_eq!(path.provenance, certified.answer.provenance, "{file}");
            assert_eq!(
                path.value.decimal.to_string(),
                certified.answer.value.decimal.to_string(),
                "{file}"
            );
            let (lower, upper) = certified.answer.value.enclosure.clone().unwrap();
            let read = |text: &str| Float::with_val(512, Float::parse(text).unwrap());
            assert!(overlap(ends(&path), (read(&lower), read(&upper))), "{file} {digits:?}");
        }
    }
}

#[test]
fn the_command_line_prints_the_proven_w_with_its_provenance() {
    let directory = std::env::temp_dir().join(format!("microslip-path-proven-{}", std::process::id()));
    std::fs::create_dir_all(&directory).unwrap();
    let file = directory.join("path.csv");
    std::fs::write(&file, constant_p_file("1", "0", &[("0.3", "0")])).unwrap();
    let contact = ["--friction", "1", "--lambda", "1", "--compliance", PERSSON];
    for digits in [None, Some("25")] {
        let mut path = vec!["path", "--harmonics", file.to_str().unwrap(), "--json"];
        let mut dissipation = vec![
            "dissipation",
            "--p0",
            "1",
            "--p1",
            "0",
            "--q1",
            "0.3",
            "--phi",
            "0",
            "--json",
        ];
        path.extend(contact);
        dissipation.extend(contact);
        if let Some(digits) = digits {
            path.extend(["--digits", digits]);
            dissipation.extend(["--digits", digits]);
        }
        let (code, path_out, stderr) = microslip(&path);
        assert_eq!(code, 0, "{stderr}");
        let (code, dissipation_out, stderr) = microslip(&dissipation);
        assert_eq!(code, 0, "{stderr}");
        let (path_json, dissipation_json): (Value, Value) = (
            serde_json::from_str(path_out.trim()).unwrap(),
            serde_json::from_str(dissipation_out.trim()).unwrap(),
        );
        for key in ["provenance", "arithmetic", "precision_bits", "digits_certified"] {
            assert_eq!(
                path_json[key], dissipation_json[key],
                "{key}: {path_json} vs {dissipation_json}"
            );
        }
        assert_eq!(path_json["W"], dissipation_json["W"]);
        assert_eq!(path_json["provenance"], "certified");
        assert!(path_json["no_enclosure"].is_null());
    }
    let _ = std::fs::remove_dir_all(&directory);
}

#[test]
fn a_batch_row_naming_a_constant_p_path_reports_the_proven_w_and_its_enclosure() {
    let directory = std::env::temp_dir().join(format!("microslip-path-proven-batch-{}", std::process::id()));
    std::fs::create_dir_all(&directory).unwrap();
    std::fs::write(
        directory.join("constant.csv"),
        constant_p_file("1", "0.05", &[("0.3", "0"), ("0.1", "-0.15")]),
    )
    .unwrap();
    std::fs::write(
        directory.join("varying.csv"),
        "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,0\n1,0.3,0,0.2,0.3\n",
    )
    .unwrap();
    let input = directory.join("in.csv");
    std::fs::write(
        &input,
        "id,friction,lambda,compliance,path\n\
         constant,0.8,1.2,\"persson:gamma=1,sigma=1\",constant.csv\n\
         varying,0.8,1.2,\"persson:gamma=1,sigma=1\",varying.csv\n",
    )
    .unwrap();
    let output = directory.join("out.jsonl");
    let (code, _, stderr) = microslip(&[
        "batch",
        "--input",
        input.to_str().unwrap(),
        "--output",
        output.to_str().unwrap(),
        "--format",
        "jsonl",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let text = std::fs::read_to_string(&output).unwrap();
    let rows: Vec<Value> = text.lines().map(|row| serde_json::from_str(row).unwrap()).collect();
    // Both rows against the row schema, every problem named with its row.
    let schema_text = std::fs::read_to_string(format!(
        "{}/docs/schema/batch-row.schema.json",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let row_schema = jsonschema::draft202012::new(&serde_json::from_str::<Value>(&schema_text).unwrap()).unwrap();
    let invalid: Vec<String> = rows
        .iter()
        .flat_map(|row| row_schema.iter_errors(row).map(move |e| format!("{e} in {row}")))
        .collect();
    assert!(invalid.is_empty(), "{invalid:?}");
    let (constant, varying) = (&rows[0], &rows[1]);
    assert_eq!(constant["provenance"], "certified");
    assert_eq!(constant["arithmetic"], "f64 intervals");
    assert!(constant["digits_certified"].as_u64().unwrap() >= 12, "{constant}");
    let (lower, upper) = (
        constant["enclosure"][0].as_str().unwrap().parse::<f64>().unwrap(),
        constant["enclosure"][1].as_str().unwrap().parse::<f64>().unwrap(),
    );
    let w = constant["W_f64"].as_f64().unwrap();
    assert!(lower <= w && w <= upper, "{constant}");
    assert_eq!(varying["provenance"], "agreement");
    assert_eq!(varying["digits_certified"], 0);
    assert!(
        varying["no_enclosure"]
            .as_str()
            .unwrap()
            .contains("constant normal load"),
        "{varying}"
    );
    let _ = std::fs::remove_dir_all(&directory);
}

/// Local extremes of dense samples of a periodic sequence, from its largest round to it
/// again (an estimate of the turning values with error of order the step squared).
fn sampled_turning_values(values: &[f64]) -> Vec<f64> {
    let n = values.len();
    let largest = (0..n).max_by(|&a, &b| values[a].total_cmp(&values[b])).unwrap();
    let turning: Vec<f64> = (0..n)
        .map(|j| (largest + j) % n)
        .filter(|&i| {
            let (before, after) = (values[(i + n - 1) % n], values[(i + 1) % n]);
            (values[i] - before) * (after - values[i]) < 0.0
        })
        .map(|i| values[i])
        .collect();
    turning.into_iter().chain([values[largest]]).collect()
}

#[test]
fn constant_p_with_two_harmonics_in_q_is_proven_and_masing_over_rainflow_cycles() {
    let contact = ("0.8", "1.2", PERSSON);
    for harmonics in [[("0.3", "0"), ("0.1", "-0.15")], [("0.25", "0.05"), ("0.2", "0.1")]] {
        let file = constant_p_file("1", "0.05", &harmonics);
        let w = proven(&file, contact, Some(20));
        assert!(w.cycles >= 1, "{file}");
        // Masing over the rainflow cycles of dense samples of Q, each the f64 four-segment W.
        let path = read_harmonics::<f64>(&file, Precision::DOUBLE).unwrap();
        let samples: Vec<f64> = (0..200_000)
            .map(|j| path.tangential.value(&(j as f64 * std::f64::consts::TAU / 200_000.0)))
            .collect();
        let masing: f64 = rainflow_ranges(&sampled_turning_values(&samples))
            .iter()
            .map(|range| {
                let case = CaseText::builder()
                    .p0(1)
                    .p1(0)
                    .q1(range / 2.0)
                    .phi(0)
                    .friction(contact.0)
                    .lambda(contact.1)
                    .compliance(contact.2)
                    .build()
                    .unwrap();
                dissipation_of(&case, None, Duration::from_secs(60))
                    .unwrap()
                    .answer
                    .value
                    .binary64
                    .unwrap()
            })
            .sum();
        let value = w.value.binary64.unwrap();
        assert!((value / masing - 1.0).abs() < 1e-8, "{value:e} vs Masing {masing:e}");
        // The event decomposition in f64 agrees to its own accuracy.
        let compliance = parse_spec::<f64>(contact.2, Precision::DOUBLE).unwrap();
        let events = path_dissipation(
            &path,
            &Contact {
                friction: 0.8,
                compliance_ratio: 1.2,
            },
            compliance.as_ref(),
            None,
        )
        .unwrap();
        assert!(
            (events.total / value - 1.0).abs() < 1e-12,
            "{:e} vs {value:e}",
            events.total
        );
    }
}

#[test]
fn a_time_shift_a_shift_of_q0_and_zero_harmonics_give_overlapping_enclosures() {
    let contact = ("1", "1", HERTZ);
    let harmonics = [("0.3", "0.1"), ("-0.12", "0.08")];
    let base = constant_p_file("1.5", "0", &harmonics);
    // A quarter turn: cos(θ + π/2) = −sin θ, sin(θ + π/2) = cos θ, and k = 2 changes sign:
    // exactly the same path, later.
    let quarter = constant_p_file("1.5", "0", &[("-0.1", "0.3"), ("0.12", "-0.08")]);
    let mean_shift = constant_p_file("1.5", "0.2", &harmonics);
    let padded = format!("{base}5,0,0,0,0\n3,0,0,0,0\n4,0,0,0,0\n");
    // A shift by 1 radian, its coefficients rounded to doubles: the same W to about 1e−16.
    let path = read_harmonics::<f64>(&base, Precision::DOUBLE).unwrap();
    let turned = path.tangential.shifted(&1.0);
    let one_radian = constant_p_file(
        "1.5",
        "0",
        &[
            (&format!("{:e}", turned.cos[1]), &format!("{:e}", turned.sin[1])),
            (&format!("{:e}", turned.cos[2]), &format!("{:e}", turned.sin[2])),
        ],
    );
    for digits in [15, 30] {
        let reference = ends(&proven(&base, contact, Some(digits)));
        for (name, other) in [
            ("quarter turn", &quarter),
            ("Q0 shift", &mean_shift),
            ("zero harmonics", &padded),
        ] {
            let enclosure = ends(&proven(other, contact, Some(digits)));
            assert!(
                overlap(reference.clone(), enclosure.clone()),
                "{name} at {digits}: {reference:?} vs {enclosure:?}"
            );
        }
    }
    // In f64 intervals the rounding of the shifted coefficients lies far inside the width.
    let (reference, shifted) = (
        ends(&proven(&base, contact, None)),
        ends(&proven(&one_radian, contact, None)),
    );
    assert!(
        overlap(reference.clone(), shifted.clone()),
        "{reference:?} vs {shifted:?}"
    );
}

/// W at `bits` of MPFR by the event decomposition, as agreement computes it.
fn w_at(contents: &str, contact: (&str, &str, &str), bits: u32) -> Float {
    let precision = Precision::bits(bits);
    let read = |text: &str| Float::with_val(bits, Float::parse(text).unwrap());
    let path = read_harmonics::<Float>(contents, precision).unwrap();
    let compliance = parse_spec::<Float>(contact.2, precision).unwrap();
    let contact = Contact {
        friction: read(contact.0),
        compliance_ratio: read(contact.1),
    };
    path_dissipation(&path, &contact, compliance.as_ref(), None)
        .unwrap()
        .total
}

#[test]
fn every_enclosure_holds_the_40_digit_agreement_value_on_random_two_harmonic_paths() {
    // A fixed linear congruential sequence: the same "random" paths every run.
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut uniform = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let contact = ("0.9", "1.1", PERSSON);
    for _ in 0..6 {
        // |Q − Q0| ≤ 0.45 + 0.25 < fP = 0.9·1.
        let mut coefficient = |scale: f64| format!("{:.4}", scale * (2.0 * uniform() - 1.0));
        let (q1c, q1s, q2c, q2s, q0) = (
            coefficient(0.3),
            coefficient(0.3),
            coefficient(0.17),
            coefficient(0.17),
            coefficient(0.1),
        );
        let file = constant_p_file("1", &q0, &[(&q1c, &q1s), (&q2c, &q2s)]);
        let (low, high) = (w_at(&file, contact, 192), w_at(&file, contact, 256));
        let agreed = Float::with_val(256, &high - &low).abs() / high.clone().abs();
        assert!(agreed < 1e-41, "{file}: the precisions agree only to {agreed:e}");
        for digits in [15, 20, 40] {
            let (lower, upper) = ends(&proven(&file, contact, Some(digits)));
            assert!(
                lower <= high && high <= upper,
                "{file} at {digits} digits: {high} outside [{lower}, {upper}]"
            );
        }
    }
}

#[test]
fn paths_it_does_not_cover_rest_on_agreement_and_say_why() {
    let contact = ("1", "1", PERSSON);
    let varying = "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,0\n1,0.3,0,0.2,0.3\n";
    assert!(matches!(
        proven_w(&request(varying, contact, Some(12))),
        Err(NotProven::NotCovered(_))
    ));
    let answer = path_answer(&request(varying, contact, Some(12))).unwrap();
    assert_eq!(answer.w.provenance, "agreement");
    assert_eq!(answer.w.digits_certified, 0);
    assert!(answer
        .w
        .no_enclosure
        .as_deref()
        .unwrap()
        .contains("constant normal load"));
    // Q = 0.4 cos θ + 0.1 cos 2θ: Q' has a triple root at π, which no precision isolates.
    let triple = constant_p_file("1", "0", &[("0.4", "0"), ("0.1", "0")]);
    let answer = path_answer(&request(&triple, contact, Some(12))).unwrap();
    assert_eq!(answer.w.provenance, "agreement");
    assert!(answer.w.detail.contains("not proven"), "{}", answer.w.detail);
}

#[test]
fn a_proof_the_budget_cuts_short_fails_rather_than_falling_back_on_agreement() {
    let constant = "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,0\n1,0,0,0.3,0\n2,0,0,0.1,0.05\n";
    let mut asked = request(constant, ("1", "1.2", PERSSON), Some(1000));
    asked.deadline = Instant::now() + Duration::from_millis(20);
    let error = path_answer(&asked).expect_err("1000 digits do not fit in 20 ms");
    assert_eq!(error.exit_code(), 1, "{error}");
    assert!(
        error.message.contains("time budget ran out before the enclosure"),
        "{error}"
    );
}
