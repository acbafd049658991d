//! Certified W per case, timed in process: `cargo run --release --example certified_timing
//! [CASE …]` prints one line per case and digit count (15, 30, 50, 100) with the best of
//! several runs, the digits and the working precision. CASE is a name below or
//! `p0,p1,q1,phi,f,lambda,SPEC` (read as the command line reads a case; phi as a multiple
//! of π when it ends in `pi`).
//! `--digits N` times N digits only; `--once` runs each case once (for callgrind);
//! `--f64` times the default f64 run and one Arb enclosure at 53 bits instead.
//! benches/arb_side_by_side.py runs it beside Arb's own `acb.integral`.

use std::time::{Duration, Instant};

use microslip::answer::Value;
use microslip::ball::Ball;
use microslip::case::{Case, CaseText};
use microslip::compliance::Compliance;
use microslip::cycle::LoadCycle;
use microslip::digits::enclosure::{certified_dissipation, enclose_dissipation};
use microslip::dissipation::{dissipation, Options};
use microslip::real::{Precision, Real};

type RealCase<R> = (LoadCycle<R>, Box<dyn Compliance<R>>);

const NAMED: [(&str, &str); 7] = [
    ("persson", "1,0.4,0.5,0.4pi,1,1,persson:gamma=1,sigma=1"),
    ("power", "1,0.4,0.5,0.4pi,1,1,power:c=0.5,beta=-0.5"),
    ("hertz", "1,0.4,0.5,0.4pi,1,1,hertz:r=1,estar=1"),
    (
        "power-sum",
        "1,0.4,0.5,0.4pi,1,1,power:c=1,beta=-0.5+power:c=0.5,beta=-1.5",
    ),
    ("near-separation", "1,0.999999,0.0005,0.5pi,1,1,persson:gamma=1,sigma=1"),
    (
        "near-separation-1e-9",
        "1,0.999999999,1e-5,0.5pi,1,1,persson:gamma=1,sigma=1",
    ),
    ("near-gross-slip", "1,0.4,0.8886569,1.5,1,1,persson:gamma=1,sigma=1"),
];

/// The case as the command line reads it: its text parsed once into a `CaseSpec`, then
/// read at each precision.
fn case<R: Real>(fields: &str) -> impl Fn(Precision) -> Result<RealCase<R>, String> + '_ {
    move |precision| {
        let parts: Vec<&str> = fields.splitn(7, ',').collect();
        let [p0, p1, q1, phi, f, lambda, spec] = parts[..] else {
            return Err(format!("'{fields}': expected p0,p1,q1,phi,f,lambda,SPEC"));
        };
        let text = CaseText {
            p0: p0.into(),
            p1: p1.into(),
            q0: "0".into(),
            q1: q1.into(),
            phi: phi.into(),
            friction: f.into(),
            lambda: Some(lambda.into()),
            nu: None,
            compliance: spec.into(),
        };
        let Case { cycle, compliance } = text
            .spec()
            .and_then(|spec| spec.at::<R>(precision))
            .map_err(|e| e.to_string())?;
        Ok((cycle, compliance))
    }
}

/// The best time of `run` over `budget` (at least one run), and its last outcome.
fn best_of<T>(budget: Duration, mut run: impl FnMut() -> T) -> (Duration, T) {
    let (mut best, started) = (Duration::MAX, Instant::now());
    loop {
        let start = Instant::now();
        let outcome = run();
        best = best.min(start.elapsed());
        if started.elapsed() >= budget {
            return (best, outcome);
        }
    }
}

/// The default f64 run beside one Arb enclosure at 53 bits (goal 53 bits), in µs.
fn double_beside_arb(name: &str, fields: &str, budget: Duration) {
    let (cycle, compliance) = case::<f64>(fields)(Precision::DOUBLE).expect("the case reads in f64");
    let (f64_time, w) = best_of(budget, || dissipation(&cycle, compliance.as_ref(), &Options::default()));
    let (cycle, compliance) = case::<Ball>(fields)(Precision::bits(53)).expect("the case reads as balls");
    let (arb_time, enclosure) = best_of(budget, || enclose_dissipation(&cycle, compliance.as_ref(), 53));
    let digits = enclosure.ok().map_or(0, |e| Value::of_ball(&e.total, 53, 17).digits());
    println!(
        "{name} f64 {:.1} µs  W = {:?}  |  Arb 53 bits {:.1} µs, {digits} certain digits",
        f64_time.as_secs_f64() * 1e6,
        w.map(|w| w.total),
        arb_time.as_secs_f64() * 1e6
    );
}

/// Removes `flag` from `args`, saying whether it was there.
fn take_flag(args: &mut Vec<String>, flag: &str) -> bool {
    let before = args.len();
    args.retain(|a| a != flag);
    args.len() != before
}

fn main() {
    let mut asked: Vec<String> = std::env::args().skip(1).collect();
    let once = take_flag(&mut asked, "--once");
    let digit_counts: Vec<u32> = match asked.iter().position(|a| a == "--digits") {
        Some(at) if at + 1 < asked.len() => {
            let counts = asked[at + 1].split(',').filter_map(|d| d.parse().ok()).collect();
            asked.drain(at..at + 2);
            counts
        }
        _ => vec![15, 30, 50, 100],
    };
    let budget = Duration::from_millis(if once { 0 } else { 400 });
    let double = take_flag(&mut asked, "--f64");
    let cases: Vec<(String, String)> = if asked.is_empty() {
        NAMED.iter().map(|(n, f)| (n.to_string(), f.to_string())).collect()
    } else {
        asked
            .iter()
            .map(|a| match NAMED.iter().find(|(n, _)| n == a) {
                Some((n, f)) => (n.to_string(), f.to_string()),
                None => (a.clone(), a.clone()),
            })
            .collect()
    };
    for (name, fields) in &cases {
        if double {
            double_beside_arb(name, fields, budget);
            continue;
        }
        let build = case::<Ball>(fields);
        for &digits in &digit_counts {
            let mut best = Duration::MAX;
            let mut outcome = None;
            let started = Instant::now();
            while started.elapsed() < budget || outcome.is_none() {
                let run = Instant::now();
                let result = certified_dissipation(&build, digits);
                best = best.min(run.elapsed());
                outcome = Some(result);
            }
            match outcome.expect("one run") {
                Ok(certified) => println!(
                    "{name} {digits} {:.3} ms  W = {}  ({} bits, {} pieces)",
                    best.as_secs_f64() * 1e3,
                    certified.value.decimal,
                    certified.enclosure.precision.in_bits(),
                    certified.enclosure.pieces
                ),
                Err(error) => println!("{name} {digits} failed: {error}"),
            }
        }
    }
}
