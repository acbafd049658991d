//! Every validation error, through the library and through the command line
//! (exit code 2, one line on stderr naming the problem, nothing on stdout).

use microslip::compliance::{parse_spec, AdmissibilityError};
use microslip::cycle::{compliance_ratio_from_poisson, CycleError, CycleKind, LoadCycle, ValidCycle};
use microslip::dissipation::{dissipation, DissipationError, Options};
use microslip::real::Precision;

mod common;
use common::microslip;

fn base() -> LoadCycle<f64> {
    common::acceptance_cycle(1.0)
}

fn validate(change: impl Fn(&mut LoadCycle<f64>)) -> CycleError {
    let mut cycle = base();
    change(&mut cycle);
    cycle.validate().expect_err("the cycle should be rejected")
}

#[test]
fn library_rejects_each_invalid_cycle_with_its_own_error() {
    assert!(base().validate().is_ok());
    assert!(matches!(
        validate(|c| c.mean_normal_load = f64::NAN),
        CycleError::NotFinite { quantity: "P0", .. }
    ));
    assert!(matches!(
        validate(|c| c.phase = f64::INFINITY),
        CycleError::NotFinite { quantity: "φ", .. }
    ));
    assert!(matches!(
        validate(|c| c.mean_normal_load = -1.0),
        CycleError::NonPositiveMeanLoad { .. }
    ));
    assert!(matches!(
        validate(|c| c.normal_amplitude = -0.1),
        CycleError::NegativeAmplitude { quantity: "P1", .. }
    ));
    assert!(matches!(
        validate(|c| c.tangential_amplitude = -0.1),
        CycleError::NegativeAmplitude { quantity: "Q1", .. }
    ));
    let separation = validate(|c| c.normal_amplitude = 1.0);
    assert!(matches!(separation, CycleError::Separation { margin, .. } if margin == 0.0));
    assert!(matches!(
        validate(|c| c.friction = 0.0),
        CycleError::NonPositiveFriction { .. }
    ));
    for lambda in [0.5, 2.5] {
        assert!(matches!(
            validate(|c| c.compliance_ratio = lambda),
            CycleError::ComplianceRatioOutOfRange { .. }
        ));
    }
    assert!(matches!(
        validate(|c| c.phase = 1e101),
        CycleError::PhaseTooLarge { .. }
    ));
    // max(Q − fP) = Q0 − fP0 + σ₋: Q0 = 0.7 crosses Q = +fP, Q0 = −0.7 crosses Q = −fP.
    match validate(|c| c.mean_tangential_load = 0.7) {
        CycleError::GrossSlip { sign: "+", excess, .. } => assert!(excess > 0.0),
        other => panic!("expected gross slip on Q = +fP, got {other:?}"),
    }
    match validate(|c| c.mean_tangential_load = -0.7) {
        CycleError::GrossSlip {
            sign: "−", excess, ..
        } => assert!(excess > 0.0),
        other => panic!("expected gross slip on Q = −fP, got {other:?}"),
    }
    assert!(matches!(
        compliance_ratio_from_poisson(&0.9),
        Err(CycleError::PoissonRatioOutOfRange { .. })
    ));
    assert!((compliance_ratio_from_poisson(&0.5).unwrap() - 1.5).abs() < 1e-15);
}

#[test]
fn gross_slip_margin_is_exact_at_the_boundary() {
    // σ₋ at φ = π/2 is √(Q1² + f²P1²); Q0 exactly fP0 − σ₋ touches the line.
    let mut cycle = base();
    cycle.phase = std::f64::consts::FRAC_PI_2;
    let sigma_minus = (0.5f64 * 0.5 + 0.4 * 0.4).sqrt();
    cycle.mean_tangential_load = 1.0 - sigma_minus + 1e-9;
    assert!(matches!(cycle.validate(), Err(CycleError::GrossSlip { .. })));
    cycle.mean_tangential_load = 1.0 - sigma_minus - 1e-9;
    assert!(cycle.validate().is_ok());
}

#[test]
fn library_rejects_non_physical_compliance() {
    let cycle = base();
    let negative = parse_spec::<f64>("power:c=-1,beta=-1", Precision::DOUBLE).unwrap();
    assert!(matches!(
        dissipation(&cycle, negative.as_ref(), &Options::default()),
        Err(DissipationError::Compliance(
            AdmissibilityError::NonPositiveSlope { .. }
        ))
    ));
    let softening = parse_spec::<f64>("poly:p0=1,coeffs=1;0.5", Precision::DOUBLE).unwrap();
    assert!(matches!(
        dissipation(&cycle, softening.as_ref(), &Options::default()),
        Err(DissipationError::Compliance(
            AdmissibilityError::PositiveCurvature { .. }
        ))
    ));
}

/// `microslip dissipation` on the base case with one flag replaced (or added).
fn dissipation_with(flag: &str, value: &str, extra: &[&str]) -> (i32, String, String) {
    dissipation_overriding(&[(flag, value)], extra)
}

/// `microslip dissipation` on the base case with flags replaced (or added).
fn dissipation_overriding(overrides: &[(&str, &str)], extra: &[&str]) -> (i32, String, String) {
    let mut args = common::case_args("dissipation", overrides);
    args.extend(extra.iter().map(|s| s.to_string()));
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    microslip(&refs)
}

fn assert_rejected(outcome: (i32, String, String), expected: &str) {
    let (code, stdout, stderr) = outcome;
    assert_eq!(code, 2, "exit code; stderr: {stderr}");
    assert!(stdout.is_empty(), "stdout should be empty, got {stdout}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "one line on stderr, got {stderr}");
    assert!(
        stderr.contains(expected),
        "stderr should mention '{expected}': {stderr}"
    );
}

#[test]
fn command_line_reports_each_invalid_cycle_in_one_line_with_exit_code_2() {
    let (code, stdout, _) = dissipation_with("", "", &[]);
    assert_eq!(code, 0);
    assert!(stdout.starts_with("W = "), "{stdout}");
    // Read as an exact decimal at every precision, so refused as text in f64 as at --digits.
    assert_rejected(dissipation_with("--p0", "nan", &[]), "'nan' is not a decimal number");
    assert_rejected(
        dissipation_with("--friction", "inf", &[]),
        "'inf' is not a decimal number",
    );
    assert_rejected(dissipation_with("--p0", "-1", &[]), "must be positive");
    assert_rejected(dissipation_with("--p1", "-0.1", &[]), "P1 = ");
    assert_rejected(dissipation_with("--q1", "-0.1", &[]), "Q1 = ");
    assert_rejected(dissipation_with("--p1", "1", &[]), "the contact separates");
    assert_rejected(dissipation_with("--friction", "0", &[]), "friction coefficient");
    assert_rejected(dissipation_with("--lambda", "2.5", &[]), "compliance ratio");
    assert_rejected(dissipation_with("--phi", "1e101", &[]), "too large");
    assert_rejected(
        dissipation_with("--q0", "0.7", &[]),
        "gross slip: the load ellipse reaches the line Q = +fP",
    );
    assert_rejected(dissipation_with("--q0", "-0.7", &[]), "Q = −fP");
    assert_rejected(dissipation_with("--p0", "abc", &[]), "'abc' is not a decimal number");
    assert_rejected(
        dissipation_with("--phi", "xpi", &[]),
        "the phase φ = 'xpi' is not a phase: write radians",
    );
}

#[test]
fn command_line_reports_bad_compliance_poisson_ratio_and_flags() {
    assert_rejected(dissipation_with("--compliance", "power:c=-1,beta=-1", &[]), "v'(P) = ");
    assert_rejected(
        dissipation_with("--compliance", "poly:p0=1,coeffs=1;0.5", &[]),
        "v''(P)",
    );
    assert_rejected(
        dissipation_with("--compliance", "bogus:x=1", &[]),
        "unknown family 'bogus'",
    );
    assert_rejected(dissipation_with("--compliance", "power:c=1", &[]), "power needs beta=");
    assert_rejected(dissipation_with("--compliance", "power:c=1,beta=x", &[]), "beta='x'");
    assert_rejected(
        dissipation_with("--compliance", "persson:gamma=1,sigma=1+", &[]),
        "empty term",
    );
    // --nu in place of --lambda: out of range, and both at once.
    let nu_case = |nu: &str| {
        microslip(&[
            "dissipation",
            "--p0",
            "1",
            "--p1",
            "0.4",
            "--q1",
            "0.5",
            "--phi",
            "1",
            "--friction",
            "1",
            "--nu",
            nu,
            "--compliance",
            "persson:gamma=1,sigma=1",
        ])
    };
    assert_rejected(nu_case("0.9"), "Poisson's ratio");
    assert_eq!(nu_case("0.3").0, 0);
    assert_rejected(dissipation_with("--nu", "0.3", &[]), "cannot be used with");
    assert_rejected(microslip(&["dissipation", "--p0", "1"]), "required");
    assert_rejected(
        dissipation_with("--digits", "0", &[]),
        "--digits must be between 1 and 1000",
    );
    assert_rejected(
        dissipation_with("--digits", "1001", &[]),
        "--digits must be between 1 and 1000",
    );
    assert_rejected(
        dissipation_with("--p0", "nan", &["--digits", "20"]),
        "'nan' is not a decimal number",
    );
}

#[test]
fn command_line_json_carries_w_segments_digits_and_inputs() {
    let (code, stdout, stderr) = dissipation_with("", "", &["--json"]);
    assert_eq!(code, 0, "{stderr}");
    let value: serde_json::Value = serde_json::from_str(stdout.trim()).expect("one JSON object");
    let w: f64 = value["W"].as_str().unwrap().parse().unwrap();
    assert!(w > 0.0);
    // The default states the digits its enclosure proves: here the 13 of f64 intervals.
    let digits = value["digits"].as_u64().unwrap();
    assert_eq!(digits, 13, "{value}");
    assert_eq!(value["digits_certified"], 13, "{value}");
    assert!(value["error_estimate"].is_null(), "{value}");
    let printed = value["W"].as_str().unwrap();
    assert_eq!(printed.split('e').next().unwrap().replace('.', "").len() as u64, digits);
    let printed_segments = ["EB", "BC", "CH", "HE"].map(|k| value["segments"][k].as_str().unwrap().to_string());
    let segments: f64 = printed_segments.iter().map(|t| t.parse::<f64>().unwrap()).sum();
    // Each segment is rounded to its own digits: the sum is W within their half units.
    let half_units: f64 = printed_segments
        .iter()
        .map(|t| {
            let (mantissa, exponent) = t.split_once('e').unwrap();
            let digits = mantissa.replace(['.', '-'], "").len() as i32;
            0.5 * 10f64.powi(exponent.parse::<i32>().unwrap() - digits + 1)
        })
        .sum();
    assert!((segments - w).abs() <= half_units + 1e-13 * w, "{value}");
    assert_eq!(value["inputs"]["phi"], "0.4pi");
    // With --digits, the same W to 30 verified digits, agreeing with f64 to 1e-13.
    let (code, stdout, stderr) = dissipation_with("", "", &["--json", "--digits", "30"]);
    assert_eq!(code, 0, "{stderr}");
    let precise: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
    assert_eq!(precise["digits_verified"], 30);
    let text = precise["W"].as_str().unwrap();
    assert_eq!(text.split('e').next().unwrap().replace('.', "").len(), 30, "{text}");
    let precise_w: f64 = text.parse().unwrap();
    assert!((precise_w - w).abs() < 1e-13 * w, "{precise_w} vs {w}");
    assert!(precise["error_estimate"].is_null());
}

#[test]
fn where_f64_could_not_resolve_w_the_default_run_proves_fourteen_digits_or_more() {
    // Near in phase with Q1 < fP1, W ~ 1e-13 is the difference of BC and CH ~ ±1.2e-2,
    // which f64 resolved to 2 digits. The default run gives 14 or 15 proven digits, and
    // they are the leading digits of a 20-digit run.
    let run = |p1: &str, q1: &str, phi: &str, extra: &[&str]| {
        let (code, stdout, stderr) = dissipation_overriding(
            &[("--p1", p1), ("--q1", q1), ("--phi", phi)],
            &[extra, &["--json"]].concat(),
        );
        assert_eq!(code, 0, "{stderr}");
        serde_json::from_str::<serde_json::Value>(stdout.trim()).unwrap()
    };
    let significand = |value: &serde_json::Value| {
        let text = value["W"].as_str().unwrap().to_string();
        let (mantissa, exponent) = text.split_once('e').unwrap();
        (mantissa.replace(['.', '-'], ""), exponent.to_string())
    };
    for (p1, q1, phi, digits, reason) in [
        ("0.4", "0.2", "1e-6", 15, "cancel"),
        ("0.4", "0.2", "1e-17", 15, "cancel"),
        // 1e-6 P0 from separation: rounding the loads alone moves W beyond 1e-12.
        ("0.999999", "0.001", "0.5pi", 15, "min(P0 − P1, P_T) = P0/2.000e6"),
        // Q1 = 2.5e-9 fP1: the slip terms of the integrands cancel to a difference 4e8 times
        // smaller, which the f64 intervals, taking the slip loads apart, prove to 14 digits.
        ("0.4", "1e-9", "0.4pi", 14, "cancel"),
    ] {
        let default = run(p1, q1, phi, &[]);
        assert_eq!(default["digits"], digits, "{default}");
        assert_eq!(default["digits_verified"], digits, "{default}");
        let arithmetic = if digits < 15 { "f64 intervals" } else { "arb balls" };
        assert_eq!(default["arithmetic"], arithmetic, "{default}");
        assert!(default["error_estimate"].is_null());
        assert_eq!(default["provenance"], "certified", "{default} ({reason})");
        let reference = run(p1, q1, phi, &["--digits", "20"]);
        let ((printed, e_printed), (twenty, e20)) = (significand(&default), significand(&reference));
        // Rounding 20 digits to the default's changes the last of them by at most one.
        let (a, b): (i64, i64) = (printed.parse().unwrap(), twenty[..digits].parse().unwrap());
        assert!(e_printed == e20 && (a - b).abs() <= 1, "{default} vs {reference}");
    }
    // The near-separation case against its catalogue reference.
    let near_separation = run("0.999999", "0.001", "0.5pi", &["--digits", "20"]);
    assert_eq!(near_separation["W"], "5.6015094587448267940e-5");
    let (code, stdout, stderr) =
        dissipation_overriding(&[("--p1", "0.999999"), ("--q1", "0.001"), ("--phi", "0.5pi")], &[]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.starts_with("W = 5.60150945874483e-5"), "{stdout}");
    // An ordinary cycle is proven too: no estimate decides a printed digit.
    let ordinary = run("0.4", "0.5", "0.4pi", &[]);
    assert!(ordinary["error_estimate"].is_null() && ordinary["provenance"] == "certified");
}

/// A cycle is validated once, by `ValidCycle::new`, which refuses what `validate` refuses
/// with the same error and classifies what it accepts.
#[test]
fn valid_cycle_is_built_only_from_a_cycle_the_theory_covers() {
    for change in [
        (|c: &mut LoadCycle<f64>| c.normal_amplitude = 1.5) as fn(&mut LoadCycle<f64>),
        |c| c.tangential_amplitude = 5.0,
        |c| c.friction = -1.0,
    ] {
        let mut cycle = base();
        change(&mut cycle);
        let expected = cycle.validate().expect_err("invalid");
        assert_eq!(ValidCycle::new(cycle).expect_err("invalid"), expected);
    }
    let kind = |change: fn(&mut LoadCycle<f64>)| {
        let mut cycle = base();
        change(&mut cycle);
        ValidCycle::new(cycle).expect("valid").kind()
    };
    assert_eq!(kind(|_| {}), CycleKind::Elliptic);
    assert_eq!(
        kind(|c| c.tangential_amplitude = 0.0),
        CycleKind::NoTangentialOscillation
    );
    assert_eq!(kind(|c| c.normal_amplitude = 0.0), CycleKind::ConstantNormalLoad);
    assert_eq!(kind(|c| c.phase = std::f64::consts::PI), CycleKind::InPhase);
    // The geometry of a valid cycle is defined even where it degenerates: P1 = 0 leaves
    // BC and CH of length 0.
    let mut constant = base();
    constant.normal_amplitude = 0.0;
    let geometry = ValidCycle::new(constant).expect("valid").geometry();
    assert_eq!(geometry.stick_angle, 0.0);
    assert!((geometry.slip_angle - std::f64::consts::PI).abs() < 1e-15);
}
