//! What several test files share.

use microslip::cycle::LoadCycle;
use microslip::real::Real;

/// The first acceptance case of the project: P0 = f = λ = 1, P1 = 0.4, Q1 = 0.5, Q0 = 0
/// (with v' = 1/P in most tests), at the given phase and the phase's precision.
#[allow(dead_code)] // not every test binary uses it
pub fn acceptance_cycle<R: Real>(phase: R) -> LoadCycle<R> {
    let one = phase.int(1);
    LoadCycle {
        mean_normal_load: one.clone(),
        normal_amplitude: one.ratio(2, 5),
        mean_tangential_load: one.int(0),
        tangential_amplitude: one.ratio(1, 2),
        phase,
        friction: one.clone(),
        compliance_ratio: one,
    }
}

/// The acceptance case as command-line flags and their values (v' = 1/P).
#[allow(dead_code)] // not every test binary runs the command line
pub const CASE_FLAGS: [(&str, &str); 7] = [
    ("--p0", "1"),
    ("--p1", "0.4"),
    ("--q1", "0.5"),
    ("--phi", "0.4pi"),
    ("--friction", "1"),
    ("--lambda", "1"),
    ("--compliance", "persson:gamma=1,sigma=1"),
];

/// The arguments of `microslip <command>` on the acceptance case, each flag in
/// `overrides` replacing the case's value or, if the case has no such flag, added after
/// it (an empty flag is ignored).
#[allow(dead_code)] // not every test binary runs the command line
pub fn case_args(command: &str, overrides: &[(&str, &str)]) -> Vec<String> {
    let value_of = |flag: &str| {
        overrides
            .iter()
            .find(|(name, _)| *name == flag)
            .map(|(_, value)| *value)
    };
    let mut args = vec![command.to_string()];
    for (flag, value) in CASE_FLAGS {
        args.extend([flag.to_string(), value_of(flag).unwrap_or(value).to_string()]);
    }
    for (flag, value) in overrides {
        if !flag.is_empty() && !CASE_FLAGS.iter().any(|(name, _)| name == flag) {
            args.extend([flag.to_string(), value.to_string()]);
        }
    }
    args
}

/// `microslip args…`: the exit code, stdout and stderr.
#[allow(dead_code)] // not every test binary runs the command line
pub fn microslip<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> (i32, String, String) {
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_microslip"))
        .args(args)
        .output()
        .expect("the binary runs");
    (
        output.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

/// What a run of [`microslip_bounded`] did.
#[allow(dead_code)] // not every test binary runs the command line
pub struct Bounded {
    pub code: i32,
    pub stdout: Vec<u8>,
    pub stderr: String,
    /// Wall time from start to exit.
    pub seconds: f64,
}

/// `microslip args…` with `input` on stdin, killed if it runs past `limit` (then why).
#[allow(dead_code)] // not every test binary runs the command line
pub fn microslip_bounded<S: AsRef<std::ffi::OsStr> + std::fmt::Debug>(
    args: &[S],
    input: &[u8],
    limit: std::time::Duration,
) -> Result<Bounded, String> {
    use std::io::{Read, Write};
    use std::process::Stdio;
    let started = std::time::Instant::now();
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_microslip"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("spawn: {e}"))?;
    let mut stdin = child.stdin.take().expect("piped stdin");
    let input = input.to_vec();
    // The child may stop reading early (a refused header): a closed pipe is no error here.
    let writer = std::thread::spawn(move || drop(stdin.write_all(&input)));
    let mut stdout = child.stdout.take().expect("piped stdout");
    let mut stderr = child.stderr.take().expect("piped stderr");
    let stdout_reader = std::thread::spawn(move || {
        let mut bytes = Vec::new();
        let _ = stdout.read_to_end(&mut bytes);
        bytes
    });
    let stderr_reader = std::thread::spawn(move || {
        let mut text = String::new();
        let _ = stderr.read_to_string(&mut text);
        text
    });
    let status = loop {
        if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
            break status;
        }
        if started.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!(
                "still running after {:.1} s (limit {:.1} s): {args:?}",
                started.elapsed().as_secs_f64(),
                limit.as_secs_f64()
            ));
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
    };
    let _ = writer.join();
    Ok(Bounded {
        code: status.code().unwrap_or(-1),
        stdout: stdout_reader.join().unwrap_or_default(),
        stderr: stderr_reader.join().unwrap_or_default(),
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// A proptest runner with a fixed seed, so that a run is repeatable: `PROPTEST_CASES`
/// replaces `default_cases`, and `MICROSLIP_FUZZ_SEED` shifts the seed for a fresh draw.
#[allow(dead_code)] // not every test binary runs property tests
pub fn seeded_runner(seed: u8, default_cases: u32) -> proptest::test_runner::TestRunner {
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(default_cases);
    let shift = std::env::var("MICROSLIP_FUZZ_SEED")
        .ok()
        .and_then(|n| n.parse::<u8>().ok());
    let seed = seed.wrapping_add(shift.unwrap_or(0));
    TestRunner::new_with_rng(
        Config {
            cases,
            failure_persistence: None,
            ..Config::default()
        },
        TestRng::from_seed(RngAlgorithm::ChaCha, &[seed; 32]),
    )
}
