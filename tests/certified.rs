//! Certified enclosures on Arb balls: every ball function contains the MPFR value at
//! twice the precision, overlapping comparisons are counted, and the enclosure of W
//! contains an MPFR reference computed at 500 bits by the library's own quadrature
//! (Gauss–Legendre to a 1e-140 tolerance) — across the families, their sums and the
//! corners of the domain — and is narrow enough for the digits asked.

mod common;

use common::PERSSON;
use microslip::answer::dissipation::dissipation_answer;
use microslip::answer::DissipationAnswerError;
use microslip::answer::{Answer, Decimal, Provenance, Value};
use microslip::ball::{hull, watch, Ball};
use microslip::case::CaseText;
use microslip::compliance::{parse_spec, Compliance, Polynomial};
use microslip::cycle::LoadCycle;
use microslip::digits::enclosure::{certified_dissipation, enclose_dissipation, CertifiedError};
use microslip::dissipation::{dissipation, Options, Segment, SegmentIntegrands};
use microslip::exact::polynomial_dissipation;
use microslip::phase::ExactPhase;
use microslip::quad::sinh_map::{resolve_peaks, Peak};
use microslip::quad::{integrate, Piece, Settings};
use microslip::real::{Precision, Real};
use rug::ops::Pow;
use rug::Float;
use std::time::Duration;

/// The digits (at most `most`) to which every point of the ball rounds, by the one printing
/// rule: `None` where not one is determined, all of them for an exact zero.
fn certain_digits(ball: &Ball, most: u32) -> Option<(String, u32)> {
    let bits = ball
        .precision()
        .in_bits()
        .max(Precision::decimal_digits(most).in_bits())
        + 64;
    match Value::of_ball(ball, bits, most).decimal {
        Decimal::Zero => Some(("0".to_string(), most)),
        decimal if decimal.digits() == 0 => None,
        decimal => Some((decimal.to_string(), decimal.digits())),
    }
}

/// A case as exact decimals (the tests' one builder); a phase ending in `pi` is that
/// multiple of π.
type Case = CaseText;

fn case(p0: &str, p1: &str, q1: &str, phi: &str, friction: &str, spec: &str) -> Case {
    common::case()
        .p0(p0)
        .p1(p1)
        .q1(q1)
        .phi(phi)
        .friction(friction)
        .compliance(spec)
        .text()
}

fn acceptance() -> Case {
    case("1", "0.4", "0.5", "0.4pi", "1", PERSSON)
}

fn number<R: Real>(text: &str, precision: Precision) -> R {
    match text.strip_suffix("pi") {
        Some(multiple) => R::parse_decimal(multiple, precision).unwrap() * &R::pi(precision),
        None => R::parse_decimal(text, precision).unwrap(),
    }
}

fn cycle_at<R: Real>(case: &Case, precision: Precision) -> LoadCycle<R> {
    LoadCycle {
        mean_normal_load: number(&case.p0, precision),
        normal_amplitude: number(&case.p1, precision),
        mean_tangential_load: number(&case.q0, precision),
        tangential_amplitude: number(&case.q1, precision),
        phase: number(&case.phi, precision),
        friction: number(&case.friction, precision),
        compliance_ratio: number(case.lambda.as_deref().expect("λ given"), precision),
    }
}

type BallCase = (LoadCycle<Ball>, Box<dyn Compliance<Ball>>);

fn ball_case(case: &Case) -> impl Fn(Precision) -> Result<BallCase, String> + '_ {
    move |precision| {
        let compliance = parse_spec::<Ball>(&case.compliance, precision).map_err(|e| e.to_string())?;
        Ok((cycle_at(case, precision), compliance))
    }
}

const REFERENCE_BITS: u32 = 500;

/// W at 500 bits by the library's Gauss–Legendre quadrature to a 1e-140 tolerance.
fn reference(case: &Case) -> Float {
    let precision = Precision::bits(REFERENCE_BITS);
    let compliance = parse_spec::<Float>(&case.compliance, precision).unwrap();
    let options = Options::default()
        .with_tolerance(Float::with_val(REFERENCE_BITS, Float::parse("1e-140").unwrap()))
        .with_max_points(4096);
    dissipation(&cycle_at(case, precision), compliance.as_ref(), &options)
        .unwrap_or_else(|e| panic!("{case:?}: {e}"))
        .total
}

/// W at 500 bits in the cycle angle itself, independently of the bottom map the library
/// takes near separation: each window of each segment in s, or through s = c + w sinh u
/// about its lowest loads (w = acosh(P0/P1)) with the loads taken from cos θ of the angle,
/// by the library's quadrature to a 1e-140 tolerance.
fn reference_in_the_angle(case: &Case) -> Float {
    let precision = Precision::bits(REFERENCE_BITS);
    let compliance = parse_spec::<Float>(&case.compliance, precision).unwrap();
    let cycle = cycle_at::<Float>(case, precision);
    let geometry = cycle.geometry().unwrap();
    let integrands = SegmentIntegrands {
        geometry: &geometry,
        compliance: compliance.as_ref(),
        remove_constant_slope: true,
    };
    let pi = Float::with_val(REFERENCE_BITS, rug::float::Constant::Pi);
    let width = Float::with_val(REFERENCE_BITS, &cycle.mean_normal_load / &cycle.normal_amplitude).acosh();
    let mut pieces = Vec::new();
    for segment in Segment::ALL {
        let (start, _) = integrands.extent(segment);
        let mut peaks = Vec::new();
        for k in -2..=3i32 {
            let lowest = Float::with_val(REFERENCE_BITS, &pi * (2 * k + 1));
            let center = Float::with_val(REFERENCE_BITS, &lowest - start);
            peaks.push(Peak {
                center,
                width: width.clone(),
            });
            if segment == Segment::CH {
                let center = Float::with_val(REFERENCE_BITS, &geometry.theta_c - &lowest);
                peaks.push(Peak {
                    center,
                    width: width.clone(),
                });
            }
        }
        for (a, b) in integrands.windows(segment) {
            for part in resolve_peaks(&a, &b, &peaks) {
                let integrand: Box<dyn Fn(&Float) -> Float + '_> = match part.map {
                    None => Box::new(move |s: &Float| integrands.integrand(segment, s)),
                    Some(map) => Box::new(move |u: &Float| {
                        let (s, rate) = map.point_and_rate(u);
                        integrands.integrand(segment, &s) * rate
                    }),
                };
                pieces.push(Piece {
                    label: segment.name(),
                    integrand,
                    start: part.start,
                    end: part.end,
                });
            }
        }
    }
    let mut settings = Settings::new(Float::with_val(REFERENCE_BITS, Float::parse("1e-140").unwrap()));
    settings.max_points = 4096;
    let integrated = integrate(&pieces, &settings).unwrap_or_else(|e| panic!("{case:?}: {e}"));
    let sum = integrated
        .values()
        .fold(Float::new(REFERENCE_BITS), |sum, value| sum + value);
    sum * &cycle.compliance_ratio
}

/// Certifies `digits` digits and checks the enclosure holds the reference and is narrow.
fn assert_certified(case: &Case, digits: u32) {
    assert_certified_against(case, digits, &reference(case));
}

/// Certifies `digits` digits and checks the enclosure holds `exact` and is narrow.
fn assert_certified_against(case: &Case, digits: u32, exact: &Float) {
    let certified = certified_dissipation(ball_case(case), digits).unwrap_or_else(|e| panic!("{case:?}: {e}"));
    let total = &certified.enclosure.total;
    assert!(
        total.contains(exact),
        "{case:?}: reference {} outside {:?}",
        exact.to_string_radix(10, Some(60)),
        total
    );
    assert!(
        certified.value.digits() >= digits,
        "{case:?}: {} digits",
        certified.value.digits()
    );
    // Narrow for the digits: within half a unit of the last digit asked (relative to a
    // leading 1, the widest such unit). The driver aims far below this, but where rounding
    // at its first precision costs bits (near separation, 1e-6: a relative 1.4e-30 at 128
    // bits for 30 digits) it may accept an enclosure that rounds with little to spare.
    let radius = total.relative_radius();
    assert!(
        radius <= 10f64.powi(1 - digits as i32) / 2.0,
        "{case:?}: relative radius {radius:e}"
    );
    // The printed digits are the reference's, rounded.
    assert_eq!(
        certified.value.decimal.to_string(),
        Real::to_scientific(exact, certified.value.digits() as usize),
        "{case:?}"
    );
}

#[test]
fn ball_functions_contain_the_mpfr_values_at_twice_the_precision() {
    let bits = 128;
    let (p, wide) = (Precision::bits(bits), 2 * bits);
    for text in ["0.3", "1.7", "123.456", "2e-30", "7e40"] {
        let x = Ball::parse_decimal(text, p).unwrap();
        let y = Float::with_val(wide, Float::parse(text).unwrap());
        let other = Ball::parse_decimal("0.45", p).unwrap();
        let other_y = Float::with_val(wide, Float::parse("0.45").unwrap());
        let mut checks: Vec<(&str, Ball, Float)> = vec![
            ("sqrt", x.sqrt(), y.clone().sqrt()),
            ("cbrt", x.cbrt(), y.clone().cbrt()),
            ("cbrt(-x)", (-x.clone()).cbrt(), (-y.clone()).cbrt()),
            ("ln", x.ln(), y.clone().ln()),
            ("ln_1p", x.ln_1p(), y.clone().ln_1p()),
            ("powr", x.powr(&other), y.clone().pow(&other_y)),
            ("powi", x.powi(-3), y.clone().pow(-3)),
            ("sin", x.sin(), y.clone().sin()),
            ("cos", x.cos(), y.clone().cos()),
            ("sin_cos.0", x.sin_cos().0, y.clone().sin()),
            ("sin_cos.1", x.sin_cos().1, y.clone().cos()),
            ("hypot", x.hypot(&other), y.clone().hypot(&other_y)),
            ("atan2", x.atan2(&-other.clone()), y.clone().atan2(&-other_y.clone())),
            ("abs", (-x.clone()).abs(), y.clone().abs()),
            ("floor", x.floor(), y.clone().floor()),
            ("x/y", x.clone() / &other, y.clone() / &other_y),
            ("x*y-y", x.clone() * &other - &other, y.clone() * &other_y - &other_y),
            ("pi", Ball::pi(p), Float::with_val(wide, rug::float::Constant::Pi)),
        ];
        // e^(−7e40) is below MPFR's exponent range, and 7e40 % 0.45 needs 41 digits of the quotient.
        if text != "7e40" {
            checks.extend([
                ("exp(-x)", (-x.clone()).exp(), (-y.clone()).exp()),
                ("exp_m1(-x)", (-x.clone()).exp_m1(), (-y.clone()).exp_m1()),
                ("x%y", x.clone() % &other, y.clone() % &other_y),
            ]);
        }
        for (name, ball, exact) in checks {
            assert!(ball.contains(&exact), "{name}({text}): {exact} outside {ball:?}");
            assert!(ball.relative_radius() < 1e-30, "{name}({text}): {ball:?}");
        }
    }
}

#[test]
fn ball_functions_outside_their_domain_are_not_finite() {
    let p = Precision::bits(64);
    let negative = Ball::parse_decimal("-0.5", p).unwrap();
    assert!(!negative.sqrt().is_finite());
    assert!(!negative.ln().is_finite());
    assert!(!(negative.int(1) / &negative.int(0)).is_finite());
    // A ball across zero: the real cube root covers both signs.
    let epsilon = negative.epsilon_like();
    let across = hull(&-epsilon.clone(), &epsilon);
    let root = across.cbrt();
    let cube_root_of_epsilon = Float::with_val(64, Float::with_val(64, 2).pow(-63)).cbrt();
    for x in [Float::new(64), cube_root_of_epsilon.clone(), -cube_root_of_epsilon] {
        assert!(root.contains(&x), "{x} outside {root:?}");
    }
}

#[test]
fn comparisons_of_overlapping_balls_are_flagged() {
    let p = Precision::bits(64);
    let third = Ball::from_i64(1, p) / &Ball::from_i64(3, p);
    let one = third.clone() * &third.int(3);
    let ((), doubts) = watch(|| {
        assert!(!one.lt(&one.int(1)));
        assert!(!one.ge(&one.int(1)));
        assert!(one != one.int(1));
        assert!(one.partial_cmp(&one.int(1)).is_none());
    });
    assert_eq!(doubts.undecided_comparisons, 4);
    let ((), doubts) = watch(|| {
        assert!(third < one);
        assert!(one > third);
        assert!(third <= third.int(1));
        assert!(third.int(0) == one.int(0));
    });
    assert!(doubts.none());
}

#[test]
fn exact_decimals_are_read_as_balls_that_contain_them() {
    for text in ["0.1", "3.141592653589793", "1e-300", "-2.5e300", "0.999999999999999"] {
        let ball = Ball::parse_decimal(text, Precision::bits(80)).unwrap();
        let exact = Float::with_val(2048, Float::parse(text).unwrap());
        assert!(ball.contains(&exact), "{text}");
        assert!(ball.relative_radius() < 1e-23, "{text}");
    }
    for text in ["", "inf", "nan", "[1 +/- 0.1]", "0x10", "pi"] {
        assert!(Ball::parse_decimal(text, Precision::bits(80)).is_err(), "{text:?}");
    }
}

#[test]
fn certain_digits_are_those_the_whole_ball_rounds_to() {
    let p = Precision::bits(200);
    let third = Ball::from_i64(1, p) / &Ball::from_i64(3, p);
    let (text, digits) = certain_digits(&third, 40).unwrap();
    assert_eq!(
        (text.as_str(), digits),
        ("3.333333333333333333333333333333333333333e-1", 40)
    );
    // [0.1234549, 0.1234551] rounds to one 6-digit decimal, to no 5-digit one, and to
    // one 4-digit one.
    let ball = hull(
        &Ball::parse_decimal("0.1234549", p).unwrap(),
        &Ball::parse_decimal("0.1234551", p).unwrap(),
    );
    assert_eq!(certain_digits(&ball, 10).unwrap(), ("1.23455e-1".to_string(), 6));
    assert_eq!(certain_digits(&ball, 5).unwrap(), ("1.235e-1".to_string(), 4));
    // A ball across zero determines no digit; an exact zero all of them.
    let across = hull(
        &Ball::parse_decimal("-1e-9", p).unwrap(),
        &Ball::parse_decimal("1e-9", p).unwrap(),
    );
    assert!(certain_digits(&across, 10).is_none());
    assert_eq!(
        certain_digits(&Ball::from_i64(0, p), 10).unwrap(),
        ("0".to_string(), 10)
    );
    // Beyond f64's range: 1/3 at 2000 bits holds about 600 digits, and all 500 asked are
    // certain (a radius taken through f64 floors at 4.9e-324 and stops at 325).
    let fine = Precision::bits(2000);
    let third = Ball::from_i64(1, fine) / &Ball::from_i64(3, fine);
    assert_eq!(
        certain_digits(&third, 500).unwrap(),
        (format!("3.{}e-1", "3".repeat(499)), 500)
    );
}

/// 400 digits, more than a radius taken through f64 could count, are certified, and their
/// leading 130 are the 500-bit reference's.
#[test]
fn digits_beyond_the_range_of_f64_are_certified() {
    let case = acceptance();
    let certified = certified_dissipation(ball_case(&case), 400).unwrap_or_else(|e| panic!("{e}"));
    assert!(certified.value.digits() >= 400, "{} digits", certified.value.digits());
    let leading = certain_digits(&certified.enclosure.total, 130).unwrap();
    assert_eq!(leading, (Real::to_scientific(&reference(&case), 130), 130));
}

#[test]
fn acceptance_case_is_certified_at_15_30_50_and_100_digits() {
    for digits in [15, 30, 50, 100] {
        assert_certified(&acceptance(), digits);
    }
}

#[test]
fn segments_sum_to_w_and_each_holds_its_reference() {
    let case = acceptance();
    let precision = Precision::bits(200);
    let (cycle, compliance) = ball_case(&case)(precision).unwrap();
    let enclosure = enclose_dissipation(&cycle, compliance.as_ref(), 200).unwrap();
    let float_precision = Precision::bits(REFERENCE_BITS);
    let float_compliance = parse_spec::<Float>(&case.compliance, float_precision).unwrap();
    let options = Options {
        relative_tolerance: Some(Float::with_val(REFERENCE_BITS, Float::parse("1e-100").unwrap())),
        ..Options::default()
    };
    let reference = dissipation(&cycle_at(&case, float_precision), float_compliance.as_ref(), &options).unwrap();
    for segment in Segment::ALL {
        let ball = enclosure.segments.get(segment);
        assert!(ball.contains(reference.segments.get(segment)), "{segment}: {ball:?}");
        assert!(ball.relative_radius() < 1e-50, "{segment}: {ball:?}");
    }
}

/// Every compliance family, a sum and a scaled sum.
const FAMILIES: [&str; 10] = [
    PERSSON,
    "power:c=1,beta=-0.5",
    "power:c=2,beta=-1.37",
    "hertz:r=1,estar=1",
    "rational:a=0.5,b=1,c=0.2",
    "exp:a=1,c=2,d=0.1",
    "poly:p0=1,coeffs=1;-0.3;0.05",
    "power:c=1,beta=-0.5+persson:gamma=0.5,sigma=1",
    "power:c=1,beta=-0.5+power:c=0.5,beta=-1.5",
    "2*hertz:r=1,estar=1+exp:a=0.3,c=1.5,d=0",
];

#[test]
fn every_family_and_sum_is_certified_at_30_digits() {
    for spec in FAMILIES {
        let mut case = acceptance();
        case.compliance = spec.into();
        assert_certified(&case, 30);
    }
}

/// The tolerance Arb aims at and the complex-ball bounds (the plain slope difference)
/// change only where Arb stops; at 100 digits each family's enclosure still holds the
/// 500-bit reference of the library's own Gauss–Legendre engine.
#[test]
fn every_family_holds_its_100_digit_reference() {
    for spec in FAMILIES {
        assert_certified(&case("1", "0.3", "0.45", "0.3", "0.9", spec), 100);
    }
}

/// A small linear congruential generator: reproducible draws without a dependency.
struct Draws(u64);

impl Draws {
    fn uniform(&mut self, low: f64, high: f64) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        low + (high - low) * ((self.0 >> 11) as f64 / (1u64 << 53) as f64)
    }
    /// A decimal with six significant digits in [low, high).
    fn decimal(&mut self, low: f64, high: f64) -> String {
        format!("{:.5e}", self.uniform(low, high))
    }
}

#[test]
fn random_cases_across_the_families_are_certified_at_40_digits() {
    let specs = [
        PERSSON,
        "power:c=1,beta=-0.25",
        "hertz:r=2,estar=0.5",
        "rational:a=0.2,b=1,c=0.1",
        "exp:a=1,c=3,d=0.2",
        "poly:p0=1,coeffs=1;-0.2",
        "persson:gamma=1,sigma=0.5+power:c=0.5,beta=-0.75",
    ];
    let mut draws = Draws(19);
    let mut certified = 0;
    while certified < 10 {
        let p1 = draws.decimal(0.05, 0.9);
        let friction = draws.decimal(0.3, 1.5);
        let phi = draws.decimal(0.05, 3.1);
        let q1 = draws.decimal(0.01, 1.2);
        let mut case = case("1", &p1, &q1, &phi, &friction, specs[certified % specs.len()]);
        case.lambda = Some(draws.decimal(1.0, 2.0));
        // Only cycles the theory covers (the draw is of loads, not of valid cycles).
        if cycle_at::<f64>(&case, Precision::DOUBLE).validate().is_err() {
            continue;
        }
        assert_certified(&case, 40);
        certified += 1;
    }
}

#[test]
fn corners_of_the_domain_are_certified() {
    let corners = [
        // Within 1e-6 of separation (Q1 must then be below √(2·1e-6) against fP0); closer
        // in `near_separation_is_certified`.
        case("1", "0.999999", "0.0005", "0.5pi", "1", PERSSON),
        // Nearly in phase and nearly out of phase: with Q1 > fP1 near the in-phase W, with
        // Q1 < fP1 near W = 0 (W ∝ φ², every segment of order 1).
        case("1", "0.4", "0.5", "1e-20", "1", PERSSON),
        case("1", "0.4", "0.5", "3.141592653589793", "1", PERSSON),
        case("1", "0.4", "0.2", "1e-20", "1", PERSSON),
        case("1", "0.4", "0.2", "3.141592653589793", "1", PERSSON),
        // Q1 = fP1 exactly: equal loads that the geometry takes the larger of.
        case("1", "0.4", "0.4", "0.4pi", "1", PERSSON),
        // Tiny amplitudes.
        case("1", "1e-12", "0.5", "0.4pi", "1", PERSSON),
        case("1", "0.4", "1e-12", "0.4pi", "1", PERSSON),
        // Load scales 1e±300.
        case("1e300", "4e299", "5e299", "0.4pi", "1", PERSSON),
        case("1e-300", "4e-301", "5e-301", "0.4pi", "1", "power:c=1,beta=-0.5"),
    ];
    for corner in &corners {
        assert_certified(corner, 30);
    }
}

/// 1e−9, 1e−12 and 1e−15 from separation (Q1 below f√(2P1δ), no gross slip), φ = π/2
/// as a multiple of π and as the decimal 1.5707963267948966, at 15 and 30 digits: each
/// enclosure holds the reference computed in the angle itself (not through the bottom
/// map) and the library's own.
#[test]
fn near_separation_is_certified() {
    let cases = [
        (case("1", "0.999999999", "1e-5", "0.5pi", "1", PERSSON), &[30][..]),
        (case("1", "0.999999999999", "1e-7", "0.5pi", "1", PERSSON), &[15, 30]),
        (
            case("1", "0.999999999999", "1e-7", "1.5707963267948966", "1", PERSSON),
            &[15, 30],
        ),
        (case("1", "0.999999999999999", "1e-8", "0.5pi", "1", PERSSON), &[15, 30]),
        (
            case("1", "0.999999999999999", "1e-8", "1.5707963267948966", "1", PERSSON),
            &[15, 30],
        ),
        (
            case("1", "0.999999999999999", "1e-16", "1.5707963267948966", "1", PERSSON),
            &[15, 30],
        ),
        (
            case("1", "0.999999999999999", "1e-8", "0.5pi", "0.8", "power:c=1,beta=-0.5"),
            &[30],
        ),
    ];
    for (case, digits) in &cases {
        let exact = reference_in_the_angle(case);
        let library = reference(case);
        let agreement = (Float::with_val(REFERENCE_BITS, &library - &exact) / &exact).abs();
        assert!(
            agreement < 1e-60,
            "{case:?}: the two references differ by {agreement:e}"
        );
        for &d in *digits {
            assert_certified_against(case, d, &exact);
        }
    }
}

#[test]
fn near_separation_the_first_precision_pays_the_bits_rounding_loses() {
    // δ = 1e−9 of P1: the integrands about the lowest load lose about log2(P1/δ) + 2 bits
    // to rounding, so 50 digits need 256 bits there, not the 192 of an ordinary case. The
    // driver starts at 256 (and ends there), rather than failing at 192 first.
    let case = case("1", "0.999999999", "1e-5", "0.5pi", "1", PERSSON);
    let certified = certified_dissipation(ball_case(&case), 50).unwrap();
    assert_eq!(certified.enclosure.precision.in_bits(), 256);
    assert!(certified.enclosure.total.contains(&reference(&case)));
    let (cycle, compliance) = ball_case(&case)(Precision::bits(192)).unwrap();
    let coarse = enclose_dissipation(&cycle, compliance.as_ref(), 179).unwrap();
    let reached = certain_digits(&coarse.total, 50).map_or(0, |(_, n)| n);
    assert!(reached < 50, "192 bits reach {reached} digits");
    // An ordinary case still starts (and ends) at 192 bits for 50 digits.
    let ordinary = certified_dissipation(ball_case(&acceptance()), 50).unwrap();
    assert_eq!(ordinary.enclosure.precision.in_bits(), 192);
}

#[test]
fn no_tangential_oscillation_is_exactly_zero() {
    let case = case("1", "0.4", "0", "0.4pi", "1", PERSSON);
    let certified = certified_dissipation(ball_case(&case), 50).unwrap();
    assert!(certified.enclosure.total.is_exact() && certified.enclosure.total.contains(&Float::new(64)));
}

#[test]
fn a_perturbation_of_1e_minus_40_moves_the_enclosure_off_the_old_value() {
    let plain = acceptance();
    let mut perturbed = acceptance();
    // v' + 1e-40·P: a linear term, which dissipates (W is linear in v', and v'' ≠ 0).
    perturbed.compliance = format!("{PERSSON}+poly:p0=0,coeffs=0;1e-40");
    let old = reference(&plain);
    let moved = certified_dissipation(ball_case(&perturbed), 50).unwrap();
    assert!(!moved.enclosure.total.contains(&old), "{:?}", moved.enclosure.total);
    let kept = certified_dissipation(ball_case(&plain), 50).unwrap();
    assert!(kept.enclosure.total.contains(&old));
}

#[test]
fn invalid_cycles_are_refused_with_the_cycle_error() {
    let gross = case("1", "0.4", "0.95", "1.5", "1", PERSSON);
    assert!(matches!(
        certified_dissipation(ball_case(&gross), 20),
        Err(CertifiedError::Cycle(_))
    ));
}

#[test]
fn near_gross_slip_is_certified() {
    // 2e-8 from gross slip: the sinh-mapped slip peaks end exactly at their centres.
    assert_certified(&case("1", "0.4", "0.8886569", "1.5", "1", PERSSON), 30);
}

/// The four-segment enclosure of W at a phase or amplitude near a degenerate cycle, which
/// must overlap the closed form's enclosure at the degenerate cycle itself: W is
/// continuous, and here differs from its limit by far less than the digits asked.
fn assert_limit_overlaps(degenerate: &Case, near: &Case, digits: u32) {
    let at = |case: &Case| {
        certified_dissipation(ball_case(case), digits)
            .unwrap_or_else(|e| panic!("{case:?}: {e}"))
            .enclosure
    };
    let (closed, limit) = (at(degenerate), at(near));
    assert!(closed.pieces > 0 && closed.segments.bc.is_exact() && closed.segments.ch.is_exact());
    let (low, high) = closed.total.bounds(400);
    let (near_low, near_high) = limit.total.bounds(400);
    assert!(
        low <= near_high && near_low <= high,
        "{degenerate:?}: {:?} and {:?} are disjoint",
        closed.total,
        limit.total
    );
    assert!(closed.total.contains(&reference(degenerate)), "{degenerate:?}");
}

#[test]
fn exactly_in_phase_is_enclosed_by_its_closed_form() {
    for spec in [
        PERSSON,
        "power:c=1,beta=-0.5",
        "hertz:r=1,estar=1",
        "poly:p0=1,coeffs=1;-0.3;0.05",
    ] {
        let mut degenerate = case("1", "0.4", "0.5", "0", "1", spec);
        degenerate.lambda = Some("1.5".into());
        let mut near = degenerate.clone();
        near.phi = "1e-60".into();
        assert_limit_overlaps(&degenerate, &near, 30);
    }
}

#[test]
fn constant_normal_load_is_enclosed_by_its_closed_form() {
    for spec in [PERSSON, "hertz:r=1,estar=1", "exp:a=1,c=2,d=0.1"] {
        let degenerate = case("1", "0", "0.3", "0.4pi", "0.8", spec);
        let mut near = degenerate.clone();
        near.p1 = "1e-60".into();
        assert_limit_overlaps(&degenerate, &near, 30);
    }
}

#[test]
fn in_phase_without_slip_is_exactly_zero() {
    // Q1 ≤ fP1 exactly in phase, also at φ = π read exactly from its text.
    let precision = Precision::bits(128);
    for (q1, phi) in [("0.3", "0"), ("0.39", "pi"), ("0.1", "-3pi")] {
        let phase = ExactPhase::parse(phi).unwrap();
        let (cycle_phase, _) = phase.reduce().unwrap().cycle_phase::<Ball>(precision);
        let (mut cycle, compliance) = ball_case(&case("1", "0.4", q1, "0", "1", PERSSON))(precision).unwrap();
        cycle.phase = cycle_phase;
        let enclosure = enclose_dissipation(&cycle, compliance.as_ref(), 128).unwrap();
        assert!(
            enclosure.total.is_exact() && enclosure.total.contains(&Float::new(64)),
            "{phi}"
        );
    }
}

#[test]
fn phases_within_1e_minus_100_of_0_and_pi_keep_their_offset() {
    let digits = 20;
    for (phi, q1) in [
        ("pi-1e-100", "0.2"),
        ("1e-100", "0.5"),
        ("pi+1e-100", "0.5"),
        ("-2pi+1e-100", "0.5"),
        ("3.141592653589793", "0.2"),
    ] {
        let phase = ExactPhase::parse(phi).unwrap();
        let base = case("1", "0.4", q1, "0", "1", PERSSON);
        let build = |precision: Precision| {
            let (mut cycle, compliance) = ball_case(&base)(precision)?;
            cycle.phase = phase
                .reduce()
                .map_err(|e| e.to_string())?
                .cycle_phase::<Ball>(precision)
                .0;
            Ok((cycle, compliance))
        };
        let certified = certified_dissipation(build, digits).unwrap_or_else(|e| panic!("{phi}: {e}"));
        // The reference: the library's quadrature in MPFR, with the phase reduced exactly
        // and enough bits for the cancellation near the multiple of π.
        let bits = 1600;
        let precision = Precision::bits(bits);
        let reduced = phase.reduce().unwrap();
        let mut cycle = cycle_at::<Float>(&base, precision);
        cycle.phase = reduced.cycle_phase::<Float>(precision).0;
        let compliance = parse_spec::<Float>(PERSSON, precision).unwrap();
        let options = Options::default().with_tolerance(Float::with_val(bits, Float::parse("1e-40").unwrap()));
        let exact = dissipation(&cycle, compliance.as_ref(), &options).unwrap().total;
        assert!(exact.is_normal(), "{phi}: W = {exact}");
        // The reference is good to its 1e-40 tolerance: the enclosure must meet it there.
        let slack = Float::with_val(bits, exact.abs_ref()) * Float::with_val(bits, Float::parse("1e-38").unwrap());
        let (low, high) = certified.enclosure.total.bounds(bits);
        assert!(
            low - &slack <= exact && exact <= high + &slack,
            "{phi}: {} outside {:?}",
            exact.to_string_radix(10, Some(30)),
            certified.enclosure.total
        );
        assert_eq!(
            certified.value.decimal.to_string(),
            Real::to_scientific(&exact, digits as usize),
            "{phi}"
        );
    }
}

/// W for a polynomial v' exactly, segment by segment, by the trigonometric polynomial
/// integrals of `exact::polynomial_dissipation` (no quadrature, no segment integrand of
/// the four-segment code): each certified segment must hold it. scripts/mutants.sh runs
/// this test on every mutation of a segment integrand, which must make it fail.
#[test]
fn segment_enclosures_hold_the_exact_polynomial_w() {
    let mut draws = Draws(7);
    let mut checked = 0;
    while checked < 6 {
        let coefficients: Vec<String> = (0..4).map(|_| draws.decimal(-2.0, 2.0)).collect();
        let spec = format!("poly:p0=1.1,coeffs={}", coefficients.join(";"));
        let p1 = draws.decimal(0.05, 0.9);
        let mut case = case(
            "1",
            &p1,
            &draws.decimal(0.01, 1.2),
            &draws.decimal(0.05, 3.1),
            "0.9",
            &spec,
        );
        case.lambda = Some(draws.decimal(1.0, 2.0));
        if cycle_at::<f64>(&case, Precision::DOUBLE).validate().is_err() {
            continue;
        }
        let bits = 300;
        let (cycle, compliance) = ball_case(&case)(Precision::bits(bits)).unwrap();
        let enclosure = enclose_dissipation(&cycle, compliance.as_ref(), bits).unwrap();
        let precision = Precision::bits(2 * bits);
        let polynomial = Polynomial {
            reference: number("1.1", precision),
            coefficients: coefficients.iter().map(|c| number(c, precision)).collect(),
        };
        let exact = polynomial_dissipation(&cycle_at::<Float>(&case, precision), &polynomial).unwrap();
        for segment in Segment::ALL {
            let ball = enclosure.segments.get(segment);
            assert!(ball.contains(exact.get(segment)), "{case:?} {segment}: {ball:?}");
            assert!(ball.relative_radius() < 1e-60, "{case:?} {segment}: {ball:?}");
        }
        checked += 1;
    }
}

// The tests below read the catalogue and printed decimals through the shared test helpers.

/// The Arb enclosure of W for a case given as text (the path the command line takes).
fn text_enclosure(
    text: &microslip::case::CaseText,
    digits: u32,
) -> Result<microslip::digits::enclosure::Certified, CertifiedError> {
    let spec = text.spec().unwrap_or_else(|e| panic!("{text:?}: {e}"));
    let read = |precision| {
        let case = spec.at::<Ball>(precision).map_err(|e| e.to_string())?;
        Ok((case.cycle, case.compliance))
    };
    certified_dissipation(read, digits)
}

/// Every committed reference value of the catalogue (tests/data/catalogue.json: 50
/// digits, written by `microslip reference --write`) is the rounding of every point of the
/// case's Arb enclosure at 60 digits — the committed digits are proven, corners included
/// (phases 1e-6 from 0 and π, in phase, P1 = 0, near gross slip, P_T near 0, 1e-6 from
/// separation, amplitudes to 1e-12, friction 0.01 and 10).
#[test]
fn every_catalogue_value_lies_in_its_enclosure() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/catalogue.json");
    let entries = microslip::catalogue::load(std::path::Path::new(path)).unwrap();
    assert_eq!(entries.len(), 21);
    for entry in &entries {
        let committed = entry
            .reference
            .as_ref()
            .unwrap_or_else(|| panic!("{}: no value", entry.name));
        let certified = text_enclosure(&entry.case, committed.digits + 10)
            .unwrap_or_else(|e| panic!("{}: no enclosure: {e}", entry.name));
        let (lower, upper) = certified
            .enclosure
            .total
            .bounds(certified.enclosure.precision.in_bits());
        common::every_point_rounds_to(&committed.w, &lower, &upper)
            .unwrap_or_else(|wrong| panic!("{}: {wrong}", entry.name));
    }
}

/// Scales a family's SPEC to loads of order `scale` = 10^k, so that the same shape of v'
/// is met at every scale (Persson, Hertz and power laws need no change).
fn scaled_spec(family: usize, k: i32) -> String {
    match family {
        0 => PERSSON.to_string(),
        1 => "power:c=1,beta=-0.25".to_string(),
        2 => "hertz:r=2,estar=0.5".to_string(),
        3 => format!("rational:a=0.2e{},b=1,c=0.1e{k}", -k),
        4 => format!("exp:a=1,c=3e{k},d=0.2"),
        5 => format!("poly:p0=1e{k},coeffs=1;-0.2e{};0.01e{}", -k, -2 * k),
        _ => format!("persson:gamma=1,sigma=0.5+power:c=0.5e{},beta=-0.75", k / 4),
    }
}

/// Random cases over every family at load scales 1e-300 … 1e300, some with Q1 or P1 down
/// to 1e-12 of P0 and some 1e-10 from gross slip: each enclosure at 40 digits holds the
/// 500-bit reference of the library's own Gauss–Legendre quadrature (a 1e-140 tolerance,
/// so more than 100 digits) and its 40 digits are the reference's, rounded.
#[test]
fn random_cases_at_the_corners_hold_their_100_digit_references() {
    let mut draws = Draws(2026);
    let mut certified = 0;
    while certified < 14 {
        let k = [-300, -120, 0, 150, 300][certified % 5];
        let family = certified % 7;
        let scale = |text: String| match text.split_once('e') {
            Some((mantissa, exponent)) => format!("{mantissa}e{}", exponent.parse::<i32>().unwrap() + k),
            None => format!("{text}e{k}"),
        };
        let p1_share = match certified % 3 {
            0 => "1e-12".to_string(),
            _ => draws.decimal(0.05, 0.9),
        };
        let friction = draws.decimal(0.3, 1.5);
        let (q1_share, phi) = match certified % 4 {
            // 1e-10 from gross slip at φ = π/2: Q1 = (1 − 1e-10) f √(1 − (P1/P0)²) P0.
            0 => {
                let f: f64 = friction.parse().unwrap();
                let p: f64 = p1_share.parse().unwrap();
                let p = Float::with_val(200, p);
                let edge: Float = Float::with_val(200, 1 - p.square()).sqrt() * f;
                let q: Float = edge * Float::with_val(200, 1 - Float::with_val(200, Float::parse("1e-10").unwrap()));
                (q.to_string_radix(10, Some(30)), "0.5pi".to_string())
            }
            1 => ("1e-12".to_string(), draws.decimal(0.05, 3.1)),
            _ => (draws.decimal(0.01, 1.2), draws.decimal(0.05, 3.1)),
        };
        let mut corner = case(
            &scale("1".into()),
            &scale(p1_share),
            &scale(q1_share),
            &phi,
            &friction,
            &scaled_spec(family, k),
        );
        corner.lambda = Some(draws.decimal(1.0, 2.0));
        if cycle_at::<Float>(&corner, Precision::bits(200)).validate().is_err() {
            continue;
        }
        assert_certified(&corner, 40);
        certified += 1;
    }
}

/// W of `case` printed by the library's one policy, with `digits` digits, or its refusal.
fn printed_w(case: &Case, digits: u32) -> Result<Answer, DissipationAnswerError> {
    dissipation_answer(case, Some(digits), Duration::from_secs(60))
}

/// An exponential v' = a·e^(−P/c) + d at loads of many decay loads c.
fn decay_case(p0: &str, p1: &str, q1: &str, phi: &str, decay_load: &str) -> Case {
    Case {
        lambda: Some("1.14".into()),
        ..case(p0, p1, q1, phi, "1.19", &format!("exp:a=2.204,c={decay_load},d=0.3174"))
    }
}

/// `text` (a decimal in scientific notation) as mantissa and decimal exponent, for
/// values whose exponents lie beyond any float's.
fn mantissa_and_exponent(text: &str) -> (String, i64) {
    let (mantissa, exponent) = text.split_once('e').expect("scientific notation");
    (mantissa.to_string(), exponent.parse().expect("an integer exponent"))
}

/// At constant normal load W = 4λf²·a·e^(−(P0 − q)/c)·(qc + qcE + 2c²(E − 1)) with q = Q1/f
/// and E = e^(−q/c), integrated by hand from the Masing loop's integral: its log10, formed
/// in MPFR at 300 bits, gives the mantissa and the exponent of W however small W is.
fn constant_normal_load_exponential(p0: &str, q1: &str) -> (Float, i64) {
    let number = |text: &str| Float::with_val(300, Float::parse(text).unwrap());
    let (p0, q1, f, lambda, a, c) = (
        number(p0),
        number(q1),
        number("1.19"),
        number("1.14"),
        number("2.204"),
        number("2.486"),
    );
    let q = q1 / &f;
    let e = (-(q.clone() / &c)).exp();
    let loop_integral = q.clone() * &c + &(q.clone() * &c * &e) + &(c.clone() * &c * 2u32 * &(e - 1u32));
    let prefactor = lambda * 4u32 * &f * &f * &a * &loop_integral;
    let log10 = prefactor.log10() - (p0 - &q) / &c / Float::with_val(300, 10u32).ln();
    let exponent = log10.clone().floor();
    let mantissa = Float::with_val(300, 10u32).pow(log10 - &exponent);
    (mantissa, exponent.to_f64() as i64)
}

/// An exponential at 10⁹ decay loads and more, where W lies far beyond the range of MPFR
/// (10^(−1.7·10⁹)): the constant-normal-load enclosure prints the digits of the Masing
/// loop integrated by hand, mantissa and exponent alike.
#[test]
fn an_exponential_far_beyond_mpfrs_range_is_proven_against_its_closed_form() {
    for p0 in ["1e4", "1e10", "1e15"] {
        let case = decay_case(p0, "0", "5e2", "0", "2.486");
        let answer = printed_w(&case, 20).expect("proven");
        assert!(
            matches!(answer.provenance, Provenance::Certified { .. }),
            "{p0}: {:?}",
            answer.provenance
        );
        let (mantissa, exponent) = mantissa_and_exponent(&answer.value.decimal.to_string());
        let (expected_mantissa, expected_exponent) = constant_normal_load_exponential(p0, "5e2");
        assert_eq!(exponent, expected_exponent, "{p0}");
        let printed = Float::with_val(300, Float::parse(&mantissa).unwrap());
        let unit = Float::with_val(300, 10u32).pow(-19i32) / 2u32;
        assert!(
            (printed - &expected_mantissa).abs() <= unit,
            "{p0}: {mantissa} against {expected_mantissa:.25}"
        );
    }
}

/// W is the same for loads and decay load scaled together, times the square of the
/// factor: at 10¹² decay loads (W ≈ 10^(−8.7·10¹¹)) the four-segment enclosures of two
/// such cases print the same digits, two decimal exponents apart. At 2000 decay loads
/// the enclosure holds Arb's own integration of the four segments (python-flint's
/// acb.integral, proofs/certified-digits.md, "Loads of many decay loads").
#[test]
fn an_exponential_at_many_decay_loads_is_proven_in_four_segments() {
    let small = printed_w(&decay_case("1e13", "5e12", "5e11", "2.39", "2.486"), 15).expect("proven");
    let large = printed_w(&decay_case("1e14", "5e13", "5e12", "2.39", "24.86"), 15).expect("proven");
    let (small_mantissa, small_exponent) = mantissa_and_exponent(&small.value.decimal.to_string());
    let (large_mantissa, large_exponent) = mantissa_and_exponent(&large.value.decimal.to_string());
    assert!(small_exponent < -800_000_000_000, "{small_exponent}");
    assert_eq!((large_mantissa, large_exponent), (small_mantissa, small_exponent + 2));
    let moderate = printed_w(&decay_case("1e4", "5e3", "5e2", "2.39", "2.486"), 15).expect("proven");
    assert_eq!(moderate.value.decimal.to_string(), "5.07262441320447e-870");
}

/// Beyond 10¹³ decay loads across the cycle the bounds cannot resolve v', and beyond
/// 2^(2^61) the decimal exponent is not printed: both are refused at once, with the reason.
#[test]
fn an_exponential_beyond_what_the_enclosure_resolves_is_refused_at_once() {
    let started = std::time::Instant::now();
    let steep = printed_w(&decay_case("1e41", "5e40", "5e39", "2.39", "2.486"), 15);
    assert!(
        matches!(steep, Err(DissipationAnswerError::Certified(CertifiedError::TooSteep { folds })) if folds > 4e40),
        "{steep:?}"
    );
    let tiny = printed_w(&decay_case("1e20", "1e7", "1e6", "2.39", "1"), 15);
    assert!(
        matches!(
            tiny,
            Err(DissipationAnswerError::Certified(
                CertifiedError::BeyondDecimalExponents
            ))
        ),
        "{tiny:?}"
    );
    assert!(started.elapsed() < Duration::from_secs(20), "{:?}", started.elapsed());
    // Near 10¹³ decay loads a cycle whose slip peak's piece outgrows Arb's evaluations is
    // refused by the enclosure at once: W lies beyond MPFR, so no agreement is tried.
    let started = std::time::Instant::now();
    let near_limit = case(
        "4.80093e7",
        "1.87577e7",
        "9.37742e6",
        "2.2408",
        "0.739",
        "exp:a=1,c=8.878e-6,d=0",
    );
    match printed_w(&near_limit, 15) {
        Ok(answer) => assert!(matches!(answer.provenance, Provenance::Certified { .. }), "{answer:?}"),
        Err(refusal) => assert!(
            matches!(
                refusal,
                DissipationAnswerError::Certified(CertifiedError::NotFinite { .. })
            ),
            "{refusal:?}"
        ),
    }
    assert!(started.elapsed() < Duration::from_secs(20), "{:?}", started.elapsed());
}

/// A ball whose size lies beyond MPFR's exponents prints by the one rule, its exponent
/// carried apart: a zero-centred one as the interval it spans, with no digit.
#[test]
fn a_ball_beyond_mpfrs_exponents_prints_its_interval() {
    let precision = Precision::bits(128);
    let tiny = Ball::from_i64(1, precision).times_power_of_two(i32::MIN) / &Ball::from_i64(3, precision);
    let around_zero = tiny.clone() - &tiny.clone();
    let printed = Value::of_ball(&around_zero, 128, 15);
    assert_eq!(printed.digits(), 0);
    let text = printed.decimal.to_string();
    assert!(text.contains("e-64645703"), "{text}");
    let third = Value::of_ball(&tiny, 128, 15);
    assert_eq!(third.digits(), 15);
    assert!(third.decimal.to_string().starts_with("1.892"), "{}", third.decimal);
}

/// A ball beyond MPFR's exponents reads into MPFR rounded outward as MPFR itself rounds
/// past its range: 0 or the least number below it, the largest finite number or infinity
/// beyond it, on the side the bound asks for.
#[test]
fn bounds_beyond_mpfrs_exponents_round_outward() {
    let precision = Precision::bits(128);
    let third = Ball::from_i64(1, precision) / &Ball::from_i64(3, precision);
    let mut least = Float::new(160);
    least.next_up();
    let mut largest = Float::with_val(160, rug::float::Special::Infinity);
    largest.next_down();
    for sign in [1, -1] {
        let tiny = third.clone().times_power_of_two(i32::MIN) * &Ball::from_i64(sign, precision);
        let huge = third.clone().times_power_of_two(i32::MAX) * &Ball::from_i64(sign, precision);
        let (tiny_low, tiny_high) = tiny.bounds(160);
        let (huge_low, huge_high) = huge.bounds(160);
        if sign > 0 {
            assert!(tiny_low.is_zero() && tiny_high == least, "{tiny_low} {tiny_high}");
            assert!(huge_low == largest && huge_high.is_infinite(), "{huge_low} {huge_high}");
        } else {
            assert!(
                tiny_low == -least.clone() && tiny_high.is_zero(),
                "{tiny_low} {tiny_high}"
            );
            assert!(
                huge_low.is_infinite() && huge_high == -largest.clone(),
                "{huge_low} {huge_high}"
            );
        }
    }
}
