//! The default answer is proven: on the reproducers of wrong f64 digits and on random rows of
//! the hard classes (cancelling sums, steep laws near separation, exponentials across many
//! decay lengths, ordinary cycles), every W printed without `--digits` comes from an enclosure
//! and is the 30-digit W rounded to its digits (proofs/printing.md; the 4,000-row run is
//! `benches/default_rows.py`).

mod common;

use std::time::Duration;

use common::Draws;
use microslip::answer::dissipation::{dissipation_report, DEFAULT_DIGITS, DEFAULT_LEAST_DIGITS};
use microslip::case::CaseText;
use rug::ops::Pow;
use rug::Float;

const BUDGET: Duration = Duration::from_secs(120);

/// Whether `printed` (N significant digits) is `reference` rounded to N digits: within half a
/// unit of its last digit.
fn rounds_to(printed: &str, reference: &str) -> bool {
    let read = |text: &str| Float::with_val(256, Float::parse(text).unwrap());
    let (mantissa, exponent) = printed.split_once('e').unwrap();
    let digits = mantissa.replace(['-', '.'], "").len() as i32;
    let half_unit = Float::with_val(256, 10).pow(exponent.parse::<i32>().unwrap() - digits + 1) / 2u32;
    (read(printed) - read(reference)).abs() <= half_unit
}

/// The default W of `case`: proven, 12 to 15 digits, and the 30-digit W rounded to them.
fn check(case: &CaseText) -> Result<(), String> {
    let default = dissipation_report(case, None, BUDGET).map_err(|e| format!("{case:?}: {e}"))?;
    let answer = &default.answer;
    if !answer.provenance.is_proven() || !(DEFAULT_LEAST_DIGITS..=DEFAULT_DIGITS).contains(&answer.digits()) {
        return Err(format!("{case:?}: {} digits, {}", answer.digits(), answer.provenance));
    }
    let reference = dissipation_report(case, Some(30), BUDGET).map_err(|e| format!("{case:?} at 30: {e}"))?;
    let (printed, truth) = (default.total(), reference.total());
    match printed == "0" || rounds_to(&printed, &truth) {
        true => Ok(()),
        false => Err(format!("{case:?}: printed {printed}, 30 digits give {truth}")),
    }
}

#[test]
fn the_reproducers_of_wrong_f64_digits_print_right_proven_digits() {
    let readme = || common::case().q1("0.5").phi("0.4pi");
    let cases = [
        (
            readme().compliance("power:c=1,beta=-2+power:c=-0.99999,beta=-2"),
            "1.23418224274732e-5",
        ),
        (
            readme().compliance("-0.99999*hertz:r=1,estar=1+hertz:r=1,estar=1"),
            "5.89194115379923e-7",
        ),
        (
            common::case()
                .p1("0.975840931079741")
                .q1("0.00987145818336688")
                .phi("2.86482")
                .friction("0.48278")
                .compliance("power:c=1.609,beta=-3.651"),
            "3.49873655240328e-1",
        ),
    ];
    for (case, expected) in cases {
        let case = case.text();
        check(&case).unwrap();
        assert_eq!(dissipation_report(&case, None, BUDGET).unwrap().total(), expected);
    }
}

/// A random row of class `class` (0 to 3): Q1 = ρ·f·P1 with Q1 + fP1 < fP0, so that the
/// cycle stays clear of gross slip.
fn row(draws: &mut Draws, class: usize) -> CaseText {
    let phi = format!("{:.5}", draws.between(0.05, 3.1));
    let friction = draws.between(0.3, 1.2);
    let (p1, rho, compliance) = match class {
        0 => {
            let p1 = draws.between(0.05, 0.75);
            let family = [
                "persson:gamma=1,sigma=1".to_string(),
                format!("power:c=1,beta={:.3}", draws.between(-3.0, -0.2)),
                "hertz:r=1,estar=1".to_string(),
                format!("exp:a=1,c={:.3},d=0.1", draws.between(0.3, 3.0)),
            ][(draws.next() * 4.0) as usize % 4]
                .clone();
            (p1, 0.3 * draws.next(), family)
        }
        1 => {
            let keep = 10f64.powf(-draws.between(1.0, 6.0));
            let p1 = draws.between(0.05, 0.75);
            let family = format!("-{:.8}*hertz:r=1,estar=1+hertz:r=1,estar=1", 1.0 - keep);
            (p1, 0.3 * draws.next(), family)
        }
        2 => {
            let gap = 10f64.powf(-draws.between(3.0, 8.0));
            let family = format!("power:c=1,beta={:.3}", draws.between(-6.0, -1.0));
            (1.0 - gap, 0.3 * gap * draws.next() / (1.0 - gap), family)
        }
        _ => {
            let p1 = draws.between(0.05, 0.6);
            let family = format!("exp:a=1,c={:.3e},d=0.001", 10f64.powf(-draws.between(1.0, 3.0)));
            (p1, 0.3 * draws.next(), family)
        }
    };
    common::case()
        .p1(format!("{p1:.12}"))
        .q1(format!("{:.6e}", rho * friction * p1))
        .phi(phi)
        .friction(format!("{friction:.4}"))
        .compliance(compliance)
        .text()
}

#[test]
fn random_rows_of_the_hard_classes_are_proven_with_right_digits() {
    let mut draws = Draws(36);
    let failures: Vec<String> = (0..40)
        .map(|k| row(&mut draws, k % 4))
        .filter_map(|case| check(&case).err())
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
