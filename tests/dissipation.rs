//! The dissipation per cycle: precision agreement, limits, closed forms and invariants.

use microslip::compliance::{Compliance, Hertz, Polynomial, PowerLaw, SlopeChange};
use microslip::cycle::{LoadCycle, ValidCycle};
use microslip::dissipation::{
    constant_normal_load, dissipation, four_segment, in_phase, HertzConfiguration, Method, MindlinDeresiewicz, Options,
    SegmentIntegrands,
};
use microslip::quad::{self, Settings};
use microslip::real::{Precision, Real};
use rug::Float;

mod common;
use common::acceptance_cycle;

fn inverse_load<R: Real>(p: Precision) -> PowerLaw<R> {
    PowerLaw {
        coefficient: R::from_i64(1, p),
        exponent: R::from_i64(-1, p),
    }
}

fn w<R: Real>(cycle: &LoadCycle<R>, compliance: &dyn Compliance<R>) -> R {
    dissipation(cycle, compliance, &Options::default()).unwrap().total
}

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn f64_and_256_bits_agree_to_1e_13_and_the_phase_ordering_holds() {
    let p = Precision::bits(256);
    let mut values = Vec::new();
    for tenths in [1, 4, 5, 9] {
        let double = w(
            &acceptance_cycle(tenths as f64 * 0.1 * std::f64::consts::PI),
            &inverse_load(Precision::DOUBLE),
        );
        let phase = Float::pi(p) * Float::from_i64(tenths, p) / Float::from_i64(10, p);
        let multi = w(&acceptance_cycle(phase), &inverse_load::<Float>(p)).to_f64();
        assert!(relative(double, multi) < 1e-13, "φ = {tenths}π/10: {double} vs {multi}");
        values.push(multi);
    }
    let (w01, w04, w05) = (values[0], values[1], values[2]);
    assert!(
        w04 > w05 && w05 > w01,
        "W(0.4π) = {w04}, W(0.5π) = {w05}, W(0.1π) = {w01}"
    );
}

#[test]
fn four_segment_result_has_70_correct_digits_at_256_bits() {
    let value_at = |bits: u32| {
        let p = Precision::bits(bits);
        let phase = Float::pi(p) * Float::from_i64(2, p) / Float::from_i64(5, p);
        w(&acceptance_cycle(phase), &inverse_load::<Float>(p))
    };
    let (at_256, at_512) = (value_at(256), value_at(512));
    let error = (Float::with_val(512, &at_256) - &at_512).abs() / &at_512;
    assert!(
        error < Float::with_val(64, 1e-70),
        "relative error {:e}",
        error.to_f64()
    );
}

#[test]
fn general_integrator_tends_linearly_to_the_in_phase_closed_form() {
    let compliance = inverse_load::<f64>(Precision::DOUBLE);
    let options = Options::default();
    for (phase, base) in [(0.0, 0.0), (std::f64::consts::PI, std::f64::consts::PI)] {
        let closed = in_phase(&ValidCycle::new(acceptance_cycle(base)).unwrap(), &compliance, &options).unwrap();
        assert_eq!(closed.method, Method::InPhase);
        let error_at = |offset: f64| {
            let phi = if phase == 0.0 { offset } else { phase - offset };
            let general = four_segment(&acceptance_cycle(phi), &compliance, &options).unwrap();
            relative(general.total, closed.total)
        };
        assert!(error_at(1e-8) < 1e-7, "φ offset 1e-8: {:e}", error_at(1e-8));
        // Linear convergence: the error falls tenfold when the offset does.
        let ratio = error_at(1e-4) / error_at(1e-5);
        assert!((ratio - 10.0).abs() < 0.5, "error ratio {ratio}");
    }
    // dissipation() routes an exactly in-phase cycle to the closed form.
    let routed = dissipation(&acceptance_cycle(0.0), &compliance, &options).unwrap();
    assert_eq!(routed.method, Method::InPhase);
    assert!(routed.total > 0.0);
}

#[test]
fn in_phase_dissipation_vanishes_when_the_load_line_is_inside_the_friction_cone() {
    let mut cycle = acceptance_cycle(0.0);
    cycle.tangential_amplitude = 0.35; // < f·P1 = 0.4
    let compliance = inverse_load::<f64>(Precision::DOUBLE);
    let closed = in_phase(
        &ValidCycle::new(cycle.clone()).unwrap(),
        &compliance,
        &Options::default(),
    )
    .unwrap();
    assert_eq!(closed.total, 0.0);
    // The ellipse at small φ dissipates in proportion to φ². f64 refuses it by default (W is
    // ~1e−11 of the segments BC and CH that cancel to it); allowed here for a loose bound.
    cycle.phase = 1e-6;
    let loose = Options {
        rounding_limit: 1.0,
        ..Options::default()
    };
    let general = four_segment(&cycle, &compliance, &loose).unwrap();
    assert!(general.total > 0.0 && general.total < 1e-5, "{}", general.total);
}

#[test]
fn constant_normal_load_closed_form_is_the_limit_of_the_general_integrator() {
    let compliance = inverse_load::<f64>(Precision::DOUBLE);
    let mut cycle = acceptance_cycle(0.3);
    cycle.normal_amplitude = 0.0;
    let closed = dissipation(&cycle, &compliance, &Options::default()).unwrap();
    assert_eq!(closed.method, Method::ConstantNormalLoad);
    cycle.normal_amplitude = 1e-10 * cycle.mean_normal_load;
    let general = four_segment(&cycle, &compliance, &Options::default()).unwrap();
    assert!(
        relative(general.total, closed.total) < 1e-8,
        "{} vs {}",
        general.total,
        closed.total
    );
}

/// A Hertz sphere of radius R = 1 with constants (G, ν) in the given configuration,
/// under P0 = 1, f = 0.5, Q1 = q·f·P0: the closed form against Mindlin–Deresiewicz.
fn mindlin_deresiewicz_mismatch(configuration: HertzConfiguration, q: &str, p: Precision) -> f64 {
    let number = |text: &str| Float::parse_decimal(text, p).unwrap();
    let md = MindlinDeresiewicz {
        shear_modulus: number("80"),
        poisson_ratio: number("0.3"),
        configuration,
    };
    let hertz = Hertz {
        radius: number("1"),
        contact_modulus: md.contact_modulus(),
    };
    let nu = md.poisson_ratio.clone();
    let lambda = (nu.int(2) - &nu) / (nu.int(2) * &(nu.int(1) - &nu));
    let (f, p0) = (number("0.5"), number("1"));
    let q1 = number(q) * &f * &p0;
    let cycle = LoadCycle {
        mean_normal_load: p0.clone(),
        normal_amplitude: number("0"),
        mean_tangential_load: number("0"),
        tangential_amplitude: q1.clone(),
        phase: number("0"),
        friction: f.clone(),
        compliance_ratio: lambda,
    };
    let closed = constant_normal_load(&ValidCycle::new(cycle.clone()).unwrap(), &hertz, &Options::default())
        .unwrap()
        .total;
    let formula = md.dissipation(&f, &p0, &q1, &hertz.contact_radius(&p0));
    ((closed - &formula) / formula).abs().to_f64()
}

#[test]
fn hertz_constant_load_closed_form_equals_mindlin_deresiewicz() {
    for q in ["0.001", "0.1", "0.37", "0.5", "0.9", "0.999"] {
        for configuration in [
            HertzConfiguration::SphereOnRigidFlat,
            HertzConfiguration::TwoIdenticalBodies,
        ] {
            let mismatch = mindlin_deresiewicz_mismatch(configuration, q, Precision::bits(256));
            assert!(mismatch < 1e-14, "q = {q}, {configuration:?}: {mismatch:e}");
        }
    }
    // In f64 the two agree too where the bracket does not cancel.
    let mismatch = mindlin_deresiewicz_mismatch(HertzConfiguration::SphereOnRigidFlat, "0.5", Precision::DOUBLE);
    assert!(mismatch < 1e-12, "{mismatch:e}");
}

#[test]
fn constant_slope_dissipates_nothing_through_the_raw_segment_formulas() {
    // Integrate v' itself, not v' − v'(P0), so that the segment formulas must cancel it.
    let raw = |p: Precision| Options::<Float> {
        remove_constant_slope: false,
        relative_tolerance: Some(Float::epsilon(p) * Float::from_i64(256, p)),
        ..Options::default()
    };
    for (bits, bound) in [(53u32, 1e-14), (256, 1e-70)] {
        let p = Precision::bits(bits);
        let constant = Polynomial {
            reference: Float::from_i64(0, p),
            coefficients: vec![Float::from_i64(3, p)],
        };
        let phase = Float::pi(p) * Float::from_i64(2, p) / Float::from_i64(5, p);
        let result = four_segment(&acceptance_cycle(phase), &constant, &raw(p)).unwrap();
        let scale = result
            .segments
            .named()
            .iter()
            .map(|(_, v)| v.to_f64().abs())
            .fold(0.0, f64::max);
        assert!(scale > 0.01, "segments should not vanish one by one: {scale}");
        assert!(
            result.total.to_f64().abs() < bound * scale,
            "{bits} bits: W = {:e}",
            result.total.to_f64()
        );
    }
}

#[test]
fn dissipation_does_not_depend_on_the_mean_tangential_load_and_has_period_pi_in_phase() {
    let compliance = inverse_load::<f64>(Precision::DOUBLE);
    let base = w(&acceptance_cycle(1.1), &compliance);
    for q0 in [-0.05, 0.02, 0.08] {
        let mut cycle = acceptance_cycle(1.1);
        cycle.mean_tangential_load = q0;
        assert!(relative(w(&cycle, &compliance), base) < 1e-14);
    }
    for shift in [-2.0, 1.0, 3.0] {
        let shifted = w(&acceptance_cycle(1.1 + shift * std::f64::consts::PI), &compliance);
        assert!(relative(shifted, base) < 1e-13, "shift {shift}π: {shifted} vs {base}");
    }
    // The same at 256 bits, with φ + π formed exactly at that precision.
    let p = Precision::bits(256);
    let phase = Float::from_f64(1.1, p);
    let compliance = inverse_load::<Float>(p);
    let at = w(&acceptance_cycle(phase.clone()), &compliance);
    let shifted = w(&acceptance_cycle(phase + Float::pi(p)), &compliance);
    let difference = ((at.clone() - shifted) / at).abs().to_f64();
    assert!(difference < 1e-70, "{difference:e}");
}

#[test]
fn no_tangential_oscillation_dissipates_nothing() {
    let mut cycle = acceptance_cycle(1.0);
    cycle.tangential_amplitude = 0.0;
    let result = dissipation(&cycle, &inverse_load::<f64>(Precision::DOUBLE), &Options::default()).unwrap();
    assert_eq!(result.method, Method::NoTangentialOscillation);
    assert_eq!(result.total, 0.0);
}

#[test]
fn segment_contributions_sum_to_the_total_and_the_stick_segment_is_elastic() {
    let compliance = inverse_load::<f64>(Precision::DOUBLE);
    let cycle = acceptance_cycle(0.4 * std::f64::consts::PI);
    let result = dissipation(&cycle, &compliance, &Options::default()).unwrap();
    let s = &result.segments;
    assert!(relative(s.eb + s.bc + s.ch + s.he, result.total) < 1e-15);
    // In BC the whole contact sticks: du = λ v'(P) dQ, so ∫ (Q − Q0) du there is an
    // independent one-line integral in θ.
    let g = cycle.geometry().unwrap();
    let n = 2000;
    let h = (g.theta_c - g.theta_b) / n as f64;
    let mut simpson = 0.0;
    for i in 0..=n {
        let theta = g.theta_b + h * i as f64;
        let p = cycle.normal_load(&theta);
        let value = g.tangential_offset(&theta) * (1.0 / p - 1.0) * g.tangential_rate(&theta);
        let weight = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        simpson += weight * value;
    }
    simpson *= h / 3.0;
    assert!(relative(s.bc, simpson) < 1e-10, "{} vs {}", s.bc, simpson);
}

#[test]
fn small_amplitude_f64_keeps_its_digits_once_the_constant_slope_is_removed() {
    // P1/P0 = 1e-8: integrating v' itself loses about eight digits to cancellation; with
    // v' − v'(P0) (the default), or with the linear part split off as well, f64 keeps them.
    let p = Precision::bits(300);
    let exact = {
        let number = |t: &str| Float::parse_decimal(t, p).unwrap();
        let cycle = LoadCycle {
            mean_normal_load: number("1"),
            normal_amplitude: number("1e-8"),
            mean_tangential_load: number("0"),
            tangential_amplitude: number("1.25e-8"),
            phase: Float::pi(p) * number("0.4"),
            friction: number("1"),
            compliance_ratio: number("1"),
        };
        w(&cycle, &inverse_load::<Float>(p)).to_f64()
    };
    let cycle = LoadCycle {
        mean_normal_load: 1.0,
        normal_amplitude: 1e-8,
        mean_tangential_load: 0.0,
        tangential_amplitude: 1.25e-8,
        phase: 0.4 * std::f64::consts::PI,
        friction: 1.0,
        compliance_ratio: 1.0,
    };
    let compliance = inverse_load::<f64>(Precision::DOUBLE);
    let error = |options: Options<f64>| relative(dissipation(&cycle, &compliance, &options).unwrap().total, exact);
    let raw = error(Options {
        remove_constant_slope: false,
        ..Options::default()
    });
    let constant = error(Options::default());
    // The linear part split off by hand: v' = 1/P about P0 = 1 is 1 − x + x²/(1 + x) in
    // x = P − P0, so W = W[x²/(1 + x)] + v''(P0)·W[x] with v''(P0) = −1 (λ = 1).
    let linear = {
        let geometry = ValidCycle::new(cycle.clone()).unwrap().geometry();
        let integrands = SegmentIntegrands {
            geometry: &geometry,
            compliance: &compliance,
            remove_constant_slope: true,
        };
        let sum = |slope: SlopeChange<'static, f64>| {
            let pieces = integrands.pieces_with_slope(slope).pieces;
            let integrated = quad::integrate(&pieces, &Settings::new(256.0 * f64::EPSILON)).unwrap();
            integrated.values().sum::<f64>()
        };
        let total = sum(Box::new(|x: &f64| x * x / (1.0 + x))) - sum(Box::new(|x: &f64| *x));
        relative(total, exact)
    };
    assert!(raw > 1e-10, "raw path error {raw:e}");
    assert!(constant < 1e-14, "constant removed: {constant:e}");
    assert!(linear < 1e-14, "linear removed: {linear:e}");
}

#[test]
fn the_error_estimate_bounds_the_error_where_convergence_slows_at_256_bits() {
    // Found by `microslip verify --seed 12`: the Gauss–Legendre gains on this case slow
    // from squaring (10, 22, then 32 digits), and an early stop that assumed squaring
    // returned W 3e-70 off with an estimate of 5e-75. Each W here must be within its
    // estimate of the 512-bit value.
    use microslip::compliance::{parse_spec, Scaled, Sum};
    let at = |bits: u32| {
        let precision = Precision::bits(bits);
        let number = |x: &str| Float::parse_decimal(x, precision).unwrap();
        let cycle = LoadCycle::<Float> {
            mean_normal_load: number("1"),
            normal_amplitude: number("0.2921014"),
            mean_tangential_load: number("0"),
            tangential_amplitude: number("0.1510382"),
            phase: number("0.831717") * &number("1").pi_like(),
            friction: number("1.667894"),
            compliance_ratio: number("1.408409"),
        };
        let term = |spec: &str, factor: &str| -> Box<dyn Compliance<Float>> {
            Box::new(Scaled {
                factor: number(factor),
                inner: parse_spec::<Float>(spec, precision).unwrap(),
            })
        };
        let sum = Sum {
            terms: vec![
                term("rational:a=0.7434767,b=2.993703,c=0.3862416", "1.788352"),
                term("persson:gamma=1.585531,sigma=0.5819344", "0.9704693"),
            ],
        };
        dissipation(&cycle, &sum, &Options::default()).unwrap()
    };
    let (coarse, fine) = (at(256), at(512));
    let error = (coarse.total.clone() - &Float::with_val(256, &fine.total)).abs();
    assert!(
        error <= coarse.error_estimate,
        "error {} beyond the estimate {}",
        error.to_f64(),
        coarse.error_estimate.to_f64()
    );
}

#[path = "common/strategies.rs"]
mod strategies;

#[test]
fn the_f64_error_estimate_bounds_the_f64_error_against_256_bits_on_random_cases() {
    // Every f64 W (inputs read from their decimals in f64, as the command line reads them)
    // must lie within its error estimate of the same decimal case computed at 256 bits to
    // 1e-60: the printing rule rounds the interval W ± estimate, so an estimate short of
    // the true error would print wrong digits. MICROSLIP_ESTIMATE_CASES=N draws N cases
    // (proofs/printing.md: 4,000); the worst ratio of error to estimate is printed.
    use microslip::case::Case;
    use proptest::prop_assert;
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let cases = std::env::var("MICROSLIP_ESTIMATE_CASES")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(48);
    let config = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    let mut runner = TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &[19; 32]));
    let worst = std::cell::Cell::new((0.0f64, 0u32));
    runner
        .run(&strategies::case(strategies::Terms::WithSums), |case| {
            let Case { cycle, compliance } = case.read::<f64>(Precision::DOUBLE).unwrap();
            let Ok(f64_run) = dissipation(&cycle, compliance.as_ref(), &Options::default()) else {
                // Refused in f64 (near separation, say): the command line computes in MPFR.
                return Ok(());
            };
            let precise = case.read::<Float>(Precision::bits(256)).unwrap();
            let options = Options {
                relative_tolerance: Some(Real::powi(&Float::with_val(256, 10), -60)),
                ..Options::default()
            };
            let reference = dissipation(&precise.cycle, precise.compliance.as_ref(), &options).unwrap();
            let error = (Float::with_val(256, f64_run.total) - &reference.total).abs().to_f64();
            let ratio = error / f64_run.error_estimate;
            let (largest, checked) = worst.get();
            worst.set((largest.max(ratio), checked + 1));
            prop_assert!(
                error <= f64_run.error_estimate,
                "W_f64 = {:e} is {error:.2e} from {}, beyond its estimate {:.2e}, for {case:?}",
                f64_run.total,
                reference.total.to_scientific(20),
                f64_run.error_estimate
            );
            Ok(())
        })
        .unwrap();
    let (largest, checked) = worst.get();
    eprintln!("{checked} f64 cases: largest error / estimate {largest:.3}");
}

#[test]
fn the_readme_shows_what_dissipation_prints() {
    // Each console example of `microslip dissipation` in the README, run from the
    // repository root, prints exactly the lines the README shows under it.
    let root = env!("CARGO_MANIFEST_DIR");
    let readme = std::fs::read_to_string(format!("{root}/README.md")).unwrap();
    let mut examples = 0;
    let mut lines = readme.lines().peekable();
    while let Some(line) = lines.next() {
        let Some(command) = line.strip_prefix("$ microslip dissipation ") else {
            continue;
        };
        let mut command = command.trim_end_matches('\\').to_string();
        let mut continued = line.ends_with('\\');
        while continued {
            let next = lines.next().unwrap();
            command.push(' ');
            command.push_str(next.trim().trim_end_matches('\\'));
            continued = next.ends_with('\\');
        }
        let mut shown = Vec::new();
        while let Some(next) = lines
            .peek()
            .filter(|next| !next.starts_with("```") && !next.starts_with('$'))
        {
            shown.push(next.to_string());
            lines.next();
        }
        let mut args = vec!["dissipation".to_string()];
        args.extend(command.split_whitespace().map(|arg| match arg.strip_prefix("table:") {
            Some(file) => format!("table:{root}/{file}"),
            None => arg.to_string(),
        }));
        let (code, stdout, stderr) = common::microslip(&args);
        assert_eq!(code, 0, "{args:?}: {stderr}");
        assert_eq!(stdout.trim_end().lines().collect::<Vec<_>>(), shown, "{args:?}");
        examples += 1;
    }
    assert!(examples >= 2, "{examples} examples");
}
