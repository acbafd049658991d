//! The range of f64: loads and compliance parameters far from 1, phases far beyond 2π,
//! and decimals f64 cannot hold. The default path (no digit count) must print digits
//! that a 30-digit verified MPFR value confirms, or refuse with a reason — never a
//! wrong number; the library in f64 must refuse rather than return one.

use std::time::Duration;

use microslip::answer::agreed::{verified_dissipation, VerifiedDissipation};
use microslip::answer::dissipation::{dissipation_report, DissipationAnswer};
use microslip::answer::DissipationAnswerError;
use microslip::case::{CaseText, InputError};
use microslip::compliance::parse_spec;
use microslip::dissipation::{dissipation, DissipationError, Options};
use microslip::real::{Precision, Real};
use rug::float::Constant;
use rug::ops::Pow;
use rug::Float;

mod common;

const BUDGET: Duration = Duration::from_secs(60);

/// The first acceptance case (φ = 0.4π) with its loads multiplied by 10^k.
fn case_at_scale(k: i32, compliance: &str) -> CaseText {
    common::case()
        .p0(format!("1e{k}"))
        .p1(format!("4e{}", k - 1))
        .q1(format!("5e{}", k - 1))
        .compliance(compliance)
        .text()
}

/// Each compliance family, with its parameters scaled with the loads (10^k) where the
/// family has a load scale of its own.
fn families(k: i32) -> Vec<String> {
    vec![
        "persson:gamma=1,sigma=1".to_string(),
        "power:c=1,beta=-1".to_string(),
        "power:c=1,beta=-0.5".to_string(),
        "power:c=1,beta=-2".to_string(),
        "hertz:r=1,estar=1".to_string(),
        format!("rational:a=1,b=1,c=1e{k}"),
        format!("exp:a=1,c=1e{k},d=1"),
        format!("poly:p0=1e{k},coeffs=2;-1e{};-0.5e{}", -k, -2 * k),
        "power:c=1,beta=-0.5 + persson:gamma=1,sigma=1".to_string(),
    ]
}

/// `printed` (d significant digits) lies within one unit of its last digit of `reference`.
fn agrees(printed: &str, digits: u32, reference: &str) -> bool {
    let p = Precision::bits(200);
    let (a, b): (Float, Float) = (
        Float::parse_decimal(printed, p).unwrap(),
        Float::parse_decimal(reference, p).unwrap(),
    );
    if b.is_zero() {
        return a.is_zero();
    }
    let unit = b.clone().abs().log10().floor() - (digits as i32 - 1);
    let unit = Float::with_val(200, 10).pow(unit);
    (a - b).abs() <= unit
}

/// The default path against 30 verified digits: agreement, or an error both paths share.
/// W of `case` on the default path, proven (f64 could not even hold the case).
fn computed_beyond_f64(case: &CaseText) -> DissipationAnswer {
    let printed = dissipation_report(case, None, BUDGET).unwrap();
    assert!(printed.answer.provenance.is_proven(), "{printed:?}");
    printed
}

/// W as the agreement of two precisions prints it.
fn printed_w(verified: &VerifiedDissipation) -> String {
    verified.answer.value.decimal.to_string()
}

fn check_default_path(case: &CaseText) -> Result<bool, String> {
    let reference = verified_dissipation(case, 30, BUDGET).map(|verified| printed_w(&verified));
    match (dissipation_report(case, None, BUDGET), reference) {
        (Ok(printed), Ok(reference)) => {
            if !agrees(&printed.total(), printed.answer.digits(), &reference) {
                return Err(format!(
                    "{case:?}: printed {} ({} digits, {}) but 30 digits give {}",
                    printed.total(),
                    printed.answer.digits(),
                    printed.answer.provenance,
                    reference
                ));
            }
            Ok(printed.answer.provenance.is_proven())
        }
        (Err(error), Err(_)) => {
            assert!(!error.to_string().is_empty());
            Ok(true)
        }
        (Ok(printed), Err(error)) => Err(format!(
            "{case:?}: printed {} where 30 digits fail: {error}",
            printed.total()
        )),
        (Err(error), Ok(reference)) => Err(format!(
            "{case:?}: refused ({error}) where 30 digits give {}",
            reference
        )),
    }
}

#[test]
fn every_family_at_load_scales_from_1e_minus_300_to_1e300_prints_right_digits() {
    let mut failures = Vec::new();
    let mut proven = 0;
    let mut cases = 0;
    // Every 20 decades; MICROSLIP_RANGE_STEP=1 runs every decade, by hand.
    let step = std::env::var("MICROSLIP_RANGE_STEP")
        .ok()
        .and_then(|v| v.parse::<usize>().ok())
        .unwrap_or(20)
        .max(1);
    for k in (-300..=300).step_by(step) {
        for spec in families(k) {
            cases += 1;
            match check_default_path(&case_at_scale(k, &spec)) {
                Ok(is_proven) => proven += usize::from(is_proven),
                Err(failure) => failures.push(failure),
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {cases} wrong:\n{}",
        failures.len(),
        failures.join("\n")
    );
    // Every default W is proven, at every scale.
    assert_eq!(proven, cases, "{proven} of {cases} proven");
}

#[test]
fn the_reported_large_load_case_is_computed_in_mpfr_not_printed_as_zero() {
    let case = common::case().p0("1e300").p1("4e299").q1("5e299").text();
    let printed = computed_beyond_f64(&case);
    assert_eq!(printed.total(), "4.06247579245824e299");
    // The library in f64 refuses, naming what left the range.
    let read = case.read::<f64>(Precision::DOUBLE).unwrap();
    match dissipation(&read.cycle, read.compliance.as_ref(), &Options::default()) {
        Err(DissipationError::OutsideRange { quantity, .. }) => assert_eq!(quantity, "P0"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn persson_and_rational_slope_changes_do_not_overflow_at_large_loads() {
    // v'(P0 + x) − v'(P0) = −x/(P0(P0 + x)) at P0 = 1e300, x = −0.4e300: −6.67e-301 (f64
    // holds it), where the product P0(P0 + x) = 6e599 would overflow.
    for spec in ["persson:gamma=1,sigma=1", "rational:a=0,b=1,c=0"] {
        let compliance = parse_spec::<f64>(spec, Precision::DOUBLE).unwrap();
        let change = compliance.slope_change(&1e300, &-4e299);
        assert!(
            (change - 1.0 / 1.5e300).abs() < 1e-15 * change.abs(),
            "{spec}: {change:e}"
        );
    }
    let hertz = parse_spec::<f64>("hertz:r=1e200,estar=1e200", Precision::DOUBLE).unwrap();
    // v' = (2/3)(9/(16 R E*²))^(1/3) P^(−1/3), R·E*² = 1e600.
    let expected = 2.0 / 3.0 * (9.0f64 / 16.0).cbrt() * 1e-200;
    assert!((hertz.slope(&1.0) - expected).abs() < 1e-15 * expected);
}

#[test]
fn a_compliance_whose_formula_underflows_inside_f64_is_computed_in_mpfr() {
    // v' = 1 + 1e250/(P + 1e300): v' and the loads are ordinary, but the change of v'
    // over the cycle, about 1e-350, underflows to 0 in f64, where W would print as 0.
    let case = case_at_scale(0, "rational:a=1,b=1e250,c=1e300");
    let printed = computed_beyond_f64(&case);
    let verified = verified_dissipation(&case, 30, BUDGET).unwrap();
    assert!(agrees(&printed.total(), printed.answer.digits(), &printed_w(&verified)));
    assert!(verified.value.total > 0);
}

/// φ reduced modulo 2π at 1000 bits in the test itself, printed with 40 digits.
fn reduced_phase_text(phi: &str) -> String {
    let bits = 1000;
    let phase = Float::with_val(bits, Float::parse(phi).unwrap());
    let turn = Float::with_val(bits, Constant::Pi) * 2u32;
    let turns = (phase.clone() / &turn).floor();
    let reduced = phase - turns * turn;
    reduced.to_string_radix(10, Some(40))
}

#[test]
fn large_phases_print_the_digits_of_the_exactly_reduced_phase() {
    for phi in [
        "12345.678",
        "999999",
        "1e5",
        "-31415.9265",
        "1e6",
        "123456789.123",
        "1e50",
        "-7.77e99",
    ] {
        let case = common::case().phi(phi).text();
        let reduced = common::case().phi(reduced_phase_text(phi)).text();
        let reference = printed_w(&verified_dissipation(&reduced, 30, BUDGET).unwrap());
        let printed = dissipation_report(&case, None, BUDGET).unwrap();
        // 12 digits, or 11 where W ± its estimate straddles only the 12th digit's boundary.
        assert!(printed.answer.digits() >= 11, "{phi}: {printed:?}");
        assert!(
            agrees(&printed.total(), printed.answer.digits(), &reference),
            "φ = {phi}: printed {} ({} digits), exact {}",
            printed.total(),
            printed.answer.digits(),
            reference
        );
        // The verified path reduces with enough bits too.
        let verified = verified_dissipation(&case, 30, BUDGET).unwrap();
        assert_eq!(printed_w(&verified), reference, "φ = {phi}");
    }
}

#[test]
fn phases_beyond_1e100_are_refused_with_the_bound() {
    let case = common::case().phi("1e101").text();
    let error = dissipation_report(&case, None, BUDGET).unwrap_err();
    assert!(error.to_string().contains("at most 1e100 rad"), "{error}");
    let error = case.read::<Float>(Precision::bits(100)).unwrap_err();
    assert!(error.to_string().contains("at most 1e100 rad"), "{error}");
}

#[test]
fn decimals_outside_f64_are_named_as_such_and_read_exactly_by_the_default_path() {
    // Each a valid cycle (decided exactly when read) whose number f64 cannot hold.
    for (field, text, quantity) in [("p1", "1e-400", "P1"), ("p0", "1e400", "P0"), ("q1", "5e-320", "Q1")] {
        let case = match field {
            "p0" => common::case().p0(text),
            "p1" => common::case().p1(text),
            _ => common::case().q1(text),
        }
        .text();
        match case.read::<f64>(Precision::DOUBLE) {
            Err(error @ InputError::OutsideF64Range { .. }) => {
                assert!(matches!(&error, InputError::OutsideF64Range { quantity: q, .. } if *q == quantity));
                assert!(error.to_string().contains("outside the range of f64"), "{error}");
            }
            other => panic!("{text}: {other:?}"),
        }
    }
    // With loads all 1e-400 the default path computes in MPFR and says why.
    let case = case_at_scale(-400, "persson:gamma=1,sigma=1");
    let printed = computed_beyond_f64(&case);
    assert_eq!(printed.total(), "4.06247579245824e-401");
    // A compliance parameter outside f64.
    let case = case_at_scale(0, "persson:gamma=1e400,sigma=1");
    let error = case.read::<f64>(Precision::DOUBLE).unwrap_err();
    assert!(
        error.to_string().contains("gamma=1e400 lies outside the range of f64"),
        "{error}"
    );
    let printed = dissipation_report(&case, None, BUDGET).unwrap();
    assert_eq!(printed.total(), "4.06247579245824e399");
    // Text that is not a number is still refused as such.
    let case = common::case().p0("1e4oo").text();
    assert!(matches!(
        dissipation_report(&case, None, BUDGET),
        Err(DissipationAnswerError::Input(InputError::Number { .. }))
    ));
}

#[test]
fn the_magnitude_band_is_that_of_f64_and_wide_in_mpfr() {
    // P0 = 1e50 is inside f64's band; 1e60 is not; MPFR takes both.
    for (k, inside) in [(50, true), (60, false), (-50, true), (-60, false)] {
        let case = case_at_scale(k, "power:c=1,beta=-1");
        let read = case.read::<f64>(Precision::DOUBLE).unwrap();
        let result = dissipation(&read.cycle, read.compliance.as_ref(), &Options::default());
        assert_eq!(result.is_ok(), inside, "1e{k}: {result:?}");
        let precise = case.read::<Float>(Precision::bits(128)).unwrap();
        assert!(dissipation(&precise.cycle, precise.compliance.as_ref(), &Options::default()).is_ok());
    }
}
