//! The compliance families and combinators: derivatives consistent with v, the
//! cancellation-free slope change, and the SPEC language.

use std::path::PathBuf;

use microslip::compliance::{
    cached_table, check_admissible, parse_spec, Compliance, ComplianceSpec, Exponential, Hertz, LoadScaled, Persson,
    Polynomial, PowerLaw, Rational, Scaled, Shifted, Sum, TableCompliance, TableInterpolant,
};
use microslip::real::{Precision, Real};
use proptest::prelude::*;
use rug::Float;

mod common;
use common::Scratch;

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

/// v'(s·r²) by the forms that keep a complex box off 0 (Persson dividing by r twice, a
/// power law raising r to 2β, combinators termwise) is v' at the product, at 300 bits, for
/// every family, their sums, multiples, shifts and load scalings, over scales and roots
/// from the bottom of a cycle 1e−12 from separation to loads of 1e6.
#[test]
fn the_slope_at_a_scaled_square_is_the_slope_at_the_product() {
    let p = Precision::bits(300);
    let inner = || parse_spec::<Float>("power:c=2,beta=-0.75", p).unwrap();
    let mut compliances: Vec<(String, Box<dyn Compliance<Float>>)> = SPECS
        .iter()
        .map(|spec| (spec.to_string(), parse_spec::<Float>(spec, p).unwrap()))
        .collect();
    compliances.push((
        "shifted".into(),
        Box::new(Shifted {
            extra_slope: Float::from_f64(0.75, p),
            inner: inner(),
        }),
    ));
    compliances.push((
        "load-scaled".into(),
        Box::new(LoadScaled {
            factor: Float::from_f64(3.0, p),
            inner: inner(),
        }),
    ));
    for (name, compliance) in &compliances {
        for (scale, root) in [(1e-12, 1.0), (1e-12, 1e3), (1e-6, 37.5), (0.4, 1.7), (2.0, 700.0)] {
            let (scale, root) = (Float::from_f64(scale, p), Float::from_f64(root, p));
            let expected = compliance.slope(&(root.clone() * &root * &scale));
            let by_parts = compliance.slope_at_scaled_square(&scale, &root);
            assert_close(&by_parts, &expected, 1e-80, name);
        }
    }
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
        ("power:c=inf,beta=1", "c='inf' is not a decimal number"),
        ("power:c=1e400,beta=1", "c=1e400 lies outside the range of f64"),
        ("power:c, beta=1", "is not key=value"),
    ];
    for (spec, expected) in cases {
        let error = parse_spec::<f64>(spec, Precision::DOUBLE).map(|_| ()).expect_err(spec);
        assert!(error.to_string().contains(expected), "{spec}: {error}");
    }
}

/// The SPECs of the round trip: every family, a multiple, a sum, and a table.
const TREE_SPECS: [&str; 11] = [
    "power:c=0.3,beta=-0.4",
    "persson:gamma=1.5,sigma=0.02",
    "hertz:r=1.1,estar=2.3",
    "poly:p0=1.2,coeffs=2;-0.5;-0.1",
    "rational:a=0.1,b=2,c=0.5",
    "exp:a=3,c=0.7,d=0.2",
    "const:c=0.4",
    "0.7*persson:gamma=1,sigma=0.3",
    "power:c=1e+0,beta=-0.5 + 2.5*exp:a=1,c=2,d=0 + const:c=0.1",
    "table:tests/data/rough-surface.csv",
    "3*table:tests/data/rough-surface.csv+power:c=0.1,beta=-1",
];

/// The same compliance built by hand, each decimal read from its text at the precision
/// (independently of the SPEC's tree): what the SPEC means.
fn by_hand<R: Real>(index: usize, precision: Precision, interpolant: TableInterpolant) -> Box<dyn Compliance<R>> {
    let d = |text: &str| R::parse_decimal(text, precision).unwrap();
    let table = || -> Box<dyn Compliance<R>> {
        Box::new(TableCompliance {
            table: cached_table("tests/data/rough-surface.csv", 0.0).unwrap(),
            interpolant,
        })
    };
    match index {
        0 => Box::new(PowerLaw {
            coefficient: d("0.3"),
            exponent: d("-0.4"),
        }),
        1 => Box::new(Persson {
            gamma: d("1.5"),
            sigma: d("0.02"),
        }),
        2 => Box::new(Hertz {
            radius: d("1.1"),
            contact_modulus: d("2.3"),
        }),
        3 => Box::new(Polynomial {
            reference: d("1.2"),
            coefficients: vec![d("2"), d("-0.5"), d("-0.1")],
        }),
        4 => Box::new(Rational {
            constant: d("0.1"),
            numerator: d("2"),
            offset: d("0.5"),
        }),
        5 => Box::new(Exponential {
            amplitude: d("3"),
            decay_load: d("0.7"),
            constant: d("0.2"),
        }),
        6 => Box::new(Polynomial {
            reference: d("0"),
            coefficients: vec![d("0.4")],
        }),
        7 => Box::new(Scaled {
            factor: d("0.7"),
            inner: Box::new(Persson {
                gamma: d("1"),
                sigma: d("0.3"),
            }),
        }),
        8 => Box::new(Sum {
            terms: vec![
                Box::new(PowerLaw {
                    coefficient: d("1"),
                    exponent: d("-0.5"),
                }),
                Box::new(Scaled {
                    factor: d("2.5"),
                    inner: Box::new(Exponential {
                        amplitude: d("1"),
                        decay_load: d("2"),
                        constant: d("0"),
                    }),
                }),
                Box::new(Polynomial {
                    reference: d("0"),
                    coefficients: vec![d("0.1")],
                }),
            ],
        }),
        9 => table(),
        _ => Box::new(Sum {
            terms: vec![
                Box::new(Scaled {
                    factor: d("3"),
                    inner: table(),
                }),
                Box::new(PowerLaw {
                    coefficient: d("0.1"),
                    exponent: d("-1"),
                }),
            ],
        }),
    }
}

/// v, v' and v'' of both at loads inside the table's range, equal to the last bit.
fn assert_same_values<R: Real>(spec: &str, built: &dyn Compliance<R>, expected: &dyn Compliance<R>, p: Precision) {
    for load in ["0.35", "1", "1.7"] {
        let x = R::parse_decimal(load, p).unwrap();
        for (what, a, b) in [
            ("v", built.approach(&x), expected.approach(&x)),
            ("v'", built.slope(&x), expected.slope(&x)),
            ("v''", built.curvature(&x), expected.curvature(&x)),
        ] {
            assert!(a == b, "{spec}: {what} at {load}: {a:?} vs {b:?} at {p:?}");
        }
    }
}

#[test]
fn the_spec_tree_builds_each_family_and_combinator_as_its_decimals_mean() {
    for (index, text) in TREE_SPECS.into_iter().enumerate() {
        let spec = ComplianceSpec::parse(text).unwrap_or_else(|e| panic!("{text}: {e}"));
        let p = Precision::DOUBLE;
        let built = spec.build::<f64>(p).unwrap();
        assert_same_values(
            text,
            built.as_ref(),
            by_hand::<f64>(index, p, TableInterpolant::Cubic).as_ref(),
            p,
        );
        let p = Precision::bits(200);
        let built = spec.build::<Float>(p).unwrap();
        assert_same_values(
            text,
            built.as_ref(),
            by_hand::<Float>(index, p, TableInterpolant::Cubic).as_ref(),
            p,
        );
        for interpolant in [TableInterpolant::HalfTable, TableInterpolant::OtherHalfTable] {
            let built = spec.build_with::<f64>(Precision::DOUBLE, interpolant).unwrap();
            let expected = by_hand::<f64>(index, Precision::DOUBLE, interpolant);
            assert_same_values(text, built.as_ref(), expected.as_ref(), Precision::DOUBLE);
        }
        assert_eq!(spec.tables().len(), usize::from(text.contains("table:")), "{text}");
    }
}

#[test]
fn a_table_is_read_once_when_its_spec_is_parsed() {
    let scratch = Scratch::new("read-once");
    let path = scratch.join("rough-surface.csv");
    std::fs::copy("tests/data/rough-surface.csv", &path).unwrap();
    let text = format!("2*table:{}", path.display());
    let spec = ComplianceSpec::parse(&text).unwrap();
    // Gone before the compliance is built: building reads nothing.
    std::fs::remove_file(&path).unwrap();
    let tables = spec.tables();
    assert_eq!(tables.len(), 1);
    assert_eq!(PathBuf::from(&tables[0].path), path);
    let by_hand = |precision| -> Box<dyn Compliance<Float>> {
        Box::new(Scaled {
            factor: Float::from_i64(2, precision),
            inner: Box::new(TableCompliance {
                table: tables[0].clone(),
                interpolant: TableInterpolant::Cubic,
            }),
        })
    };
    for bits in [64, 200] {
        let p = Precision::bits(bits);
        assert_same_values(&text, spec.build::<Float>(p).unwrap().as_ref(), by_hand(p).as_ref(), p);
    }
    assert!(spec.build::<f64>(Precision::DOUBLE).is_ok());
    // Parsing again does read, and says the file is gone.
    let error = ComplianceSpec::parse(&text).unwrap_err().to_string();
    assert!(error.contains("cannot be read"), "{error}");
}

#[test]
fn numbers_f64_cannot_hold_are_refused_in_f64_and_read_above() {
    let spec = ComplianceSpec::parse("power:c=1e-400,beta=-1").unwrap();
    let error = spec
        .build::<f64>(Precision::DOUBLE)
        .map(|_| ())
        .unwrap_err()
        .to_string();
    assert!(error.contains("c=1e-400 lies outside the range of f64"), "{error}");
    let p = Precision::bits(64);
    let compliance = spec.build::<Float>(p).unwrap();
    let expected = Float::with_val(64, Float::parse("1e-400").unwrap());
    assert_eq!(compliance.slope(&Float::from_i64(1, p)), expected);
}

#[cfg(feature = "certified")]
#[test]
fn balls_from_the_spec_enclose_the_exact_decimals() {
    use microslip::ball::Ball;
    // 0.1 and 1/3-like decimals are not binary: a point would miss the exact value.
    let spec = ComplianceSpec::parse("const:c=0.1+power:c=0.333333333333333333333333333333,beta=-1").unwrap();
    let p = Precision::bits(128);
    let compliance = spec.build::<Ball>(p).unwrap();
    let slope = compliance.slope(&Ball::from_i64(1, p));
    let exact = Float::with_val(2000, Float::parse("0.433333333333333333333333333333").unwrap());
    assert!(slope.contains(&exact), "{slope:?}");
    assert!(!slope.contains(&Float::with_val(2000, 0.1f64 + 0.333_333_333_333_333_3)));
}

/// A compliance with its form hidden: `check_admissible` can only sample it.
#[derive(Debug)]
struct FormHidden(Box<dyn Compliance<f64>>);

impl Compliance<f64> for FormHidden {
    fn approach(&self, load: &f64) -> f64 {
        self.0.approach(load)
    }
    fn slope(&self, load: &f64) -> f64 {
        self.0.slope(load)
    }
    fn curvature(&self, load: &f64) -> f64 {
        self.0.curvature(load)
    }
    fn describe(&self) -> String {
        self.0.describe()
    }
}

prop_compose! {
    /// A power law, a Persson or Hertz compliance, or a positive multiple or sum of them,
    /// with parameters of either sign and magnitudes from 1e-300 to 1e300.
    fn formed_compliance()(
        family in 0..5usize,
        c in prop_oneof![-2.0..2.0f64, (-300.0..300.0f64).prop_map(|e| 10f64.powf(e))],
        beta in prop_oneof![-3.0..1.0f64, Just(0.0), Just(-1.0)],
        factor in prop_oneof![-1.0..3.0f64, Just(1e300)],
    ) -> Box<dyn Compliance<f64>> {
        let power = |c: f64| -> Box<dyn Compliance<f64>> { Box::new(PowerLaw { coefficient: c, exponent: beta }) };
        match family {
            0 => power(c),
            1 => Box::new(Persson { gamma: c, sigma: factor }),
            2 => Box::new(Hertz { radius: c.abs(), contact_modulus: factor.abs() }),
            3 => Box::new(Scaled { factor, inner: power(c) }),
            _ => Box::new(Sum { terms: vec![power(c), Box::new(Persson { gamma: factor, sigma: 1.0 })] }),
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// Deciding admissibility from a family's form gives exactly what sampling gives:
    /// never a pass that sampling would refuse (v' underflowing or overflowing included),
    /// and the same refusal where it does not decide.
    #[test]
    fn admissibility_by_form_agrees_with_sampling(
        compliance in formed_compliance(),
        low_exponent in -310.0..300.0f64,
        width in prop_oneof![0.0..2.0f64, Just(0.0), 2.0..600.0f64],
    ) {
        let low = 10f64.powf(low_exponent);
        let high = low * 10f64.powf(width);
        prop_assume!(high.is_finite());
        let by_form = compliance.admissible_by_form(&low, &high);
        let checked = check_admissible(compliance.as_ref(), &low, &high);
        let sampled = check_admissible(&FormHidden(compliance), &low, &high);
        // Debug, not ==: a refusal may carry a NaN curvature.
        prop_assert_eq!(format!("{checked:?}"), format!("{sampled:?}"));
        prop_assert!(!by_form || sampled.is_ok());
    }
}

#[test]
fn admissibility_by_form_decides_the_families_it_knows() {
    let persson = Persson { gamma: 1.0, sigma: 1.0 };
    assert!(persson.admissible_by_form(&0.5, &1.5));
    // v' = P softens as it is pressed: not admissible, and not decided by the form.
    let softening = PowerLaw {
        coefficient: 1.0,
        exponent: 1.0,
    };
    assert!(!softening.admissible_by_form(&0.5, &1.5));
    // v' = 1e-300·P^-1 underflows to 0 at 1e30: sampling refuses it, so the form must not pass it.
    let vanishing = PowerLaw {
        coefficient: 1e-300,
        exponent: -1.0,
    };
    assert!(!vanishing.admissible_by_form(&1.0, &1e30));
    assert!(check_admissible(&vanishing, &1.0, &1e30).is_err());
    // Families without a form rule are sampled.
    let polynomial = Polynomial {
        reference: 1.0,
        coefficients: vec![1.0, -0.5],
    };
    assert!(!polynomial.admissible_by_form(&0.5, &1.5));
    assert!(check_admissible(&polynomial, &0.5, &1.5).is_ok());
}
