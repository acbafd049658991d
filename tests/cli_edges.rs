//! What a newcomer meets at the edges of the command line and its files: standard output
//! as a file name, phases that look like degrees, the help naming every compliance family,
//! the table's flags and formats, `--quiet`, suggestions for misspelt names, units in
//! batch headers, facts.json without unexplained nulls, one-line parse errors, signals,
//! input refused whole, overlong records, duplicate table keys and control characters.

use std::path::Path;
use std::time::{Duration, Instant};

mod common;
use common::{case_args, microslip, run, Scratch};

use microslip::compliance::FAMILIES;

const PERSSON: &str = "persson:gamma=1,sigma=1";

/// Exit 2, nothing on stdout, one line on stderr containing `expected`; that line.
fn refused_in_one_line(outcome: (i32, String, String), expected: &str) -> String {
    let (code, stdout, stderr) = outcome;
    assert_eq!(code, 2, "exit code; stderr: {stderr}");
    assert!(stdout.is_empty(), "stdout should be empty: {stdout}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "one line on stderr: {stderr}");
    assert!(
        stderr.contains(expected),
        "stderr should mention '{expected}': {stderr}"
    );
    stderr
}

fn json(text: &str) -> serde_json::Value {
    serde_json::from_str(text.trim()).unwrap_or_else(|e| panic!("{e}: {text}"))
}

/// The acceptance case's batch header and a row with `phi`.
const BATCH_HEADER: &str = "id,p0,p1,q1,phi,friction,lambda,compliance";

/// `microslip batch` with `input` on stdin, written to stdout, with `extra` flags:
/// the exit code, stdout and stderr.
fn batch_on_stdin(input: impl AsRef<[u8]>, extra: &[&str]) -> (i32, String, String) {
    let output = run(["batch", "--input", "-", "--output", "-"])
        .args(extra)
        .stdin(input)
        .output();
    (
        output.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

fn batch_row(id: usize, phi: &str) -> String {
    format!("{id},1,0.4,0.5,{phi},1,1,\"{PERSSON}\"\n")
}

#[test]
fn the_loop_goes_to_standard_output_and_the_report_to_standard_error() {
    let args = case_args(
        "simulate",
        &[
            ("--loop", "-"),
            ("--elements", "20"),
            ("--steps", "40"),
            ("--tolerance", "0.5"),
        ],
    );
    let (code, stdout, stderr) = microslip(&args);
    assert_eq!(code, 0, "{stderr}");
    let mut lines = stdout.lines();
    assert_eq!(lines.next(), Some("theta,P,Q,u"));
    let samples: Vec<Vec<f64>> = lines
        .map(|line| line.split(',').map(|cell| cell.parse().unwrap()).collect())
        .collect();
    assert!(samples.len() >= 40, "{} samples", samples.len());
    // P = P0 + P1 cos θ on every sample of the loop.
    for sample in &samples {
        assert!((sample[1] - (1.0 + 0.4 * sample[0].cos())).abs() < 1e-9, "{sample:?}");
    }
    assert!(stderr.starts_with("W = 4.0"), "the report on stderr: {stderr}");
    // A picture has two formats to choose from by name: standard output is refused for it.
    let args = case_args("simulate", &[("--plot", "-")]);
    refused_in_one_line(microslip(&args), "standard output has no name to choose the format by");
}

#[test]
fn a_bare_phase_beyond_a_turn_is_read_as_radians_with_a_warning() {
    let dissipation = case_args("dissipation", &[("--phi", "72")]);
    let small_amplitude: Vec<String> = ["small-amplitude", "--rho", "1.25", "--phi", "72"]
        .map(String::from)
        .to_vec();
    let series: Vec<String> = ["series", "--rho", "1.25", "--phi", "72", "--order", "2"]
        .map(String::from)
        .to_vec();
    for args in [&dissipation, &small_amplitude, &series] {
        let (code, stdout, stderr) = microslip(args);
        assert_eq!(code, 0, "{args:?}: {stderr}");
        assert!(!stdout.is_empty(), "the computation proceeds: {args:?}");
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(
            stderr.contains("--phi 72 is read as 72 radians") && stderr.contains("72deg") && stderr.contains("0.4pi"),
            "{stderr}"
        );
    }
    // 72 rad is not 72°: the warned run computes at 72 radians, as written.
    let w = |phi: &str| {
        let mut args = case_args("dissipation", &[("--phi", phi)]);
        args.push("--json".into());
        json(&microslip(&args).1)["W_f64"].clone()
    };
    let (radians, exact, degrees) = (w("72"), w("72.0"), w("72deg"));
    assert!(radians.is_f64() && radians == exact, "{radians} {exact}");
    assert_ne!(radians, degrees);
    for quiet_phase in ["72deg", "0.4pi", "6.28"] {
        let (code, _, stderr) = microslip(&case_args("dissipation", &[("--phi", quiet_phase)]));
        assert_eq!((code, stderr.as_str()), (0, ""), "{quiet_phase}");
    }
    // A refusal stays one line: the warning is for runs that succeed.
    refused_in_one_line(
        microslip(&case_args("dissipation", &[("--phi", "72"), ("--p0", "-1")])),
        "P0",
    );
    // A batch warns once, at the first such row.
    let input = format!(
        "{BATCH_HEADER}\n{}{}{}",
        batch_row(1, "0.4pi"),
        batch_row(2, "72"),
        batch_row(3, "100")
    );
    let (code, _, stderr) = batch_on_stdin(input, &[]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("line 3: phi 72 is read as 72 radians"), "{stderr}");
}

#[test]
fn the_help_of_every_command_taking_a_compliance_lists_every_family() {
    for command in ["dissipation", "simulate", "series", "table"] {
        let (code, help, _) = microslip(&[command, "--help"]);
        assert_eq!(code, 0);
        for family in &FAMILIES {
            assert!(
                help.contains(&family.usage()),
                "{command} --help lacks {}: {help}",
                family.usage()
            );
            assert!(help.contains(family.compliance.split_whitespace().next().unwrap()));
        }
        assert!(help.contains("table:FILE[,smoothing=TOL]"), "{help}");
        // The short help names them all too.
        let (_, short, _) = microslip(&[command, "-h"]);
        for family in &FAMILIES {
            assert!(short.contains(family.name), "{command} -h lacks {}", family.name);
        }
    }
}

#[test]
fn the_table_takes_its_parameters_and_writes_text_csv_and_json() {
    let (code, text, stderr) = microslip(&["table"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(!text.contains("0.0000000e0"), "{text}");
    assert!(text.contains("the paper's Fig. 5"), "{text}");
    // φ = 0 with Q1 ≤ fP1: nothing slips, W is exactly 0, printed 0.
    let first_row = text.lines().nth(2).unwrap();
    let cells: Vec<&str> = first_row.split_whitespace().collect();
    assert_eq!(&cells[..3], ["0", "0", "0"], "{first_row}");
    assert_eq!(cells[cells.len() - 2..], ["gross", "slip"], "{first_row}");

    let (code, csv, stderr) = microslip(&["table", "--format", "csv"]);
    assert_eq!(code, 0, "{stderr}");
    let rows: Vec<Vec<&str>> = csv.lines().map(|line| line.split(',').collect()).collect();
    assert_eq!(rows[0], ["phi_over_pi", "Q1", "W", "regime"]);
    assert_eq!(rows.len(), 1 + 11 * 4);
    assert_eq!(rows[1], ["0", "0.2", "0", "no slip"]);
    assert_eq!(rows[3][3], "partial slip");
    assert!(
        (rows[3][2].parse::<f64>().unwrap() - 6.0933466e-2).abs() < 1e-9,
        "{:?}",
        rows[3]
    );
    assert_eq!(rows[4], ["0", "0.6", "", "gross slip"]);

    // Settable parameters: each cell is the W of that case.
    // The case but for Q1 and φ, as flags both commands take.
    let case = [
        "--p0",
        "2",
        "--p1",
        "0.6",
        "--friction",
        "0.8",
        "--lambda",
        "1.5",
        "--compliance",
        "power:c=1,beta=-2",
    ];
    let mut args = vec!["table", "--q1", "0.5,0.9", "--phase-steps", "4", "--format", "json"];
    args.extend(case);
    let (code, out, stderr) = microslip(&args);
    assert_eq!(code, 0, "{stderr}");
    let report = json(&out);
    assert_eq!(report["inputs"]["p0"], "2");
    assert_eq!(report["inputs"]["compliance"], "power:c=1,beta=-2");
    let cells = report["cells"].as_array().unwrap();
    assert_eq!(cells.len(), 5 * 2);
    let cell = &cells[2 * 2 + 1];
    assert_eq!(cell["phi"], "2pi/4");
    assert_eq!(cell["Q1"], "0.9");
    assert_eq!(cell["phi_over_pi"], 0.5);
    let mut single = vec!["dissipation", "--q1", "0.9", "--phi", "pi/2", "--json"];
    single.extend(case);
    let single = json(&microslip(&single).1);
    // The same proven W: the binary64 nearest the middle of the same enclosure.
    assert_eq!(cell["W"], single["W_f64"], "{cell} against {single}");
    assert!(!out.contains("null"), "{out}");
    refused_in_one_line(microslip(&["table", "--phase-steps", "0"]), "--phase-steps must be");
}

#[test]
fn help_says_proven_digits_and_how_long_the_quick_runs_take() {
    for command in ["dissipation", "batch", "small-amplitude", "series"] {
        let (_, help, _) = microslip(&[command, "--help"]);
        let digits = help.split("--digits").nth(1).unwrap().split("\n  -").next().unwrap();
        assert!(digits.contains("prove"), "{command}: {digits}");
        assert!(
            !digits.contains("verif") && !digits.contains("ertified"),
            "{command}: {digits}"
        );
    }
    for command in ["verify", "accuracy"] {
        let (_, help, _) = microslip(&[command, "--help"]);
        let quick = help.split("--quick").nth(1).unwrap().lines().next().unwrap();
        assert!(quick.contains(" s on 2 cores"), "{command}: {quick}");
    }
}

#[test]
fn quiet_silences_warnings_and_progress_but_not_errors() {
    let mut args = case_args("dissipation", &[("--phi", "72")]);
    args.push("--quiet".into());
    let (code, stdout, stderr) = microslip(&args);
    assert_eq!((code, stderr.as_str()), (0, ""));
    assert!(stdout.starts_with("W = "));
    // The batch's summary of failed rows is a warning too.
    let input = format!("{BATCH_HEADER}\n{}", batch_row(1, "x"));
    let (code, stdout, stderr) = batch_on_stdin(input, &["--quiet"]);
    assert_eq!((code, stderr.as_str()), (1, ""));
    assert!(stdout.contains("is not a phase"), "{stdout}");
    let mut args = case_args("dissipation", &[("--p0", "-1")]);
    args.push("-q".into());
    refused_in_one_line(microslip(&args), "P0");
}

#[test]
fn a_misspelt_family_or_key_suggests_the_nearest() {
    for (spec, nearest) in [
        ("persón:gamma=1,sigma=1", "persson"),
        ("persso:gamma=1,sigma=1", "persson"),
        ("hertzz:r=1,estar=1", "hertz"),
        ("Power:c=1,beta=-1", "power"),
        ("persson:gama=1,sigma=1", "gamma"),
        ("table:tests/data/rough-surface.csv,smothing=1e-3", "smoothing"),
    ] {
        let stderr = refused_in_one_line(
            microslip(&case_args("dissipation", &[("--compliance", spec)])),
            &format!("did you mean `{nearest}`?"),
        );
        assert!(
            stderr.contains("known") || stderr.contains("takes") || stderr.contains("table takes"),
            "{stderr}"
        );
    }
    let (_, _, stderr) = microslip(&case_args("dissipation", &[("--compliance", "zzzz:c=1")]));
    assert!(!stderr.contains("did you mean"), "{stderr}");
}

#[test]
fn batch_headers_may_carry_units_as_table_headers_do() {
    let plain = format!("{BATCH_HEADER}\n{}", batch_row(1, "0.4pi"));
    let with_units = format!(
        "id,P0 [N],p1 (N),Q1 [N],phi (rad),friction,lambda,compliance\n{}",
        batch_row(1, "0.4pi")
    );
    let outputs: Vec<String> = [plain, with_units]
        .into_iter()
        .map(|input| {
            let (code, stdout, stderr) = batch_on_stdin(input, &["--format", "jsonl"]);
            assert_eq!(code, 0, "{stderr}");
            stdout
        })
        .collect();
    let (plain, with_units) = (json(&outputs[0]), json(&outputs[1]));
    assert_eq!(plain["W"], with_units["W"]);
    assert_eq!(
        with_units["inputs"]["P0 [N]"], "1",
        "a column is echoed as written under its own name: {with_units}"
    );
    // The same column twice, once with a unit, is a column named twice.
    let twice = format!(
        "p0,P0 [N],p1,q1,phi,friction,lambda,compliance\n1,{}",
        batch_row(1, "1")
    );
    let (code, _, stderr) = batch_on_stdin(twice, &[]);
    assert_eq!(code, 2);
    assert!(stderr.contains("names the column 'P0 [N]' twice"), "{stderr}");
}

#[test]
fn facts_json_has_no_unexplained_null() {
    let directory = Scratch::new("facts");
    let (code, _, stderr) = microslip(&["figures", "--out", directory.to_str().unwrap()]);
    assert_eq!(code, 0, "{stderr}");
    let text = std::fs::read_to_string(directory.join("facts.json")).unwrap();
    assert!(!text.contains("null"), "{text}");
    let facts = json(&text);
    let gains = facts["fig5_out_of_phase_gain"].as_object().unwrap();
    let unbounded = facts["fig5_out_of_phase_gain_unbounded"].as_object().unwrap();
    // Every amplitude has a gain or the reason it has none, never both.
    for key in ["0.2", "0.3", "0.4", "0.5", "0.6"] {
        assert!(gains.contains_key(key) != unbounded.contains_key(key), "{key}");
    }
    assert!(gains["0.5"].as_f64().unwrap() > 1.0);
    assert!(unbounded["0.2"].as_str().unwrap().contains("nothing slips"));
    assert!(unbounded["0.6"].as_str().unwrap().contains("gross slip"));
}

#[test]
fn every_parse_error_is_one_line_and_help_is_not_an_error() {
    refused_in_one_line(
        microslip(&["series", "--rho", "1", "--phi", "1", "--order", "-1"]),
        "unexpected argument '-1'",
    );
    let stderr = refused_in_one_line(microslip(&["tabel"]), "unrecognized subcommand 'tabel'");
    assert!(stderr.contains("a similar subcommand exists: 'table'"), "{stderr}");
    let stderr = refused_in_one_line(microslip(&["table", "--formt", "csv"]), "--formt");
    assert!(stderr.contains("--format"), "{stderr}");
    refused_in_one_line(microslip(&["table", "--format", "xml"]), "xml");
    for args in [&["--help"][..], &["table", "--help"], &["--version"]] {
        let (code, stdout, stderr) = microslip(args);
        assert_eq!((code, stderr.as_str()), (0, ""), "{args:?}");
        assert!(stdout.lines().count() >= 1, "{args:?}");
    }
}

/// A batch input of `rows` cheap rows.
fn big_input(rows: usize) -> String {
    let mut input = format!("{BATCH_HEADER}\n");
    for id in 0..rows {
        input.push_str(&batch_row(id, "0.4pi"));
    }
    input
}

/// The names in `directory` other than `keep`.
fn others(directory: &Path, keep: &[&str]) -> Vec<String> {
    std::fs::read_dir(directory)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| !keep.contains(&name.as_str()))
        .collect()
}

/// A running command, killed and waited for when dropped before it ends (a failed assertion),
/// so that the scratch directory it writes in is removed after it rather than under it.
struct Ended(std::process::Child);

impl Drop for Ended {
    fn drop(&mut self) {
        if let Ok(None) = self.0.try_wait() {
            let _ = self.0.kill();
        }
        let _ = self.0.wait();
    }
}

#[test]
fn a_signal_during_a_batch_leaves_no_temporary_file_and_the_output_as_it_was() {
    use std::os::unix::process::ExitStatusExt;
    let directory = Scratch::new("signals");
    let input = directory.join("in.csv");
    std::fs::write(&input, big_input(200_000)).unwrap();
    let output = directory.join("out.csv");
    for (signal, number) in [("TERM", 15), ("INT", 2), ("HUP", 1)] {
        std::fs::write(&output, "old\n").unwrap();
        let mut batch = Ended(
            run([
                "batch",
                "--input",
                input.to_str().unwrap(),
                "--output",
                output.to_str().unwrap(),
            ])
            .spawn(),
        );
        // Until the temporary file exists: the batch is writing.
        let started = Instant::now();
        while others(&directory, &["in.csv", "out.csv"]).is_empty() {
            assert!(
                started.elapsed() < Duration::from_secs(60),
                "no temporary file appeared"
            );
            std::thread::sleep(Duration::from_millis(5));
        }
        std::thread::sleep(Duration::from_millis(300));
        let killed = std::process::Command::new("kill")
            .args([format!("-{signal}"), batch.0.id().to_string()])
            .status()
            .unwrap();
        assert!(killed.success());
        let status = batch.0.wait().unwrap();
        assert_eq!(
            status.signal(),
            Some(number),
            "{signal}: ended by the signal, {status:?}"
        );
        assert_eq!(
            others(&directory, &["in.csv", "out.csv"]),
            Vec::<String>::new(),
            "{signal}"
        );
        assert_eq!(std::fs::read_to_string(&output).unwrap(), "old\n", "{signal}");
    }
}

#[test]
fn a_file_that_stops_being_csv_is_refused_before_any_row_is_written() {
    let directory = Scratch::new("nul");
    let mut input = big_input(499);
    input.push_str("500,1,0.4,0.5,0.4pi,1,1,const:c=\0\n");
    let path = directory.join("in.csv");
    std::fs::write(&path, input.as_bytes()).unwrap();
    let (code, stdout, stderr) = microslip(&["batch", "--input", path.to_str().unwrap(), "--output", "-"]);
    assert_eq!((code, stdout.as_str()), (2, ""), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("line 501 holds a NUL byte"), "{stderr}");
    // From standard input the rows stream: those before the chunk of the bad line go out
    // complete and in order, then exit 2 names the line.
    let (code, stdout, _) = batch_on_stdin(input.as_bytes(), &[]);
    assert_eq!(code, 2);
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), 1 + 256, "the header and the first chunk");
    for (k, line) in lines[1..].iter().enumerate() {
        assert!(
            line.starts_with(&format!("{k},1,0.4,")) && line.contains("4.062475792458e-1"),
            "{line}"
        );
    }
}

#[test]
fn a_record_over_one_mebibyte_is_refused_in_a_batch_and_in_a_table() {
    let long = " ".repeat(1_100_000);
    let input = format!(
        "{BATCH_HEADER}\n{}1,1,0.4,0.5,0.4pi,1,1,\"{PERSSON}{long}\"\n",
        batch_row(0, "1")
    );
    let (code, stdout, stderr) = batch_on_stdin(input, &[]);
    assert_eq!((code, stdout.as_str()), (2, ""), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("line 3 is longer than 1 MiB"), "{stderr}");
    // A row just under the limit is a row.
    let under = " ".repeat(1_000_000);
    let input = format!("{BATCH_HEADER}\n1,1,0.4,0.5,0.4pi,1,1,\"{PERSSON}{under}\"\n");
    let (code, _, stderr) = batch_on_stdin(input, &[]);
    assert_eq!(code, 0, "{stderr}");

    let directory = Scratch::new("long-table");
    let table = directory.join("t.csv");
    std::fs::write(&table, format!("load,slope\n0.5,2\n1,1{long}\n1.5,0.66\n2,0.5\n")).unwrap();
    let spec = format!("table:{}", table.display());
    let stderr = refused_in_one_line(
        microslip(&case_args("dissipation", &[("--compliance", &spec)])),
        "longer than 1 MiB",
    );
    assert!(stderr.contains("line 3"), "{stderr}");
}

#[test]
fn a_table_key_given_twice_is_refused() {
    let root = env!("CARGO_MANIFEST_DIR");
    let table = format!("{root}/tests/data/rough-surface.csv");
    for (spec, key) in [
        (format!("table:{table},smoothing=1e-3,smoothing=1e-2"), "smoothing"),
        (format!("table:{table},file={table}"), "file"),
    ] {
        refused_in_one_line(
            microslip(&case_args("dissipation", &[("--compliance", &spec)])),
            &format!("table gives '{key}' twice"),
        );
    }
}

#[test]
fn control_characters_of_the_input_are_escaped_in_messages() {
    let directory = Scratch::new("control");
    let table = directory.join("t.csv");
    std::fs::write(&table, "load,slope\n0.5,2\n1,1\0\n1.5,0.66\n2,0.5\n").unwrap();
    let spec = format!("table:{}", table.display());
    let stderr = refused_in_one_line(
        microslip(&case_args("dissipation", &[("--compliance", &spec)])),
        "slope '1\\0' is not a number",
    );
    assert!(!stderr.contains('\0'));
    for spec in ["persson\u{1b}[31m:gamma=1,sigma=1", "persson:gamma=1\u{7},sigma=1"] {
        let (code, _, stderr) = microslip(&case_args("dissipation", &[("--compliance", spec)]));
        assert_eq!(code, 2);
        assert!(!stderr.chars().any(|c| c.is_control() && c != '\n'), "{stderr:?}");
        assert!(stderr.contains("\\u{1b}") || stderr.contains("\\u{7}"), "{stderr}");
    }
    // A phase is quoted escaped too, on stderr and in a batch's error column.
    let (code, _, stderr) = microslip(&case_args("dissipation", &[("--phi", "1\u{7}")]));
    assert_eq!(code, 2);
    assert!(stderr.contains("'1\\u{7}'"), "{stderr}");
    let input = format!("{BATCH_HEADER}\n{}", batch_row(1, "1\u{7}"));
    let (_, stdout, _) = batch_on_stdin(input, &[]);
    // (The input's own cell is echoed as it was: data, not a message.)
    let error = stdout.split("line 2: ").nth(1).unwrap();
    assert!(error.contains("'1\\u{7}'") && !error.contains('\u{7}'), "{stdout}");
}
