//! No panic and no NaN, ever: arbitrary inputs give a finite W ≥ 0 or a typed error,
//! through the library and through the command line.

use microslip::compliance::parse_spec;
use microslip::cycle::LoadCycle;
use microslip::dissipation::{dissipation, Options};
use microslip::real::Precision;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use rug::Float;

/// A runner with a fixed seed; MICROSLIP_FUZZ_SCALE multiplies the case count and
/// MICROSLIP_FUZZ_SEED shifts the seed, for longer runs by hand (CI uses the defaults).
fn runner(cases: u32, seed: u8) -> TestRunner {
    let setting = |name: &str| std::env::var(name).ok().and_then(|v| v.parse::<u32>().ok());
    let scale = setting("MICROSLIP_FUZZ_SCALE").unwrap_or(1).max(1);
    let seed = seed.wrapping_add(setting("MICROSLIP_FUZZ_SEED").unwrap_or(0) as u8);
    let config = Config {
        cases: cases * scale,
        failure_persistence: None,
        ..Config::default()
    };
    TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &[seed; 32]))
}

/// Any f64, with the awkward ones (NaN, infinities, zeros, subnormals, huge) over-represented.
fn awkward_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(5e-324),
        Just(f64::MIN_POSITIVE),
        Just(1e300),
        Just(-1e300),
        Just(f64::MAX),
        -1e7..1e7f64,
        -2.0..2.0f64,
        any::<f64>(),
    ]
}

const SPECS: [&str; 6] = [
    "persson:gamma=1,sigma=1",
    "power:c=1,beta=-3",
    "hertz:r=1,estar=1",
    "exp:a=1,c=1,d=0.1",
    "rational:a=0,b=1,c=0",
    "power:c=1,beta=-0.01 + const:c=2",
];

fn check(cycle: &LoadCycle<f64>, spec: &str) -> Result<(), TestCaseError> {
    let compliance = parse_spec::<f64>(spec, Precision::DOUBLE).unwrap();
    match dissipation(cycle, compliance.as_ref(), &Options::default()) {
        Ok(result) => {
            prop_assert!(result.total.is_finite(), "W = {} for {cycle:?} {spec}", result.total);
            prop_assert!(result.total >= 0.0, "W = {} < 0 for {cycle:?} {spec}", result.total);
            prop_assert!(result.error_estimate.is_finite());
        }
        Err(error) => prop_assert!(!error.to_string().is_empty()),
    }
    Ok(())
}

#[test]
fn arbitrary_f64_inputs_give_a_finite_nonnegative_w_or_a_typed_error() {
    let inputs = (prop::array::uniform7(awkward_f64()), 0..SPECS.len());
    runner(3000, 7)
        .run(&inputs, |(v, spec)| {
            let cycle = LoadCycle {
                mean_normal_load: v[0],
                normal_amplitude: v[1],
                mean_tangential_load: v[2],
                tangential_amplitude: v[3],
                phase: v[4],
                friction: v[5],
                compliance_ratio: v[6],
            };
            check(&cycle, SPECS[spec])
        })
        .unwrap();
}

#[test]
fn nearly_valid_cycles_at_every_scale_give_a_finite_nonnegative_w_or_a_typed_error() {
    // Mostly inside the theory: scales from 1e-300 to 1e300, phases far outside [0, 2π],
    // amplitudes up to and beyond the gross-slip and separation limits.
    let inputs = (
        -300i32..300,
        0.0..1.05f64,
        0.0..1.2f64,
        -0.5..0.5f64,
        -1e6..1e6f64,
        -3i32..2,
        1.0..2.0f64,
        0..SPECS.len(),
    );
    runner(1500, 11)
        .run(
            &inputs,
            |(exponent, p1, q1, q0, phase, friction_exponent, lambda, spec)| {
                let p0 = 10f64.powi(exponent);
                let f = 10f64.powi(friction_exponent);
                let cycle = LoadCycle {
                    mean_normal_load: p0,
                    normal_amplitude: p1 * p0,
                    mean_tangential_load: q0 * f * p0,
                    tangential_amplitude: q1 * f * p0,
                    phase,
                    friction: f,
                    compliance_ratio: lambda,
                };
                check(&cycle, SPECS[spec])
            },
        )
        .unwrap();
}

#[test]
fn admissible_cycles_and_compliances_give_w_within_1e_10_or_say_f64_cannot_resolve_it() {
    // Every family the gate draws, and sums of them, on cycles inside the theory: W is
    // finite, positive and carries an error estimate within 1e-10 of it, or the library
    // says f64 cannot resolve the case. Near in phase with Q1 ≪ fP1 the estimate reaches
    // 3.3e-12 of W; the command line then prints MPFR digits and says why.
    runner(300, 43)
        .run(&strategies::drawn(strategies::Terms::WithSums), |case| {
            let read = case.0.read::<f64>(Precision::DOUBLE).unwrap();
            match dissipation(&read.cycle, read.compliance.as_ref(), &Options::default()) {
                Ok(result) => {
                    prop_assert!(result.total.is_finite() && result.total > 0.0, "W = {}", result.total);
                    prop_assert!(
                        result.error_estimate <= 1e-10 * result.total,
                        "estimate {:e} of W = {:e}",
                        result.error_estimate,
                        result.total
                    );
                }
                Err(error) => prop_assert!(
                    matches!(error, microslip::dissipation::DissipationError::IllConditioned { .. }),
                    "{error}"
                ),
            }
            Ok(())
        })
        .unwrap();
}

#[test]
fn arbitrary_spec_strings_parse_or_fail_cleanly_at_any_precision() {
    let valid = LoadCycle {
        mean_normal_load: 1.0,
        normal_amplitude: 0.4,
        mean_tangential_load: 0.0,
        tangential_amplitude: 0.5,
        phase: 1.2,
        friction: 1.0,
        compliance_ratio: 1.2,
    };
    let spec = prop_oneof![
        "[a-z:=,;+*0-9.eE -]{0,48}",
        "(power|persson|hertz|poly|rational|exp|const):[a-z]{1,6}=[-0-9.eE+]{0,12}(,[a-z0-9]{1,6}=[-0-9.;eE+]{0,12}){0,3}",
        "\\PC{0,24}",
    ];
    runner(4000, 23)
        .run(&spec, |spec| {
            let _ = parse_spec::<Float>(&spec, Precision::bits(128));
            if let Ok(compliance) = parse_spec::<f64>(&spec, Precision::DOUBLE) {
                match dissipation(&valid, compliance.as_ref(), &Options::default()) {
                    Ok(result) => prop_assert!(result.total.is_finite() && result.total >= 0.0, "{spec}"),
                    Err(error) => prop_assert!(!error.to_string().is_empty()),
                }
            }
            Ok(())
        })
        .unwrap();
}

#[test]
fn command_line_never_panics_on_arbitrary_specs_and_numbers() {
    let inputs = (
        "[a-z:=,;+*0-9.eE-]{0,30}",
        prop_oneof![Just("nan".to_string()), Just("1e999".to_string()), "[-0-9.e]{1,8}"],
        prop::bool::ANY,
    );
    runner(60, 31)
        .run(&inputs, |(spec, number, precise)| {
            let mut args = common::case_args("dissipation", &[("--p1", &number), ("--compliance", &spec)]);
            if precise {
                args.extend(["--digits".to_string(), "20".to_string()]);
            }
            let output = common::run(&args).output();
            let code = output.status.code().unwrap_or(-1);
            let stderr = String::from_utf8_lossy(&output.stderr);
            prop_assert!(code == 0 || code == 2, "exit {code} for {args:?}: {stderr}");
            if code == 2 {
                prop_assert_eq!(stderr.trim_end().lines().count(), 1, "{}", stderr);
                prop_assert!(output.stdout.is_empty());
            }
            Ok(())
        })
        .unwrap();
}

mod common;
#[path = "common/strategies.rs"]
mod strategies;

fn acceptance(phase: f64, tangential_amplitude: f64) -> LoadCycle<f64> {
    LoadCycle {
        tangential_amplitude,
        ..common::acceptance_cycle(phase)
    }
}

#[test]
fn results_below_the_full_precision_range_are_refused_not_rounded() {
    let mut cycle = acceptance(1.0, 0.5);
    let scale = 1e-157;
    cycle.mean_normal_load *= scale;
    cycle.normal_amplitude *= scale;
    cycle.tangential_amplitude *= scale;
    // v' = P^(-0.01): W scales as P^1.99, about 1e-312 here, inside f64's subnormals.
    let compliance = parse_spec::<f64>("power:c=1,beta=-0.01", Precision::DOUBLE).unwrap();
    let error = dissipation(&cycle, compliance.as_ref(), &Options::default()).unwrap_err();
    assert!(
        matches!(error, microslip::dissipation::DissipationError::OutsideRange { .. }),
        "{error}"
    );
    // The same case at 128 bits has no such limit and scales exactly.
    let exact = |k: &str| {
        let p = Precision::bits(128);
        let number = |t: &str| microslip::real::Real::parse_decimal(t, p).unwrap();
        let k: Float = number(k);
        let cycle = LoadCycle {
            mean_normal_load: k.clone(),
            normal_amplitude: number("0.4") * &k,
            mean_tangential_load: number("0"),
            tangential_amplitude: number("0.5") * &k,
            phase: number("1"),
            friction: number("1"),
            compliance_ratio: number("1"),
        };
        let compliance = parse_spec::<Float>("power:c=1,beta=-0.01", p).unwrap();
        dissipation(&cycle, compliance.as_ref(), &Options::default())
            .unwrap()
            .total
    };
    let ratio = (exact("1e-157") / exact("1")).to_f64();
    let expected = 10f64.powf(-157.0 * 1.99);
    assert!(
        ((ratio - expected) / expected).abs() < 1e-12,
        "{ratio:e} vs {expected:e}"
    );
}

#[test]
fn rounding_noise_around_zero_dissipation_is_reported_as_zero_within_its_error() {
    // Q1 < fP1 and φ = 1e-17: W ≈ 1e-17 × O(1), below the rounding noise of O(1) segments.
    let compliance = parse_spec::<f64>("persson:gamma=1,sigma=1", Precision::DOUBLE).unwrap();
    for phase in [1e-17, 3e-17, 1e-16, std::f64::consts::PI - 1e-16] {
        let result = dissipation(&acceptance(phase, 0.3), compliance.as_ref(), &Options::default()).unwrap();
        assert!(result.total >= 0.0, "φ = {phase:e}: W = {:e}", result.total);
        assert!(
            result.total <= result.error_estimate + 1e-15,
            "φ = {phase:e}: W = {:e}",
            result.total
        );
    }
}
