//! The small-amplitude series W = λ f² Σ v⁽ⁿ⁺¹⁾(P0)/n! · P1ⁿ⁺² Iₙ(ρ, φ): its coefficients,
//! its truncation orders, its convergence and radius, and the `series` command.

use microslip::compliance::{parse_spec, Polynomial};
use microslip::cycle::LoadCycle;
use microslip::dissipation::{dissipation, four_segment, Options};
use microslip::exact::{closed_form_coefficient, partial_sums, series_coefficients};
use microslip::real::{Precision, Real};
use rug::Float;

mod common;
use common::microslip;

fn float(text: &str, bits: u32) -> Float {
    Float::parse_decimal(text, Precision::bits(bits)).unwrap()
}

fn cycle(p1: &Float, rho: f64, phase_fraction: f64, friction: f64) -> LoadCycle<Float> {
    let bits = p1.prec();
    let f = Float::from_f64(friction, Precision::bits(bits));
    LoadCycle {
        mean_normal_load: float("1", bits),
        normal_amplitude: p1.clone(),
        mean_tangential_load: float("0", bits),
        tangential_amplitude: Float::from_f64(rho, Precision::bits(bits)) * &f * p1,
        phase: Float::pi(Precision::bits(bits)) * Float::from_f64(phase_fraction, Precision::bits(bits)),
        friction: f,
        compliance_ratio: float("1.3", bits),
    }
}

#[test]
fn acceptance_index_one_is_the_small_amplitude_coefficient_and_index_zero_vanishes() {
    let (code, stdout, stderr) = microslip(&[
        "series", "--rho", "2", "--phi", "0.5pi", "--order", "4", "--digits", "35", "--json",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let value: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
    assert_eq!(value["inputs"]["rho"], "2");
    assert_eq!(value["inputs"]["phi"], "0.5pi");
    assert_eq!(value["digits"], 35);
    let coefficients = value["coefficients"].as_array().unwrap();
    assert_eq!(coefficients.len(), 5);
    let (code, stdout, _) = microslip(&["small-amplitude", "--rho", "2", "--phi", "0.5pi", "--digits", "35"]);
    assert_eq!(code, 0);
    let i = stdout.split_whitespace().nth(7).unwrap();
    assert!(stdout.contains("proven (rigorous enclosure at "), "{stdout}");
    assert_eq!(coefficients[1].as_str().unwrap(), i);
    assert_eq!(i, "-8.5865010335991924342112268879281007e0");
    let zero: f64 = coefficients[0].as_str().unwrap().parse().unwrap();
    assert_eq!(zero, 0.0);
    // Without --digits: 15 certified digits, and the f64 values beside them.
    let (code, stdout, stderr) = microslip(&["series", "--rho", "0.5", "--phi", "0.3pi", "--order", "30", "--json"]);
    assert_eq!(code, 0, "{stderr}");
    let value: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
    assert_eq!(value["coefficients"].as_array().unwrap().len(), 31);
    assert_eq!(value["digits"], 15, "{stdout}");
    assert_eq!(value["coefficients_f64"].as_array().unwrap().len(), 31);
}

#[test]
fn series_command_refuses_in_its_own_terms() {
    for (args, expected) in [
        (
            &["series", "--rho", "-1", "--phi", "1", "--order", "3"][..],
            "ρ = Q1/(fP1) must be a positive",
        ),
        (
            &["series", "--rho", "1", "--phi", "x", "--order", "3"][..],
            "the phase φ = 'x' is not a phase: write radians",
        ),
        (
            &["series", "--rho", "1", "--phi", "1", "--order", "0"][..],
            "order of the series",
        ),
        (
            &["series", "--rho", "1", "--phi", "1", "--order", "3", "--digits", "0"][..],
            "digits",
        ),
    ] {
        let (code, stdout, stderr) = microslip(args);
        assert_eq!(code, 2, "{args:?}: {stdout}");
        assert!(stdout.is_empty());
        assert!(
            stderr.contains(expected) && stderr.lines().count() == 1,
            "{args:?}: {stderr}"
        );
    }
}

#[test]
fn case_partial_sums_approach_the_four_segment_w() {
    let mut args = common::case_args("series", &[("--p1", "0.2"), ("--q1", "0.15"), ("--order", "12")]);
    args.push("--json".to_string());
    let (code, stdout, stderr) = microslip(&args);
    assert_eq!(code, 0, "{stderr}");
    let value: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
    let w: f64 = value["W"].as_str().unwrap().parse().unwrap();
    let sums: Vec<f64> = value["partial_sums"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["value"].as_str().unwrap().parse().unwrap())
        .collect();
    assert_eq!(sums.len(), 12);
    // Geometric convergence: each few orders gain a factor ≈ L·P1/P0 ≈ 0.2 or better.
    let errors: Vec<f64> = sums.iter().map(|s| (s - w).abs() / w).collect();
    let shown: Vec<String> = errors.iter().map(|e| format!("{e:.2e}")).collect();
    println!("relative errors of W_1 … W_12: {}", shown.join(" "));
    assert!(errors[0] < 0.2 && errors[5] < 1e-4 && errors[11] < 1e-8, "{errors:?}");
}

#[test]
fn index_one_equals_the_closed_form_and_index_thirty_the_quadrature() {
    let bits = 300;
    for (rho, phi) in [
        ("0.001", "0.3"),
        ("0.7", "2.9"),
        ("1", "1.1"),
        ("40", "0.01"),
        ("1000", "1.5"),
    ] {
        let (rho, phi) = (float(rho, bits), float(phi, bits));
        let values = series_coefficients(&rho, &phi, 1).unwrap();
        let (closed, exact) = (closed_form_coefficient(&rho, &phi), values[1].0.clone());
        let relative = ((exact - &closed) / &closed).abs().to_f64();
        assert!(relative < 1e-80, "ρ = {rho}, φ = {phi}: {relative:e}");
        let bound = values[0].1.clone() * &rho.epsilon_like() * 1024i32;
        assert!(values[0].0.clone().abs() <= bound, "I₀ = {}", values[0].0);
    }
    // I₃₀ against the quadrature of v' = (P − P0)³⁰ on the cycle P1 = f = λ = 1.
    let rho = float("0.8", bits);
    let phi = Float::pi(Precision::bits(bits)) * float("0.35", bits);
    let exact = series_coefficients(&rho, &phi, 30).unwrap()[30].0.clone();
    let one = float("1", bits);
    let cycle = LoadCycle {
        mean_normal_load: float("10", bits),
        normal_amplitude: one.clone(),
        mean_tangential_load: float("0", bits),
        tangential_amplitude: rho.clone(),
        phase: phi,
        friction: one.clone(),
        compliance_ratio: one.clone(),
    };
    let mut coefficients = vec![float("0", bits); 31];
    coefficients[30] = one.clone();
    let monomial = Polynomial {
        reference: float("10", bits),
        coefficients,
    };
    let options = Options {
        check_compliance: false,
        ..Options::default()
    };
    let quadrature = four_segment(&cycle, &monomial, &options).unwrap().total;
    let relative = ((exact.clone() - &quadrature) / &exact).abs().to_f64();
    assert!(relative < 1e-70, "I₃₀ = {exact}: quadrature {quadrature}, {relative:e}");
}

#[test]
fn truncation_at_order_n_leaves_p1_to_the_n_plus_3() {
    let bits = 256;
    for spec in [
        "persson:gamma=1,sigma=0.5",
        "power:c=2,beta=-0.37",
        "exp:a=2,c=0.8,d=0.1",
        "rational:a=0.2,b=1.5,c=0.4",
        "hertz:r=1,estar=3",
    ] {
        let compliance = parse_spec::<Float>(spec, Precision::bits(bits)).unwrap();
        let errors: Vec<Vec<Float>> = ["0.01", "0.005"]
            .iter()
            .map(|p1| {
                let cycle = cycle(&float(p1, bits), 1.7, 0.37, 0.6);
                let w = dissipation(&cycle, compliance.as_ref(), &Options::default())
                    .unwrap()
                    .total;
                let sums = partial_sums(&cycle, compliance.as_ref(), 10).unwrap();
                sums.into_iter().map(|s| (s - &w).abs()).collect()
            })
            .collect();
        for n in [1usize, 2, 5, 10] {
            let order = (errors[0][n - 1].clone() / &errors[1][n - 1]).log2().to_f64();
            println!("{spec}: N = {n}, fitted order {order:.4}");
            assert!((order - (n + 3) as f64).abs() < 0.1, "{spec}, N = {n}: order {order}");
        }
    }
}

/// |Iₙ| ≈ C n^(−α) Lⁿ: L from a least-squares fit of ln|Iₙ| on (1, ln n, n), n = 12 … 30.
fn growth(rho: f64, phase: f64) -> f64 {
    let values = series_coefficients(&rho, &phase, 30).unwrap();
    let rows: Vec<[f64; 4]> = (12..=30)
        .map(|n| [1.0, (n as f64).ln(), n as f64, values[n].0.abs().ln()])
        .collect();
    // Normal equations, 3 × 3, solved by Cramer's rule.
    let mut a = [[0.0; 3]; 3];
    let mut b = [0.0; 3];
    for row in &rows {
        for i in 0..3 {
            b[i] += row[i] * row[3];
            for j in 0..3 {
                a[i][j] += row[i] * row[j];
            }
        }
    }
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let mut third = a;
    for i in 0..3 {
        third[i][2] = b[i];
    }
    (det(third) / det(a)).exp()
}

#[test]
fn coefficients_grow_as_the_reach_of_the_slip_loads_below_p0() {
    // The loads P_S and P_K reach down to P_T = P0 − (σ₊ + σ₋)/(2f): in units of fP1 the
    // coefficients grow as Lⁿ with L = (σ̂₊ + σ̂₋)/2, so for v' = 1/P the series converges
    // for P1/P0 < 1/L, i.e. exactly while P_T > 0.
    // (Where L is close to 1 the loads P0 ± P1 compete with it at n ≤ 30: not fitted here.)
    for (rho, fraction) in [(0.5, 0.3), (1.0, 0.5), (2.0, 0.25), (0.6, 0.5), (3.0, 0.6)] {
        let phase = fraction * std::f64::consts::PI;
        let (c, s) = (phase.cos(), phase.sin());
        let reach = ((rho * c + 1.0f64).hypot(rho * s) + (rho * c - 1.0f64).hypot(rho * s)) / 2.0;
        let fitted = growth(rho, phase);
        println!("ρ = {rho}, φ = {fraction}π: fitted L = {fitted:.5}, (σ̂₊ + σ̂₋)/2 = {reach:.5}");
        assert!(
            (fitted / reach - 1.0).abs() < 0.02,
            "ρ = {rho}, φ = {fraction}π: L {fitted} against {reach}"
        );
    }
}

#[test]
fn every_family_gives_derivatives_of_every_order() {
    let bits = 200;
    let p = Precision::bits(bits);
    let load = float("0.8", bits);
    for spec in [
        "persson:gamma=1.3,sigma=0.4",
        "power:c=2,beta=-0.37",
        "hertz:r=1,estar=3",
        "poly:p0=1,coeffs=2;0.5;-0.1;0.03",
        "exp:a=2,c=0.8,d=0.1",
        "rational:a=0.2,b=1.5,c=0.4",
        "persson:gamma=1,sigma=1 + exp:a=1,c=2,d=0",
    ] {
        let compliance = parse_spec::<Float>(spec, p).unwrap();
        assert_eq!(
            compliance.derivative(1, &load).unwrap(),
            compliance.slope(&load),
            "{spec}"
        );
        let curvature = compliance.curvature(&load);
        let second: Float = compliance.derivative(2, &load).unwrap();
        assert!((second - &curvature).abs() <= curvature.abs() * 1e-55 + 1e-55, "{spec}");
        // v⁽ⁿ⁺¹⁾ against the central difference of v⁽ⁿ⁾ with h = 1e−20 (error ~ h² and ε/h).
        let h = float("1e-20", bits);
        for n in [2usize, 5, 12] {
            let up = compliance.derivative(n, &(load.clone() + &h)).unwrap();
            let down = compliance.derivative(n, &(load.clone() - &h)).unwrap();
            let difference: Float = (up - down) / (h.clone() * 2i32);
            let exact = compliance.derivative(n + 1, &load).unwrap();
            let scale: Float = exact
                .clone()
                .abs()
                .max_of(&compliance.derivative(n, &load).unwrap().abs())
                + 1e-30;
            assert!(
                ((difference - &exact).abs() / scale).to_f64() < 1e-30,
                "{spec}: order {}",
                n + 1
            );
        }
    }
}

/// Gate row 7c over many seeds (by hand: `cargo test --release --test series
/// gate_row_7c -- --ignored --nocapture`, about 4 minutes): the fitted truncation orders stay
/// within the row's tolerance for every seed, including phases near π where the order is
/// approached slowly.
#[test]
#[ignore]
fn gate_row_7c_holds_for_forty_seeds() {
    let mut worst = 0.0f64;
    for seed in 0..40u64 {
        let report = microslip::verify::claims::series_claim(seed + 18, 20);
        println!("seed {seed}: worst {:.4}, {}", report.worst_error, report.note);
        assert!(report.passed, "seed {seed}: {}", report.note);
        worst = worst.max(report.worst_error);
    }
    println!("worst fitted order − (N + 3) over 800 cases: {worst:.4}");
}

/// The phase k·π + `offset` (radians) at `bits`, computed directly (not reduced).
fn phase_at(k: i64, offset: &str, bits: u32) -> Float {
    Float::with_val(bits, rug::float::Constant::Pi) * k + float(offset, bits)
}

/// The phase as the command line writes it.
fn phase_text(k: i64, offset: &str) -> String {
    match (k, offset.strip_prefix('-')) {
        (0, _) => offset.to_string(),
        (_, Some(magnitude)) => format!("{k}pi-{magnitude}"),
        _ => format!("{k}pi+{offset}"),
    }
}

/// Whether `reference` lies in an answer's enclosure and rounds to the digits printed.
fn encloses(answer: &microslip::answer::Answer, reference: &Float) -> Result<(), String> {
    let (lower, upper) = answer
        .value
        .enclosure
        .as_ref()
        .ok_or_else(|| format!("no enclosure: {answer:?}"))?;
    let bits = reference.prec();
    if !(float(lower, bits) <= *reference && *reference <= float(upper, bits)) {
        return Err(format!("{reference} outside [{lower}, {upper}]"));
    }
    let printed = answer.value.decimal.to_string();
    let digits = answer.value.digits();
    if reference.to_scientific(digits as usize) != printed {
        return Err(format!("{reference} does not round to {printed}"));
    }
    Ok(())
}

/// (ρ, k, offset) cases: random ordinary ones, φ within 1e−100 of 0 and of π (either side),
/// ρ near 1, ρ → 0 and large ρ.
fn shapes() -> Vec<(String, i64, String)> {
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = |modulus: u64| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state % modulus
    };
    let mut cases: Vec<(String, i64, String)> = [
        ("0.5", 1, "-1e-100"),
        ("0.5", 0, "1e-100"),
        ("2", 0, "-1e-100"),
        ("3", 1, "1e-100"),
        ("1.000001", 0, "1e-6"),
        ("0.999999999999", 0, "0.7"),
        ("1", 0, "1.5707963267948966"),
        ("1e-12", 0, "0.9"),
        ("1e-200", 1, "-0.3"),
        ("1e12", 0, "2.5"),
        ("1", 0, "3.141592653589793"),
    ]
    .iter()
    .map(|(rho, k, offset)| (rho.to_string(), *k, offset.to_string()))
    .collect();
    for _ in 0..12 {
        let rho = format!("{}.{}e{}", 1 + next(9), next(1000), next(7) as i64 - 3);
        let k = next(5) as i64 - 2;
        let offset = format!("{}0.{:03}", if next(2) == 1 { "-" } else { "" }, 1 + next(999));
        cases.push((rho, k, offset));
    }
    cases
}

/// I(ρ, φ) and I₁ … I₄ as printed at 30 digits enclose the closed form and the exact
/// trigonometric integrals evaluated in MPFR at 2000 bits on the phase kπ + x itself.
#[test]
fn coefficient_enclosures_contain_2000_bit_references() {
    use microslip::answer::series::{coefficient_answer, coefficient_answers};
    let bits = 2000;
    let budget = std::time::Duration::from_secs(60);
    for (rho, k, offset) in shapes() {
        let phi = phase_text(k, &offset);
        let (rho_value, phi_value) = (float(&rho, bits), phase_at(k, &offset, bits));
        let i = coefficient_answer(&rho, &phi, Some(30), budget).unwrap_or_else(|e| panic!("{rho}, {phi}: {e}"));
        let reference = closed_form_coefficient(&rho_value, &phi_value);
        encloses(&i, &reference).unwrap_or_else(|e| panic!("I({rho}, {phi}): {e}"));
        assert_eq!(i.value.digits(), 30, "I({rho}, {phi})");
        #[cfg(feature = "certified")]
        assert!(i.provenance.is_proven(), "I({rho}, {phi}): {:?}", i.provenance);
        let answers =
            coefficient_answers(&rho, &phi, 4, Some(30), budget).unwrap_or_else(|e| panic!("{rho}, {phi}: {e}"));
        let references = series_coefficients(&rho_value, &phi_value, 4).unwrap();
        assert_eq!(answers[0].provenance.key(), "exact");
        for n in 1..=4 {
            encloses(&answers[n], &references[n].0).unwrap_or_else(|e| panic!("I_{n}({rho}, {phi}): {e}"));
            #[cfg(feature = "certified")]
            assert!(answers[n].provenance.is_proven(), "I_{n}({rho}, {phi})");
        }
    }
}

/// A case's partial sums at 30 digits enclose the sums evaluated in MPFR at 2000 bits, for
/// several compliance families and phases near 0 and π.
#[test]
fn partial_sum_enclosures_contain_2000_bit_references() {
    use microslip::answer::series::partial_sum_answers;
    use microslip::case::{Case, CaseText};
    let budget = std::time::Duration::from_secs(60);
    for (spec, phi) in [
        ("persson:gamma=1,sigma=1", "0.4pi"),
        ("power:c=1,beta=-0.5", "pi-1e-100"),
        ("rational:a=1,b=0.5,c=1", "1e-100"),
        ("exp:a=1,c=1,d=1", "3.141592653589793"),
        ("persson:gamma=1,sigma=1+2*power:c=1,beta=-0.5", "2.9"),
    ] {
        let case = CaseText {
            p0: "1".into(),
            p1: "0.2".into(),
            q0: "0.05".into(),
            q1: "0.1".into(),
            phi: phi.into(),
            friction: "1".into(),
            lambda: Some("1.3".into()),
            nu: None,
            compliance: spec.into(),
        };
        let answers = partial_sum_answers(&case, 4, Some(30), budget).unwrap_or_else(|e| panic!("{spec}, {phi}: {e}"));
        let Case { cycle, compliance } = case.read::<Float>(Precision::bits(2000)).unwrap();
        let references = partial_sums(&cycle, compliance.as_ref(), 4).unwrap();
        for (n, (sum, reference)) in answers.sums.iter().zip(&references).enumerate() {
            encloses(sum, reference).unwrap_or_else(|e| panic!("W_{} ({spec}, {phi}): {e}", n + 1));
            #[cfg(feature = "certified")]
            assert!(sum.provenance.is_proven(), "W_{} ({spec}, {phi})", n + 1);
        }
    }
}

/// Exact values print as exact, with no digits computed, at any --digits.
#[test]
fn exact_values_print_as_exact_at_500_digits() {
    let exact_rows = |stdout: &str| stdout.lines().filter(|line| line.contains("(exact: ")).count();
    let (code, stdout, stderr) = microslip(&["small-amplitude", "--rho", "1", "--phi", "pi", "--digits", "500"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("= 0   (exact: in phase"), "{stdout}");
    let (code, stdout, stderr) = microslip(&[
        "series", "--rho", "0.3", "--phi", "-2pi", "--order", "5", "--digits", "500",
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(exact_rows(&stdout), 6, "{stdout}");
    for overrides in [
        &[("--compliance", "const:c=0.8")][..],
        &[("--q1", "0")][..],
        &[("--phi", "pi"), ("--q1", "0.3")][..],
    ] {
        let mut args = common::case_args("series", overrides);
        args.extend(["--order", "3", "--digits", "500"].map(String::from));
        let (code, stdout, stderr) = microslip(&args);
        assert_eq!(code, 0, "{stderr}");
        assert!(
            stdout.starts_with("W = 0 and W_N = 0 for N = 1 … 3 (exact: "),
            "{stdout}"
        );
    }
    // ρ > 1 in phase slips: its Iₙ are computed, never printed as exact. At ρ = 2, φ = π the
    // closed form has σ₊ = 3, σ₋ = 1, S² − 4 = 12, Z = 25 − 165 + 239 − 3 = 96 and sin φ = 0,
    // so I₁ = −12·96/(96·1·3) = −4 exactly.
    let (code, stdout, _) = microslip(&["series", "--rho", "2", "--phi", "pi", "--order", "2", "--digits", "40"]);
    assert_eq!(code, 0);
    assert_eq!(exact_rows(&stdout), 1, "{stdout}");
    assert!(
        stdout.contains("I_1   = -4.000000000000000000000000000000000000000e0   (proven"),
        "{stdout}"
    );
}

/// The reproducers (small-amplitude's is in tests/exact_values.rs): proven digits,
/// not zeros, not refused.
#[test]
fn the_reproducers_give_proven_digits() {
    let (code, stdout, _) = microslip(&["series", "--rho", "0.5", "--phi", "pi-1e-100", "--order", "2", "--json"]);
    assert_eq!(code, 0);
    let json: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
    for n in 1..=2 {
        let value = &json["values"][n];
        let printed: f64 = value["value"].as_str().unwrap().parse().unwrap();
        assert!(printed != 0.0 && value["provenance"] == "certified", "{stdout}");
    }
    let (code, stdout, stderr) = microslip(&["series", "--rho", "1.000001", "--phi", "1e-6", "--order", "2"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("I_1   = -3.68157194030210e-6   (proven"), "{stdout}");
}

/// A refused ρ is quoted as the double nearest the exact decimal (−1/5 reads −2e-1), not
/// rounded towards zero.
#[test]
fn a_refused_ratio_is_quoted_as_its_nearest_double() {
    use microslip::answer::series::coefficient_answers;
    let error = coefficient_answers("-0.2", "1", 2, None, std::time::Duration::from_secs(10)).unwrap_err();
    assert!(error.to_string().ends_with("(got -2e-1)"), "{error}");
}
