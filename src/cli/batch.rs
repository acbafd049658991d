//! `microslip batch`: W for every row of a CSV file, as CSV or JSON lines, row by row
//! as the input streams in.

use std::collections::VecDeque;
use std::io::{Read, Write};
use std::path::Path;
use std::sync::Arc;
use std::time::{Duration, Instant};

use clap::Args;

use microslip::batch::{self, BatchError, BatchInput, InputRow, RowPool, RowResult, Ticket};
use microslip::files::{check_writable, StreamedOutput};

use super::case::Jobs;
use super::parse::{self, radians_warning};
use super::progress::Progress;
use super::report::{warn, Failure};

#[derive(Args)]
#[command(after_help = INPUT_CHECKED)]
pub struct BatchArgs {
    /// Input CSV (`-` for stdin): p0,p1,q1,phi,friction,lambda or nu,compliance; optional q0, id;
    /// or path (a path file, relative to the CSV) with optional drive in place of p0,p1,q0,q1,phi.
    #[arg(long)]
    pub input: String,
    /// Output (`-` for stdout); a regular file is written whole or not at all, a device or FIFO in place.
    #[arg(long)]
    pub output: String,
    /// Significant digits for every row (1–1000), proven by a rigorous enclosure where one can be had
    /// (the provenance column says what vouches for each); without it, the 12–15 digits
    /// an f64 interval enclosure proves (Arb balls, for 15, where it proves fewer).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::digits)]
    pub digits: Option<u32>,
    /// Output format.
    #[arg(long, value_parser = ["csv", "jsonl"], default_value = "csv")]
    pub format: String,
    /// Time budget of each row, in seconds (up to 1e6): a row that runs out fails alone.
    #[arg(long, allow_hyphen_values = true, value_parser = parse::seconds, default_value = "60")]
    pub max_seconds: Duration,
    #[command(flatten)]
    pub jobs: Jobs,
}

/// When input that is no batch CSV is found, and what has been written by then.
const INPUT_CHECKED: &str = "An input file is read whole for what would stop the batch (a NUL byte, \
a record over 1 MiB, an unclosed quote) before any row is computed: such input exits 2 with nothing \
written. Standard input streams, so rows are computed and written 256 at a time as they arrive; \
input that stops being CSV part-way then exits 2 naming its line, an output file is left as it was, \
and standard output (or a device) keeps the complete rows before that chunk, in input order.";

/// Rows read before they are computed together (on all cores) and written, in order.
const ROWS_PER_CHUNK: usize = 256;

/// Runs a batch; Ok(failed rows). Nothing is written when the input cannot be read, and
/// nothing computed when the output cannot be written.
pub fn run(args: &BatchArgs) -> Result<usize, Failure> {
    let output_path = Path::new(&args.output);
    check_writable(output_path, &[])?;
    let (mut input, input_is_file) = open_input(&args.input)?;
    let refused = |e: BatchError| Failure::refused(format!("{}: {e}", input_name(&args.input)));
    let header = input.header.clone();
    let mut output = StreamedOutput::create(output_path).map_err(|e| Failure::failed(e.to_string()))?;
    let lost = |e: std::io::Error| Failure::failed(format!("{}: {e}", args.output));
    let jsonl = args.format == "jsonl";
    // The CSV header goes out with the first rows, so that input refused before them
    // leaves a stream output empty.
    let mut pending = if jsonl { Vec::new() } else { batch::csv_header(&header)? };
    // A file has been read whole already, so the next chunk is read and handed in while
    // this one is computed (the threads never wait for it); a stream is answered a chunk
    // at a time, so that a program feeding it rows never waits for rows it has not sent.
    let chunks_in_hand = if input_is_file { 2 } else { 1 };
    let pool = RowPool::new(rayon::current_num_threads(), args.digits, args.max_seconds);
    let mut in_hand: VecDeque<(Ticket, Arc<[InputRow]>)> = VecDeque::new();
    let (mut input_ended, mut refusal) = (false, None);
    let progress = Progress::new(0);
    let started = Instant::now();
    let (mut rows_read, mut rows_done, mut failed) = (0, 0, 0);
    let mut phase_warning = None;
    loop {
        while !input_ended && refusal.is_none() && in_hand.len() < chunks_in_hand {
            let chunk: Vec<InputRow> = match input.by_ref().take(ROWS_PER_CHUNK).collect() {
                Ok(chunk) => chunk,
                Err(error) => {
                    refusal = Some(error);
                    break;
                }
            };
            if chunk.is_empty() {
                input_ended = true;
                break;
            }
            if phase_warning.is_none() {
                phase_warning = first_phase_warning(&chunk);
            }
            rows_read += chunk.len();
            let chunk: Arc<[InputRow]> = chunk.into();
            in_hand.push_back((pool.hand_in(Arc::clone(&chunk)), chunk));
        }
        let Some((ticket, chunk)) = in_hand.pop_front() else {
            break;
        };
        let results = pool.collect(ticket, &mut |answered| progress.at_of(answered, rows_read, "rows"));
        let mut bytes = std::mem::take(&mut pending);
        bytes.extend(rows_text(jsonl, &header, &chunk, &results)?);
        rows_done += chunk.len();
        failed += results.iter().filter(|r| !RowResult::succeeded(r)).count();
        match output.write_all(&bytes).and_then(|()| output.flush()) {
            // The reader of standard output has gone: nothing more is wanted.
            Err(error) if error.kind() == std::io::ErrorKind::BrokenPipe => {
                progress.finish();
                return Ok(failed);
            }
            written => written.map_err(lost)?,
        }
    }
    // Input that stops being CSV part-way: the chunks before it are written, not the rest.
    if let Some(error) = refusal {
        progress.finish();
        return Err(refused(error));
    }
    progress.finish();
    output.write_all(&pending).map_err(lost)?;
    output.finish().map_err(|e| Failure::failed(e.to_string()))?;
    // Said once the input has been read whole: a refused input stays one line.
    if let Some(warning) = phase_warning {
        warn(&format!("{warning} (the first such row)"));
    }
    if failed > 0 || args.output != "-" {
        summarize(rows_done, failed, started);
    }
    Ok(failed)
}

/// The warning of the first row of `chunk` whose phase looks like degrees.
fn first_phase_warning(chunk: &[InputRow]) -> Option<String> {
    chunk.iter().find_map(|row| {
        let phi = row.case.as_ref().ok().map(|case| case.phi.as_str())?;
        radians_warning(&format!("line {}: phi", row.line), phi)
    })
}

/// The rows of a chunk as written: JSON lines, or CSV records under `header`.
fn rows_text(jsonl: bool, header: &[String], chunk: &[InputRow], results: &[RowResult]) -> Result<Vec<u8>, Failure> {
    Ok(if jsonl {
        super::json::lines(&super::json::batch_rows(header, chunk, results))?
    } else {
        batch::csv_rows(header, chunk, results)?
    })
}

/// How the batch input is named in messages.
fn input_name(input: &str) -> &str {
    if input == "-" {
        "standard input"
    } else {
        input
    }
}

/// The batch input `input` (a file, or `-` for standard input) opened as a stream of rows,
/// with its path files named relative to its directory, and whether it is a regular file
/// (then read whole for what would stop the batch before any row is computed).
fn open_input(input: &str) -> Result<(BatchInput<Box<dyn Read>>, bool), Failure> {
    let refused = |e: BatchError| Failure::refused(format!("{}: {e}", input_name(input)));
    let open = || std::fs::File::open(input).map_err(|e| Failure::refused(format!("{input}: {e}")));
    let source: Box<dyn Read> = if input == "-" {
        Box::new(std::io::stdin().lock())
    } else {
        Box::new(open()?)
    };
    let input_is_file = input != "-" && std::fs::metadata(input).is_ok_and(|m| m.is_file());
    if input_is_file {
        batch::check_input(std::io::BufReader::new(open()?)).map_err(refused)?;
    }
    let mut rows = batch::read_input(source).map_err(refused)?;
    // A row's path file is named relative to the batch input's directory.
    if let Some(directory) = Path::new(input).parent().filter(|_| input != "-") {
        rows = rows.relative_to(directory);
    }
    Ok((rows, input_is_file))
}

/// The one line on stderr that ends a batch: rows, time, failures.
fn summarize(rows_done: usize, failed: usize, started: Instant) {
    warn(&format!(
        "{rows_done} {} in {:.2} s, {failed} failed{}",
        if rows_done == 1 { "row" } else { "rows" },
        started.elapsed().as_secs_f64(),
        if failed > 0 { " (see their error column)" } else { "" }
    ));
}
