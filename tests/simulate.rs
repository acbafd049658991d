//! The brute-force history simulation against the four-segment integrals, and its
//! own consistency: two energy measures, two initial paths, Q0, a constant compliance.

use microslip::case::Case;
use microslip::compliance::{parse_spec, Polynomial};
use microslip::cycle::LoadCycle;
use microslip::dissipation::{dissipation, Method, Options};
use microslip::real::Precision;
use microslip::simulate::{simulate, InitialPath, SimulationOptions};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

fn runner(cases: u32, seed: u8) -> TestRunner {
    let config = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &[seed; 32]))
}

#[test]
fn simulation_agrees_with_the_four_segment_integrals_on_random_compliances_and_cycles() {
    // Random families (power laws and their sums, Persson, rational, exponential,
    // admissible polynomials, and sums of them), P1/P0 in (0.05, 0.9), Q1 inside the
    // gross-slip limit, φ in (0, π); a failure shrinks to a small case.
    // The issue asks 1e-5; the default resolution reaches 1e-6 (worst of 140 random cases
    // 8e-8, proofs/independent-simulation.md), and its own estimate bounds its error.
    runner(10, 41)
        .run(&strategies::drawn(strategies::Terms::Single), |case| {
            let Case { cycle, compliance } = case.0.read::<f64>(Precision::DOUBLE).unwrap();
            let exact = dissipation(&cycle, compliance.as_ref(), &Options::default())
                .unwrap()
                .total;
            let simulated = simulate(&cycle, compliance.as_ref(), &SimulationOptions::default()).unwrap();
            let error = ((simulated.w_work - exact) / exact).abs();
            prop_assert!(
                error < 1e-6,
                "{case:?}: simulated {} vs {exact} ({error:e})",
                simulated.w_work
            );
            prop_assert!(
                error <= simulated.estimated_rel_error,
                "{case:?}: error {error:e} beyond the estimate {:e}",
                simulated.estimated_rel_error
            );
            let friction_error = ((simulated.w_friction - exact) / exact).abs();
            prop_assert!(
                friction_error < 1e-5,
                "{case:?}: friction {} vs {exact} ({friction_error:e})",
                simulated.w_friction
            );
            Ok(())
        })
        .unwrap();
}

/// W by one run (no extrapolation) at the given resolution, relative to the exact W.
fn single_run_error(
    cycle: &LoadCycle<f64>,
    compliance: &dyn microslip::compliance::Compliance<f64>,
    elements: usize,
    steps: usize,
) -> f64 {
    let exact = dissipation(cycle, compliance, &Options::default()).unwrap().total;
    let options = SimulationOptions {
        elements: Some(elements),
        steps: Some(steps),
        extrapolate: false,
        ..SimulationOptions::default()
    };
    (simulate(cycle, compliance, &options).unwrap().w_work - exact) / exact
}

#[test]
fn element_and_step_errors_are_second_order_which_the_extrapolation_assumes() {
    // A steep power law near separation (the hardest family): halving the element spacing
    // at a fine step, and the step at a fine bed, each divides the error by about 4.
    let compliance = parse_spec::<f64>("power:c=1.266701,beta=-1.720441", Precision::DOUBLE).unwrap();
    let cycle = LoadCycle {
        normal_amplitude: 0.6687011,
        tangential_amplitude: 0.8871182,
        phase: 0.4709744 * std::f64::consts::PI,
        friction: 1.668352,
        compliance_ratio: 1.060435,
        ..acceptance()
    };
    let orders = |errors: [f64; 3]| [(errors[0] / errors[1]).log2(), (errors[1] / errors[2]).log2()];
    let in_elements = orders([100, 200, 400].map(|n| single_run_error(&cycle, compliance.as_ref(), n, 9600)));
    let in_steps = orders([300, 600, 1200].map(|m| single_run_error(&cycle, compliance.as_ref(), 3200, m)));
    for order in in_elements.iter().chain(&in_steps) {
        assert!(
            (1.7..2.3).contains(order),
            "orders in elements {in_elements:?}, in steps {in_steps:?}"
        );
    }
}

#[test]
fn simulation_reproduces_the_closed_forms() {
    // Constant normal load (Cattaneo–Mindlin with Masing), in phase (the paper's appendix)
    // and Mindlin–Deresiewicz for a Hertz contact: `dissipation` takes the closed form there.
    let persson = parse_spec::<f64>("persson:gamma=1,sigma=1", Precision::DOUBLE).unwrap();
    let hertz = parse_spec::<f64>("hertz:r=1,estar=1", Precision::DOUBLE).unwrap();
    let cases: [(LoadCycle<f64>, &dyn microslip::compliance::Compliance<f64>, Method); 4] = [
        (
            LoadCycle {
                normal_amplitude: 0.0,
                ..acceptance()
            },
            persson.as_ref(),
            Method::ConstantNormalLoad,
        ),
        (
            LoadCycle {
                phase: 0.0,
                ..acceptance()
            },
            persson.as_ref(),
            Method::InPhase,
        ),
        (
            LoadCycle {
                phase: std::f64::consts::PI,
                tangential_amplitude: 0.55,
                ..acceptance()
            },
            persson.as_ref(),
            Method::InPhase,
        ),
        (
            LoadCycle {
                normal_amplitude: 0.0,
                ..acceptance()
            },
            hertz.as_ref(),
            Method::ConstantNormalLoad,
        ),
    ];
    for (cycle, compliance, method) in cases {
        let exact = dissipation(&cycle, compliance, &Options::default()).unwrap();
        assert_eq!(exact.method, method);
        assert!(exact.total > 0.0);
        let simulated = simulate(&cycle, compliance, &SimulationOptions::default()).unwrap();
        let error = ((simulated.w_work - exact.total) / exact.total).abs();
        assert!(
            error < 1e-6,
            "{cycle:?}: {} vs {} ({error:e})",
            simulated.w_work,
            exact.total
        );
    }
}

mod common;
use common::Scratch;
#[path = "common/strategies.rs"]
mod strategies;

fn acceptance() -> LoadCycle<f64> {
    common::acceptance_cycle(0.4 * std::f64::consts::PI)
}

#[test]
fn steady_dissipation_depends_neither_on_the_initial_path_nor_on_q0() {
    let compliance = parse_spec::<f64>("power:c=1,beta=-0.7", Precision::DOUBLE).unwrap();
    let options = |initial_path| SimulationOptions {
        initial_path,
        elements: Some(400),
        steps: Some(400),
        extrapolate: false,
        ..SimulationOptions::default()
    };
    let first = simulate(
        &acceptance(),
        compliance.as_ref(),
        &options(InitialPath::NormalThenTangential),
    )
    .unwrap();
    let second = simulate(&acceptance(), compliance.as_ref(), &options(InitialPath::Proportional)).unwrap();
    assert!(
        ((first.w_work - second.w_work) / first.w_work).abs() < 1e-9,
        "{} vs {}",
        first.w_work,
        second.w_work
    );
    let mut shifted = acceptance();
    shifted.mean_tangential_load = 0.15;
    let with_q0 = simulate(
        &shifted,
        compliance.as_ref(),
        &options(InitialPath::NormalThenTangential),
    )
    .unwrap();
    assert!(
        ((with_q0.w_work - first.w_work) / first.w_work).abs() < 1e-9,
        "{} vs {}",
        with_q0.w_work,
        first.w_work
    );
}

#[test]
fn the_work_of_the_load_and_the_frictional_work_agree() {
    let compliance = parse_spec::<f64>("exp:a=2,c=0.8,d=0.3", Precision::DOUBLE).unwrap();
    let result = simulate(&acceptance(), compliance.as_ref(), &SimulationOptions::default()).unwrap();
    assert!(((result.w_work - result.w_friction) / result.w_work).abs() < 1e-6);
    assert!(result.estimated_rel_error < 1e-4);
    let exact = dissipation(&acceptance(), compliance.as_ref(), &Options::default())
        .unwrap()
        .total;
    assert!(((result.w_work - exact) / exact).abs() <= result.estimated_rel_error.max(1e-7));
}

#[test]
fn a_constant_compliance_dissipates_nothing_in_the_simulation() {
    let constant = Polynomial {
        reference: 0.0,
        coefficients: vec![2.0],
    };
    let options = SimulationOptions {
        elements: Some(100),
        steps: Some(200),
        extrapolate: false,
        ..SimulationOptions::default()
    };
    let result = simulate(&acceptance(), &constant, &options).unwrap();
    assert!(
        result.w_work.abs() < 1e-14 && result.w_friction.abs() < 1e-14,
        "{result:?}"
    );
}

#[test]
fn simulate_command_prints_json_and_writes_the_loop() {
    let dir = Scratch::new("loop");
    let csv = dir.join("loop.csv");
    let output = common::run(common::case_args("simulate", &[]))
        .args(["--json", "--loop"])
        .arg(&csv)
        .output();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let value: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let w = value["W_f64"].as_f64().unwrap();
    let compliance = parse_spec::<f64>("persson:gamma=1,sigma=1", Precision::DOUBLE).unwrap();
    let exact = dissipation(&acceptance(), compliance.as_ref(), &Options::default())
        .unwrap()
        .total;
    assert!((w - exact).abs() < 1e-6 * exact, "{w} vs {exact}");
    assert!(value["W_friction_f64"].as_f64().is_some() && value["estimated_rel_error"].as_f64().is_some());
    assert_eq!(value["elements"], 1600);
    for name in ["cycle.svg", "cycle.png"] {
        let picture = dir.join(name);
        let drawn = common::run(common::case_args("simulate", &[("--phi", "1.4pi")]))
            .args(["--elements", "100", "--steps", "200", "--tolerance", "1e-3", "--plot"])
            .arg(&picture)
            .output();
        assert!(drawn.status.success(), "{}", String::from_utf8_lossy(&drawn.stderr));
        let bytes = std::fs::read(&picture).unwrap();
        assert!(bytes.len() > 10_000, "{name}: {} bytes", bytes.len());
        if name.ends_with(".svg") {
            let svg = String::from_utf8(bytes).unwrap();
            for label in ["EB", "BC", "CH", "HE", "|Q| = fP", "hysteresis loop"] {
                assert!(svg.contains(label), "{name} lacks {label}");
            }
        } else {
            assert_eq!(&bytes[1..4], b"PNG");
        }
    }
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.starts_with("theta,P,Q,u\n"));
    assert_eq!(text.lines().count(), 2 + 4800);
    let bad = common::run(common::case_args("simulate", &[("--p1", "1.2"), ("--phi", "1")])).output();
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("the contact separates"));
}
