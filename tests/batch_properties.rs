//! Property tests of `batch` and `reference` on the command line: random CSVs (comment
//! lines, ids that look like comments, empty and short rows, bad cells, duplicated
//! columns), outputs that are links, devices, FIFOs or standard output, endless input,
//! and budgets. Whatever the input: every row out for every row in, in order; nothing
//! but a regular file replaced; never a panic (101) or an abort (134); never a run
//! beyond its budget and a second. 24 random CSVs by default (`PROPTEST_CASES=N`).

use std::io::Write;
use std::os::unix::fs::FileTypeExt;
use std::path::Path;
use std::process::{Child, Command};
use std::time::{Duration, Instant};

use proptest::prelude::*;

mod common;
use common::Scratch;
use proptest::test_runner::{TestCaseError, TestRunner};

fn text(path: &Path) -> String {
    path.display().to_string()
}

fn spawn(args: &[&str]) -> Child {
    common::run(args).spawn()
}

use common::Bounded as Outcome;

/// Runs to the end with `input` on stdin, killed (and the test failed) after `limit`.
fn run(args: &[&str], input: &[u8], limit: Duration) -> Outcome {
    common::run(args)
        .stdin(input)
        .within(limit)
        .unwrap_or_else(|why| panic!("{why}"))
}

fn runner(seed: u8) -> TestRunner {
    common::seeded_runner(seed, 24)
}

const COLUMNS: [&str; 9] = [
    "id",
    "p0",
    "p1",
    "q1",
    "phi",
    "friction",
    "lambda",
    "compliance",
    "note",
];

/// A random batch CSV: comment lines, a header (perhaps with a column named twice), rows.
#[derive(Clone, Debug)]
struct RandomCsv {
    comments: Vec<String>,
    /// The index of a column named a second time at the end of the header.
    duplicate: Option<usize>,
    rows: Vec<Vec<String>>,
}

impl RandomCsv {
    fn header(&self) -> Vec<String> {
        let mut header: Vec<String> = COLUMNS.iter().map(|c| c.to_string()).collect();
        if let Some(i) = self.duplicate {
            header.push(COLUMNS[i].to_uppercase());
        }
        header
    }

    fn text(&self) -> String {
        let mut out = String::new();
        for comment in &self.comments {
            out.push_str(comment);
            out.push('\n');
        }
        out.push_str(&self.header().join(","));
        out.push('\n');
        for row in &self.rows {
            out.push_str(&row.join(","));
            out.push('\n');
        }
        out
    }

    /// The id of each row as the csv crate reads the row alone (quotes removed, trimmed).
    fn ids(&self) -> Vec<String> {
        self.rows
            .iter()
            .map(|row| {
                let line = row.join(",");
                let mut reader = csv::ReaderBuilder::new()
                    .has_headers(false)
                    .flexible(true)
                    .trim(csv::Trim::All)
                    .from_reader(line.as_bytes());
                let record = reader.records().next().expect("a record").expect("CSV");
                record.get(0).unwrap_or("").to_string()
            })
            .collect()
    }
}

fn cell(choices: &'static [&'static str]) -> impl Strategy<Value = String> {
    proptest::sample::select(choices).prop_map(str::to_string)
}

fn row() -> impl Strategy<Value = Vec<String>> {
    let full = (
        cell(&["#1", "# two", "#", "row", "\"#quoted, id\"", "", "  #spaced  "]),
        cell(&["1", "2.5", "one", "", "1e-400", "0.30000000000000000001"]),
        cell(&["0.4", "0.1", "-1", ""]),
        cell(&["0.5", "0.05", "3"]),
        cell(&["0.4pi", "1", "0", "pi/2"]),
        cell(&["1", "0.5"]),
        cell(&["1", "1.5", ""]),
        cell(&[
            "\"persson:gamma=1,sigma=1\"",
            "const:c=1",
            "\"power:c=0.5,beta=-0.5\"",
            "nonsense",
        ]),
        cell(&["", "x", "#"]),
    )
        .prop_map(|(a, b, c, d, e, f, g, h, i)| vec![a, b, c, d, e, f, g, h, i]);
    prop_oneof![
        6 => full,
        1 => Just(vec![String::new(); COLUMNS.len()]),
        1 => cell(&["#short", "#", "a,1"]).prop_map(|id| vec![id]),
    ]
}

fn random_csv() -> impl Strategy<Value = RandomCsv> {
    (
        proptest::collection::vec(cell(&["# a comment", "#id,p0,\"unclosed", "#"]), 0..3),
        prop_oneof![4 => Just(None), 1 => (0..COLUMNS.len()).prop_map(Some)],
        proptest::collection::vec(row(), 0..10),
    )
        .prop_map(|(comments, duplicate, rows)| RandomCsv {
            comments,
            duplicate,
            rows,
        })
}

/// The output formats of `batch --format`.
#[derive(Clone, Copy, Debug)]
enum Format {
    Csv,
    JsonLines,
}

impl Format {
    /// Its name on the command line.
    fn flag(self) -> &'static str {
        match self {
            Format::Csv => "csv",
            Format::JsonLines => "jsonl",
        }
    }
}

/// Either format, shrinking to CSV.
fn formats() -> impl Strategy<Value = Format> {
    any::<bool>().prop_map(|jsonl| if jsonl { Format::JsonLines } else { Format::Csv })
}

/// The ids of the output, in order, from CSV or JSON lines.
fn output_ids(bytes: &[u8], format: Format) -> Vec<String> {
    if let Format::JsonLines = format {
        String::from_utf8_lossy(bytes)
            .lines()
            .map(|line| {
                let value: serde_json::Value = serde_json::from_str(line).expect("a JSON line");
                value["inputs"]["id"].as_str().unwrap_or("").to_string()
            })
            .collect()
    } else {
        let mut reader = csv::ReaderBuilder::new().flexible(false).from_reader(bytes);
        reader
            .records()
            .map(|record| record.expect("an output record")[0].to_string())
            .collect()
    }
}

fn one_line_refusal(outcome: &Outcome, needle: &str) -> Result<(), TestCaseError> {
    prop_assert_eq!(outcome.code, 2, "{}", outcome.stderr);
    prop_assert!(outcome.stdout.is_empty());
    prop_assert_eq!(outcome.stderr.trim_end().lines().count(), 1, "{}", outcome.stderr);
    prop_assert!(outcome.stderr.contains(needle), "{}", outcome.stderr);
    Ok(())
}

#[test]
fn every_row_in_gives_one_row_out_in_order_and_a_column_named_twice_is_refused() {
    let dir = Scratch::new("random");
    let count = std::sync::atomic::AtomicUsize::new(0);
    runner(21)
        .run(&(random_csv(), formats(), 0..3usize), |(csv, format, target)| {
            let count = count.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            // Standard output, a file, or a link to a file.
            let file = dir.join(format!("out-{count}.txt"));
            let link = dir.join(format!("link-{count}.txt"));
            std::os::unix::fs::symlink(&file, &link).expect("link");
            let output = match target {
                0 => "-".to_string(),
                1 => text(&file),
                _ => text(&link),
            };
            let args = ["batch", "--input", "-", "--output", &output, "--format", format.flag()];
            let outcome = run(&args, csv.text().as_bytes(), Duration::from_secs(60));
            if let Some(i) = csv.duplicate {
                one_line_refusal(
                    &outcome,
                    &format!("names the column '{}' twice", COLUMNS[i].to_uppercase()),
                )?;
                prop_assert!(!file.exists(), "a refused input wrote its output");
                return Ok(());
            }
            prop_assert!(
                outcome.code == 0 || outcome.code == 1,
                "{}: {}",
                outcome.code,
                outcome.stderr
            );
            let written = if target == 0 {
                outcome.stdout.clone()
            } else {
                std::fs::read(&file).expect("the output file")
            };
            prop_assert_eq!(output_ids(&written, format), csv.ids(), "{}", csv.text());
            prop_assert!(std::fs::symlink_metadata(&link).expect("link").file_type().is_symlink());
            Ok(())
        })
        .unwrap();
    // No temporary file left beside the outputs.
    for entry in std::fs::read_dir(&dir).expect("dir") {
        let name = entry.expect("entry").file_name().to_string_lossy().into_owned();
        assert!(!name.starts_with('.'), "{name} left behind");
    }
}

const CASES: &str = "id,p0,p1,q1,phi,friction,lambda,compliance\n\
                     a,1,0.4,0.5,0.4pi,1,1,\"persson:gamma=1,sigma=1\"\n\
                     #b,1,0.4,0.5,0.2pi,1,1,\"persson:gamma=1,sigma=1\"\n";

#[test]
fn devices_fifos_and_standard_output_are_written_in_place_and_never_replaced() {
    let dir = Scratch::new("in-place");
    let input = dir.join("in.csv");
    std::fs::write(&input, CASES).expect("input");
    // A character device.
    let outcome = run(
        &["batch", "--input", &text(&input), "--output", "/dev/null"],
        b"",
        Duration::from_secs(60),
    );
    assert_eq!(outcome.code, 0, "{}", outcome.stderr);
    assert!(std::fs::metadata("/dev/null")
        .expect("null")
        .file_type()
        .is_char_device());
    // Standard output by its names.
    for name in ["-", "/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"] {
        let outcome = run(
            &["batch", "--input", &text(&input), "--output", name],
            b"",
            Duration::from_secs(60),
        );
        assert_eq!(outcome.code, 0, "{name}: {}", outcome.stderr);
        assert_eq!(output_ids(&outcome.stdout, Format::Csv), ["a", "#b"], "{name}");
    }
    // A FIFO, through a link: the reader gets every row, and both stay what they were.
    let fifo = dir.join("fifo");
    assert!(Command::new("mkfifo").arg(&fifo).status().expect("mkfifo").success());
    let link = dir.join("to-fifo.csv");
    std::os::unix::fs::symlink(&fifo, &link).expect("link");
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).expect("read the FIFO"))
    };
    let outcome = run(
        &[
            "batch",
            "--input",
            &text(&input),
            "--output",
            &text(&link),
            "--format",
            "jsonl",
        ],
        b"",
        Duration::from_secs(60),
    );
    assert_eq!(outcome.code, 0, "{}", outcome.stderr);
    assert_eq!(
        output_ids(&reader.join().expect("reader"), Format::JsonLines),
        ["a", "#b"]
    );
    assert!(std::fs::symlink_metadata(&fifo).expect("fifo").file_type().is_fifo());
    assert!(std::fs::symlink_metadata(&link).expect("link").file_type().is_symlink());
}

#[test]
fn an_output_that_cannot_be_written_is_refused_before_any_row_is_computed() {
    let dir = Scratch::new("unwritable");
    // One row that would take its whole budget: refused long before it.
    let slow = "p0,p1,q1,phi,friction,lambda,compliance\n1,0.4,0.5,0.4pi,1,1,\"persson:gamma=1,sigma=1\"\n";
    let missing = text(&dir.join("no/such/directory/out.csv"));
    let directory = text(&dir);
    let loop_link = dir.join("loop");
    std::os::unix::fs::symlink("loop", &loop_link).expect("link");
    for (output, needle) in [
        ("", "the output name is empty"),
        (missing.as_str(), "does not exist"),
        (directory.as_str(), "is a directory"),
        (&text(&loop_link), "symbolic links"),
    ] {
        let args = [
            "batch",
            "--input",
            "-",
            "--output",
            output,
            "--digits",
            "1000",
            "--max-seconds",
            "20",
        ];
        let outcome = run(&args, slow.as_bytes(), Duration::from_secs(10));
        assert!(outcome.seconds < 5.0, "{output:?}: took {} s", outcome.seconds);
        assert_eq!(outcome.code, 2, "{output:?}: {}", outcome.stderr);
        assert!(outcome.stdout.is_empty());
        assert_eq!(outcome.stderr.trim_end().lines().count(), 1, "{}", outcome.stderr);
        assert!(outcome.stderr.contains(needle), "{output:?}: {}", outcome.stderr);
    }
}

/// The resident memory of a running process, in KiB.
fn resident_kib(pid: u32) -> u64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap_or_default();
    status
        .lines()
        .find_map(|line| line.strip_prefix("VmRSS:"))
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|kib| kib.parse().ok())
        .unwrap_or(0)
}

#[test]
fn endless_input_is_refused_or_streamed_in_bounded_memory() {
    // NUL bytes, and a line without end: one line on stderr, exit 2, nothing written.
    let outcome = run(
        &["batch", "--input", "/dev/zero", "--output", "-"],
        b"",
        Duration::from_secs(30),
    );
    let refused = |outcome: &Outcome, needle: &str| {
        assert_eq!(outcome.code, 2, "{}", outcome.stderr);
        assert!(outcome.stdout.is_empty());
        assert_eq!(outcome.stderr.trim_end().lines().count(), 1, "{}", outcome.stderr);
        assert!(outcome.stderr.contains(needle), "{}", outcome.stderr);
    };
    refused(&outcome, "NUL byte");
    let endless_line = vec![b'x'; 3 << 20];
    let outcome = run(
        &["batch", "--input", "-", "--output", "-"],
        &endless_line,
        Duration::from_secs(30),
    );
    refused(&outcome, "runs past 1 MiB");
    let mut unclosed = b"p0,p1,q1,phi,friction,lambda,compliance\n\"".to_vec();
    unclosed.extend(std::iter::repeat_n(b'\n', 3 << 20));
    let outcome = run(
        &["batch", "--input", "-", "--output", "-"],
        &unclosed,
        Duration::from_secs(30),
    );
    refused(&outcome, "unclosed quote");
    // Endless rows on stdin: rows come out as they are computed, memory stays flat.
    let mut child = spawn(&["batch", "--input", "-", "--output", "-"]);
    let mut stdin = child.stdin.take().expect("stdin");
    let feeder = std::thread::spawn(move || {
        let _ = stdin.write_all(b"id,p0,p1,q1,phi,friction,lambda,compliance\n");
        let row = b"r,1,0.4,0.5,0.4pi,1,1,const:c=1\n".repeat(1000);
        while stdin.write_all(&row).is_ok() {}
    });
    let mut stdout = std::io::BufReader::new(child.stdout.take().expect("stdout"));
    let mut line = String::new();
    let mut rows = 0;
    let mut memory = Vec::new();
    let started = Instant::now();
    while rows < 60_000 && started.elapsed() < Duration::from_secs(60) {
        line.clear();
        if std::io::BufRead::read_line(&mut stdout, &mut line).expect("read") == 0 {
            break;
        }
        rows += 1;
        if rows % 10_000 == 0 {
            memory.push(resident_kib(child.id()));
        }
    }
    assert!(child.try_wait().expect("wait").is_none(), "the stream ended early");
    let _ = child.kill();
    let _ = child.wait();
    drop(stdout);
    let _ = feeder.join();
    assert!(rows >= 20_000, "only {rows} rows streamed");
    // Bounded: no more than a few hundred rows are held, whatever has passed.
    let (first, last) = (memory[0], *memory.last().expect("samples"));
    assert!(
        last < first + 16 * 1024,
        "resident memory grew from {first} KiB to {last} KiB"
    );
}

#[test]
fn no_batch_row_and_no_reference_run_outlasts_its_budget_by_a_second() {
    let dir = Scratch::new("budget");
    let input = dir.join("in.csv");
    std::fs::write(&input, CASES).expect("input");
    let outcome = run(
        &[
            "batch",
            "--input",
            &text(&input),
            "--output",
            "-",
            "--digits",
            "1000",
            "--max-seconds",
            "1",
            "--format",
            "jsonl",
        ],
        b"",
        Duration::from_secs(30),
    );
    // Two rows, at most one budget each (they may run one after the other on one core).
    assert!(outcome.seconds < 2.0 * 1.0 + 1.0, "{} s", outcome.seconds);
    assert_ne!(outcome.code, 101);
    assert_ne!(outcome.code, 134);
    assert_eq!(output_ids(&outcome.stdout, Format::JsonLines), ["a", "#b"]);
    let catalogue = dir.join("catalogue.json");
    let entry = |name: &str, p0: &str, compliance: &str| {
        serde_json::json!({"name": name, "description": "", "case": {
            "p0": p0, "p1": "0.4", "q0": "0", "q1": "0.5", "phi": "0.4pi", "friction": "1",
            "lambda": "1", "nu": null, "compliance": compliance}})
    };
    let table = format!("table:{}/tests/data/rough-surface.csv", env!("CARGO_MANIFEST_DIR"));
    let entries = serde_json::json!([
        entry("persson", "1", "persson:gamma=1,sigma=1"),
        entry("hertz", "1", "hertz:r=1,estar=1"),
    ]);
    std::fs::write(&catalogue, entries.to_string()).expect("catalogue");
    let catalogue_text = text(&catalogue);
    let reference = |extra: &[&str]| {
        let mut args = vec!["reference", "--catalogue", &catalogue_text];
        args.extend_from_slice(extra);
        run(&args, b"", Duration::from_secs(30))
    };
    // The budget is the run's: both cases at 1000 digits cannot finish in one second.
    let outcome = reference(&["--digits", "1000", "--max-seconds", "1"]);
    assert!(outcome.seconds < 1.0 + 1.0, "{} s", outcome.seconds);
    assert_eq!(outcome.code, 1, "{}", outcome.stderr);
    // Named, whether the library's own budget or the run's watchdog stopped it.
    assert!(
        outcome.stderr.contains("'persson'") || outcome.stderr.contains("  persson: "),
        "{}",
        outcome.stderr
    );
    // A case that does not compute is a failure, named; never reproduced.
    let entries = serde_json::json!([entry("not-a-number", "nan", "persson:gamma=1,sigma=1")]);
    std::fs::write(&catalogue, entries.to_string()).expect("catalogue");
    let outcome = reference(&[]);
    assert_eq!(outcome.code, 1, "{}", outcome.stderr);
    assert!(
        outcome
            .stderr
            .contains("not-a-number: no stored value, cannot be computed"),
        "{}",
        outcome.stderr
    );
    let before = std::fs::read(&catalogue).expect("catalogue");
    let outcome = reference(&["--write"]);
    assert_eq!(outcome.code, 1, "{}", outcome.stderr);
    assert!(outcome.stderr.contains("case 'not-a-number'"), "{}", outcome.stderr);
    let entries = serde_json::json!([entry("measured", "1", &table)]);
    std::fs::write(&catalogue, entries.to_string()).expect("catalogue");
    let before_table = std::fs::read(&catalogue).expect("catalogue");
    // A table's case stores its interpolant's proven digits; checking then reproduces them.
    let outcome = reference(&["--write", "--digits", "30"]);
    assert_eq!(outcome.code, 0, "{}", outcome.stderr);
    let written: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&catalogue).expect("catalogue")).expect("JSON");
    assert_eq!(written[0]["reference"]["digits"], 30, "{written}");
    let outcome = reference(&[]);
    assert_eq!(outcome.code, 0, "{}", outcome.stderr);
    assert_ne!(before, before_table);
}
