//! `microslip batch`: W for every row of a CSV file, as CSV or JSON lines.

use std::path::Path;
use std::time::{Duration, Instant};

use clap::Args;

use microslip::batch;
use microslip::files::{check_writable, write_atomically};

use super::case::Jobs;
use super::parse;
use super::progress::Progress;
use super::report::{warn, Failure};

#[derive(Args)]
pub struct BatchArgs {
    /// Input CSV (`-` for stdin): p0,p1,q1,phi,friction,lambda or nu,compliance; optional q0, id.
    #[arg(long)]
    pub input: String,
    /// Output file (`-` for stdout), written whole or not at all.
    #[arg(long)]
    pub output: String,
    /// Verified significant digits for every row (1–1000); without it, f64 as a single run.
    #[arg(long, allow_hyphen_values = true, value_parser = parse::digits)]
    pub digits: Option<u32>,
    /// Output format.
    #[arg(long, value_parser = ["csv", "jsonl"], default_value = "csv")]
    pub format: String,
    /// Time budget per row computed in MPFR (--digits, or where f64 does not suffice), in seconds (up to 1e6).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::seconds, default_value = "60")]
    pub max_seconds: Duration,
    #[command(flatten)]
    pub jobs: Jobs,
}

/// Runs a batch; Ok(failed rows). Nothing is written when the input cannot be read.
pub fn run(args: &BatchArgs) -> Result<usize, Failure> {
    if args.output != "-" {
        check_writable(Path::new(&args.output), &[])?;
    }
    let input = if args.input == "-" {
        batch::read_input(std::io::stdin().lock())?
    } else {
        let file = std::fs::File::open(&args.input).map_err(|e| Failure::refused(format!("{}: {e}", args.input)))?;
        batch::read_input(std::io::BufReader::new(file))
            .map_err(|e| Failure::refused(format!("{}: {e}", args.input)))?
    };
    let progress = Progress::new(input.rows.len());
    let done = std::sync::atomic::AtomicUsize::new(0);
    let started = Instant::now();
    let results = batch::run(&input, args.digits, args.max_seconds, &|| {
        let finished = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        progress.at(finished, "rows");
    });
    progress.finish();
    let contents = match args.format.as_str() {
        "jsonl" => super::json::lines(&batch::records(&input, &results))?,
        _ => batch::to_csv(&input, &results)?,
    };
    if args.output == "-" {
        let mut stdout = std::io::stdout().lock();
        match std::io::Write::write_all(&mut stdout, &contents).and_then(|()| std::io::Write::flush(&mut stdout)) {
            Err(error) if error.kind() != std::io::ErrorKind::BrokenPipe => {
                return Err(Failure::failed(format!("writing to standard output: {error}")));
            }
            _ => {}
        }
    } else {
        write_atomically(Path::new(&args.output), |file| std::fs::write(file, &contents))
            .map_err(|e| Failure::failed(e.to_string()))?;
    }
    let failed = results.iter().filter(|r| !r.succeeded()).count();
    if failed > 0 || args.output != "-" {
        warn(&format!(
            "{} rows in {:.2} s, {failed} failed{}",
            results.len(),
            started.elapsed().as_secs_f64(),
            if failed > 0 { " (see their error column)" } else { "" }
        ));
    }
    Ok(failed)
}
