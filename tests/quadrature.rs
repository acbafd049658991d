//! The quadrature rules against exact values.

use std::sync::Arc;

use microslip::quad::engine::{self, FixedRule, Piece, QuadError, Rule, RuleError, Settings, Stop};
use microslip::quad::{gauss_legendre, tanh_sinh};
use microslip::real::{Precision, Real};
use rug::Float;

/// ∫₋₁¹ x^k dx.
fn monomial_integral<R: Real>(k: i64, like: &R) -> R {
    if k % 2 == 1 {
        like.int(0)
    } else {
        like.ratio(2, k + 1)
    }
}

fn check_polynomial_exactness<R: Real>(precision: Precision, tolerance: f64) {
    for n in [1usize, 2, 3, 8, 13, 32] {
        let table = gauss_legendre::node_table::<R>(n, precision);
        let one = R::from_i64(1, precision);
        for k in 0..(2 * n as i64) {
            let value = table.integrate(|x: &R| x.powi(k as i32), &(-one.clone()), &one);
            let exact = monomial_integral(k, &one);
            let error = (value - &exact).abs().to_f64_lossy();
            assert!(error < tolerance, "n={n}, x^{k}: error {error:e}");
        }
        // Degree 2n is the first the rule misses, by exactly 2^(2n+1) (n!)^4 / ((2n+1) ((2n)!)^2).
        let k = 2 * n as i64;
        let value = table.integrate(|x: &R| x.powi(k as i32), &(-one.clone()), &one);
        let shortfall = monomial_integral(k, &one) - value;
        let expected = gauss_error_on_x_to_the_2n(n, &one);
        if expected.to_f64_lossy() > 1e6 * tolerance {
            let relative = ((shortfall - &expected) / &expected).abs().to_f64_lossy();
            assert!(relative < 1e-6, "n={n}: x^{k} shortfall off by {relative:e} relative");
        }
    }
}

/// The Gauss–Legendre error on x^(2n): 2^(2n+1) (n!)^4 / ((2n+1) ((2n)!)^2).
fn gauss_error_on_x_to_the_2n<R: Real>(n: usize, one: &R) -> R {
    let factorial = |m: usize| (1..=m as i64).fold(one.clone(), |acc, i| acc * &one.int(i));
    one.int(2).powi(2 * n as i32 + 1) * &factorial(n).powi(4) / (one.int(2 * n as i64 + 1) * &factorial(2 * n).square())
}

#[test]
fn gauss_legendre_is_exact_on_polynomials_of_degree_2n_minus_1_in_f64() {
    check_polynomial_exactness::<f64>(Precision::DOUBLE, 1e-13);
}

#[test]
fn gauss_legendre_is_exact_on_polynomials_of_degree_2n_minus_1_at_200_bits() {
    check_polynomial_exactness::<Float>(Precision::bits(200), 1e-55);
}

/// One piece for the engine.
fn piece<'a, R: Real>(label: &'static str, integrand: impl Fn(&R) -> R + 'a, start: R, end: R) -> Piece<'a, R> {
    Piece {
        label,
        integrand: Box::new(integrand),
        start,
        end,
    }
}

#[test]
fn gauss_legendre_gives_pi_to_100_digits() {
    let p = Precision::bits(360);
    let (zero, one) = (Float::from_i64(0, p), Float::from_i64(1, p));
    let tolerance = Float::parse_decimal("1e-104", p).unwrap();
    let settings = Settings {
        first_points: 8,
        max_points: 1024,
        ..Settings::new(tolerance.clone())
    };
    let pieces = [piece("π", |x: &Float| x.int(4) / (x.int(1) + &x.square()), zero, one)];
    let integrated = engine::integrate(&pieces, &settings).unwrap();
    let result = &integrated.pieces[0];
    assert!(result.estimate.converged);
    assert!(matches!(
        result.stop,
        Stop::Converged | Stop::Predicted | Stop::RoundingFloor
    ));
    let points = result.rule.gauss_legendre_points();
    assert!(points <= 1024 && points == integrated.largest_rule);
    let error = (result.estimate.value.clone() - Float::pi(p)).abs();
    assert!(
        error < Float::parse_decimal("1e-100", p).unwrap(),
        "error {}",
        error.to_f64()
    );
    assert!(result.estimate.error < tolerance.clone() * 4u32);
    // A positive integrand: ∫|f| is the integral itself.
    let magnitude_error = (result.magnitude.clone() - Float::pi(p)).abs();
    assert!(magnitude_error < Float::parse_decimal("1e-100", p).unwrap());
}

/// Where Gauss–Legendre converges only algebraically (an end-point singularity), the
/// engine hands the piece to tanh–sinh and still reaches the tolerance; the error of a
/// piece it adds to the others' is counted once in the total.
#[test]
fn engine_falls_back_to_tanh_sinh_on_an_end_point_singularity() {
    let p = Precision::bits(200);
    let reference = cos_over_sqrt_series(p);
    let (zero, one) = (Float::from_i64(0, p), Float::from_i64(1, p));
    let pieces = [
        piece(
            "smooth",
            |x: &Float| x.int(4) / (x.int(1) + &x.square()),
            zero.clone(),
            one.clone(),
        ),
        piece("singular", |x: &Float| x.cos() / x.sqrt(), zero, one),
    ];
    let integrated = engine::integrate(&pieces, &Settings::new(Float::parse_decimal("1e-52", p).unwrap())).unwrap();
    let singular = &integrated.pieces[1];
    assert!(singular.estimate.converged);
    let error = (singular.estimate.value.clone() - &reference).abs() / &reference;
    assert!(error < 1e-50, "relative error {:e}", error.to_f64());
    // Tanh–sinh finished it: the doubling sequence up to the largest rule costs less than
    // twice that rule, and the piece took more.
    assert!(singular.estimate.evaluations > 2 * integrated.largest_rule);
    assert_eq!(singular.stop, Stop::TanhSinh);
    assert!(matches!(singular.rule, Rule::TanhSinh { after } if after <= integrated.largest_rule));
    // A check by a finer fixed rule starts from the largest rule on the piece tanh–sinh finished.
    assert_eq!(integrated.check_rules()[1], integrated.largest_rule);
    let summed = integrated.pieces[0].estimate.error.clone() + &singular.estimate.error;
    assert_eq!(integrated.error, summed);
    let evaluations: usize = integrated.pieces.iter().map(|piece| piece.estimate.evaluations).sum();
    assert_eq!(integrated.evaluations, evaluations);
}

#[test]
fn engine_names_the_piece_that_is_not_finite_and_stops_at_the_deadline() {
    let pieces = [
        piece("fine", |x: &f64| x.exp(), 0.0, 1.0),
        piece("broken", |x: &f64| 1.0 / (x - 0.5).abs().min(0.0), 0.0, 1.0),
    ];
    let error = engine::integrate(&pieces, &Settings::new(1e-13)).unwrap_err();
    assert_eq!(error, QuadError::NotFinite { piece: "broken" });
    let settings = Settings {
        deadline: Some(std::time::Instant::now()),
        ..Settings::new(1e-13)
    };
    let error = engine::integrate(&pieces[..1], &settings).unwrap_err();
    assert_eq!(error, QuadError::OutOfTime);
}

/// A fixed rule integrates each piece once with its own rule, the error from the rule of
/// a quarter of the points.
#[test]
fn engine_fixed_rules_use_each_piece_s_own_rule() {
    let pieces = [
        piece("exp", |x: &f64| x.exp(), 0.0, 1.0),
        piece("cos", |x: &f64| x.cos(), 0.0, 1.0),
    ];
    let settings = Settings {
        fixed: Some(FixedRule {
            points: 8,
            per_piece: Some(vec![4, 16]),
            error: RuleError::QuarterRule,
        }),
        ..Settings::new(1e-13)
    };
    let integrated = engine::integrate(&pieces, &settings).unwrap();
    assert_eq!(integrated.check_rules(), vec![4, 16]);
    assert_eq!(integrated.stops(), vec![Stop::Fixed, Stop::Fixed]);
    assert_eq!(integrated.evaluations, 4 + 1 + 16 + 4);
    assert!((integrated.pieces[1].estimate.value - 1f64.sin()).abs() < 1e-15);
    // Four points leave exp ~1e−9 off, which the single point of the coarse rule oversizes.
    let exp = &integrated.pieces[0].estimate;
    assert!((exp.value - (1f64.exp() - 1.0)).abs() < exp.error && exp.error < 0.1);
}

#[test]
fn tanh_sinh_nodes_are_cached_per_level_and_precision() {
    let first = tanh_sinh::nodes::<Float>(3, Precision::bits(150));
    assert!(Arc::ptr_eq(&first, &tanh_sinh::nodes::<Float>(3, Precision::bits(150))));
    assert!(!Arc::ptr_eq(
        &first,
        &tanh_sinh::nodes::<Float>(3, Precision::bits(151))
    ));
    assert!(!Arc::ptr_eq(
        &first,
        &tanh_sinh::nodes::<Float>(4, Precision::bits(150))
    ));
    // Level 3 adds the odd multiples of 1/8 up to u_max; level 0 has the midpoint.
    let level = tanh_sinh::nodes::<f64>(3, Precision::DOUBLE);
    assert!(!level.has_middle && tanh_sinh::nodes::<f64>(0, Precision::DOUBLE).has_middle);
    let (complement, weight) = &level.nodes[0];
    let s = std::f64::consts::FRAC_PI_2 * 0.125f64.sinh();
    assert!((complement - (1.0 - s.tanh())).abs() < 1e-15);
    let expected = std::f64::consts::FRAC_PI_2 * 0.125f64.cosh() / s.cosh().powi(2);
    assert!((weight - expected).abs() < 1e-15);
}

/// ∫₀¹ x^(−1/2) cos x dx = Σₖ (−1)^k / ((2k)! (2k + 1/2)), summed until the terms vanish.
fn cos_over_sqrt_series(p: Precision) -> Float {
    let mut sum = Float::from_i64(0, p);
    let mut factorial = Float::from_i64(1, p);
    for k in 0..200i64 {
        if k > 0 {
            factorial *= Float::from_i64((2 * k - 1) * (2 * k), p);
        }
        let denominator = factorial.clone() * &(Float::from_i64(4 * k + 1, p) / Float::from_i64(2, p));
        let term = Float::from_i64(1, p) / denominator;
        if k % 2 == 0 {
            sum += term;
        } else {
            sum -= term;
        }
    }
    sum
}

#[test]
fn tanh_sinh_integrates_an_inverse_square_root_singularity_to_50_digits() {
    let p = Precision::bits(200);
    let reference = cos_over_sqrt_series(p);
    let (zero, one) = (Float::from_i64(0, p), Float::from_i64(1, p));
    let tolerance = Float::parse_decimal("1e-55", p).unwrap();
    let estimate = tanh_sinh::integrate(|x: &Float| x.cos() / x.sqrt(), &zero, &one, &tolerance, 12);
    assert!(estimate.converged, "error estimate {}", estimate.error.to_f64());
    let error = (estimate.value.clone() - &reference).abs() / &reference;
    assert!(
        error < Float::parse_decimal("1e-50", p).unwrap(),
        "relative error {:e}",
        error.to_f64()
    );
    // The same integral by Gauss–Legendre converges only algebraically: far from 50 digits at 512 points.
    let gauss = gauss_legendre::node_table::<Float>(512, p).integrate(|x: &Float| x.cos() / x.sqrt(), &zero, &one);
    let gauss_error = ((gauss - &reference).abs() / &reference).to_f64();
    assert!(gauss_error > 1e-10, "Gauss–Legendre error {gauss_error:e}");
}

#[test]
fn tanh_sinh_in_f64_reaches_full_precision_on_smooth_and_singular_integrands() {
    let estimate = tanh_sinh::integrate(|x: &f64| 4.0 / (1.0 + x * x), &0.0, &1.0, &1e-15, 10);
    assert!(
        (estimate.value - std::f64::consts::PI).abs() < 4e-15,
        "{}",
        estimate.value
    );
    let reference = cos_over_sqrt_series(Precision::bits(64)).to_f64();
    let estimate = tanh_sinh::integrate(|x: &f64| x.cos() / x.sqrt(), &0.0, &1.0, &1e-15, 10);
    assert!(
        (estimate.value - reference).abs() < 1e-14 * reference,
        "{} vs {}",
        estimate.value,
        reference
    );
}

#[test]
fn tanh_sinh_integrates_a_reversed_interval_to_minus_the_integral() {
    // The in-phase closed form integrates from P1 down to −Q1/f; a reversed interval used to
    // evaluate the midpoint only.
    let forward = tanh_sinh::integrate(|x: &f64| x.exp(), &-0.5, &0.4, &1e-15, 10);
    let reversed = tanh_sinh::integrate(|x: &f64| x.exp(), &0.4, &-0.5, &1e-15, 10);
    let exact = 0.4f64.exp() - (-0.5f64).exp();
    assert!((forward.value - exact).abs() < 1e-15, "{}", forward.value);
    assert!((reversed.value + exact).abs() < 1e-15, "{}", reversed.value);
    assert!(reversed.converged);
}

/// The stop of a single piece integrated alone, with its value.
fn stop_of(piece: Piece<'_, f64>, settings: &Settings<f64>) -> (Stop, f64, f64) {
    let integrated = engine::integrate(&[piece], settings).unwrap();
    let result = &integrated.pieces[0];
    (result.stop, result.estimate.value, result.estimate.error)
}

#[test]
fn engine_reports_an_empty_piece_a_converged_one_and_one_at_its_rounding_floor() {
    let settings = Settings::new(1e-13);
    let (stop, value, _) = stop_of(piece("empty", |x: &f64| x.exp(), 0.5, 0.5), &settings);
    assert_eq!((stop, value), (Stop::Empty, 0.0));
    // A quadratic is exact at 16 points: the first doubling changes nothing.
    let (stop, value, _) = stop_of(piece("x²", |x: &f64| x * x, 0.0, 3.0), &settings);
    assert_eq!(stop, Stop::Converged);
    assert!((value - 9.0).abs() < 1e-14, "{value}");
    // ∫₀¹ (cos x − sin 1) dx = 0: the rules' values are rounding, far above a share
    // of the tolerance relative to a sum that is itself zero, and below 64ε∫|f|.
    let sin_one = 1f64.sin();
    let (stop, value, error) = stop_of(
        piece("cos − sin 1", move |x: &f64| x.cos() - sin_one, 0.0, 1.0),
        &settings,
    );
    assert_eq!(stop, Stop::RoundingFloor, "value {value:e}");
    assert!(value.abs() <= error && error < 1e-14, "{value:e} ± {error:e}");
}

#[test]
fn engine_stops_a_doubling_early_on_a_predicted_error() {
    // 4/(1 + x²) converges geometrically; at 200 bits the last doubling before the
    // tolerance gains several digits, and the predicted error clears it one doubling early.
    let p = Precision::bits(200);
    let (zero, one) = (Float::from_i64(0, p), Float::from_i64(1, p));
    let tolerance = Float::parse_decimal("1e-50", p).unwrap();
    let settings = Settings {
        first_points: 8,
        ..Settings::new(tolerance.clone())
    };
    let pieces = [piece("π", |x: &Float| x.int(4) / (x.int(1) + &x.square()), zero, one)];
    let integrated = engine::integrate(&pieces, &settings).unwrap();
    let result = &integrated.pieces[0];
    assert_eq!(result.stop, Stop::Predicted);
    let error = (result.estimate.value.clone() - Float::pi(p)).abs();
    assert!(error <= result.estimate.error && result.estimate.error <= tolerance.clone() * 4u32);
}

/// A smooth integrand with a deterministic pseudo-random perturbation of relative size
/// `amplitude` at every point: rounding noise far above the rounding floor.
fn noisy(amplitude: f64) -> impl Fn(&f64) -> f64 {
    move |x: &f64| {
        let mut bits = x.to_bits().wrapping_mul(0x9e37_79b9_7f4a_7c15);
        bits ^= bits >> 29;
        bits = bits.wrapping_mul(0xbf58_476d_1ce4_e5b9);
        bits ^= bits >> 32;
        let unit = (bits >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
        x.exp() * (1.0 + amplitude * unit)
    }
}

#[test]
fn engine_accepts_noise_near_the_tolerance_and_refuses_it_far_above() {
    let exact = 1f64.exp() - 1.0;
    // Noise of 1e−10 against a tolerance of 1e−12: both rules stall, within a small
    // multiple of the tolerance.
    let (stop, value, error) = stop_of(piece("noisy", noisy(1e-10), 0.0, 1.0), &Settings::new(1e-12));
    assert_eq!(stop, Stop::Noise, "{value} ± {error:e}");
    assert!(
        (value - exact).abs() <= error + 1e-10 && error < 1e-9,
        "{value} ± {error:e}"
    );
    // A thousandfold tighter tolerance: the working precision cannot give it.
    let pieces = [piece("noisy", noisy(1e-10), 0.0, 1.0)];
    let error = engine::integrate(&pieces, &Settings::new(1e-15)).unwrap_err();
    assert!(matches!(error, QuadError::NotConverged { .. }), "{error:?}");
}

/// The engine does not start a rule it predicts to end past the deadline. Each evaluation
/// takes at least a millisecond and the integrand never converges (noise), so with 100 ms
/// the 16- and 32-point rules may run (48 ms at least) but not the 64-point one (64 ms
/// more): the engine stops having spent at most 48 evaluations, with `OutOfTime`.
#[test]
fn engine_does_not_start_a_rule_predicted_to_end_past_the_deadline() {
    let count = std::sync::atomic::AtomicUsize::new(0);
    let noise = noisy(1e-6);
    let slow = |x: &f64| {
        count.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
        std::thread::sleep(std::time::Duration::from_millis(1));
        noise(x)
    };
    let settings = Settings {
        deadline: Some(std::time::Instant::now() + std::time::Duration::from_millis(100)),
        ..Settings::new(1e-12)
    };
    let error = engine::integrate(&[piece("slow", slow, 0.0, 1.0)], &settings).unwrap_err();
    assert_eq!(error, QuadError::OutOfTime);
    let spent = count.load(std::sync::atomic::Ordering::SeqCst);
    assert!(spent <= 16 + 32, "{spent} evaluations");
}
