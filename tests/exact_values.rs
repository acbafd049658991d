//! Exact values by reason and the phase as written (proofs/exact-values.md): phases within
//! 1e−100 of 0 and π and decimal approximations of π get W's relative digits, every exact
//! zero prints at once as exact, the series' exact values are marked, and every way of
//! writing a phase gives the same W.

use std::time::Duration;

use microslip::answer::dissipation::dissipation_report;
use microslip::case::CaseText;
use microslip::real::{Precision, Real};
use rug::Float;

mod common;
use common::{case_args, microslip};

/// The near-in-phase case: Persson, P0 = 1, P1 = 0.4, Q1 = 0.2 (ρ = 1/2), f = λ = 1.
fn case(phi: &str, compliance: &str) -> CaseText {
    common::case().q1("0.2").phi(phi).compliance(compliance).text()
}

const PERSSON: &str = "persson:gamma=1,sigma=1";

/// W as printed without --digits, as a 200-bit number (how long it takes is measured by
/// `bash benches/reproducers.sh`, not here).
fn w(phi: &str) -> Float {
    let printed = dissipation_report(&case(phi, PERSSON), None, Duration::from_secs(60))
        .unwrap_or_else(|e| panic!("φ = {phi}: {e}"));
    Float::parse_decimal(&printed.total(), Precision::bits(200)).unwrap()
}

fn relative(a: &Float, b: &Float) -> f64 {
    (a.clone() - b).abs().to_f64() / b.clone().abs().to_f64()
}

/// W(φ)/sin²φ near 0 and near π: W is analytic in the offset δ with W = c δ² (1 + O(δ)), so the
/// ratio at δ = 1e−50 equals the ratio at δ = 1e−20 to ~1e−20, an independent computation at
/// a phase 30 orders of magnitude away.
#[test]
fn a_phase_near_a_multiple_of_pi_gives_w_its_relative_digits() {
    for (near, far, delta_near, delta_far) in [
        ("1e-50", "1e-20", "1e-50", "1e-20"),
        ("pi-1e-50", "pi-1e-20", "1e-50", "1e-20"),
        ("-pi+1e-50", "3pi+1e-20", "1e-50", "1e-20"),
        // sin²φ below f64's range
        ("pi-1e-200", "pi-1e-20", "1e-200", "1e-20"),
    ] {
        let (w_near, w_far) = (w(near), w(far));
        let square = |text: &str| Float::parse_decimal(text, Precision::bits(200)).unwrap().square();
        let (c_near, c_far) = (w_near / square(delta_near), w_far / square(delta_far));
        assert!(relative(&c_near, &c_far) < 1e-13, "{near}: {c_near} vs {far}: {c_far}");
    }
    // The values: 9.4595720774407e−102 at φ = 1e−50, 3.1531906924802409140e−202 at π − 1e−100.
    let (code, stdout, stderr) = microslip(&case_args(
        "dissipation",
        &[("--q1", "0.2"), ("--phi", "pi-1e-100"), ("--digits", "20")],
    ));
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.starts_with("W = 3.1531906924802409140e-202"), "{stdout}");
    let (code, stdout, _) = microslip(&[
        "small-amplitude",
        "--rho",
        "0.5",
        "--phi",
        "pi-1e-100",
        "--digits",
        "20",
    ]);
    assert_eq!(code, 0);
    // Near π with ρ < 1, I → −(8/3)ρ²δ²/(1 + ρ) = −4.44…e−201, with a relative correction O(δ²).
    assert!(
        stdout.contains("= -4.4444444444444444444e-201   (proven (rigorous enclosure at "),
        "{stdout}"
    );
    let (code, stdout, _) = microslip(&["series", "--rho", "0.5", "--phi", "pi-1e-100", "--order", "2"]);
    assert_eq!(code, 0);
    assert!(stdout.contains("I_1   = -4.44444444444444e-201"), "{stdout}");
}

/// Where sin²φ underflows f64 (φ below about 1e−154) the default is proven all the same:
/// the segments, up to 1.2e-2, cancel to a W of about φ², which the enclosure resolves.
#[test]
fn a_phase_whose_square_underflows_f64_is_proven_by_default() {
    for (phi, exponent) in [("1e-100", "e-202"), ("1e-160", "e-322"), ("1e-300", "e-602")] {
        let (code, stdout, stderr) = microslip(&case_args("dissipation", &[("--q1", "0.2"), ("--phi", phi)]));
        assert_eq!(code, 0, "{stderr}");
        let first = stdout.lines().next().unwrap();
        assert!(
            first.contains(exponent) && first.contains("15 significant digits, proven"),
            "φ = {phi}: {stdout}"
        );
    }
}

/// `3.141592653589793` is a decimal 1.2246…e−16 below π: W = c_π δ² with c_π from φ = π − 1e−30
/// and δ = π − 3.141592653589793 computed in MPFR here.
#[test]
fn decimal_approximations_of_pi_are_not_pi() {
    let bits = 300;
    let pi = Float::with_val(bits, rug::float::Constant::Pi);
    let tiny = Float::parse_decimal("1e-60", Precision::bits(bits)).unwrap();
    let c_pi = w("pi-1e-30");
    let c_zero = w("1e-30");
    let (c_pi, c_zero) = (c_pi / &tiny, c_zero / &tiny);
    for decimal in ["3.141592653589793", "3.14159265358979323846", "-3.141592653589793"] {
        let value = Float::parse_decimal(decimal, Precision::bits(bits)).unwrap();
        // 3.14… lies just below π; −3.14… just above −π, i.e. just above 0 modulo π.
        let (offset, constant) = if value > 0 {
            (pi.clone() - &value, &c_pi)
        } else {
            (value + &pi, &c_zero)
        };
        let printed = w(decimal);
        assert!(printed != 0, "φ = {decimal} printed W = 0");
        let expected = constant.clone() * offset.square();
        assert!(
            relative(&printed, &expected) < 1e-13,
            "φ = {decimal}: {printed} vs {expected}"
        );
    }
    // φ = 3.141592653589793, 1.2e-16 off π: W = 1.79304398627923e−33.
    let printed = w("3.141592653589793");
    assert!(
        relative(
            &printed,
            &Float::parse_decimal("1.79304398627923e-33", Precision::bits(bits)).unwrap()
        ) < 1e-14
    );
}

#[test]
fn every_exact_zero_prints_at_once_as_exact() {
    let constant = "v'' ≡ 0 on [P_T, P0 + P1]";
    for (overrides, reason) in [
        (vec![("--compliance", "const:c=0.8")], constant),
        (vec![("--compliance", "2*const:c=1")], constant),
        (vec![("--compliance", "const:c=1+const:c=2")], constant),
        (vec![("--compliance", "poly:p0=1,coeffs=1;0;0")], constant),
        (vec![("--compliance", "rational:a=1,b=0,c=1")], constant),
        (vec![("--compliance", "exp:a=0,c=1,d=1")], constant),
        (
            vec![("--compliance", "power:c=1,beta=-1+power:c=-1,beta=-1+const:c=1")],
            constant,
        ),
        (vec![("--q1", "0")], "Q1 = 0"),
        (vec![("--phi", "pi"), ("--q1", "0.4")], "nothing slips"),
        (vec![("--phi", "-2pi"), ("--q1", "0.2")], "nothing slips"),
        (vec![("--phi", "180deg"), ("--q1", "0.2")], "nothing slips"),
    ] {
        for digits in ["", "25", "300"] {
            let mut args = case_args("dissipation", &overrides);
            if !digits.is_empty() {
                args.extend(["--digits".to_string(), digits.to_string()]);
            }
            // A budget no computation could meet: an exact value is not computed.
            args.extend(["--max-seconds".to_string(), "1e-6".to_string()]);
            let (code, stdout, stderr) = microslip(&args);
            assert_eq!(code, 0, "{args:?}: {stderr}");
            assert!(
                stdout.starts_with("W = 0   (exact: ") && stdout.contains(reason),
                "{args:?}: {stdout}"
            );
            args.push("--json".to_string());
            let (_, stdout, _) = microslip(&args);
            let json: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
            assert_eq!(json["W"], "0");
            assert!(json["exact"].as_str().unwrap().contains(reason), "{stdout}");
        }
    }
    // An exact zero outside the theory is still refused.
    let (code, _, stderr) = microslip(&case_args(
        "dissipation",
        &[("--compliance", "const:c=1"), ("--q1", "2")],
    ));
    assert_eq!(code, 2);
    assert!(stderr.contains("gross slip"), "{stderr}");
}

#[test]
fn values_that_are_not_exactly_zero_are_not_printed_as_zero() {
    for overrides in [
        // The coefficients cancel only to 1e−10: v'' = −1e−10·P⁻² ≠ 0.
        vec![(
            "--compliance",
            "power:c=1,beta=-1+power:c=-0.9999999999,beta=-1+const:c=1",
        )],
        // In phase but Q1 > fP1: it slips.
        vec![("--phi", "pi"), ("--q1", "0.5")],
        // φ = 1e−8 (W ≈ 9.46e−18, which f64 printed as 0).
        vec![("--phi", "1e-8"), ("--q1", "0.2")],
        // Q1 tiny but not zero.
        vec![("--q1", "1e-30")],
    ] {
        let (code, stdout, stderr) = microslip(&case_args("dissipation", &overrides));
        assert_eq!(code, 0, "{overrides:?}: {stderr}");
        let value: f64 = stdout.split_whitespace().nth(2).unwrap().parse().unwrap();
        assert!(value != 0.0 && !stdout.contains("exact"), "{overrides:?}: {stdout}");
    }
    // Near in phase the printed W/φ² is the constant 0.0945957207744072… (from φ = 1e−20).
    let (code, stdout, _) = microslip(&case_args("dissipation", &[("--phi", "1e-8"), ("--q1", "0.2")]));
    assert_eq!(code, 0);
    let value: f64 = stdout.split_whitespace().nth(2).unwrap().parse().unwrap();
    let far = w("1e-20");
    let expected = far.to_f64() * 1e40 * 1e-16;
    assert!((value / expected - 1.0).abs() < 1e-7, "{value} vs {expected}");
}

/// v' = a·exp(−P/c) + d at loads of 10⁹ c: every change of v' over the cycle rounds to 0 in
/// f64 (and in MPFR's default exponent range), so f64 gives W = 0, which it printed as a
/// 0 of 4294967295 digits. W is about exp(−2·10⁹): a positive number that is no exact zero.
#[test]
fn a_w_that_rounds_to_zero_in_f64_is_not_printed_as_zero() {
    let overrides = [
        ("--p0", "1e10"),
        ("--p1", "5e9"),
        ("--q1", "5e8"),
        ("--compliance", "exp:a=2.204,c=2.486,d=0.3174"),
        ("--max-seconds", "2"),
    ];
    let (code, stdout, stderr) = microslip(&case_args("dissipation", &overrides));
    assert_eq!(code, 0, "{stderr}");
    // W ≈ 10^(−8.7·10⁸), below f64 and MPFR alike: its decimal exponent is carried apart.
    let w = stdout.split_whitespace().nth(2).unwrap();
    let (mantissa, exponent) = w.split_once('e').unwrap();
    assert!(mantissa.parse::<f64>().unwrap() >= 1.0, "{stdout}");
    assert!(exponent.parse::<i64>().unwrap() < -800_000_000, "{stdout}");
    assert!(stdout.contains("proven") && !stdout.contains("(exact"), "{stdout}");
}

/// The same underflow in the f64 simulation and in the series' partial sums: neither is
/// printed as 0 or as digits it cannot hold; each fails (exit 1) saying what gives W.
#[test]
fn a_w_below_the_range_of_a_command_is_refused_there_not_printed_as_zero() {
    let exponential = |p0: &'static str, p1: &'static str, q1: &'static str| {
        vec![
            ("--p0", p0),
            ("--p1", p1),
            ("--q1", q1),
            ("--compliance", "exp:a=2.204,c=2.486,d=0.3174"),
        ]
    };
    let (code, stdout, stderr) = microslip(&case_args("simulate", &exponential("1e4", "5e3", "5e2")));
    assert_eq!(code, 1, "{stdout}{stderr}");
    assert!(stdout.is_empty() && stderr.contains("rounds to 0 in f64"), "{stderr}");
    let mut beyond = exponential("1e10", "5e9", "5e8");
    beyond.push(("--order", "2"));
    let (code, stdout, stderr) = microslip(&case_args("series", &beyond));
    assert_eq!(code, 1, "{stdout}{stderr}");
    assert!(stdout.is_empty() && stderr.contains("beyond 2^(±2^29)"), "{stderr}");
}

#[test]
fn simulation_of_a_constant_compliance_gives_zero() {
    let (code, stdout, stderr) = microslip(&case_args("simulate", &[("--compliance", "const:c=1")]));
    assert_eq!(code, 0, "{stderr}");
    let value: f64 = stdout.split_whitespace().nth(2).unwrap().parse().unwrap();
    assert_eq!(value, 0.0, "{stdout}");
}

#[test]
fn the_series_prints_its_exact_values_as_exact() {
    // The series of the case P1 = 0.1 with the given Q1, φ, SPEC and order, plus `extra` words.
    let series = |q1: &str, phi: &str, spec: &str, order: &str, extra: &[&str]| {
        let overrides = [
            ("--p1", "0.1"),
            ("--q1", q1),
            ("--phi", phi),
            ("--compliance", spec),
            ("--order", order),
        ];
        let mut args = case_args("series", &overrides);
        args.extend(extra.iter().map(|word| word.to_string()));
        microslip(&args)
    };
    // v' = 2 − 0.5(P − 1) is linear: W_N = W exactly for every N ≥ 1.
    for digits in [&[][..], &["--digits", "25"][..]] {
        let (code, stdout, stderr) = series("0.1", "0.4pi", "poly:p0=1,coeffs=2;-0.5", "3", digits);
        assert_eq!(code, 0, "{stderr}");
        let rows: Vec<&str> = stdout
            .lines()
            .filter(|line| line.trim_start().starts_with(|c: char| c.is_ascii_digit()))
            .collect();
        assert_eq!(rows.len(), 3, "{stdout}");
        for row in rows {
            assert!(
                row.trim_end()
                    .ends_with("0   (exact: v' is a polynomial of degree ≤ N, so the series ends at order N)"),
                "{row}"
            );
        }
    }
    // For v' = 1/P the differences are computed, non-zero, shrinking.
    let (code, stdout, _) = series("0.1", "0.4pi", PERSSON, "2", &["--json"]);
    assert_eq!(code, 0);
    let json: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
    for difference in json["differences"].as_array().unwrap() {
        let value: f64 = difference["value"].as_str().unwrap().parse().unwrap();
        assert!(value != 0.0 && difference["exact"].is_null(), "{stdout}");
    }
    // Exact zeros in case form: constant v', Q1 = 0, in phase with ρ ≤ 1; at once, without --digits.
    for (q1, phi, spec) in [
        ("0.1", "0.4pi", "const:c=1"),
        ("0", "0.4pi", PERSSON),
        ("0.04", "pi", PERSSON),
    ] {
        // A budget no computation could meet: an exact value is not computed.
        let (code, stdout, stderr) = series(q1, phi, spec, "3", &["--max-seconds", "1e-6"]);
        assert_eq!(code, 0, "{stderr}");
        assert!(
            stdout.starts_with("W = 0 and W_N = 0 for N = 1 … 3 (exact: "),
            "{stdout}"
        );
    }
    // I₀ is exact; in phase with ρ ≤ 1 every Iₙ is.
    let (_, stdout, _) = microslip(&["series", "--rho", "2", "--phi", "0.3", "--order", "2"]);
    assert!(
        stdout.contains("I_0   = 0   (exact: the constant term of v' dissipates nothing)"),
        "{stdout}"
    );
    let (_, stdout, _) = microslip(&["series", "--rho", "1", "--phi", "pi", "--order", "2", "--json"]);
    let json: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
    assert!(
        json["values"]
            .as_array()
            .unwrap()
            .iter()
            .all(|v| v["exact"].as_str().is_some()),
        "{stdout}"
    );
}

/// ρ = 1.000001, φ = 1e−6 was refused (I₀'s rounding bound); I₁ is the small-amplitude
/// coefficient, here computed by the exact trigonometric integration and compared with the
/// closed form at 200 bits.
#[test]
fn the_series_at_rho_just_above_one_is_not_refused() {
    for digits in [None, Some("30")] {
        let mut args = vec!["series", "--rho", "1.000001", "--phi", "1e-6", "--order", "2", "--json"];
        if let Some(digits) = digits {
            args.extend(["--digits", digits]);
        }
        let (code, stdout, stderr) = microslip(&args);
        assert_eq!(code, 0, "{stderr}");
        let json: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
        let i1 = Float::parse_decimal(json["coefficients"][1].as_str().unwrap(), Precision::bits(200)).unwrap();
        let p = Precision::bits(200);
        let closed = microslip::exact::closed_form_coefficient(
            &Float::parse_decimal("1.000001", p).unwrap(),
            &Float::parse_decimal("1e-6", p).unwrap(),
        );
        assert!(relative(&i1, &closed) < 1e-12, "{i1} vs {closed}");
    }
}

#[test]
fn phases_written_every_way_give_the_same_w() {
    let printed = |phi: &str| {
        let (code, stdout, stderr) = microslip(&case_args("dissipation", &[("--phi", phi), ("--digits", "30")]));
        assert_eq!(code, 0, "{phi}: {stderr}");
        stdout
            .lines()
            .next()
            .unwrap()
            .split_whitespace()
            .nth(2)
            .unwrap()
            .to_string()
    };
    for group in [
        &[
            "0.4pi", "0.4*pi", "0.4π", "72deg", "72°", "2pi/5", "2*pi/5", "-3pi/5", "1.4pi",
        ][..],
        &["pi/2", "π/2", "0.5pi", "90deg", "-pi/2"],
        &["3pi/4", "0.75pi", "135°", "-pi/4"],
        &["pi/2+1e-3", "0.5pi+0.001", "-pi/2+1e-3"],
    ] {
        let first = printed(group[0]);
        for phi in &group[1..] {
            assert_eq!(printed(phi), first, "{phi} against {}", group[0]);
        }
    }
    for phi in ["pi/0", "72 degrees", "pi*2", "1/2", "pi+-1"] {
        let (code, stdout, stderr) = microslip(&case_args("dissipation", &[("--phi", phi)]));
        assert_eq!(code, 2, "{phi}");
        assert!(stdout.is_empty());
        assert!(
            stderr.lines().count() == 1 && stderr.contains("pi/2") && stderr.contains("72deg"),
            "{phi}: {stderr}"
        );
    }
}

/// Random phases kπ + δ with tiny δ of either sign: W/δ² is the constant of its side (0 for
/// δ > 0, π for δ < 0, whatever k), never 0.
#[test]
fn property_w_over_the_offset_squared_tends_to_a_constant() {
    let near_zero = w("1e-20");
    let near_pi = w("pi-1e-20");
    let scale = Float::parse_decimal("1e40", Precision::bits(200)).unwrap();
    let (c_zero, c_pi) = (near_zero * &scale, near_pi * &scale);
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = |modulus: u64| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state % modulus
    };
    for _ in 0..12 {
        let k = next(9) as i64 - 4;
        let exponent = 25 + next(60);
        let mantissa = 1 + next(9);
        let negative = next(2) == 1;
        let sign = if negative { "-" } else { "+" };
        let phi = format!("{k}pi{sign}{mantissa}e-{exponent}");
        let value = w(&phi);
        assert!(value != 0, "φ = {phi} printed 0");
        let delta = Float::parse_decimal(&format!("{mantissa}e-{exponent}"), Precision::bits(200)).unwrap();
        let ratio = value / delta.square();
        let expected = if negative { &c_pi } else { &c_zero };
        assert!(relative(&ratio, expected) < 1e-13, "φ = {phi}: {ratio} vs {expected}");
    }
}
