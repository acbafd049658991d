//! One `aft` call timed in process, on python/benches/aft_timing.py's inputs (h = [0, 1, 3],
//! 128 time points, U = [1e-3, 1e-2, 0, 2e-3, 1e-3] at P = 1, f = 0.5, λ = 1.2):
//! `cargo run --release --example aft_timing [CALLS] [SPEC …]` prints, per compliance, the
//! best of seven runs of CALLS calls (default 20000) in µs per call, in wall time and in the
//! CPU time of the thread (Linux's schedstat; on a shared machine the better measure of what
//! an idle one would take), and a checksum of the
//! force and Jacobian (the same inputs give the same sum, so two builds can be compared
//! value for value). Without SPECs it times the benchmark's compliances. `--values` prints
//! instead every force and Jacobian entry over a spread of displacements, one per line,
//! for comparing two builds entry by entry. `--normal` (before CALLS) times instead the
//! element under the normal load P = 1 + 0.3 cos t + 0.05 sin 3t (the spring bed of
//! `DEFAULT_ELEMENTS` elements).

use std::hint::black_box;
use std::time::Instant;

use microslip::aft::{aft, aft_with_normal_load, FrictionElement, NormalLoad, VaryingLoadElement, DEFAULT_ELEMENTS};

const COMPLIANCES: [&str; 5] = [
    "hertz:r=1,estar=100",
    "persson:gamma=0.01,sigma=1",
    "power:c=0.02,beta=-0.5",
    "power:c=0.02,beta=-1.5",
    "exp:a=0.02,c=1,d=0.01",
];
const HARMONICS: [usize; 3] = [0, 1, 3];
const DISPLACEMENT: [f64; 5] = [1e-3, 1e-2, 0.0, 2e-3, 1e-3];
/// The normal load's harmonics of `--normal`, about P = 1.
const NORMAL_HARMONICS: [f64; 5] = [0.0, 0.3, 0.0, 0.0, 0.05];
const TIME_POINTS: usize = 128;
const RUNS: usize = 7;

fn main() {
    let mut arguments = std::env::args().skip(1).peekable();
    let values = arguments.next_if(|a| a == "--values").is_some();
    let normal = arguments.next_if(|a| a == "--normal").is_some();
    let calls: usize = match arguments.next_if(|a| a.parse::<usize>().is_ok()) {
        Some(count) => count.parse().unwrap_or(20000),
        None => 20000,
    };
    let given: Vec<String> = arguments.collect();
    let specs: Vec<&str> = if given.is_empty() {
        COMPLIANCES.to_vec()
    } else {
        given.iter().map(String::as_str).collect()
    };
    for spec in specs {
        let element = match FrictionElement::from_spec(1.0, 0.5, 1.2, spec) {
            Ok(element) => element,
            Err(error) => {
                eprintln!("{spec}: {error}");
                std::process::exit(2);
            }
        };
        if values {
            print_values(spec, &element);
            continue;
        }
        let load = NormalLoad {
            mean: 1.0,
            harmonics: &HARMONICS,
            coefficients: &NORMAL_HARMONICS,
            time_points: TIME_POINTS,
        };
        let varying = normal.then(|| {
            VaryingLoadElement::from_spec(&load, 0.5, 1.2, spec, DEFAULT_ELEMENTS).expect("the normal load is valid")
        });
        let call = |displacement: &[f64]| match &varying {
            Some(varying) => aft_with_normal_load(varying, displacement),
            None => aft(&element, &HARMONICS, displacement, TIME_POINTS),
        };
        let force = call(&DISPLACEMENT).expect("the benchmark's inputs are valid");
        let checksum: f64 = force.force.iter().chain(&force.jacobian).sum();
        let (mut wall, mut cpu) = (f64::INFINITY, f64::INFINITY);
        for _ in 0..RUNS {
            let (started, cpu_started) = (Instant::now(), thread_cpu_seconds());
            for _ in 0..calls {
                black_box(call(black_box(&DISPLACEMENT)).ok());
            }
            wall = wall.min(started.elapsed().as_secs_f64() / calls as f64);
            cpu = cpu.min((thread_cpu_seconds() - cpu_started) / calls as f64);
        }
        println!(
            "{spec:32} {:7.2} µs wall {:7.2} µs CPU per call   checksum {checksum:.17e}",
            wall * 1e6,
            cpu * 1e6
        );
    }
}

/// The time this thread has run on a CPU, in seconds (NaN where /proc does not say).
fn thread_cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|text| text.split_whitespace().next()?.parse::<f64>().ok())
        .map_or(f64::NAN, |nanoseconds| nanoseconds * 1e-9)
}

/// Every force and Jacobian entry for displacements from deep microslip to gross slip.
fn print_values(spec: &str, element: &FrictionElement) {
    let mut state = 40u64;
    let mut uniform = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    };
    for scale in [1e-6, 1e-4, 1e-3, 5e-3, 1e-2, 2e-2, 4e-2] {
        for trial in 0..20 {
            let displacement: Vec<f64> = (0..5).map(|_| scale * uniform()).collect();
            let force = aft(element, &HARMONICS, &displacement, TIME_POINTS).expect("finite inputs");
            for (i, value) in force.force.iter().chain(&force.jacobian).enumerate() {
                println!("{spec} {scale:e} {trial} {i} {value:e}");
            }
        }
    }
}
