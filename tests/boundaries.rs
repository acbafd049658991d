//! The boundaries of the theory (separation, gross slip, λ, ν) decided exactly from the
//! decimals as written, admissibility (v' > 0, v'' ≤ 0) proven, and budgets that run out
//! never passed off as answers: the f64 default and `--digits` make the same decision.

mod common;

use std::time::Duration;

use common::case;
use microslip::answer::dissipation::dissipation_report;
use microslip::answer::Provenance;
use microslip::answer::{DissipationAnswerError, ExitStatus};
use microslip::case::InputError;
use microslip::compliance::AdmissibilityError;
use microslip::cycle::CycleError;
use microslip::dissipation::DissipationError;

const BUDGET: Duration = Duration::from_secs(60);

/// W in the default mode and at `--digits 20`, each as (printed W, proven?).
fn both_modes(text: &microslip::case::CaseText) -> [Result<(String, bool), DissipationAnswerError>; 2] {
    [None, Some(20)].map(|digits| {
        dissipation_report(text, digits, BUDGET).map(|report| {
            let proven = report.answer.provenance.is_proven();
            (report.answer.value.decimal.to_string(), proven)
        })
    })
}

/// Whether `printed`, a decimal of n significant digits, is `proven` (a longer decimal)
/// rounded to n digits.
fn rounds_to(printed: &str, proven: &str) -> bool {
    let mantissa = printed.split(['e', 'E']).next().unwrap();
    let n = mantissa.chars().filter(char::is_ascii_digit).count();
    let exact = rug::Float::with_val(256, rug::Float::parse(proven).unwrap());
    let rounded = rug::Float::with_val(256, rug::Float::parse(exact.to_string_radix(10, Some(n))).unwrap());
    rounded == rug::Float::with_val(256, rug::Float::parse(printed).unwrap())
}

fn cycle_error(result: &Result<(String, bool), DissipationAnswerError>) -> Option<&CycleError> {
    match result {
        Err(DissipationAnswerError::Input(InputError::Cycle(error))) => Some(error),
        _ => None,
    }
}

/// Both modes answer, the proven W begins with `expected`, and the default prints it
/// rounded.
fn assert_answered(text: &microslip::case::CaseText, expected: &str) {
    let [default, digits] = both_modes(text);
    let (default, digits) = (
        default.unwrap_or_else(|e| panic!("default refused {text:?}: {e}")),
        digits.unwrap_or_else(|e| panic!("--digits refused {text:?}: {e}")),
    );
    assert!(digits.1, "--digits 20 is proven: {digits:?}");
    assert!(digits.0.starts_with(expected), "{digits:?}");
    assert!(rounds_to(&default.0, &digits.0), "{default:?} against {digits:?}");
}

/// Both modes refuse with the same cycle error, which `check` accepts.
fn assert_refused(text: &microslip::case::CaseText, check: impl Fn(&CycleError) -> bool) {
    for result in both_modes(text) {
        let error = cycle_error(&result).unwrap_or_else(|| panic!("{text:?} should be refused, got {result:?}"));
        assert!(check(error), "{text:?}: {error}");
    }
}

#[test]
fn separation_is_decided_on_the_decimals_not_their_f64_copies() {
    // P1 = 0.99999999999999999 rounds to 1 in f64; the exact cycle keeps 1e-17 from separation.
    let near = case().p1("0.99999999999999999").q1("1e-25").phi("pi/2");
    assert_answered(&near.clone().text(), "1.51348375045834");
    for (p1, inside) in [
        ("0.9999999999999999999999999999999999999999", true),
        ("1.0000000000000000000000000000000000000001", false),
        ("1", false),
    ] {
        let text = case().p1(p1).q1("1e-45").phi("pi/2").text();
        if inside {
            for result in both_modes(&text) {
                assert!(result.is_ok(), "{p1}: {result:?}");
            }
        } else {
            assert_refused(&text, |e| matches!(e, CycleError::Separation { .. }));
        }
    }
}

#[test]
fn a_phase_at_the_edge_of_its_reading_below_a_multiple_of_pi_is_proven() {
    // 3π/2 is read as the offset −π/2 below 2π, the edge of the offsets [−π/2, 0) read below
    // π: both readings give π/2 there. Each of these cycles mirrors the one at π/2 (Q at −θ),
    // with the same W.
    let [_, mirrored] = both_modes(&case().phi("pi/2").text());
    let mirrored = mirrored.unwrap().0;
    for phi in ["3pi/2", "-pi/2", "1.5pi", "7pi/2", "-5pi/2"] {
        let [default, digits] = both_modes(&case().phi(phi).text());
        let (default, digits) = (default.unwrap(), digits.unwrap());
        assert!(default.1 && digits.1, "{phi}: {default:?} {digits:?}");
        assert_eq!(digits.0, mirrored, "{phi}");
        assert!(
            rounds_to(&default.0, &digits.0),
            "{phi}: {default:?} against {digits:?}"
        );
    }
}

#[test]
fn a_refusal_quotes_the_exact_margin_not_one_rounded_towards_zero() {
    // 1 − 1.2 = −1/5 exactly: the message reads −2e-1 (the double nearest), in both modes.
    let text = case().p1("1.2").text();
    for result in both_modes(&text) {
        let message = result.unwrap_err().to_string();
        assert!(
            message.contains("P0 − P1 = -2e-1 ≤ 0 (P0 = 1e0, P1 = 1.2e0)"),
            "{message}"
        );
    }
    let text = case().p1("0.4").q1("0.5").friction("-0.3").text();
    for result in both_modes(&text) {
        let message = result.unwrap_err().to_string();
        assert!(message.contains("f = -3e-1"), "{message}");
    }
}

#[test]
fn gross_slip_is_decided_exactly_on_both_sides_of_the_cone() {
    // A margin of +5.2e-19 fP0, which f64 rounds away.
    let thin = case()
        .p1("0.99999933332014679")
        .q1("6.6667985320947576e-10")
        .phi("pi+1e-12")
        .friction("0.001")
        .lambda("2");
    assert_answered(&thin.text(), "4.5918722769865");
    // At φ = π/2, cos φ = 0 exactly: max(Q − fP) = Q0 − fP0 + √(Q1² + f²P1²) = Q0 − 0.5.
    let at = |q0: &str| case().p1("0.3").q1("0.4").phi("pi/2").q0(q0).text();
    for result in both_modes(&at("0.4999999999999999999999999999999999999999")) {
        assert!(result.is_ok(), "{result:?}");
    }
    for q0 in [
        "0.5000000000000000000000000000000000000001",
        "0.5",
        "-0.5000000000000000000000000000000000000001",
    ] {
        assert_refused(&at(q0), |e| matches!(e, CycleError::GrossSlip { .. }));
    }
    // At φ = π/3, cos φ = 1/2 exactly: σ² = Q1² + f²P1² − Q1 f P1 = 0.16 + 0.09 − 0.12 = 0.13.
    let third = |q0: &str| case().p1("0.3").q1("0.4").phi("pi/3").q0(q0).text();
    let sigma = 0.13f64.sqrt();
    assert!(both_modes(&third(&format!("{:.12}", 1.0 - sigma - 1e-9)))
        .iter()
        .all(Result::is_ok));
    assert_refused(&third(&format!("{:.12}", 1.0 - sigma + 1e-9)), |e| {
        matches!(e, CycleError::GrossSlip { sign: "+", .. })
    });
}

#[test]
fn the_compliance_ratio_and_poissons_ratio_are_decided_exactly() {
    for nu in [
        "0.66666666666666666667",
        "0.6666666666666666666666666666666666666667",
        "-1e-40",
    ] {
        assert_refused(&case().nu(nu).text(), |e| {
            matches!(e, CycleError::PoissonRatioOutOfRange { .. })
        });
    }
    for nu in ["0.66666666666666666666", "0", "0.5"] {
        assert!(both_modes(&case().nu(nu).text()).iter().all(Result::is_ok), "ν = {nu}");
    }
    for lambda in [
        "2.0000000000000000000000000000000000000001",
        "0.9999999999999999999999999999999999999999",
    ] {
        assert_refused(&case().lambda(lambda).text(), |e| {
            matches!(e, CycleError::ComplianceRatioOutOfRange { .. })
        });
    }
    for lambda in ["1.9999999999999999999999999999999999999999", "2", "1"] {
        assert!(
            both_modes(&case().lambda(lambda).text()).iter().all(Result::is_ok),
            "λ = {lambda}"
        );
    }
}

#[test]
fn a_convex_compliance_is_refused_in_both_modes_naming_a_load() {
    for spec in [
        "poly:p0=1,coeffs=2;1e-40",
        "power:c=1,beta=1e-300",
        "power:c=1,beta=-2+power:c=-1.00001,beta=-2",
    ] {
        for result in both_modes(&case().compliance(spec).text()) {
            let refused = matches!(
                result,
                Err(DissipationAnswerError::Dissipation(DissipationError::Compliance(
                    AdmissibilityError::PositiveCurvature { .. } | AdmissibilityError::NonPositiveSlope { .. }
                )))
            );
            assert!(refused, "{spec}: {result:?}");
        }
    }
}

#[test]
fn a_convex_compliance_is_refused_on_paths_and_by_the_simulation_however_small_its_convex_term() {
    // Their f64 checks sample v'' with a tolerance of a few ulps of v'/P, which a convex
    // term of 1e-40 passes: `path` printed W = -2.5e-42 "proven" and `simulate` (of a case
    // or of a path file) blamed f64.
    let scratch = common::Scratch::new("convex-paths");
    let file = |name: &str, text: &str| {
        let path = scratch.join(name);
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_string()
    };
    let constant_q = file(
        "q.csv",
        "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,0\n1,0,0,0.3,0\n2,0,0,0.1,0.05\n",
    );
    let varying = file(
        "pq.csv",
        "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,0\n1,0.3,0,0.3,0.1\n2,0,0.1,0.1,0.05\n",
    );
    let sliding = file(
        "u.csv",
        "k,P_cos,P_sin,u_cos,u_sin\n0,1,0,0,0\n1,0,0,3,0\n2,0,0,1,0.5\n",
    );
    let contact = ["--friction", "1", "--lambda", "1", "--compliance"];
    let runs: Vec<Vec<&str>> = vec![
        vec!["path", "--harmonics", &constant_q],
        vec!["path", "--harmonics", &constant_q, "--digits", "20"],
        vec!["path", "--harmonics", &varying],
        vec!["path", "--harmonics", &sliding, "--drive", "displacement"],
        vec!["simulate", "--p0", "1", "--p1", "0.3", "--q1", "0.3", "--phi", "1"],
        // The simulation of a path file proves it on the loads its elements slip over.
        vec!["simulate", "--harmonics", &constant_q, "--tolerance", "1e-2"],
        vec!["simulate", "--harmonics", &varying, "--tolerance", "1e-2"],
        vec![
            "simulate",
            "--harmonics",
            &sliding,
            "--drive",
            "displacement",
            "--tolerance",
            "1e-2",
        ],
    ];
    for run in &runs {
        for (spec, admissible) in [("poly:p0=1,coeffs=2;1e-40", false), ("poly:p0=1,coeffs=2;-1e-1", true)] {
            let args: Vec<&str> = run.iter().chain(&contact).copied().chain([spec]).collect();
            let (code, stdout, stderr) = common::microslip(&args);
            if admissible {
                assert_eq!(code, 0, "{args:?}: {stderr}");
                assert!(!stdout.contains("W = -"), "{args:?}: {stdout}");
            } else {
                assert_eq!(code, 2, "{args:?}: {stdout}");
                assert!(
                    stdout.is_empty() && stderr.contains("v''(P) = 1.0000e-40 > 0 at P = "),
                    "{args:?}: {stderr}"
                );
                assert_eq!(stderr.lines().count(), 1, "{stderr}");
            }
        }
    }
}

#[test]
fn a_paths_boundaries_are_decided_on_its_decimals_not_their_f64_copies() {
    let scratch = common::Scratch::new("path-boundaries");
    let harmonics = |name: &str, p1: &str, q1: &str| {
        let path = scratch.join(name);
        let text = format!("k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,0\n1,{p1},0,{q1},0\n");
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_string()
    };
    let run_as = |command: &str, file: &str, ratio: &[&str]| {
        persson_path_file(command, file, &[&["--friction", "1"], ratio].concat())
    };
    let run = |file: &str, ratio: &[&str]| run_as("path", file, ratio);
    let tiny = "0000000000000000000000000000000000000001";
    let below_one = "0.9999999999999999999999999999999999999999";
    let lambda = ["--lambda", "1"];
    // Outside by 1e-40: refused (exit 2), quoting the exact margin.
    for (file, quoted) in [
        (
            harmonics("separates.csv", &format!("1.{tiny}"), "0.1"),
            "P = -1e-40 ≤ 0",
        ),
        (
            harmonics("slides.csv", "0", &format!("1.{tiny}")),
            "+Q − fP = 1e-40 ≥ 0",
        ),
    ] {
        // The simulation of a path file decides them alike.
        for command in ["path", "simulate"] {
            let (code, stdout, stderr) = run_as(command, &file, &lambda);
            assert!(
                code == 2 && stdout.is_empty() && stderr.contains(quoted),
                "{command} {file}: {code} {stderr}"
            );
        }
    }
    // Inside by 1e-40, where the f64 copy reaches the boundary: never refused as outside; the
    // outputs, computed in f64, fail (exit 1) saying why.
    for file in [
        harmonics("keeps-contact.csv", below_one, "1e-50"),
        harmonics("sticks.csv", "0", below_one),
    ] {
        for command in ["path", "simulate"] {
            let (code, stdout, stderr) = run_as(command, &file, &lambda);
            assert!(code == 1 && stdout.is_empty(), "{command} {file}: {code} {stderr}");
            assert!(
                stderr.contains("rounded to f64 the path crosses a boundary that its decimals keep off"),
                "{stderr}"
            );
        }
    }
    // λ and ν: refused by their decimals, which the refusal quotes.
    let ordinary = harmonics("ordinary.csv", "0.3", "0.2");
    for ratio in [
        ["--lambda", "2.0000000000000000000000000000000000000001"],
        ["--lambda", below_one],
        ["--nu", "0.66666666666666666667"],
    ] {
        let (code, stdout, stderr) = run(&ordinary, &ratio);
        assert!(
            code == 2 && stdout.is_empty() && stderr.contains(ratio[1]),
            "{ratio:?}: {code} {stderr}"
        );
    }
    // ν just below 2/3 (λ just below 2) is inside, and at constant P proven.
    let constant_p = harmonics("constant-p.csv", "0", "0.3");
    for nu in [
        "0.66666666666666666666",
        "0.6666666666666666666666666666666666666666666",
    ] {
        let (code, stdout, stderr) = run(&constant_p, &["--nu", nu]);
        assert!(
            code == 0 && stdout.contains("certified: proven"),
            "{nu}: {code} {stdout} {stderr}"
        );
    }
}

#[test]
fn a_cancelling_but_concave_sum_is_admissible_and_proven() {
    // v' = 1e-5/P², concave, written as a difference of two steep terms.
    let text = case().compliance("power:c=1,beta=-2+power:c=-0.99999,beta=-2").text();
    let single = case().compliance("power:c=0.00001,beta=-2").text();
    let [_, digits] = both_modes(&text);
    let [_, reference] = both_modes(&single);
    let (digits, reference) = (digits.unwrap(), reference.unwrap());
    assert!(digits.1 && reference.1);
    assert_eq!(digits.0, reference.0);
}

#[test]
fn a_budget_that_runs_out_is_a_failure_not_an_unproven_answer() {
    // A case that once answered by agreement after 1.6 s of a 5 s budget, with exit 0.
    let text = case()
        .p0("1e-300")
        .p1("7.2659167100239962e-301")
        .q1("5.8415471045620484e-301")
        .phi("0.2548pi")
        .friction("1.682")
        .lambda("1.3287")
        .compliance("power:c=1,beta=-1+power:c=-1,beta=-1+exp:a=1.05e-07,c=1e-300,d=0")
        .text();
    // Too little time for 30 proven digits: a failure (exit 1), never agreement.
    match dissipation_report(&text, Some(30), Duration::from_millis(300)) {
        Err(error) => assert!(error.is_failure(), "{error}"),
        Ok(report) => assert!(
            report.answer.provenance.is_proven() || matches!(report.answer.provenance, Provenance::Exact(_)),
            "{:?}",
            report.answer.provenance
        ),
    }
}

/// `command` (`path` or `simulate`) on the harmonics `file` with Persson's compliance and
/// `options` (the contact's among them): exit code, stdout, stderr.
fn persson_path_file(command: &str, file: &str, options: &[&str]) -> (i32, String, String) {
    let mut args = vec![command, "--harmonics", file, "--compliance", "persson:gamma=1,sigma=1"];
    args.extend_from_slice(options);
    common::microslip(&args)
}

#[test]
fn a_paths_refusal_quotes_only_digits_that_its_enclosure_proves() {
    // The margins of 128-bit balls, quoted by their middles, read 9.999999999999992e-24 for
    // 1e-23 and 1.0999999999999997e-23 for 1.1e-23; and they were of Q/f − P, not Q − fP.
    let scratch = common::Scratch::new("path-quotes");
    let zeros = "0".repeat(22);
    for (multiple, friction) in [
        (1, "1"),
        (3, "1"),
        (7, "1"),
        (11, "0.5"),
        (13, "1"),
        (17, "0.5"),
        (123_456_789, "1"),
    ] {
        let file = scratch.join(format!("slides-{multiple}.csv"));
        // Q1 − f = `multiple` units of its last digit, at P = 1.
        let (q1, places) = match friction {
            "1" => (format!("1.{zeros}{multiple}"), 22),
            _ => (format!("0.5{zeros}{multiple}"), 23),
        };
        std::fs::write(&file, format!("k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,0\n1,0,0,{q1},0\n")).unwrap();
        let excess: f64 = format!("{multiple}e-{}", places + multiple.to_string().len())
            .parse()
            .unwrap();
        for command in ["path", "simulate"] {
            let (code, _, stderr) = persson_path_file(
                command,
                file.to_str().unwrap(),
                &["--friction", friction, "--lambda", "1"],
            );
            assert!(
                code == 2 && stderr.contains(&format!("+Q − fP = {excess:e} ≥ 0")),
                "{command} {q1}: {code} {stderr}"
            );
        }
    }
}

#[test]
fn a_paths_boundaries_are_not_decided_on_balls_past_the_budget() {
    // Kept off separation by 1e-60: f64 intervals cannot tell, balls can.
    let scratch = common::Scratch::new("path-boundary-budget");
    let file = scratch.join("near-separation.csv");
    let p1 = format!("0.{}", "9".repeat(60));
    std::fs::write(
        &file,
        format!("k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,0\n1,{p1},0,1e-70,0\n"),
    )
    .unwrap();
    let file = file.to_str().unwrap();
    let run = |budget: &str| {
        persson_path_file(
            "path",
            file,
            &["--friction", "1", "--lambda", "1", "--max-seconds", budget],
        )
    };
    let (code, stdout, stderr) = run("0.000001");
    assert!(code == 1 && stdout.is_empty(), "{code} {stderr}");
    assert!(
        stderr.contains("the time budget ran out before the path's boundaries were decided"),
        "{stderr}"
    );
    // With time, balls decide it inside; its f64 copy separates, which the outputs cannot follow.
    let (code, _, stderr) = run("60");
    assert!(
        code == 1 && stderr.contains("rounded to f64 the path crosses"),
        "{code} {stderr}"
    );
}

#[test]
fn the_default_carries_the_rounding_of_a_cancelling_compliance() {
    // f64 once printed 1.23418224274e-5 and 5.89194115377e-7 here: the last digit wrong.
    for spec in [
        "power:c=1,beta=-2+power:c=-0.99999,beta=-2",
        "-0.99999*hertz:r=1,estar=1+hertz:r=1,estar=1",
    ] {
        let [default, digits] = both_modes(&case().compliance(spec).text());
        let (default, digits) = (default.unwrap(), digits.unwrap());
        assert!(digits.1, "{spec}: {digits:?}");
        assert!(
            rounds_to(&default.0, &digits.0),
            "{spec}: {default:?} against {digits:?}"
        );
    }
}
