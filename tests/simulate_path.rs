//! `microslip simulate --harmonics FILE | --samples FILE`: the history simulation of any
//! periodic path driven by force or by displacement, against the harmonic cycle it
//! generalizes (the same loop), against `microslip path` (the event decomposition, the
//! Masing loop), and its one-line refusals.

mod common;

use std::path::Path;

use common::{microslip, samples_text, Scratch, PERSSON};
use microslip::compliance::{parse_spec, Compliance};
use microslip::path::displacement::DisplacementCycle;
use microslip::path::input::{read_driven_harmonics, read_harmonics};
use microslip::path::{path_dissipation, Contact, Drive, LoadPath};
use microslip::real::Precision;
use microslip::simulate::{simulate_displacement_path, simulate_path, SimulationOptions};
use serde_json::Value;

/// Two harmonics in P and in Q.
const TWO_HARMONICS: &str = "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0.05,0\n1,0.25,0.05,0.2,-0.3\n2,0.08,-0.04,0.1,0.06\n";

/// P = 1 + 0.3 cos θ + 0.2 cos 2θ has a local maximum 0.9 at θ = π inside its range
/// [0.74375, 1.5]; Q = 0.3 sin θ + 0.1 cos 3θ.
const LOCAL_EXTREME: &str = "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,0\n1,0.3,0,0,0.3\n2,0.2,0,0,0\n3,0,0,0.1,0\n";

/// Displacement driving at P = 1.2: two harmonics in u.
const DISPLACEMENT: &str = "k,P_cos,P_sin,u_cos,u_sin\n0,1.2,0,0.01,0\n1,0,0,0.2,-0.1\n2,0,0,0.08,0.05\n";

/// The same at amplitudes that reach gross slip on Hertz's contact.
const HERTZ_GROSS_SLIP: &str = "k,P_cos,P_sin,u_cos,u_sin\n0,1.2,0,0.01,0\n1,0,0,1.2,-0.5\n2,0,0,0.3,0.3\n";

/// And on the power law v' = 1/√P.
const POWER_GROSS_SLIP: &str = "k,P_cos,P_sin,u_cos,u_sin\n0,1.2,0,0.01,0\n1,0,0,2.5,-1.5\n2,0,0,0.5,0.3\n";

/// Two harmonics in P and in u.
const VARYING_LOAD: &str = "k,P_cos,P_sin,u_cos,u_sin\n0,1.2,0,0.01,0\n1,0.3,0.1,0.2,-0.1\n2,0.1,-0.05,0.08,0.06\n";

/// The contact of every run here: f = 0.8, λ = 1.2, v' = 1/P.
const CONTACT: [&str; 6] = ["--friction", "0.8", "--lambda", "1.2", "--compliance", PERSSON];

/// `microslip <command> --<format> FILE <CONTACT> extra…` with `contents` in FILE.
fn on_file(directory: &Path, command: &str, format: &str, contents: &str, extra: &[&str]) -> (i32, String, String) {
    on_file_with(directory, command, format, contents, PERSSON, extra)
}

/// [`on_file`] with another compliance.
fn on_file_with(
    directory: &Path,
    command: &str,
    format: &str,
    contents: &str,
    compliance: &str,
    extra: &[&str],
) -> (i32, String, String) {
    let file = directory.join(format!("{format}.csv"));
    std::fs::write(&file, contents).unwrap();
    let mut args = vec![command, &format!("--{format}"), file.to_str().unwrap()]
        .into_iter()
        .map(str::to_string)
        .collect::<Vec<_>>();
    args.extend(
        CONTACT[..4]
            .iter()
            .chain(&["--compliance", compliance])
            .chain(extra)
            .map(|s| s.to_string()),
    );
    microslip(&args)
}

/// The compliance and the contact of [`CONTACT`], for the library.
fn persson_contact() -> (Box<dyn Compliance<f64>>, Contact<f64>) {
    let compliance = parse_spec::<f64>(PERSSON, Precision::DOUBLE).unwrap();
    let contact = Contact {
        friction: 0.8,
        compliance_ratio: 1.2,
    };
    (compliance, contact)
}

/// The JSON document of a run that succeeded.
fn json_of((code, stdout, stderr): (i32, String, String)) -> Value {
    assert_eq!(code, 0, "{stderr}");
    serde_json::from_str(stdout.trim()).unwrap_or_else(|e| panic!("{e}: {stdout}"))
}

/// The problems docs/schema/simulate.schema.json finds in a document (none where it conforms).
fn schema_problems(document: &Value) -> Vec<String> {
    let path = format!("{}/docs/schema/simulate.schema.json", env!("CARGO_MANIFEST_DIR"));
    let schema: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let validator = jsonschema::draft202012::new(&schema).unwrap_or_else(|e| panic!("{path}: {e}"));
    validator.iter_errors(document).map(|error| error.to_string()).collect()
}

/// W (f64) and the estimated relative error of a `simulate --json` run.
fn simulated(document: &Value) -> (f64, f64) {
    (
        document["W_f64"].as_f64().unwrap(),
        document["estimated_rel_error"].as_f64().unwrap(),
    )
}

#[test]
fn a_harmonic_path_file_gives_the_w_of_its_case_flags() {
    let directory = Scratch::new("harmonic");
    for (q0, q1, phi) in [(0.0, 0.4, 0.3), (0.05, 0.35, 1.2), (-0.05, 0.3, 2.5), (0.0, 0.4, 4.0)] {
        let (p0, p1) = (1.0, 0.4);
        let text = format!(
            "k,P_cos,P_sin,Q_cos,Q_sin\n0,{p0:e},0,{q0:e},0\n1,{p1:e},0,{:e},{:e}\n",
            q1 * f64::cos(phi),
            q1 * f64::sin(phi)
        );
        let resolution = ["--elements", "100", "--steps", "300", "--tolerance", "1e-3", "--json"];
        let from_file = json_of(on_file(&directory, "simulate", "harmonics", &text, &resolution));
        let mut flags: Vec<String> = ["simulate", "--p0", "1", "--p1", "0.4"]
            .iter()
            .map(|s| s.to_string())
            .collect();
        for (flag, value) in [("--q0", q0), ("--q1", q1), ("--phi", phi)] {
            flags.extend([flag.to_string(), format!("{value:e}")]);
        }
        flags.extend(CONTACT.iter().chain(&resolution).map(|s| s.to_string()));
        let from_flags = json_of(microslip(&flags));
        let ((file_w, _), (flags_w, _)) = (simulated(&from_file), simulated(&from_flags));
        assert!(
            (file_w / flags_w - 1.0).abs() < 1e-12,
            "φ = {phi}: {file_w} vs {flags_w}"
        );
        assert_eq!(from_file["elements"], from_flags["elements"]);
        for document in [&from_file, &from_flags] {
            assert_eq!(schema_problems(document), Vec::<String>::new(), "{document}");
        }
        assert_eq!(
            from_file["inputs"]["harmonics"].as_str(),
            Some(directory.join("harmonics.csv").to_str().unwrap())
        );
    }
}

#[test]
fn the_simulation_of_two_harmonics_agrees_with_microslip_path_within_its_estimate() {
    let directory = Scratch::new("two-harmonics");
    for contents in [TWO_HARMONICS, LOCAL_EXTREME] {
        let simulation = json_of(on_file(&directory, "simulate", "harmonics", contents, &["--json"]));
        let (w, estimate) = simulated(&simulation);
        let path = json_of(on_file(&directory, "path", "harmonics", contents, &["--json"]));
        let exact = path["W_f64"].as_f64().unwrap();
        let error = (w / exact - 1.0).abs();
        assert!(
            error <= estimate && estimate <= 1e-6,
            "{contents}: {w} vs {exact}, estimate {estimate}"
        );
        assert!(error < 1e-4);
    }
}

#[test]
fn the_library_simulates_a_path_as_the_event_decomposition_integrates_it() {
    let (compliance, contact) = persson_contact();
    for contents in [TWO_HARMONICS, LOCAL_EXTREME] {
        let path = read_harmonics::<f64>(contents, Precision::DOUBLE).unwrap();
        let result = simulate_path(&path, &contact, compliance.as_ref(), &SimulationOptions::default()).unwrap();
        let exact = path_dissipation(&path, &contact, compliance.as_ref(), None)
            .unwrap()
            .total;
        for w in [result.w_work, result.w_friction] {
            assert!((w / exact - 1.0).abs() <= result.estimated_rel_error, "{w} vs {exact}");
        }
        // The steady loop starts and ends at the path's θ = 0 and follows its loads.
        let (first, last) = (result.steady_loop[0], result.steady_loop[result.steady_loop.len() - 1]);
        assert_eq!((first.theta, last.theta), (0.0, std::f64::consts::TAU));
        assert!((first.displacement - last.displacement).abs() < 1e-12);
        let middle = result.steady_loop[result.steps / 3];
        assert!((middle.normal_load - path.normal.value(&middle.theta)).abs() < 1e-15);
        assert!((middle.tangential_load - path.tangential.value(&middle.theta)).abs() < 1e-15);
    }
}

#[test]
fn samples_and_harmonics_of_one_path_give_one_w() {
    let directory = Scratch::new("samples");
    let path = read_harmonics::<f64>(TWO_HARMONICS, Precision::DOUBLE).unwrap();
    let samples = samples_text(&path, 16);
    let resolution = ["--elements", "100", "--steps", "300", "--tolerance", "1e-3", "--json"];
    let from_samples = json_of(on_file(&directory, "simulate", "samples", &samples, &resolution));
    let from_harmonics = json_of(on_file(&directory, "simulate", "harmonics", TWO_HARMONICS, &resolution));
    let ((sampled, _), (harmonic, _)) = (simulated(&from_samples), simulated(&from_harmonics));
    assert!((sampled / harmonic - 1.0).abs() < 1e-10, "{sampled} vs {harmonic}");
    assert!(from_samples["inputs"]["samples"].is_string() && from_samples["inputs"].get("harmonics").is_none());
    assert_eq!(schema_problems(&from_samples), Vec::<String>::new(), "{from_samples}");
}

#[test]
fn the_loop_of_a_path_is_written_whole() {
    let directory = Scratch::new("loop");
    let out = directory.join("loop.csv");
    let extra = [
        "--elements",
        "50",
        "--steps",
        "100",
        "--tolerance",
        "0.5",
        "--loop",
        out.to_str().unwrap(),
    ];
    let (code, stdout, stderr) = on_file(&directory, "simulate", "harmonics", TWO_HARMONICS, &extra);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.starts_with("W = "), "{stdout}");
    let text = std::fs::read_to_string(&out).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "theta,P,Q,u");
    // The finest of three runs: 4 × 100 steps, and θ = 0.
    assert_eq!(lines.len(), 1 + 401);
    let row: Vec<f64> = lines[1].split(',').map(|c| c.parse().unwrap()).collect();
    assert!(
        row[0] == 0.0 && (row[1] - 1.33).abs() < 1e-15 && (row[2] - 0.35).abs() < 1e-15,
        "{row:?}"
    );
}

#[test]
fn bad_path_input_is_refused_in_one_line_and_leaves_no_file() {
    let directory = Scratch::new("refusals");
    let out = directory.join("loop.csv");
    let keep_out = ["--loop", out.to_str().unwrap()];
    let refused = |(code, stdout, stderr): (i32, String, String), expected: &str| {
        assert_eq!(code, 2, "{stderr}");
        assert!(stdout.is_empty(), "{stdout}");
        assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
        assert!(stderr.contains(expected), "{expected}: {stderr}");
        assert!(!out.exists());
    };
    // A path file and the case flags together.
    for flag in ["--p0", "--q0", "--phi"] {
        let extra = [&keep_out[..], &[flag, "1"]].concat();
        refused(
            on_file(&directory, "simulate", "harmonics", TWO_HARMONICS, &extra),
            "cannot be used with",
        );
    }
    let extra = [&keep_out[..], &["--harmonics", "other.csv"]].concat();
    refused(
        on_file(&directory, "simulate", "samples", "P,Q\n1,0\n1,0\n1,0\n", &extra),
        "cannot be used with",
    );
    // A malformed file, a missing one, and paths outside the theory, as `microslip path` says.
    let cases = [
        ("k,P_cos,P_sin,Q_cos\n0,1,0,0\n", "column Q_sin"),
        ("k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,zero\n", "line 2"),
        (
            "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,0\n1,0.5,0,0,0\n2,0.9,0.3,0,0\n",
            "separates",
        ),
        (
            "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,0\n1,0.2,0,0,0\n2,0,0,0.7,0.3\n",
            "gross slip",
        ),
    ];
    for (contents, expected) in cases {
        let simulated = on_file(&directory, "simulate", "harmonics", contents, &keep_out);
        let (_, _, path_stderr) = on_file(&directory, "path", "harmonics", contents, &[]);
        assert_eq!(simulated.2, path_stderr, "{contents:?}");
        refused(simulated, expected);
    }
    let separating = on_file(&directory, "simulate", "harmonics", cases[2].0, &keep_out);
    assert!(separating.2.contains("at θ = "), "{}", separating.2);
    let mut missing: Vec<&str> = vec!["simulate", "--harmonics", "/nonexistent/path.csv"];
    missing.extend(CONTACT.iter().chain(&keep_out));
    refused(microslip(&missing), "cannot read the path file");
    // Driven by displacement: a contact that separates (naming θ) or a u that does not move.
    let drive = [&keep_out[..], &["--drive", "displacement"]].concat();
    let separating = "k,P_cos,P_sin,u_cos,u_sin\n0,1,0,0,0\n1,0.5,0,0.2,0\n2,0.9,0.3,0,0\n";
    let (code, stdout, stderr) = on_file(&directory, "simulate", "harmonics", separating, &drive);
    assert!(stderr.contains("at θ = "), "{stderr}");
    refused((code, stdout, stderr), "separates");
    let still = "k,P_cos,P_sin,u_cos,u_sin\n0,1,0,0.1,0\n1,0.3,0,0,0\n";
    refused(
        on_file(&directory, "simulate", "harmonics", still, &drive),
        "does not vary",
    );
    refused(
        on_file(&directory, "simulate", "harmonics", TWO_HARMONICS, &drive),
        "column u_cos",
    );
    // `microslip path` does not follow a varying P under displacement driving, and names
    // the command that does.
    refused(
        on_file(
            &directory,
            "path",
            "harmonics",
            VARYING_LOAD,
            &["--drive", "displacement"],
        ),
        "microslip simulate --drive displacement",
    );
    let plot = directory.join("loop.svg");
    let extra = [&keep_out[..], &["--plot", plot.to_str().unwrap()]].concat();
    refused(
        on_file(&directory, "simulate", "harmonics", TWO_HARMONICS, &extra),
        "--plot",
    );
    assert!(!plot.exists());
}

/// W, its estimate and the Q amplitude of `simulate --drive displacement --json`, and W
/// and the Q amplitude of `path --drive displacement --json`, on one file and compliance.
fn displacement_pair(directory: &Path, contents: &str, compliance: &str) -> ((f64, f64, f64), (f64, f64)) {
    let drive = ["--drive", "displacement", "--json"];
    let simulation = json_of(on_file_with(
        directory,
        "simulate",
        "harmonics",
        contents,
        compliance,
        &drive,
    ));
    assert_eq!(schema_problems(&simulation), Vec::<String>::new(), "{simulation}");
    assert_eq!(simulation["inputs"]["drive"], "displacement");
    let (w, estimate) = simulated(&simulation);
    let path = json_of(on_file_with(
        directory,
        "path",
        "harmonics",
        contents,
        compliance,
        &drive,
    ));
    let number = |document: &Value, key: &str| document[key].as_f64().unwrap_or_else(|| panic!("{key}: {document}"));
    (
        (w, estimate, number(&simulation, "q_amplitude")),
        (number(&path, "W_f64"), number(&path, "q_amplitude")),
    )
}

#[test]
fn displacement_driving_at_constant_load_agrees_with_microslip_path_below_and_beyond_gross_slip() {
    let directory = Scratch::new("displacement");
    let hertz = "hertz:r=1,estar=1";
    let power = "power:c=1,beta=-0.5";
    let cases = [
        (DISPLACEMENT, PERSSON, false),
        (DISPLACEMENT, power, false),
        (DISPLACEMENT, hertz, false),
        (HERTZ_GROSS_SLIP, hertz, true),
        (POWER_GROSS_SLIP, power, true),
    ];
    for (contents, compliance, gross_slip) in cases {
        let ((w, estimate, q_amplitude), (exact, exact_q_amplitude)) =
            displacement_pair(&directory, contents, compliance);
        let error = (w / exact - 1.0).abs();
        assert!(
            error <= estimate && estimate <= 1e-6 && error < 1e-4,
            "{compliance}: {w} vs {exact}, estimate {estimate}"
        );
        // Q's amplitude from the finest loop, fP = 0.96 where the contact slides.
        assert!(
            (q_amplitude / exact_q_amplitude - 1.0).abs() < 1e-6,
            "{compliance}: {q_amplitude} vs {exact_q_amplitude}"
        );
        assert_eq!(
            (exact_q_amplitude - 0.96).abs() < 1e-12,
            gross_slip,
            "{compliance}: {exact_q_amplitude}"
        );
    }
}

#[test]
fn one_harmonic_displacement_dissipates_the_force_driven_w_at_its_q_amplitude() {
    let (compliance, contact) = persson_contact();
    for amplitude in [0.05, 0.3, 1.5] {
        let driven = LoadPath::harmonic(&1.2, &0.0, &0.0, &amplitude, &0.0);
        let cycle = DisplacementCycle::new(&driven, &contact, compliance.as_ref()).unwrap();
        let loads = cycle.turning_loads();
        let q_amplitude =
            0.5 * (loads.iter().copied().fold(f64::MIN, f64::max) - loads.iter().copied().fold(f64::MAX, f64::min));
        let simulated =
            simulate_displacement_path(&driven, &contact, compliance.as_ref(), &SimulationOptions::default()).unwrap();
        let forced = LoadPath::harmonic(&1.2, &0.0, &0.0, &q_amplitude, &0.0);
        let exact = path_dissipation(&forced, &contact, compliance.as_ref(), None)
            .unwrap()
            .total;
        for w in [simulated.w_work, simulated.w_friction] {
            let error = (w / exact - 1.0).abs();
            assert!(
                error <= simulated.estimated_rel_error && error < 1e-6,
                "A = {amplitude}: {w} vs {exact}"
            );
        }
        assert!((simulated.tangential_amplitude() / q_amplitude - 1.0).abs() < 1e-6);
        assert!((simulated.displacement_amplitude() / amplitude - 1.0).abs() < 1e-12);
    }
}

#[test]
fn a_varying_normal_load_under_displacement_driving_closes_its_loop_and_converges() {
    let (compliance, contact) = persson_contact();
    let path = read_driven_harmonics::<f64>(VARYING_LOAD, Precision::DOUBLE, Drive::Displacement).unwrap();
    let simulate = |elements: usize, steps: usize| {
        let options = SimulationOptions {
            elements: Some(elements),
            steps: Some(steps),
            ..SimulationOptions::default()
        };
        simulate_displacement_path(&path, &contact, compliance.as_ref(), &options).unwrap()
    };
    let (result, finer) = (simulate(400, 1200), simulate(800, 2400));
    assert!(result.w_work > 0.0);
    // The estimate bounds the difference from a run at twice the resolution, and the two
    // measures of W agree within it.
    let estimate = result.estimated_rel_error;
    assert!(estimate < 1e-5, "{estimate}");
    assert!(
        (result.w_work / finer.w_work - 1.0).abs() <= estimate,
        "{} vs {}",
        result.w_work,
        finer.w_work
    );
    assert!((result.w_friction / result.w_work - 1.0).abs() <= estimate);
    // The loop follows the prescribed P and u and closes: Q at θ = 2π is Q at θ = 0.
    let (first, last) = (result.steady_loop[0], result.steady_loop[result.steady_loop.len() - 1]);
    assert!(
        (first.tangential_load - last.tangential_load).abs() < 1e-12,
        "{first:?} vs {last:?}"
    );
    for sample in [first, result.steady_loop[result.steps / 3], last] {
        assert!((sample.normal_load - path.normal.value(&sample.theta)).abs() < 1e-14);
        assert!((sample.displacement - path.tangential.value(&sample.theta)).abs() < 1e-14);
        assert!(sample.tangential_load.abs() <= 0.8 * sample.normal_load);
    }
}

#[test]
fn samples_of_a_displacement_driven_path_give_the_w_of_its_harmonics() {
    let directory = Scratch::new("displacement-samples");
    let path = read_driven_harmonics::<f64>(VARYING_LOAD, Precision::DOUBLE, Drive::Displacement).unwrap();
    let samples = samples_text(&path, 16).replacen("P,Q", "P,u", 1);
    let resolution = [
        "--drive",
        "displacement",
        "--elements",
        "100",
        "--steps",
        "300",
        "--tolerance",
        "1e-3",
        "--json",
    ];
    let from_samples = json_of(on_file(&directory, "simulate", "samples", &samples, &resolution));
    let from_harmonics = json_of(on_file(&directory, "simulate", "harmonics", VARYING_LOAD, &resolution));
    let ((sampled, _), (harmonic, _)) = (simulated(&from_samples), simulated(&from_harmonics));
    assert!((sampled / harmonic - 1.0).abs() < 1e-10, "{sampled} vs {harmonic}");
    // The text report gives Q's amplitude and the loss factor too.
    let (code, stdout, stderr) = on_file(&directory, "simulate", "samples", &samples, &resolution[..8]);
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stdout.contains("Q amplitude") && stdout.contains("loss factor"),
        "{stdout}"
    );
}
