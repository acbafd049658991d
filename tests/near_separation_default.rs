//! The proven default near separation (proofs/printing.md, "Near separation in f64
//! intervals"): with P0 − P1 read exactly from the decimals, cycles within 1e-3 to 1e-9 of
//! separation are proven to 12 digits or more in f64 intervals, their enclosures hold the
//! 30-digit W and print it rounded; the exactly read P0 − P1 narrows the enclosure by
//! orders of magnitude against P0 − P1 formed from the rounded P0 and P1.

use std::time::Duration;

use microslip::answer::dissipation::dissipation_of;
use microslip::answer::{Answer, Arithmetic};
use microslip::case::{Case, CaseSpec, CaseText};
use microslip::digits::enclosure::{enclose_dissipation, enclose_dissipation_with_lowest_load, INTERVAL_GOAL_BITS};
use microslip::interval::Interval;
use microslip::real::Precision;
use rug::ops::Pow;
use rug::{Float, Rational};

const BUDGET: Duration = Duration::from_secs(120);

/// P0 = 1, P1 = 1 − δ, f = λ = 1.
fn case(p1: &str, q1: &str, phi: &str, compliance: &str) -> CaseSpec {
    CaseText::builder()
        .p0(1)
        .p1(p1)
        .q1(q1)
        .phi(phi)
        .friction(1)
        .lambda(1)
        .compliance(compliance)
        .build()
        .expect("a case inside the theory")
}

/// The cycles the f64 intervals prove near separation: Q1 = 0.1·√(2δ) at φ = π/2 (the
/// ellipse's width a tenth of what gross slip allows) and Q1 = δ/2 at φ = 0.4π.
const PROVEN: [(&str, &str, &str, &str); 7] = [
    ("0.999", "4.472e-3", "0.5pi", "persson:gamma=1,sigma=1"),
    ("0.999", "4.472e-3", "0.5pi", "power:c=1,beta=-1.5"),
    ("0.999", "4.472e-3", "0.5pi", "hertz:r=1,estar=1"),
    ("0.999999", "1.414e-4", "0.5pi", "persson:gamma=1,sigma=1"),
    ("0.999999", "1.414e-4", "0.5pi", "power:c=1,beta=-1.5"),
    ("0.999999", "5e-7", "0.4pi", "persson:gamma=1,sigma=1"),
    ("0.999999999", "4.472e-6", "0.5pi", "persson:gamma=1,sigma=1"),
];

/// A printed decimal at 256 bits.
fn read(text: &str) -> Float {
    Float::with_val(256, Float::parse(text).expect("a decimal"))
}

/// The middle of the answer's enclosure.
fn middle(answer: &Answer) -> Float {
    let (lower, upper) = answer.value.enclosure.as_ref().expect("an enclosure");
    (read(lower) + read(upper)) / 2u32
}

#[test]
fn near_separation_is_proven_in_intervals_and_prints_the_30_digit_w_rounded() {
    for (p1, q1, phi, compliance) in PROVEN {
        let spec = case(p1, q1, phi, compliance);
        let answer = dissipation_of(&spec, None, BUDGET).expect("W").answer;
        let label = format!("P1 = {p1}, Q1 = {q1}, φ = {phi}, {compliance}");
        assert_eq!(
            answer.provenance.arithmetic(),
            Some(Arithmetic::F64Intervals),
            "{label}: {} digits, {}",
            answer.digits(),
            answer.provenance
        );
        assert!(answer.digits() >= 12, "{label}: {} digits", answer.digits());
        let truth = middle(&dissipation_of(&spec, Some(30), BUDGET).expect("W to 30 digits").answer);
        let (lower, upper) = answer.value.enclosure.as_ref().expect("an enclosure");
        assert!(
            read(lower) <= truth && truth <= read(upper),
            "{label}: [{lower}, {upper}] does not hold {truth}"
        );
        assert_prints_rounded(&label, &answer, &truth);
    }
}

/// The printed digits are the 30-digit W `truth` rounded: within half a unit of the last.
fn assert_prints_rounded(label: &str, answer: &Answer, truth: &Float) {
    let printed = answer.value.decimal.to_string();
    let (mantissa, exponent) = printed.split_once('e').expect("an exponent");
    let digits = mantissa.replace(['-', '.'], "").len() as i32;
    let exponent: i32 = exponent.parse().expect("an exponent");
    let half_unit = Float::with_val(256, 10).pow(exponent - digits + 1) / 2u32;
    assert!(
        (read(&printed) - truth).abs() <= half_unit,
        "{label}: printed {printed}, 30 digits give {truth}"
    );
}

/// Away from φ ≡ π/2 (sin²φ below 5/6) a cycle near separation is left to the Arb ladder:
/// BC and CH, each up to 1/sin²φ times W, cancel there beyond what doubles prove. The cycle
/// the intervals prove at φ = 0.4π is printed from Arb balls at φ = 0.2π, to 15 digits that
/// are the 30-digit W rounded.
#[test]
fn near_separation_away_from_a_quarter_phase_is_left_to_the_arb_ladder() {
    for (phi, arithmetic) in [("0.4pi", Arithmetic::F64Intervals), ("0.2pi", Arithmetic::ArbBalls)] {
        let spec = case("0.999999", "5e-7", phi, "persson:gamma=1,sigma=1");
        let answer = dissipation_of(&spec, None, BUDGET).expect("W").answer;
        assert_eq!(answer.provenance.arithmetic(), Some(arithmetic), "φ = {phi}");
        let truth = middle(&dissipation_of(&spec, Some(30), BUDGET).expect("W to 30 digits").answer);
        assert_prints_rounded(&format!("φ = {phi}"), &answer, &truth);
    }
}

/// The relative width of an interval enclosure of W.
fn relative_width(total: &Interval) -> f64 {
    let (lower, upper) = total.real_bounds();
    (upper - lower) / (0.5 * (lower + upper)).abs()
}

#[test]
fn the_exactly_read_lowest_load_narrows_the_enclosure() {
    let spec = case("0.999999", "1.414e-4", "0.5pi", "persson:gamma=1,sigma=1");
    let Case { cycle, compliance } = spec.at::<Interval>(Precision::DOUBLE).expect("a case in doubles");
    let lowest = spec
        .lowest_normal_load::<Interval>(Precision::DOUBLE)
        .expect("P0 − P1 in doubles");
    // 1 − 0.999999 = 10⁻⁶ exactly, enclosed by the two doubles around it.
    let (below, above) = lowest.real_bounds();
    let exact = Rational::from((1, 1_000_000));
    let (below_exactly, above_exactly) = (Rational::from_f64(below), Rational::from_f64(above));
    assert!(
        below_exactly.is_some_and(|b| b < exact)
            && above_exactly.is_some_and(|a| exact < a)
            && above == below.next_up(),
        "{lowest:?}"
    );
    let exact = enclose_dissipation_with_lowest_load(&cycle, Some(&lowest), compliance.as_ref(), INTERVAL_GOAL_BITS)
        .expect("an enclosure")
        .total;
    let rounded = enclose_dissipation(&cycle, compliance.as_ref(), INTERVAL_GOAL_BITS)
        .expect("an enclosure")
        .total;
    let truth = middle(&dissipation_of(&spec, Some(30), BUDGET).expect("W to 30 digits").answer);
    for total in [&exact, &rounded] {
        let (lower, upper) = total.real_bounds();
        assert!(
            Float::with_val(53, lower) <= truth && truth <= Float::with_val(53, upper),
            "{total:?}"
        );
    }
    let (narrow, wide) = (relative_width(&exact), relative_width(&rounded));
    assert!(narrow < 1e-12, "{narrow:e}");
    assert!(wide > 100.0 * narrow, "{wide:e} against {narrow:e}");
}
