//! The default answer's first rung, f64 intervals (proofs/printing.md, "The proven
//! default"): on random ordinary rows of every compliance family the interval enclosure
//! of W holds the 30-digit W and its 12 to 15 digits are that W rounded; rows the
//! intervals cannot prove to 12 digits climb to Arb's balls and still print 15 proven
//! digits.

mod common;

use std::time::Duration;

use microslip::answer::dissipation::{dissipation_report, DEFAULT_DIGITS, DEFAULT_LEAST_DIGITS};
use microslip::answer::{Answer, Arithmetic, Decimal};
use microslip::case::{Case, CaseText};
use microslip::digits::enclosure::{enclose_dissipation, INTERVAL_GOAL_BITS};
use microslip::interval::Interval;
use microslip::real::Precision;
use microslip::verify::generators::{cycle_case, Draw, Family, CYCLE};
use rug::ops::Pow;
use rug::Float;

const BUDGET: Duration = Duration::from_secs(120);

/// Random rows per family (six families of the gate's draws and Hertz).
const ROWS_PER_FAMILY: usize = 300;

/// The gate's ordinary cycles (P0 = 1, P1/P0 ∈ (0.05, 0.9), φ ∈ (0.02π, 0.98π), Q1 inside
/// the gross-slip amplitude) with a member of every family in turn, and Hertz.
fn ordinary_rows(seed: u64, per_family: usize) -> Vec<CaseText> {
    let mut draw = Draw::new(seed);
    let mut rows = Vec::new();
    for _ in 0..per_family {
        for family in Family::ALL {
            let cycle = draw.parameters(&CYCLE);
            let values = draw.parameters(family.parameters());
            rows.push(cycle_case(&cycle, |loads| family.spec(&values, loads)));
        }
        let cycle = draw.parameters(&CYCLE);
        let radius = draw.uniform(0.1, 10.0);
        rows.push(cycle_case(&cycle, |_| format!("hertz:r={radius},estar=1")));
    }
    rows
}

/// A printed decimal at 256 bits.
fn read(text: &str) -> Float {
    Float::with_val(256, Float::parse(text).expect("a decimal"))
}

/// Whether `printed` (N significant digits) is `reference` rounded to N digits: within half
/// a unit of its last digit.
fn rounds_to(printed: &str, reference: &str) -> bool {
    let (mantissa, exponent) = printed.split_once('e').expect("an exponent");
    let digits = mantissa.replace(['-', '.'], "").len() as i32;
    let half_unit = Float::with_val(256, 10).pow(exponent.parse::<i32>().expect("an exponent") - digits + 1) / 2u32;
    (read(printed) - read(reference)).abs() <= half_unit
}

/// Whether the answer's enclosure holds `value`.
fn holds(answer: &Answer, value: &Float) -> bool {
    let (lower, upper) = answer.value.enclosure.as_ref().expect("an enclosure");
    read(lower) <= *value && *value <= read(upper)
}

/// The middle of the answer's enclosure.
fn middle(answer: &Answer) -> Float {
    let (lower, upper) = answer.value.enclosure.as_ref().expect("an enclosure");
    (read(lower) + read(upper)) / 2u32
}

/// The default answer of `case` against `--digits 30`: proven in `arithmetic` (either
/// where `None`), with `digits` significant digits, its enclosure holding the middle of
/// the 30-digit one, and W and every segment the 30-digit values rounded to their digits;
/// and the f64 interval enclosure of W, whatever digits it proves, holding that middle.
fn check(
    case: &CaseText,
    arithmetic: Option<Arithmetic>,
    digits: std::ops::RangeInclusive<u32>,
) -> Result<Arithmetic, String> {
    let default = dissipation_report(case, None, BUDGET).map_err(|e| format!("{case:?}: {e}"))?;
    let answer = &default.answer;
    let used = answer
        .provenance
        .arithmetic()
        .ok_or_else(|| format!("{case:?}: {}", answer.provenance))?;
    if arithmetic.is_some_and(|arithmetic| arithmetic != used) || !digits.contains(&answer.digits()) {
        return Err(format!("{case:?}: {} digits, {}", answer.digits(), answer.provenance));
    }
    let reference = dissipation_report(case, Some(30), BUDGET).map_err(|e| format!("{case:?} at 30: {e}"))?;
    let truth = middle(&reference.answer);
    if !holds(answer, &truth) {
        return Err(format!(
            "{case:?}: {:?} does not hold the 30-digit W {}",
            answer.value.enclosure,
            reference.total()
        ));
    }
    if let Some(enclosure) = interval_enclosure(case) {
        let (lower, upper) = enclosure.real_bounds();
        if !(Float::with_val(53, lower) <= truth && truth <= Float::with_val(53, upper)) {
            return Err(format!(
                "{case:?}: the f64 intervals' {enclosure:?} does not hold {}",
                reference.total()
            ));
        }
    }
    let printed = std::iter::once((&answer.value, &reference.answer.value)).chain(
        answer
            .segments
            .iter()
            .zip(&reference.answer.segments)
            .flat_map(|(ours, theirs)| {
                ours.iter()
                    .zip(theirs.iter())
                    .map(|((_, ours), (_, theirs))| (ours, theirs))
            }),
    );
    // A segment with no digit determined (an enclosure about zero) prints none to check.
    for (ours, truth) in printed.filter(|(ours, _)| ours.digits() != 0 && ours.decimal != Decimal::Zero) {
        let (ours, truth) = (ours.decimal.to_string(), truth.decimal.to_string());
        if !rounds_to(&ours, &truth) {
            return Err(format!("{case:?}: printed {ours}, 30 digits give {truth}"));
        }
    }
    Ok(used)
}

/// W's enclosure in f64 intervals, where they give one.
fn interval_enclosure(case: &CaseText) -> Option<Interval> {
    let Case { cycle, compliance } = case.read::<Interval>(Precision::DOUBLE).ok()?;
    enclose_dissipation(&cycle, compliance.as_ref(), INTERVAL_GOAL_BITS)
        .ok()
        .map(|enclosure| enclosure.total)
}

/// The least share of ordinary rows the f64 intervals prove to 12 digits or more (about
/// four in five of the gate's draws, which reach phases within 0.02π of 0 and π and P1 up
/// to 0.9 P0, where rounding in doubles is amplified most).
const LEAST_INTERVAL_SHARE: f64 = 0.7;

#[test]
fn on_ordinary_rows_of_every_family_the_default_and_the_intervals_hold_and_round_the_30_digit_w() {
    let rows = ordinary_rows(36, ROWS_PER_FAMILY);
    assert!(rows.len() >= 2000);
    let (mut failures, mut by_intervals) = (Vec::new(), 0);
    for case in &rows {
        match check(case, None, DEFAULT_LEAST_DIGITS..=DEFAULT_DIGITS) {
            Ok(Arithmetic::F64Intervals) => by_intervals += 1,
            Ok(_) => {}
            Err(failure) => failures.push(failure),
        }
    }
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
    );
    let share = by_intervals as f64 / rows.len() as f64;
    assert!(
        share >= LEAST_INTERVAL_SHARE,
        "{by_intervals} of {} rows by f64 intervals",
        rows.len()
    );
}

#[test]
fn ordinary_rows_print_at_least_twelve_proven_digits_most_of_them_from_f64_intervals() {
    let rows = ordinary_rows(2026, ROWS_PER_FAMILY);
    let mut counts = std::collections::BTreeMap::new();
    for case in &rows {
        let answer = dissipation_report(case, None, BUDGET).expect("an answer").answer;
        assert!(answer.provenance.is_proven(), "{case:?}: {}", answer.provenance);
        assert!(!matches!(answer.value.decimal, Decimal::Zero), "{case:?}");
        let arithmetic = answer.provenance.arithmetic().expect("an enclosure");
        *counts.entry((arithmetic.key(), answer.digits())).or_insert(0usize) += 1;
    }
    let (mut by_intervals, mut fewer_than_least) = (0, 0);
    for (&(arithmetic, digits), &count) in &counts {
        by_intervals += if arithmetic == Arithmetic::F64Intervals.key() {
            count
        } else {
            0
        };
        fewer_than_least += if digits < DEFAULT_LEAST_DIGITS { count } else { 0 };
    }
    assert_eq!(fewer_than_least, 0, "{counts:?}");
    // Arb's balls give all 15 digits where they serve.
    assert!(
        counts
            .keys()
            .all(|&(arithmetic, digits)| arithmetic == Arithmetic::F64Intervals.key() || digits == DEFAULT_DIGITS),
        "{counts:?}"
    );
    assert!(
        by_intervals as f64 >= LEAST_INTERVAL_SHARE * rows.len() as f64,
        "{counts:?}"
    );
}

#[test]
fn rows_the_intervals_cannot_prove_to_twelve_digits_climb_to_arb_for_fifteen() {
    let readme = || common::case().q1("0.5").phi("0.4pi");
    let rows = [
        // 1e−9 from separation: rounding in doubles is amplified a billionfold.
        common::case()
            .p1("0.999999999")
            .q1("1e-5")
            .phi("0.5pi")
            .compliance("persson:gamma=1,sigma=1"),
        // Exponentials across a thousand decay lengths.
        readme().compliance("exp:a=1,c=0.001,d=0.001"),
        // Sums cancelling to 1e−5 of their terms.
        readme().compliance("power:c=1,beta=-2+power:c=-0.99999,beta=-2"),
        readme().compliance("-0.99999*hertz:r=1,estar=1+hertz:r=1,estar=1"),
    ];
    for row in rows {
        check(&row.text(), Some(Arithmetic::ArbBalls), DEFAULT_DIGITS..=DEFAULT_DIGITS).unwrap();
    }
}

#[test]
fn digits_asked_up_to_twelve_come_from_the_intervals_where_they_prove_them() {
    let case = common::case().q1("0.5").phi("0.4pi").text();
    let reference = dissipation_report(&case, Some(30), BUDGET).expect("30 digits").total();
    for digits in [1, 6, 10, DEFAULT_LEAST_DIGITS] {
        let answer = dissipation_report(&case, Some(digits), BUDGET)
            .expect("an answer")
            .answer;
        assert_eq!(
            answer.provenance.arithmetic(),
            Some(Arithmetic::F64Intervals),
            "{digits}"
        );
        assert_eq!(answer.digits(), digits);
        assert!(rounds_to(&answer.value.decimal.to_string(), &reference), "{answer:?}");
    }
    // Beyond them, Arb's ladder, as before.
    let answer = dissipation_report(&case, Some(DEFAULT_LEAST_DIGITS + 1), BUDGET)
        .expect("an answer")
        .answer;
    assert_eq!(answer.provenance.arithmetic(), Some(Arithmetic::ArbBalls));
}
