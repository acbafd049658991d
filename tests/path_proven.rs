//! Proven W of a periodic path at constant normal load: the certified four-segment W for
//! one harmonic (the same digits, overlapping enclosures), Masing's rule over rainflow
//! cycles for two, invariance under a time shift, a shift of Q0 and zero harmonics, and
//! the enclosures against W at 40 digits by agreement; under displacement driving the
//! force-driven W at the resulting Q amplitude, gross slip, and the enclosures against
//! agreement; paths it does not cover say why.
#![cfg(feature = "certified")]

mod common;

use std::time::{Duration, Instant};

use common::{microslip, Scratch, PERSSON};
use microslip::answer::dissipation::dissipation_of;
use microslip::answer::path::proven::{proven_w, ProvenW, SummedOver};
use microslip::answer::{path::path_answer, ExitStatus};
use microslip::case::CaseText;
use microslip::compliance::parse_spec;
use microslip::path::displacement::rainflow_ranges;
use microslip::path::input::{read_driven_harmonics, read_harmonics};
use microslip::path::{
    displacement_dissipation, path_dissipation, Contact, Drive, MasingLaw, PathFormat, PathRequest, RatioText,
};
use microslip::real::Precision;
use rug::ops::Pow;
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

/// The same at constant P with u = u0 + Σ uc_k cos kθ + us_k sin kθ, displacement-driven.
fn displacement_file(p0: &str, u0: &str, harmonics: &[(&str, &str)]) -> String {
    constant_p_file(p0, u0, harmonics).replacen("Q_cos,Q_sin", "u_cos,u_sin", 1)
}

fn request(contents: &str, contact: (&str, &str, &str), digits: Option<u32>) -> PathRequest {
    driven_request(contents, contact, Drive::Force, digits)
}

fn driven_request(
    contents: &str,
    (friction, lambda, spec): (&str, &str, &str),
    drive: Drive,
    digits: Option<u32>,
) -> PathRequest {
    PathRequest {
        file: "path.csv".to_string(),
        contents: contents.to_string(),
        format: PathFormat::Harmonics,
        drive,
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

fn proven_by_displacement(contents: &str, contact: (&str, &str, &str), digits: Option<u32>) -> ProvenW {
    proven_w(&driven_request(contents, contact, Drive::Displacement, digits))
        .unwrap_or_else(|why| panic!("{contents}: {why}"))
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

/// The path's proven W and the certified four-segment W of `case`, the same cycle: both
/// proven, their enclosures overlapping.
fn proven_beside_four_segments(
    file: &str,
    contact: (&str, &str, &str),
    case: &microslip::case::CaseSpec,
    digits: Option<u32>,
) -> (ProvenW, microslip::answer::Answer) {
    let path = proven(file, contact, digits);
    let certified = dissipation_of(case, digits, Duration::from_secs(60)).unwrap().answer;
    assert!(
        certified.provenance.is_proven() && path.provenance.is_proven(),
        "{file}"
    );
    let (lower, upper) = certified.value.enclosure.clone().unwrap();
    let read = |text: &str| Float::with_val(512, Float::parse(text).unwrap());
    assert!(overlap(ends(&path), (read(&lower), read(&upper))), "{file} {digits:?}");
    (path, certified)
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
            let (path, certified) = proven_beside_four_segments(&file, (friction, lambda, spec), &case, digits);
            assert_eq!(path.provenance, certified.provenance, "{file}");
            assert_eq!(
                path.value.decimal.to_string(),
                certified.value.decimal.to_string(),
                "{file}"
            );
        }
    }
}

#[test]
fn a_harmonic_path_whose_normal_load_varies_is_proven_and_prints_the_four_segment_digits() {
    // P = P0 + P1 cos θ and Q = Q0 + Q1 sin θ: the four-segment cycle at φ = π/2, every
    // coefficient as written.
    let cases = [
        ("1", "0.4", "0", "0.5", "1", "1", PERSSON),
        ("1", "0.3", "0.1", "0.35", "0.8", "1.2", PERSSON),
        ("1", "0.3", "0", "0.4", "1", "1", HERTZ),
        ("2", "0.5", "-0.2", "0.7", "0.9", "1.5", HERTZ),
    ];
    for (p0, p1, q0, q1, friction, lambda, spec) in cases {
        let file = format!("k,P_cos,P_sin,Q_cos,Q_sin\n0,{p0},0,{q0},0\n1,{p1},0,0,{q1}\n");
        let case = CaseText::builder()
            .p0(p0)
            .p1(p1)
            .q0(q0)
            .q1(q1)
            .phi("pi/2")
            .friction(friction)
            .lambda(lambda)
            .compliance(spec)
            .build()
            .unwrap();
        for digits in [None, Some(25)] {
            let (path, certified) = proven_beside_four_segments(&file, (friction, lambda, spec), &case, digits);
            assert!(matches!(path.summed, SummedOver::Segments(n) if n >= 4), "{file}");
            if digits.is_some() {
                assert_eq!(
                    path.value.decimal.to_string(),
                    certified.value.decimal.to_string(),
                    "{file}"
                );
            } else {
                assert!(path.value.digits() >= 12, "{file}");
            }
        }
    }
}

#[test]
fn every_enclosure_holds_the_agreement_value_on_random_paths_whose_normal_load_varies() {
    let mut uniform = fixed_uniform(0x2545_f491_4f6c_dd1d);
    let mut covered = 0;
    for _ in 0..6 {
        let mut coefficient = |scale: f64| format!("{:.4}", scale * (2.0 * uniform() - 1.0));
        // |Q| ≤ 0.1 + 0.45 + 0.25 < f·min P = 1.1·0.72.
        let (mean, qc1, qs1, qc2, qs2) = (
            coefficient(0.1),
            coefficient(0.3),
            coefficient(0.3),
            coefficient(0.17),
            coefficient(0.17),
        );
        let (pc1, ps1, pc2, ps2) = (
            coefficient(0.13),
            coefficient(0.13),
            coefficient(0.06),
            coefficient(0.06),
        );
        let file = format!(
            "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,{mean},0\n1,{pc1},{ps1},{qc1},{qs1}\n2,{pc2},{ps2},{qc2},{qs2}\n"
        );
        let contact = ("1.1", "1.3", PERSSON);
        let agreed = w_agreed_to_41_digits(&file, contact, Drive::Force);
        for digits in [None, Some(30)] {
            let Ok(proven) = proven_w(&request(&file, contact, digits)) else {
                continue;
            };
            covered += usize::from(digits.is_none());
            let (lower, upper) = ends(&proven);
            assert!(
                lower <= agreed && agreed <= upper,
                "{file} at {digits:?} digits: {agreed} outside [{lower}, {upper}]"
            );
            assert!(proven.value.digits() >= digits.unwrap_or(12), "{file}");
        }
    }
    assert!(covered >= 4, "only {covered} of 6 paths proven");
}

#[test]
fn the_command_line_prints_the_proven_w_with_its_provenance() {
    let directory = Scratch::new("cli");
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
}

#[test]
fn batch_rows_naming_constant_p_paths_report_the_proven_w_and_its_enclosure() {
    let directory = Scratch::new("batch");
    std::fs::write(
        directory.join("constant.csv"),
        constant_p_file("1", "0.05", &[("0.3", "0"), ("0.1", "-0.15")]),
    )
    .unwrap();
    std::fs::write(
        directory.join("driven.csv"),
        displacement_file("1", "0.02", &[("0.3", "0"), ("0.1", "-0.15")]),
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
        "id,friction,lambda,compliance,path,drive\n\
         constant,0.8,1.2,\"persson:gamma=1,sigma=1\",constant.csv,\n\
         varying,0.8,1.2,\"persson:gamma=1,sigma=1\",varying.csv,\n\
         driven,0.8,1.2,\"persson:gamma=1,sigma=1\",driven.csv,displacement\n",
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
    let (constant, varying, driven) = (&rows[0], &rows[1], &rows[2]);
    assert_eq!(driven["method"], "path-displacement");
    for proven in [constant, varying, driven] {
        assert_eq!(proven["provenance"], "certified");
        if proven != varying {
            assert_eq!(proven["arithmetic"], "f64 intervals");
        }
        assert!(proven["digits_certified"].as_u64().unwrap() >= 12, "{proven}");
        let (lower, upper) = (
            proven["enclosure"][0].as_str().unwrap().parse::<f64>().unwrap(),
            proven["enclosure"][1].as_str().unwrap().parse::<f64>().unwrap(),
        );
        let w = proven["W_f64"].as_f64().unwrap();
        assert!(lower <= w && w <= upper, "{proven}");
    }
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
        assert!(matches!(w.summed, SummedOver::RainflowCycles(n) if n >= 1), "{file}");
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

/// W at `bits` of MPFR, as agreement computes it: by the event decomposition (force
/// driving) or Masing over the rainflow cycles of u (displacement driving).
fn w_at(contents: &str, contact: (&str, &str, &str), drive: Drive, bits: u32) -> Float {
    let precision = Precision::bits(bits);
    let read = |text: &str| Float::with_val(bits, Float::parse(text).unwrap());
    let path = read_driven_harmonics::<Float>(contents, precision, drive).unwrap();
    let compliance = parse_spec::<Float>(contact.2, precision).unwrap();
    let contact = Contact {
        friction: read(contact.0),
        compliance_ratio: read(contact.1),
    };
    let w = match drive {
        Drive::Force => path_dissipation(&path, &contact, compliance.as_ref(), None),
        Drive::Displacement => displacement_dissipation(&path, &contact, compliance.as_ref(), None),
    };
    w.unwrap().total
}

/// W at 256 bits, checked to agree with 192 bits to 41 digits.
fn w_agreed_to_41_digits(contents: &str, contact: (&str, &str, &str), drive: Drive) -> Float {
    let (low, high) = (w_at(contents, contact, drive, 192), w_at(contents, contact, drive, 256));
    let agreed = Float::with_val(256, &high - &low).abs() / high.clone().abs();
    assert!(agreed < 1e-41, "{contents}: the precisions agree only to {agreed:e}");
    high
}

/// A fixed linear congruential sequence of uniform numbers in [0, 1): the same "random"
/// paths every run.
fn fixed_uniform(mut state: u64) -> impl FnMut() -> f64 {
    move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A two-harmonic path file at P = 1 from the fixed sequence, written by `file`: its mean
/// within ±0.1, each coefficient of harmonic k within ±`scales`[k − 1], to 4 decimals.
fn random_two_harmonic_file(
    uniform: &mut impl FnMut() -> f64,
    scales: [f64; 2],
    file: fn(&str, &str, &[(&str, &str)]) -> String,
) -> String {
    let mut coefficient = |scale: f64| format!("{:.4}", scale * (2.0 * uniform() - 1.0));
    let (c1, s1, c2, s2, mean) = (
        coefficient(scales[0]),
        coefficient(scales[0]),
        coefficient(scales[1]),
        coefficient(scales[1]),
        coefficient(0.1),
    );
    file("1", &mean, &[(&c1, &s1), (&c2, &s2)])
}

/// Every enclosure proven at 15, 20 and 40 digits holds W at 256 bits, which agrees with
/// 192 bits to 41 digits.
fn assert_enclosures_hold_the_agreement_value(file: &str, contact: (&str, &str, &str), drive: Drive) {
    let agreed = w_agreed_to_41_digits(file, contact, drive);
    for digits in [15, 20, 40] {
        let proven =
            proven_w(&driven_request(file, contact, drive, Some(digits))).unwrap_or_else(|why| panic!("{file}: {why}"));
        let (lower, upper) = ends(&proven);
        assert!(
            lower <= agreed && agreed <= upper,
            "{file} at {digits} digits: {agreed} outside [{lower}, {upper}]"
        );
    }
}

#[test]
fn every_enclosure_holds_the_40_digit_agreement_value_on_random_two_harmonic_paths() {
    let mut uniform = fixed_uniform(0x9e37_79b9_7f4a_7c15);
    for _ in 0..6 {
        // |Q − Q0| ≤ 0.45 + 0.25 < fP = 0.9·1.
        let file = random_two_harmonic_file(&mut uniform, [0.3, 0.17], constant_p_file);
        assert_enclosures_hold_the_agreement_value(&file, ("0.9", "1.1", PERSSON), Drive::Force);
    }
}

#[test]
fn paths_it_does_not_cover_rest_on_agreement_and_say_why() {
    let contact = ("1", "1", PERSSON);
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

/// The amplitude g(Q_a) = λf (v(P) − v(P − Q_a/f)) of u whose cycle has Q amplitude Q_a,
/// at 512 bits, as a 60-digit decimal.
fn displacement_amplitude(load: &str, amplitude: &str, (friction, lambda, spec): (&str, &str, &str)) -> String {
    let precision = Precision::bits(512);
    let read = |text: &str| Float::with_val(512, Float::parse(text).unwrap());
    let compliance = parse_spec::<Float>(spec, precision).unwrap();
    let contact = Contact {
        friction: read(friction),
        compliance_ratio: read(lambda),
    };
    let law = MasingLaw::new(&read(load), &contact, compliance.as_ref());
    law.initial_displacement(&read(amplitude)).to_string_radix(10, Some(60))
}

#[test]
fn displacement_driving_at_constant_p_is_proven_and_equals_the_force_driven_w_at_its_q_amplitude() {
    for (amplitude, contact) in [
        ("0.3", ("0.8", "1.2", PERSSON)),
        ("0.7", ("0.8", "1.2", PERSSON)),
        ("0.45", ("0.9", "1.5", HERTZ)),
    ] {
        // u = g(Q_a) cos θ: one cycle of range 2g(Q_a), whose Q amplitude is Q_a.
        let u = displacement_amplitude("1", amplitude, contact);
        let by_u = displacement_file("1", "0.1", &[(&u, "0")]);
        let by_q = constant_p_file("1", "0", &[(amplitude, "0")]);
        for digits in [None, Some(25)] {
            let (driven, forced) = (
                proven_by_displacement(&by_u, contact, digits),
                proven(&by_q, contact, digits),
            );
            assert!(driven.provenance.is_proven(), "{by_u}");
            assert_eq!(driven.provenance, forced.provenance, "{by_u} {digits:?}");
            assert_eq!(driven.summed, SummedOver::RainflowCycles(1));
            assert!(overlap(ends(&driven), ends(&forced)), "{by_u} {digits:?}");
            if digits.is_some() {
                assert_eq!(
                    driven.value.decimal.to_string(),
                    forced.value.decimal.to_string(),
                    "{by_u}"
                );
            } else {
                // By default each prints the digits its own f64 intervals prove.
                let (a, b) = (driven.value.binary64.unwrap(), forced.value.binary64.unwrap());
                assert!(
                    driven.value.digits() >= 12 && (a / b - 1.0).abs() < 1e-12,
                    "{a:e} vs {b:e}"
                );
            }
        }
    }
}

#[test]
fn every_displacement_enclosure_holds_the_40_digit_agreement_value_on_random_two_harmonic_u_paths() {
    let mut uniform = fixed_uniform(0x2545_f491_4f6c_dd1d);
    for contact in [("0.9", "1.1", PERSSON), ("0.7", "1.3", HERTZ)] {
        for _ in 0..3 {
            let file = random_two_harmonic_file(&mut uniform, [0.4, 0.25], displacement_file);
            assert_enclosures_hold_the_agreement_value(&file, contact, Drive::Displacement);
        }
    }
}

#[test]
fn displacement_cycles_in_gross_slip_are_proven_and_hold_the_agreement_value() {
    // g(fP) = λf (v(P) − v(0)) is finite for these compliances; Persson's never slides.
    let cases = [
        (displacement_file("1", "0", &[("1.5", "0")]), ("0.8", "1.2", HERTZ), 1),
        (
            displacement_file("1.3", "0.1", &[("0.9", "0.4"), ("0.5", "-0.3")]),
            ("0.8", "1.2", HERTZ),
            2,
        ),
        (
            displacement_file("1", "0", &[("1.2", "0.3"), ("0.2", "0")]),
            ("0.8", "1.2", "rational:a=0.1,b=1,c=0.5"),
            1,
        ),
        (displacement_file("1", "0", &[("3", "0")]), ("0.8", "1.2", PERSSON), 1),
    ];
    for (file, contact, cycles) in cases {
        let agreed = w_agreed_to_41_digits(&file, contact, Drive::Displacement);
        for digits in [None, Some(30)] {
            let w = proven_by_displacement(&file, contact, digits);
            assert_eq!(w.summed, SummedOver::RainflowCycles(cycles), "{file}");
            let (lower, upper) = ends(&w);
            assert!(
                lower <= agreed && agreed <= upper,
                "{file} {digits:?}: {agreed} outside [{lower}, {upper}]"
            );
            assert!(w.value.digits() >= digits.unwrap_or(12), "{file}");
        }
    }
}

#[test]
fn a_displacement_driven_path_reports_certified_on_the_command_line() {
    let directory = Scratch::new("displacement");
    let file = directory.join("displacement.csv");
    std::fs::write(&file, displacement_file("1", "0.02", &[("0.3", "0"), ("0.1", "-0.15")])).unwrap();
    let mut texts = Vec::new();
    for (digits, arithmetic) in [(None, "f64 intervals"), (Some("30"), "arb balls")] {
        let mut args = vec![
            "path",
            "--harmonics",
            file.to_str().unwrap(),
            "--drive",
            "displacement",
            "--friction",
            "0.8",
            "--lambda",
            "1.2",
            "--compliance",
            PERSSON,
            "--json",
        ];
        if let Some(digits) = digits {
            args.extend(["--digits", digits]);
        }
        let (code, stdout, stderr) = microslip(&args);
        assert_eq!(code, 0, "{stderr}");
        let json: Value = serde_json::from_str(stdout.trim()).unwrap();
        assert_eq!(json["provenance"], "certified", "{json}");
        assert_eq!(json["arithmetic"], arithmetic, "{json}");
        assert_eq!(json["drive"], "displacement");
        assert!(json["no_enclosure"].is_null(), "{json}");
        let certified = json["digits_certified"].as_u64().unwrap();
        assert!(certified >= digits.map_or(12, |d| d.parse().unwrap()), "{json}");
        texts.push(json["W"].as_str().unwrap().to_string());
    }
    // The default digits are those of the 30 proven, rounded: within half a unit of the
    // default's last digit.
    let (default, thirty) = (&texts[0], &texts[1]);
    let (mantissa, exponent) = default.split_once('e').unwrap();
    let last_digit = exponent.parse::<i32>().unwrap() - (mantissa.len() as i32 - 2);
    let read = |text: &str| Float::with_val(256, Float::parse(text).unwrap());
    let half_unit = Float::with_val(256, 10).pow(last_digit) / 2;
    assert!(
        Float::with_val(256, read(default) - read(thirty)).abs() <= half_unit,
        "{default} vs {thirty}"
    );
}

#[test]
fn samples_at_a_constant_load_that_is_no_double_are_proven_like_their_harmonics() {
    // P = 1.3 in every sample: read as the decimal it is, a constant exactly. Its
    // enclosures' sums of cosines would leave harmonics about 0 that no comparison decides,
    // and the path was taken as one whose P varies.
    let directory = Scratch::new("constant-samples");
    let mut samples = String::from("P,Q\n");
    for j in 0..12 {
        let theta = std::f64::consts::TAU * f64::from(j) / 12.0;
        samples.push_str(&format!("1.3,{:.17e}\n", 0.3 * theta.cos() + 0.1 * (2.0 * theta).sin()));
    }
    let sampled = directory.join("samples.csv");
    let harmonics = directory.join("harmonics.csv");
    std::fs::write(&sampled, samples).unwrap();
    std::fs::write(
        &harmonics,
        "k,P_cos,P_sin,Q_cos,Q_sin\n0,1.3,0,0,0\n1,0,0,0.3,0\n2,0,0,0,0.1\n",
    )
    .unwrap();
    let w = |format: &str, file: &std::path::Path| {
        let args = [
            "path",
            format,
            file.to_str().unwrap(),
            "--friction",
            "1",
            "--lambda",
            "1",
            "--compliance",
            PERSSON,
            "--digits",
            "20",
            "--json",
        ];
        let (code, stdout, stderr) = microslip(&args);
        assert_eq!(code, 0, "{stderr}");
        let document: Value = serde_json::from_str(stdout.trim()).unwrap();
        assert_eq!(document["provenance"], "certified", "{format}: {stdout}");
        document["W_f64"].as_f64().unwrap()
    };
    let (from_samples, from_harmonics) = (w("--samples", &sampled), w("--harmonics", &harmonics));
    // The samples are the path's values to 17 digits.
    assert!(
        (from_samples - from_harmonics).abs() < 1e-14 * from_harmonics,
        "{from_samples} {from_harmonics}"
    );
}
