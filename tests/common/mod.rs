//! What several test files share.

use microslip::case::{CaseBuilder, CaseText};
use microslip::cycle::LoadCycle;
use microslip::path::LoadPath;
use microslip::real::Real;

mod scratch;
#[allow(unused_imports)] // not every test binary writes files
pub use scratch::Scratch;

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

/// The acceptance case (P0 = f = λ = 1, P1 = 0.4, Q0 = 0, Q1 = 0.5, φ = 0.4π,
/// v' = Persson with γ = σ = 1) in the library's builder, to be changed where a test
/// needs another: `case().p1("0.6").phi("0.5pi").text()`.
#[allow(dead_code)] // not every test binary builds cases
pub fn case() -> CaseBuilder {
    CaseText::builder()
        .p0("1")
        .p1("0.4")
        .q1("0.5")
        .phi("0.4pi")
        .friction("1")
        .lambda("1")
        .compliance(PERSSON)
}

/// The acceptance case's compliance: Persson's v' with γ = σ = 1.
#[allow(dead_code)] // not every test binary builds cases
pub const PERSSON: &str = "persson:gamma=1,sigma=1";

/// The acceptance case as command-line flags and their values (v' = 1/P).
#[allow(dead_code)] // not every test binary runs the command line
pub const CASE_FLAGS: [(&str, &str); 7] = [
    ("--p0", "1"),
    ("--p1", "0.4"),
    ("--q1", "0.5"),
    ("--phi", "0.4pi"),
    ("--friction", "1"),
    ("--lambda", "1"),
    ("--compliance", PERSSON),
];

/// The two cases whose f64 W was printed with a wrong last digit (Persson's v', and
/// v' = P⁻³ with Q0 ≠ 0), as the flags of a whole case.
#[allow(dead_code)] // not every test binary runs the reproducers
pub const MISROUNDED_F64_CASES: [&[(&str, &str)]; 2] = [
    &[
        ("--p0", "1"),
        ("--p1", "0.82575"),
        ("--q1", "0.25651"),
        ("--phi", "1.7464"),
        ("--friction", "1.217"),
        ("--lambda", "1.78"),
        ("--compliance", PERSSON),
    ],
    &[
        ("--p0", "1"),
        ("--p1", "0.3"),
        ("--q0", "0.12526586642305143"),
        ("--q1", "0.7650853137335195"),
        ("--phi", "1"),
        ("--friction", "0.8"),
        ("--lambda", "1.2"),
        ("--compliance", "power:c=1,beta=-3"),
    ],
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
    let output = run(args).output();
    (
        output.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

/// One run of the binary, built up before it starts: `run(args).stdin(…).output()`.
#[allow(dead_code)] // not every test binary runs the command line
pub struct Run {
    args: Vec<std::ffi::OsString>,
    input: Vec<u8>,
    directory: Option<std::path::PathBuf>,
    stdout: Option<std::fs::File>,
    file_size_limit_kib: Option<u32>,
}

/// `microslip args…`, to be given more (arguments, stdin, a directory) and then run.
#[allow(dead_code)] // not every test binary runs the command line
pub fn run<S: AsRef<std::ffi::OsStr>>(args: impl IntoIterator<Item = S>) -> Run {
    Run {
        args: args.into_iter().map(|arg| arg.as_ref().to_os_string()).collect(),
        input: Vec::new(),
        directory: None,
        stdout: None,
        file_size_limit_kib: None,
    }
}

/// What a run of the binary did.
#[allow(dead_code)] // not every test binary runs the command line
pub struct Bounded {
    pub code: i32,
    pub stdout: Vec<u8>,
    pub stderr: String,
    /// Wall time from start to exit.
    pub seconds: f64,
}

#[allow(dead_code)] // not every test binary uses every part of the runner
impl Run {
    /// One more argument.
    pub fn arg(mut self, arg: impl AsRef<std::ffi::OsStr>) -> Self {
        self.args.push(arg.as_ref().to_os_string());
        self
    }

    /// More arguments.
    pub fn args<S: AsRef<std::ffi::OsStr>>(mut self, args: impl IntoIterator<Item = S>) -> Self {
        self.args
            .extend(args.into_iter().map(|arg| arg.as_ref().to_os_string()));
        self
    }

    /// The bytes on its stdin (none unless given; stdin is closed after them).
    pub fn stdin(mut self, input: impl AsRef<[u8]>) -> Self {
        self.input = input.as_ref().to_vec();
        self
    }

    /// Run in `directory` rather than the test's.
    pub fn current_dir(mut self, directory: impl AsRef<std::path::Path>) -> Self {
        self.directory = Some(directory.as_ref().to_path_buf());
        self
    }

    /// Its stdout written to `file` rather than captured.
    pub fn stdout_to(mut self, file: std::fs::File) -> Self {
        self.stdout = Some(file);
        self
    }

    /// Files it writes limited to `kib` KiB, as a full disk would stop it: a write beyond
    /// the limit fails with "File too large" rather than a signal.
    pub fn file_size_limit_kib(mut self, kib: u32) -> Self {
        self.file_size_limit_kib = Some(kib);
        self
    }

    /// The command, with stdin, stdout and stderr piped (stdout to its file if given).
    fn command(self) -> (std::process::Command, Vec<u8>) {
        use std::process::{Command, Stdio};
        let program = env!("CARGO_BIN_EXE_microslip");
        let mut command = match self.file_size_limit_kib {
            None => Command::new(program),
            Some(kib) => {
                let mut shell = Command::new("bash");
                shell
                    .arg("-c")
                    .arg(format!("trap '' XFSZ; ulimit -f {kib}; exec \"$0\" \"$@\""))
                    .arg(program);
                shell
            }
        };
        command.args(&self.args).stdin(Stdio::piped()).stderr(Stdio::piped());
        match self.stdout {
            Some(file) => command.stdout(file),
            None => command.stdout(Stdio::piped()),
        };
        if let Some(directory) = &self.directory {
            command.current_dir(directory);
        }
        (command, self.input)
    }

    /// Started, with stdin, stdout and stderr piped for the test to use (the input given
    /// by [`Run::stdin`] is not written).
    pub fn spawn(self) -> std::process::Child {
        self.command().0.spawn().expect("the binary runs")
    }

    /// Run to its end: the exit status, stdout and stderr.
    pub fn output(self) -> std::process::Output {
        let (mut command, input) = self.command();
        let mut child = command.spawn().expect("the binary runs");
        let mut stdin = child.stdin.take().expect("piped stdin");
        // The child may stop reading early (a refused header): a closed pipe is no error here.
        let writer = std::thread::spawn(move || drop(std::io::Write::write_all(&mut stdin, &input)));
        let output = child.wait_with_output().expect("the binary ends");
        let _ = writer.join();
        output
    }

    /// Run to its end, killed if it runs past `limit` (then why).
    pub fn within(self, limit: std::time::Duration) -> Result<Bounded, String> {
        use std::io::{Read, Write};
        let described = format!("{:?}", self.args);
        let started = std::time::Instant::now();
        let (mut command, input) = self.command();
        let mut child = command.spawn().map_err(|e| format!("spawn: {e}"))?;
        let mut stdin = child.stdin.take().expect("piped stdin");
        // The child may stop reading early (a refused header): a closed pipe is no error here.
        let writer = std::thread::spawn(move || drop(stdin.write_all(&input)));
        let stdout = child.stdout.take();
        let mut stderr = child.stderr.take().expect("piped stderr");
        let stdout_reader = std::thread::spawn(move || {
            let mut bytes = Vec::new();
            if let Some(mut stdout) = stdout {
                let _ = stdout.read_to_end(&mut bytes);
            }
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
                    "still running after {:.1} s (limit {:.1} s): {described}",
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
}

/// `microslip args…` with `input` on stdin, killed if it runs past `limit` (then why).
#[allow(dead_code)] // not every test binary runs the command line
pub fn microslip_bounded<S: AsRef<std::ffi::OsStr>>(
    args: &[S],
    input: &[u8],
    limit: std::time::Duration,
) -> Result<Bounded, String> {
    run(args).stdin(input).within(limit)
}

/// The stderr of a run that failed with exit code 1 and printed nothing on stdout.
#[allow(dead_code)] // not every test binary checks a failed run
pub fn failed_with_one(output: &std::process::Output) -> String {
    assert_eq!(
        output.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(output.stdout.is_empty());
    String::from_utf8_lossy(&output.stderr).into_owned()
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

/// A decimal read at 1024 bits (exact for the decimals tests print and compare).
#[allow(dead_code)] // not every test binary reads printed digits
pub fn read_decimal(text: &str) -> Result<rug::Float, String> {
    rug::Float::parse(text.trim())
        .map(|parsed| rug::Float::with_val(1024, parsed))
        .map_err(|_| format!("{text:?} is not a number"))
}

/// The numbers that round to `printed`, a decimal in scientific notation whose
/// significant digits are all printed: those within half a unit of its last digit.
#[allow(dead_code)] // not every test binary reads printed digits
pub fn half_unit_interval(printed: &str) -> Result<(rug::Float, rug::Float), String> {
    let (mantissa, exponent) = printed
        .split_once('e')
        .ok_or_else(|| format!("{printed:?} is not scientific"))?;
    let digits = mantissa.chars().filter(char::is_ascii_digit).count() as i64;
    let exponent: i64 = exponent.parse().map_err(|_| format!("{printed:?} has no exponent"))?;
    let value = read_decimal(printed)?;
    let half_unit = read_decimal(&format!("5e{}", exponent - digits))?;
    Ok((value.clone() - &half_unit, value + &half_unit))
}

/// Whether every point of [`lower`, `upper`] rounds to `printed`, a decimal in
/// scientific notation whose significant digits are all printed: both ends lie within
/// half a unit of its last digit.
#[allow(dead_code)] // not every test binary checks printed digits
pub fn every_point_rounds_to(printed: &str, lower: &rug::Float, upper: &rug::Float) -> Result<(), String> {
    let (low, high) = half_unit_interval(printed)?;
    let show = |x: &rug::Float| x.to_string_radix(10, Some(25));
    if lower > upper {
        return Err(format!("[{}, {}] is no interval", show(lower), show(upper)));
    }
    (low <= *lower && *upper <= high).then_some(()).ok_or_else(|| {
        format!(
            "{printed} printed, but [{}, {}] leaves [{}, {}]",
            show(lower),
            show(upper),
            show(&low),
            show(&high)
        )
    })
}

/// A deterministic stream of numbers in [0, 1) (SplitMix64): random rows that are the same on
/// every run.
#[allow(dead_code)] // not every test binary draws rows
pub struct Draws(pub u64);

#[allow(dead_code)]
impl Draws {
    /// The next number in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The next number in [low, high).
    pub fn between(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * self.next()
    }
}

/// One period of `count` samples of `path` at equal steps of θ from 0, as the text of a
/// `P,Q` file.
#[allow(dead_code)] // not every test binary writes path files
pub fn samples_text(path: &LoadPath<f64>, count: usize) -> String {
    std::iter::once("P,Q\n".to_string())
        .chain((0..count).map(|j| {
            let theta = j as f64 * std::f64::consts::TAU / count as f64;
            format!("{:e},{:e}\n", path.normal.value(&theta), path.tangential.value(&theta))
        }))
        .collect()
}
