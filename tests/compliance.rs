//! The compliance families and combinators: derivatives consistent with v, the
//! cancellation-free slope change, and the SPEC language.

use microslip::compliance::{parse_spec, Compliance, LoadScaled, Shifted};
use microslip::real::{Precision, Real};
use rug::Float;

const SPECS: [&str; 9] = [
    "power:c=1,beta=-1",
    "power:c=0.3,beta=-0.4",
    "persson:gamma=1,sigma=0.02",
    "hertz:r=1,estar=1",
    "poly:p0=1,coeffs=2;-0.5;-0.1",
    "rational:a=0.1,b=2,c=0.5",
    "exp:a=3,c=0.7,d=0.2",
    "const:c=4",
    "2*persson:gamma=1,sigma=1 + power:c=1e+0,beta=-0.5 + 0.5*exp:a=1,c=2,d=0",
];

/// Central difference of `g` at `x` with step 1e-25 at 300 bits (error ~1e-50).
fn derivative(g: impl Fn(&Float) -> Float, x: &Float) -> Float {
    let h = Float::parse_decimal("1e-25", x.precision()).unwrap();
    (g(&(x.clone() + &h)) - g(&(x.clone() - &h))) / (h * Float::from_i64(2, x.precision()))
}

fn assert_close(a: &Float, b: &Float, tolerance: f64, what: &str) {
    let scale = a
        .clone()
        .abs()
        .max_of(&b.clone().abs())
        .max_of(&Float::from_i64(1, a.precision()));
    let error = ((a.clone() - b).abs() / scale).to_f64();
    assert!(
        error < tolerance,
        "{what}: {} vs {} ({error:e})",
        a.to_f64(),
        b.to_f64()
    );
}

#[test]
fn slope_and_curvature_are_the_derivatives_of_the_approach() {
    let p = Precision::bits(300);
    for spec in SPECS {
        let compliance = parse_spec::<Float>(spec, p).unwrap();
        for load in ["0.3", "1", "1.7"] {
            let x = Float::parse_decimal(load, p).unwrap();
            let slope = derivative(|y| compliance.approach(y), &x);
            assert_close(&compliance.slope(&x), &slope, 1e-40, &format!("{spec} v' at {load}"));
            let curvature = derivative(|y| compliance.slope(y), &x);
            assert_close(
                &compliance.curvature(&x),
                &curvature,
                1e-40,
                &format!("{spec} v'' at {load}"),
            );
        }
    }
}

#[test]
fn slope_change_matches_the_difference_of_slopes_and_keeps_its_digits_in_f64() {
    let p = Precision::bits(300);
    for spec in SPECS {
        let exact = parse_spec::<Float>(spec, p).unwrap();
        let double = parse_spec::<f64>(spec, Precision::DOUBLE).unwrap();
        for offset in [0.3, -0.2, 1e-9, -1e-13] {
            let reference = Float::from_i64(1, p);
            let shift = Float::from_f64(offset, p);
            let expected = exact.slope(&(reference.clone() + &shift)) - exact.slope(&reference);
            assert_close(&exact.slope_change(&reference, &shift), &expected, 1e-60, spec);
            if expected.is_zero() {
                assert_eq!(double.slope_change(&1.0, &offset), 0.0, "{spec}");
                continue;
            }
            // In f64 the difference itself, not just its absolute size, is accurate.
            let relative = ((Float::from_f64(double.slope_change(&1.0, &offset), p) - &expected) / &expected)
                .abs()
                .to_f64();
            assert!(relative < 1e-12, "{spec}, offset {offset}: relative error {relative:e}");
        }
    }
}

#[test]
fn combinators_shift_and_scale_as_documented() {
    let p = Precision::DOUBLE;
    let base = || parse_spec::<f64>("power:c=2,beta=-0.5", p).unwrap();
    let shifted = Shifted {
        extra_slope: 0.75,
        inner: base(),
    };
    let scaled_loads = LoadScaled {
        factor: 3.0,
        inner: base(),
    };
    let b = base();
    for load in [0.5, 1.0, 2.0] {
        assert_eq!(shifted.slope(&load), b.slope(&load) + 0.75);
        assert_eq!(shifted.curvature(&load), b.curvature(&load));
        assert_eq!(
            shifted.slope_change(&1.0, &(load - 1.0)),
            b.slope_change(&1.0, &(load - 1.0))
        );
        assert!((scaled_loads.slope(&load) - b.slope(&(load / 3.0))).abs() < 1e-15);
        assert!((scaled_loads.curvature(&load) - b.curvature(&(load / 3.0)) / 3.0).abs() < 1e-14);
        assert!((scaled_loads.approach(&load) - 3.0 * b.approach(&(load / 3.0))).abs() < 1e-14);
    }
    let sum = parse_spec::<f64>("power:c=2,beta=-0.5 + 3*const:c=1", p).unwrap();
    assert!((sum.slope(&4.0) - (2.0 * 0.5 + 3.0)).abs() < 1e-15);
}

#[test]
fn spec_numbers_are_exact_decimals_at_the_working_precision() {
    let p = Precision::bits(200);
    let compliance = parse_spec::<Float>("const:c=0.1", p).unwrap();
    let tenth = compliance.slope(&Float::from_i64(1, p));
    let ten_tenths = tenth * Float::from_i64(10, p) - Float::from_i64(1, p);
    assert!(ten_tenths.abs() < Float::parse_decimal("1e-59", p).unwrap());
}

#[test]
fn malformed_specs_are_rejected_with_a_reason() {
    let cases = [
        ("", "empty term"),
        ("2*", "names no family"),
        ("power", "power needs c="),
        ("power:c=1,beta=-1,x=2", "no parameter 'x'"),
        ("power:c=1,c=2,beta=1", "gives 'c' twice"),
        ("hertz:r=0,estar=1", "needs r > 0"),
        ("poly:p0=1,coeffs=1;;2", "coeffs=''"),
        ("power:c=1;beta=2", "power needs beta="),
        ("power:c=1x,beta=2", "c='1x' is not a decimal number"),
        ("persson:gamma=1,sigma=1 + ", "empty term"),
        ("x*persson:gamma=1,sigma=1", "multiplier='x'"),
        ("power:c=inf,beta=1", "c=inf is not finite"),
        ("power:c, beta=1", "is not key=value"),
    ];
    for (spec, expected) in cases {
        let error = parse_spec::<f64>(spec, Precision::DOUBLE).map(|_| ()).expect_err(spec);
        assert!(error.to_string().contains(expected), "{spec}: {error}");
    }
}
