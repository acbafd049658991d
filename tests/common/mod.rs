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
