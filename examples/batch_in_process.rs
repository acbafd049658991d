//! The in-process cost of a batch's rows: `cargo run --release --example batch_in_process
//! -- ROWS.csv [REPEATS]` reads the rows as `microslip batch` reads them and times W of each
//! (`dissipation_report`, the default f64 answer) one after another, without the batch's
//! threads, progress or output. Prints the rows answered, the CPU seconds of the best of
//! REPEATS passes (default 3) and the microseconds per row: the denominator of the batch's
//! per-row overhead ratio (benches/batch_overhead.sh).

use std::time::Duration;

use microslip::answer::dissipation::dissipation_report;
use microslip::batch::read_input;

/// CPU time of this process, user and system (the machine is shared: wall time would count
/// other work), as the batch's is measured.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // utime and stime, fields 14 and 15, after the command name in parentheses.
    let fields: Vec<&str> = stat.rsplit(')').next().unwrap_or("").split_whitespace().collect();
    let ticks: f64 = [11, 12]
        .iter()
        .filter_map(|&i| fields.get(i)?.parse::<f64>().ok())
        .sum();
    ticks / 100.0
}

fn main() {
    let mut arguments = std::env::args().skip(1);
    let Some(path) = arguments.next() else {
        eprintln!("usage: batch_in_process ROWS.csv [REPEATS]");
        std::process::exit(2);
    };
    let repeats: usize = arguments.next().and_then(|r| r.parse().ok()).unwrap_or(3);
    let file = std::fs::File::open(&path).unwrap_or_else(|error| {
        eprintln!("{path}: {error}");
        std::process::exit(2);
    });
    let input = read_input(std::io::BufReader::new(file)).unwrap_or_else(|error| {
        eprintln!("{path}: {error}");
        std::process::exit(2);
    });
    let cases: Vec<_> = input.filter_map(|row| row.ok()?.case.ok()).collect();
    let budget = Duration::from_secs(60);
    let mut best = f64::INFINITY;
    let mut answered = 0;
    for _ in 0..repeats.max(1) {
        let start = cpu_seconds();
        answered = cases
            .iter()
            .filter(|case| dissipation_report(case, None, budget).is_ok())
            .count();
        best = best.min(cpu_seconds() - start);
    }
    println!(
        "{answered} of {} rows, {best:.3} s CPU, {:.1} µs per row",
        cases.len(),
        best / cases.len().max(1) as f64 * 1e6
    );
}
