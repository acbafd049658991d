//! f64 intervals against Arb balls at 256 bits: every interval holds the exact value of
//! what it computes (the ball, whose radius is far below an ulp of a double, lies inside
//! it), real and complex, at points and over wide arguments; results at points are a few
//! ulps wide; the Gauss–Legendre integrator encloses exact integrals narrowly.

use microslip::ball::Ball;
use microslip::doubts::{watch, with_analytic};
use microslip::interval::gauss::integrate;
use microslip::interval::Interval;
use microslip::real::{Precision, Real};
use proptest::prelude::*;
use rug::ops::Pow;
use rug::{Float, Integer, Rational};

const BITS: u32 = 256;

fn ball(x: f64) -> Ball {
    ball_at(x, BITS)
}

fn ball_at(x: f64, bits: u32) -> Ball {
    Ball::from_f64(x, Precision::bits(bits))
}

fn point(x: f64) -> Interval {
    Interval::from_f64(x, Precision::DOUBLE)
}

/// Whether the span [lo, hi] holds the exact value that `exact` encloses at any
/// precision: the ball at 256 bits, or where it overlaps an end of the span (a value
/// within 2^−256 of a double, such as cosh(2^−200) against 1), at up to 4096 bits.
fn span_holds(lo: f64, hi: f64, exact: &dyn Fn(u32) -> Ball) -> bool {
    span_holds_in(lo, hi, exact, EVERYWHERE)
}

/// The whole line: the range of a function not known to be bounded.
const EVERYWHERE: (f64, f64) = (f64::NEG_INFINITY, f64::INFINITY);

/// [`span_holds`] for a value known to lie in `range` (the ball clipped to it): the
/// intervals' functions clip their enclosures to such ranges (e^x − 1 ≥ −1), where no
/// precision may resolve the exact value (e^−4096 − 1 against −1).
fn span_holds_in(lo: f64, hi: f64, exact: &dyn Fn(u32) -> Ball, range: (f64, f64)) -> bool {
    [BITS, 1024, 4096].into_iter().any(|bits| {
        let ball = exact(bits);
        let (low, high) = ball.bounds(bits + 64);
        let (low, high) = (
            low.max(&Float::with_val(64, range.0)),
            high.min(&Float::with_val(64, range.1)),
        );
        ball.is_real() && ball.is_finite() && low >= lo && high <= hi
    })
}

/// Whether the real interval holds the exact value.
fn holds(value: &Interval, exact: &dyn Fn(u32) -> Ball) -> bool {
    holds_in(value, exact, EVERYWHERE)
}

/// Whether the real interval holds the exact value, known to lie in `range`.
fn holds_in(value: &Interval, exact: &dyn Fn(u32) -> Ball, range: (f64, f64)) -> bool {
    let (lo, hi) = value.real_bounds();
    value.is_real() && span_holds_in(lo, hi, exact, range)
}

/// The range of a function of the tests.
fn range(name: &str) -> (f64, f64) {
    match name {
        "exp" | "sqrt" | "abs" | "square" | "hypot" => (0.0, f64::INFINITY),
        "exp_m1" => (-1.0, f64::INFINITY),
        "cosh" => (1.0, f64::INFINITY),
        "sin" | "cos" => (-1.0, 1.0),
        _ => EVERYWHERE,
    }
}

/// A ball that stands for itself at every precision asked.
fn fixed(ball: &Ball) -> impl Fn(u32) -> Ball + '_ {
    move |_| ball.clone()
}

/// The doubles from lo to hi, ends included, less one.
fn ulps(value: &Interval) -> u64 {
    let order = |x: f64| {
        let bits = x.to_bits() as i64;
        if bits < 0 {
            i64::MIN - bits
        } else {
            bits
        }
    };
    let (lo, hi) = value.real_bounds();
    (order(hi) - order(lo)) as u64
}

/// The functions of one argument, by name, for either type.
const UNARY: [&str; 15] = [
    "sqrt", "cbrt", "ln", "ln_1p", "exp", "exp_m1", "sin", "cos", "sinh", "cosh", "abs", "square", "cube", "inverse",
    "power",
];

fn unary<R: Real>(name: &str, x: &R) -> R {
    match name {
        "sqrt" => x.sqrt(),
        "cbrt" => x.cbrt(),
        "ln" => x.ln(),
        "ln_1p" => x.ln_1p(),
        "exp" => x.exp(),
        "exp_m1" => x.exp_m1(),
        "sin" => x.sin(),
        "cos" => x.cos(),
        "sinh" => x.sinh_cosh().0,
        "cosh" => x.sinh_cosh().1,
        "abs" => x.abs(),
        "square" => x.square(),
        "cube" => x.powi(3),
        "inverse" => x.int(1) / x.clone(),
        "power" => x.powr(&x.ratio(7, 4)),
        _ => unreachable!("{name}"),
    }
}

/// The functions of two arguments, by name, for either type.
const BINARY: [&str; 8] = ["add", "sub", "mul", "div", "powr", "hypot", "atan2", "powi"];

fn binary<R: Real>(name: &str, x: &R, y: &R) -> R {
    match name {
        "add" => x.clone() + y,
        "sub" => x.clone() - y,
        "mul" => x.clone() * y,
        "div" => x.clone() / y,
        "powr" => x.powr(y),
        "hypot" => x.hypot(y),
        "atan2" => x.atan2(y),
        "powi" => x.powi(y.to_f64_lossy().clamp(-40.0, 40.0) as i32),
        _ => unreachable!("{name}"),
    }
}

/// Doubles of every size: ±m·2^e with m in [1, 2) and e in `exponents`.
fn double(exponents: std::ops::Range<i32>) -> impl Strategy<Value = f64> {
    (any::<bool>(), 1.0f64..2.0, exponents).prop_map(|(negative, m, e)| {
        let x = m * 2f64.powi(e);
        if negative {
            -x
        } else {
            x
        }
    })
}

/// An argument: mostly moderate, sometimes tiny or huge, sometimes an edge.
fn argument() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => double(-8..8),
        2 => double(-1070..1020),
        1 => proptest::sample::select(vec![
            0.0, -0.0, 1.0, -1.0, 5e-324, -5e-324, f64::MIN_POSITIVE, 709.78, -745.1, 1e300, -1e300,
            std::f64::consts::FRAC_PI_2, std::f64::consts::PI, -std::f64::consts::PI, 1e22, 0.5, -0.5,
        ]),
    ]
}

/// Checks `interval` against the exact `ball`: held where the ball is finite, at most
/// `most_ulps` wide where both are, not finite where the ball is indeterminate.
fn check(
    name: &str,
    what: &str,
    interval: &Interval,
    exact_at: &dyn Fn(u32) -> Ball,
    most_ulps: u64,
) -> Result<(), TestCaseError> {
    let exact = exact_at(BITS);
    if !exact.is_finite() {
        prop_assert!(!interval.is_finite(), "{what}: {interval:?} for an indeterminate ball");
        return Ok(());
    }
    prop_assert!(
        holds_in(interval, exact_at, range(name)),
        "{what}: {interval:?} does not hold {exact:?}"
    );
    if interval.is_finite() {
        prop_assert!(
            ulps(interval) <= most_ulps,
            "{what}: {interval:?} is {} ulps wide",
            ulps(interval)
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    #[test]
    fn functions_at_points_hold_the_exact_values_within_four_ulps(x in argument(), y in argument()) {
        for name in UNARY {
            let exact = |bits| unary(name, &ball_at(x, bits));
            check(name, &format!("{name}({x:e})"), &unary(name, &point(x)), &exact, 4)?;
        }
        for name in BINARY {
            let what = format!("{name}({x:e}, {y:e})");
            let exact = |bits| binary(name, &ball_at(x, bits), &ball_at(y, bits));
            check(name, &what, &binary(name, &point(x), &point(y)), &exact, 4)?;
        }
    }

    #[test]
    fn functions_over_wide_arguments_hold_every_value_inside(
        a in argument(), width in double(-30..4), fractions in proptest::collection::vec(0.0f64..1.0, 4)
    ) {
        // At least the next double: a width below a's ulp would give a point.
        let b = (a + width.abs()).max(a.next_up());
        let wide = Interval::new(a, b);
        // The ends, points between, and where sine and cosine turn (kπ/2 near the middle).
        let turn = (a * 0.5 + b * 0.5) / std::f64::consts::FRAC_PI_2;
        let mut inside: Vec<f64> = fractions.iter().map(|t| a + (b - a) * t).collect();
        inside.extend([a, b]);
        if turn.abs() < 1e15 {
            let k = turn.round();
            inside.extend((-2..=2).map(|j| (k + f64::from(j)) * std::f64::consts::FRAC_PI_2));
        }
        for x in inside.into_iter().filter(|x| (a..=b).contains(x)) {
            for name in UNARY {
                let value = unary(name, &wide);
                let exact_at = |bits| unary(name, &ball_at(x, bits));
                let exact = exact_at(BITS);
                // An indeterminate interval (NaN: an argument outside the domain) holds everything.
                if exact.is_finite() && !value.real_bounds().0.is_nan() {
                    prop_assert!(holds_in(&value, &exact_at, range(name)), "{name}([{a:e}, {b:e}]) = {value:?} ∌ f({x:e}) = {exact:?}");
                }
            }
            for name in ["powr", "hypot", "atan2"] {
                // The wide interval against a point, and a point against it.
                let y = 0.75;
                for (first, second, flipped) in [(wide, point(y), false), (point(y), wide, true)] {
                    let exact_at = |bits| {
                        let (u, v) = (ball_at(x, bits), ball_at(y, bits));
                        if flipped { binary(name, &v, &u) } else { binary(name, &u, &v) }
                    };
                    let exact = exact_at(BITS);
                    let value = binary(name, &first, &second);
                    if exact.is_finite() && !value.real_bounds().0.is_nan() {
                        prop_assert!(holds_in(&value, &exact_at, range(name)), "{name}: {value:?} ∌ {exact:?} at {x:e}");
                    }
                }
            }
        }
    }

    #[test]
    fn complex_functions_hold_their_values_at_every_point_of_the_rectangle(
        re in double(-6..4), im in double(-6..4), sizes in (double(-20..-1), double(-20..-1)),
        fractions in (0.0f64..1.0, 0.0f64..1.0)
    ) {
        let (re_end, im_end) = (re + sizes.0.abs(), im + sizes.1.abs());
        let rectangle = Interval::rectangle((re, re_end), (im, im_end));
        let x = re + (re_end - re) * fractions.0;
        let y = im + (im_end - im) * fractions.1;
        prop_assume!((re..=re_end).contains(&x) && (im..=im_end).contains(&y));
        for (index, (name, parts)) in complex_references(x, y, BITS).into_iter().enumerate() {
            let (value, doubts) = watch(|| with_analytic(true, || unary(name, &rectangle)));
            let Some((exact_re, exact_im)) = parts else {
                // Not analytic on the rectangle: an indeterminate value and a doubt.
                prop_assert!(!value.is_finite() && !doubts.none(), "{name}: {value:?}");
                continue;
            };
            if value.is_finite() {
                let ((a, b), (c, d)) = (value.real_bounds(), value.imaginary_bounds());
                let part = |imaginary: bool| move |bits| {
                    let parts = complex_references(x, y, bits).swap_remove(index).1.expect("off the cut");
                    if imaginary { parts.1 } else { parts.0 }
                };
                prop_assert!(span_holds(a, b, &part(false)), "{name} at ({x:e}, {y:e}): re {value:?} ∌ {exact_re:?}");
                prop_assert!(span_holds(c, d, &part(true)), "{name} at ({x:e}, {y:e}): im {value:?} ∌ {exact_im:?}");
            } else {
                // Only where the rectangle meets the branch cut may it refuse.
                prop_assert!(re <= 0.0 && im <= 0.0 && im_end >= 0.0, "{name}: {value:?} on {rectangle:?}");
            }
        }
    }
}

/// The exact values (real and imaginary parts, as balls from the real formulas) of the
/// functions at x + iy; `None` for a function whose branch cut the point lies on or past
/// (x ≤ 0 with y = 0) — never reached by the rectangles of the test but for x ≤ 0, y = 0.
#[allow(clippy::type_complexity)]
fn complex_references(x: f64, y: f64, bits: u32) -> Vec<(&'static str, Option<(Ball, Ball)>)> {
    let (x, y) = (&ball_at(x, bits), &ball_at(y, bits));
    let (sin_x, cos_x) = x.sin_cos();
    let (sin_y, cos_y) = y.sin_cos();
    let (sinh_x, cosh_x) = x.sinh_cosh();
    let (sinh_y, cosh_y) = y.sinh_cosh();
    let exp_x = x.exp();
    let modulus = x.hypot(y);
    let angle = y.atan2(x);
    let on_cut = *x <= x.int(0) && *y == y.int(0);
    let polar = |power: Ball| {
        let scale = modulus.powr(&power);
        let turned = angle.clone() * &power;
        (scale.clone() * &turned.cos(), scale * &turned.sin())
    };
    let norm = x.square() + &y.square();
    let branch = |parts: (Ball, Ball)| (!on_cut).then_some(parts);
    vec![
        ("sqrt", branch(polar(x.ratio(1, 2)))),
        ("ln", branch((modulus.ln(), angle.clone()))),
        ("power", branch(polar(x.ratio(7, 4)))),
        ("exp", Some((exp_x.clone() * &cos_y, exp_x.clone() * &sin_y))),
        ("exp_m1", Some((exp_x.clone() * &cos_y - &x.int(1), exp_x * &sin_y))),
        ("sin", Some((sin_x.clone() * &cosh_y, cos_x.clone() * &sinh_y))),
        ("cos", Some((cos_x.clone() * &cosh_y, -(sin_x.clone() * &sinh_y)))),
        ("sinh", Some((sinh_x.clone() * &cos_y, cosh_x.clone() * &sin_y))),
        ("cosh", Some((cosh_x * &cos_y, sinh_x * &sin_y))),
        (
            "cube",
            Some((
                x.powi(3) - &(x.int(3) * x * &y.square()),
                x.int(3) * &x.square() * y - &y.powi(3),
            )),
        ),
        ("inverse", Some((x.clone() / &norm, -(y.clone() / &norm)))),
    ]
}

#[test]
fn sine_and_cosine_reach_their_extrema_inside_an_interval_and_only_there() {
    let half_pi = std::f64::consts::FRAC_PI_2;
    // [π/2 − 0.1, π/2 + 0.1] holds sine's maximum: its upper end is 1.
    let around_top = Interval::new(half_pi - 0.1, half_pi + 0.1);
    assert_eq!(around_top.sin().real_bounds().1, 1.0);
    // Just below π/2 (the double below it is below π/2): increasing, below 1.
    let below = Interval::new(1.0, half_pi);
    assert!(below.sin().real_bounds().1 <= 1.0 && below.sin().real_bounds().0 > 0.84);
    // [3π/2 ± 0.1]: sine's minimum −1; cosine's range there holds 0 and is narrow.
    let three_halves = Interval::new(3.0 * half_pi - 0.1, 3.0 * half_pi + 0.1);
    assert_eq!(three_halves.sin().real_bounds().0, -1.0);
    let (lo, hi) = three_halves.cos().real_bounds();
    assert!(lo < 0.0 && hi > 0.0 && hi - lo < 0.21, "{lo} {hi}");
    // A period or more: [−1, 1]; far out, a narrow interval still turns correctly.
    assert_eq!(Interval::new(0.0, 7.0).cos().real_bounds(), (-1.0, 1.0));
    let far = 1e6 * std::f64::consts::PI;
    let near_far = Interval::new(far - 1e-3, far + 1e-3).cos();
    let exact = ball(far).cos();
    // 10⁶π, an even multiple of π, lies inside: the upper end is 1.
    let (lo, hi) = near_far.real_bounds();
    assert!(
        holds(&near_far, &fixed(&exact)) && hi == 1.0 && lo > 0.999 && lo < 1.0,
        "{near_far:?}"
    );
}

#[test]
fn inputs_are_enclosed_by_the_doubles_nearest_them() {
    let p = Precision::DOUBLE;
    let tenth = Interval::parse_decimal("0.1", p).unwrap();
    let exact_tenth = Ball::parse_decimal("0.1", Precision::bits(BITS)).unwrap();
    assert!(holds(&tenth, &fixed(&exact_tenth)) && ulps(&tenth) == 1, "{tenth:?}");
    assert!(Interval::parse_decimal("1.5", p).unwrap().is_exact());
    for bad in ["", "abc", "inf", "nan", "1e", "0x10"] {
        assert!(Interval::parse_decimal(bad, p).is_err(), "{bad}");
    }
    // Below the least subnormal: [0, 5e-324]; beyond the largest double: [MAX, ∞].
    let tiny = Interval::from_rational(&Rational::from((1, Integer::from(10).pow(400u32))), p);
    assert_eq!(tiny.real_bounds(), (0.0, 5e-324));
    let huge = Interval::parse_decimal("1e400", p).unwrap();
    assert_eq!(huge.real_bounds(), (f64::MAX, f64::INFINITY));
    let third = Interval::from_rational(&Rational::from((1, 3)), p);
    assert!(holds(&third, &fixed(&(ball(1.0) / &ball(3.0)))) && ulps(&third) == 1);
    let big = Rational::from((Integer::from(10).pow(30u32) + 7u32, 3));
    let exact = Ball::from_rational(&big, Precision::bits(BITS));
    assert!(holds(&Interval::from_rational(&big, p), &fixed(&exact)));
    let float = Float::with_val(200, 1) / 7u32;
    assert!(holds(
        &Interval::from_float(&float, p),
        &fixed(&Ball::from_float(&float, Precision::bits(BITS)))
    ));
    // 2⁶³ − 1 lies between the doubles 2⁶³ − 1024 and 2⁶³; 2⁵³ + 1 between 2⁵³ and 2⁵³ + 2.
    assert_eq!(
        Interval::from_i64(i64::MAX, p).real_bounds(),
        (2f64.powi(63) - 1024.0, 2f64.powi(63))
    );
    assert_eq!(
        Interval::from_i64((1 << 53) + 1, p).real_bounds(),
        (2f64.powi(53), 2f64.powi(53) + 2.0)
    );
    assert!(Interval::from_i64(-(1 << 53), p).is_exact());
    let pi = Interval::pi(p);
    assert!(holds(&pi, &|bits| Ball::pi(Precision::bits(bits))) && ulps(&pi) == 1);
}

#[test]
fn multiples_of_pi_are_enclosed_tightly_however_large() {
    let p = Precision::DOUBLE;
    for (multiple, offset) in [
        (Rational::from(3), Rational::from((1, 3))),
        (Rational::from(Integer::from(10).pow(100u32)), Rational::from((-1, 7))),
        (Rational::from((-5, 2)), Rational::from(0)),
        (
            Rational::from(-1),
            Rational::from((314159265358979u64, 100000000000000u64)),
        ),
    ] {
        let value = Interval::enclose_pi_multiple(&multiple, &offset, p).unwrap();
        let exact = Ball::enclose_pi_multiple(&multiple, &offset, Precision::bits(BITS)).unwrap();
        assert!(holds(&value, &fixed(&exact)), "{value:?} ∌ {exact:?}");
        assert!(ulps(&value) <= 2 || value.width() < 1e-28, "{value:?}");
    }
}

#[test]
fn comparisons_decide_disjoint_intervals_and_count_the_rest() {
    let (one, two) = (point(1.0), point(2.0));
    let third = point(1.0) / point(3.0);
    let (answers, doubts) = watch(|| {
        [
            one.lt(&two),
            two.gt(&one),
            one.le(&one),
            one.ge(&one),
            one.eq(&one),
            third.lt(&one),
            third.gt(&one),
        ]
    });
    assert_eq!(answers, [true, true, true, true, true, true, false]);
    assert!(doubts.none());
    assert!(one.max_of(&two).is_exact() && one.min_of(&two).real_bounds() == (1.0, 1.0));
    let wide = Interval::new(0.5, 1.5);
    let (answers, doubts) = watch(|| [wide.lt(&one), wide.ge(&one), wide.eq(&one)]);
    assert_eq!(answers, [false; 3]);
    assert_eq!(doubts.undecided_comparisons, 3);
    // max needs no decision on real intervals.
    let (larger, doubts) = watch(|| wide.max_of(&one));
    assert!(larger.real_bounds() == (1.0, 1.5) && doubts.none());
}

#[test]
fn branch_cuts_and_undecided_signs_are_doubts_in_analytic_mode() {
    let across_cut = Interval::rectangle((-2.0, -1.0), (-0.5, 0.5));
    let straddling = Interval::rectangle((-0.5, 0.5), (1.0, 2.0));
    let (values, doubts) = watch(|| {
        with_analytic(true, || {
            [
                across_cut.ln(),
                across_cut.sqrt(),
                across_cut.powr(&point(0.5)),
                straddling.cbrt(),
                point(-1.0).ln_1p(),
                point(1.0).atan2(&point(1.0)),
                Interval::new(0.5, 1.5).floor(),
            ]
        })
    });
    assert!(values.iter().all(|v| !v.is_finite()), "{values:?}");
    assert_eq!(doubts.not_analytic, 7);
    let (value, doubts) = watch(|| with_analytic(true, || straddling.abs()));
    assert!(!value.is_finite() && doubts.undecided_comparisons == 1);
    // Off the cut, the same functions are analytic; real arguments keep their real form.
    let (values, doubts) = watch(|| with_analytic(true, || [across_cut.exp(), point(2.0).sqrt(), point(3.0).ln()]));
    assert!(doubts.none() && values.iter().all(Real::is_finite));
    assert!(holds(&values[1], &|bits| ball_at(2.0, bits).sqrt()) && ulps(&values[1]) <= 2);
    // Outside analytic mode a real negative argument is indeterminate, as f64 gives NaN.
    assert!(!point(-1.0).sqrt().is_finite() && !point(-1.0).ln().is_finite() && point(-1.0).sqrt().is_real());
}

/// The integrand under the analytic mode the rule asks for.
fn analytic(f: impl Fn(&Interval) -> Interval) -> impl Fn(&Interval, bool) -> Option<Interval> {
    move |x, required| Some(with_analytic(required, || f(x)))
}

/// An integral: its name, integrand, limits and exact value.
type Case = (&'static str, Box<dyn Fn(&Interval) -> Interval>, f64, f64, Ball);

#[test]
fn the_integrator_encloses_exact_integrals_narrowly() {
    let b = |x: f64| ball(x);
    let cases: Vec<Case> = vec![
        (
            "e^x",
            Box::new(|x: &Interval| x.exp()),
            1.0,
            2.0,
            b(2.0).exp() - &b(1.0).exp(),
        ),
        (
            "1/(1+x²)",
            Box::new(|x: &Interval| x.int(1) / (x.square() + x.int(1))),
            0.0,
            1.0,
            Ball::pi(Precision::bits(BITS)) / &b(4.0),
        ),
        (
            "x^-0.5",
            Box::new(|x: &Interval| x.powr(&x.ratio(-1, 2))),
            1.0,
            2.0,
            (b(2.0).sqrt() - &b(1.0)) * &b(2.0),
        ),
        (
            "e^(-100x)",
            Box::new(|x: &Interval| (*x * x.int(-100)).exp()),
            0.0,
            1.0,
            (b(1.0) - &b(-100.0).exp()) / &b(100.0),
        ),
        (
            "ln x",
            Box::new(|x: &Interval| x.ln()),
            1.0,
            2.0,
            b(2.0) * &b(2.0).ln() - &b(1.0),
        ),
        (
            "sin(20x)",
            Box::new(|x: &Interval| (*x * x.int(20)).sin()),
            0.0,
            1.0,
            (b(1.0) - &b(20.0).cos()) / &b(20.0),
        ),
        (
            "1/(x+3)",
            Box::new(|x: &Interval| x.int(1) / (*x + x.int(3))),
            0.0,
            10.0,
            (b(13.0) / &b(3.0)).ln(),
        ),
    ];
    for (name, f, a, z, exact) in cases {
        let integrand = analytic(f);
        let value = integrate(&integrand, &point(a), &point(z), 1e-17, 256).unwrap_or_else(|| panic!("{name}: none"));
        assert!(holds(&value, &fixed(&exact)), "{name}: {value:?} ∌ {exact:?}");
        // Rounding errors scale with ∫|f|, which is the integral but for sin(20x) (whose
        // integral cancels to 0.03 of it: ∫₀¹ |sin 20x| dx > 0.6).
        let scale = if name == "sin(20x)" {
            0.6
        } else {
            value.real_bounds().0.abs()
        };
        assert!(value.width() < 1e-13 * scale, "{name}: {value:?} is too wide");
    }
}

#[test]
fn the_integrator_gives_up_where_no_ellipse_avoids_a_singularity() {
    // 1/x across 0 and x^-½ up to its singular end: no part near 0 has a bound.
    let reciprocal = analytic(|x: &Interval| x.int(1) / x);
    assert!(integrate(&reciprocal, &point(-1.0), &point(1.0), 1e-15, 256).is_none());
    let root = analytic(|x: &Interval| x.powr(&x.ratio(-1, 2)));
    assert!(integrate(&root, &point(0.0), &point(1.0), 1e-15, 256).is_none());
    // An integrand refusing every rectangle.
    let never = |x: &Interval, analytic: bool| (!analytic).then_some(*x);
    assert!(integrate(&never, &point(0.0), &point(1.0), 1e-15, 256).is_none());
}

#[test]
fn the_error_bound_is_not_below_the_true_error() {
    // A loose tolerance: the rule stops at few points, and the interval, whose width is
    // mostly the bound, must still hold the exact value.
    let integrand = analytic(|x: &Interval| x.exp());
    let value = integrate(&integrand, &point(-1.0), &point(1.0), 1e-6, 256).unwrap();
    let exact = ball(1.0).exp() - &ball(-1.0).exp();
    assert!(holds(&value, &fixed(&exact)), "{value:?}");
    assert!(value.width() > 1e-9 && value.width() < 4e-6, "{value:?}");
}
