//! The command line keeps its promises: nothing panics, every refusal is one line on
//! stderr naming the problem (and, where one applies, the flag that helps) with nothing
//! on stdout, output never half-written, JSON with one vocabulary, and every example in
//! the help and the README runs.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

mod common;
use common::{microslip, Scratch, CASE_FLAGS};

/// `microslip <command>` on the acceptance case with `extra` flags (a flag given again
/// in `extra` replaces the case's).
fn on_case(command: &str, extra: &[&str]) -> (i32, String, String) {
    let mut args = vec![command];
    for (flag, value) in CASE_FLAGS {
        if !extra.contains(&flag) {
            args.extend([flag, value]);
        }
    }
    args.extend(extra);
    microslip(&args)
}

/// A refusal or failure: the exit code, one line on stderr containing `expected`, nothing on stdout.
fn assert_one_line_failure(outcome: (i32, String, String), code: i32, expected: &str) {
    let (actual, stdout, stderr) = outcome;
    assert_eq!(actual, code, "exit code; stderr: {stderr}");
    assert!(stdout.is_empty(), "stdout should be empty, got {stdout}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "one line on stderr, got {stderr}");
    assert!(
        stderr.contains(expected),
        "stderr should mention '{expected}': {stderr}"
    );
}

fn json(stdout: &str) -> serde_json::Value {
    serde_json::from_str(stdout.trim()).unwrap_or_else(|e| panic!("{e}: {stdout}"))
}

#[test]
fn bare_microslip_prints_usage_and_the_subcommands_on_stderr() {
    let (code, stdout, stderr) = microslip::<&str>(&[]);
    assert_eq!(code, 2);
    assert!(stdout.is_empty());
    assert!(stderr.contains("Usage: microslip [OPTIONS] <COMMAND>"), "{stderr}");
    for command in [
        "dissipation",
        "simulate",
        "small-amplitude",
        "verify",
        "reference",
        "table",
    ] {
        assert!(stderr.contains(command), "{command}: {stderr}");
    }
}

#[test]
fn missing_arguments_are_all_named_on_one_line() {
    let expected = "missing required arguments: --p0, --p1, --q1, --phi, --friction, --compliance, --lambda (or --nu)";
    assert_one_line_failure(microslip(&["dissipation"]), 2, expected);
    assert_one_line_failure(microslip(&["simulate"]), 2, expected);
    assert_one_line_failure(
        microslip(&["small-amplitude"]),
        2,
        "missing required arguments: --rho, --phi",
    );
    assert_one_line_failure(
        microslip(&["series"]),
        2,
        "missing required arguments: --phi, --order, --rho or --p0",
    );
    assert_one_line_failure(
        microslip(&["series", "--phi", "1", "--order", "2", "--p0", "1"]),
        2,
        "missing required arguments: --p1, --q1, --friction, --compliance, --lambda or --nu",
    );
    for (command, missing) in [
        ("batch", "--input, --output"),
        ("reference", "--catalogue"),
        ("figures", "--out"),
        ("accuracy", "--out"),
        ("completions", "<SHELL> (one of bash, elvish, fish, powershell, zsh)"),
    ] {
        assert_one_line_failure(
            microslip(&[command]),
            2,
            &format!("missing required arguments: {missing}"),
        );
    }
    assert_one_line_failure(
        microslip(&["dissipation", "--p0", "1", "--p1", "0.4", "--nu", "0.3"]),
        2,
        "missing required arguments: --q1, --phi, --friction, --compliance",
    );
    let (_, _, stderr) = on_case("dissipation", &["--lambda", "1"]);
    assert!(stderr.is_empty());
    // Neither --lambda nor --nu.
    let args: Vec<&str> = std::iter::once("dissipation")
        .chain(
            CASE_FLAGS
                .iter()
                .filter(|(flag, _)| *flag != "--lambda")
                .flat_map(|(flag, value)| [*flag, *value]),
        )
        .collect();
    assert_one_line_failure(microslip(&args), 2, "missing required arguments: --lambda (or --nu)");
}

#[test]
fn out_of_range_values_say_the_admitted_range() {
    for digits in ["-1", "0", "1001", "4294967296", "x"] {
        assert_one_line_failure(
            on_case("dissipation", &["--digits", digits]),
            2,
            &format!("--digits must be between 1 and 1000 (got '{digits}')"),
        );
    }
    for command in ["dissipation", "simulate"] {
        for seconds in ["1e19", "1e300", "0", "-1", "nan", "inf"] {
            assert_one_line_failure(
                on_case(command, &["--max-seconds", seconds]),
                2,
                "--max-seconds must be a positive number of seconds, at most 1e6",
            );
        }
    }
    for seconds in ["1e19", "1e300"] {
        assert_one_line_failure(
            microslip(&["small-amplitude", "--rho", "1", "--phi", "1", "--max-seconds", seconds]),
            2,
            "--max-seconds must be a positive number",
        );
        assert_one_line_failure(
            microslip(&["reference", "--catalogue", "x.json", "--max-seconds", seconds]),
            2,
            "--max-seconds must be a positive number",
        );
    }
    assert_one_line_failure(
        on_case("simulate", &["--elements", "-5"]),
        2,
        "--elements must be a whole number of at least 20",
    );
    assert_one_line_failure(
        on_case("simulate", &["--steps", "10"]),
        2,
        "--steps must be a whole number of at least 40",
    );
    assert_one_line_failure(
        on_case("simulate", &["--tolerance", "2"]),
        2,
        "--tolerance must be a number between 0 and 1",
    );
    assert_one_line_failure(
        microslip(&["verify", "--seed", "-3"]),
        2,
        "--seed must be a whole number",
    );
}

#[test]
fn a_closed_pipe_ends_the_program_quietly() {
    for args in [&["table"][..], &["verify", "--quick"][..]] {
        let mut child = common::run(args).spawn();
        // Close the reading end at once: the program's write meets a closed pipe.
        drop(child.stdout.take());
        let mut stderr = String::new();
        child.stderr.take().unwrap().read_to_string(&mut stderr).unwrap();
        let status = child.wait().unwrap();
        assert_eq!(status.code(), Some(0), "{args:?}: {stderr}");
        assert!(stderr.is_empty(), "{args:?}: {stderr}");
    }
}

#[test]
fn a_write_error_on_stdout_is_one_line_and_exit_1() {
    if !Path::new("/dev/full").exists() {
        return;
    }
    let output = common::run(["table"])
        .stdout_to(std::fs::OpenOptions::new().write(true).open("/dev/full").unwrap())
        .output();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(
        stderr.contains("writing to standard output: No space left on device"),
        "{stderr}"
    );
}

#[test]
fn simulate_prints_only_vouched_digits_and_fails_short_of_its_tolerance() {
    let (code, stdout, stderr) = on_case("simulate", &["--json"]);
    assert_eq!(code, 0, "{stderr}");
    let value = json(&stdout);
    let digits = value["digits"].as_u64().unwrap() as usize;
    let estimate = value["estimated_rel_error"].as_f64().unwrap();
    assert!(estimate <= 1e-6 && estimate <= 10f64.powi(-(digits as i32)), "{value}");
    // The printing rule gives up a digit whose rounding boundary W ± the estimate straddles.
    assert!(estimate > 10f64.powi(-(digits as i32) - 2) || digits == 15, "{value}");
    assert_eq!(value["provenance"], "simulated");
    let w = value["W"].as_str().unwrap();
    assert_eq!(w.split('e').next().unwrap().replace('.', "").len(), digits, "{value}");
    assert_eq!(
        w.parse::<f64>().unwrap(),
        format!("{:.*e}", digits - 1, value["W_f64"].as_f64().unwrap())
            .parse::<f64>()
            .unwrap()
    );
    // The friction far too high for the grid: W_work and W_friction disagree by orders of magnitude.
    assert_one_line_failure(
        on_case("simulate", &["--friction", "1e8"]),
        1,
        "exceeds the tolerance 1e-6",
    );
    // A coarse grid passes a looser tolerance and fails the default.
    let coarse = ["--elements", "100", "--steps", "200"];
    assert_one_line_failure(on_case("simulate", &coarse), 1, "estimated relative error");
    let (code, stdout, stderr) = on_case("simulate", &[&coarse[..], &["--tolerance", "1e-3"]].concat());
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("significant digits"), "{stdout}");
}

#[test]
fn simulate_refuses_what_cannot_fit_and_stops_at_its_time_budget() {
    for elements in ["10000000", "4294967296", "18446744073709551615"] {
        assert_one_line_failure(
            on_case("simulate", &["--elements", elements]),
            2,
            "bytes of memory, more than",
        );
    }
    // Running out of time is no refusal of the input: exit 1, as for every command.
    assert_one_line_failure(
        on_case("simulate", &["--steps", "1000000", "--max-seconds", "0.5"]),
        1,
        "the time budget ran out",
    );
}

#[test]
fn every_compliance_example_in_the_help_runs() {
    let (code, help, _) = microslip(&["dissipation", "--help"]);
    assert_eq!(code, 0);
    let compliance_help = help
        .split("--compliance <COMPLIANCE>")
        .nth(2)
        .and_then(|rest| rest.split("--digits").next())
        .expect("--compliance in the options");
    let examples: Vec<&str> = compliance_help
        .split('`')
        .skip(1)
        .step_by(2)
        .filter(|s| s.contains(':'))
        .collect();
    assert!(examples.len() >= 5, "{examples:?}");
    for spec in examples {
        let (code, stdout, stderr) = on_case("dissipation", &["--compliance", spec]);
        assert_eq!(code, 0, "{spec}: {stderr}");
        assert!(stdout.starts_with("W = "), "{spec}: {stdout}");
    }
    assert!(help.contains("Poisson's ratio ν in [0, 2/3]"), "{help}");
}

/// The README's console examples (`$ microslip …`, continued lines joined) and the
/// example column of its SPEC table.
fn readme_examples() -> (Vec<Vec<String>>, Vec<String>) {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let mut commands = Vec::new();
    let mut pending: Option<String> = None;
    for line in readme.lines() {
        let line = line.trim();
        if let Some(mut command) = pending.take() {
            command.push(' ');
            command.push_str(line.trim_end_matches('\\'));
            if line.ends_with('\\') {
                pending = Some(command);
            } else {
                commands.push(command);
            }
        } else if let Some(command) = line.strip_prefix("$ microslip ") {
            if line.ends_with('\\') {
                pending = Some(command.trim_end_matches('\\').to_string());
            } else {
                commands.push(command.to_string());
            }
        }
    }
    // A redirection (`> FILE`) is the reader's: the test reads standard output instead.
    let split = |command: String| {
        command
            .split_whitespace()
            .take_while(|w| *w != ">")
            .map(|w| w.trim_matches('\'').to_string())
            .collect()
    };
    let specs = readme_spec_rows().into_iter().map(|row| row.example).collect();
    (commands.into_iter().map(split).collect(), specs)
}

#[test]
fn every_example_in_the_readme_runs() {
    let (commands, specs) = readme_examples();
    assert!(commands.len() >= 4, "{commands:?}");
    assert!(specs.len() >= 7, "{specs:?}");
    let root = env!("CARGO_MANIFEST_DIR");
    for command in &commands {
        // Commands that write files get a scratch directory for them.
        let mut args: Vec<String> = command.clone();
        let directory = Scratch::new("readme");
        let mut previous = String::new();
        for arg in args.iter_mut() {
            let is_output = ["--loop", "--plot", "--out", "--output"].contains(&previous.as_str());
            previous = arg.clone();
            if is_output && arg != "-" {
                *arg = directory.join(&*arg).display().to_string();
            } else if arg.starts_with("tests/") {
                *arg = format!("{root}/{arg}");
            } else if let Some(file) = arg.strip_prefix("table:tests/") {
                *arg = format!("table:{root}/tests/{file}");
            }
        }
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        let (code, stdout, stderr) = microslip(&refs);
        if args[0] == "batch" {
            let output = args.iter().skip_while(|a| *a != "--output").nth(1).expect("--output");
            if output == "-" {
                // The README's failing example: its one row, in gross slip, fails alone (exit 1)
                // and is written with its reason, exactly as the README shows it.
                assert_eq!(code, 1, "{command:?}: {stderr}");
                assert!(stderr.contains("1 failed"), "{command:?}: {stderr}");
                assert_eq!(
                    readme_block_after(&format!("$ microslip {}", command.join(" "))),
                    stdout,
                    "the README's failing batch output"
                );
            } else {
                // The README's sweep: every row computed (exit 0) and written exactly as shown.
                assert_eq!(code, 0, "{command:?}: {stderr}");
                assert!(stderr.contains(" 0 failed"), "{command:?}: {stderr}");
                let written = std::fs::read_to_string(output).unwrap_or_default();
                assert_eq!(written.lines().count(), 8, "{written}");
                assert_eq!(
                    readme_block_after("$ cat sweep.csv"),
                    written,
                    "the README's batch output"
                );
            }
            continue;
        }
        assert_eq!(code, 0, "{command:?}: {stderr}");
        assert!(!stdout.is_empty(), "{command:?}");
    }
    for spec in &specs {
        let spec = match spec.strip_prefix("table:tests/") {
            Some(file) => format!("table:{root}/tests/{file}"),
            None => spec.clone(),
        };
        let (code, _, stderr) = on_case("dissipation", &["--compliance", &spec]);
        assert_eq!(code, 0, "{spec}: {stderr}");
    }
}

/// The lines of the README's console block after the line `prompt`, up to the block's end.
fn readme_block_after(prompt: &str) -> String {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let start = readme.find(&format!("{prompt}\n")).expect("the prompt in the README") + prompt.len() + 1;
    let length = readme[start..].find("```").expect("the end of the block");
    readme[start..start + length].to_string()
}

/// A row of the README's SPEC table.
struct SpecRow {
    template: String,
    slope: String,
    example: String,
}

/// The README's SPEC table (checked to be the only one, set apart by a blank line).
fn readme_spec_rows() -> Vec<SpecRow> {
    let readme = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/README.md")).unwrap();
    let lines: Vec<&str> = readme.lines().collect();
    let headers: Vec<usize> = (0..lines.len()).filter(|&i| lines[i].starts_with("| SPEC |")).collect();
    assert_eq!(headers.len(), 1, "one SPEC table");
    assert!(
        headers[0] > 0 && lines[headers[0] - 1].trim().is_empty(),
        "a blank line before the table"
    );
    lines[headers[0] + 2..]
        .iter()
        .take_while(|line| line.starts_with('|'))
        .map(|line| {
            let cells: Vec<&str> = line.split('|').map(|cell| cell.trim().trim_matches('`')).collect();
            assert_eq!(cells.len(), 5, "three columns: {line}");
            SpecRow {
                template: cells[1].to_string(),
                slope: cells[2].to_string(),
                example: cells[3].to_string(),
            }
        })
        .collect()
}

#[test]
fn the_readme_has_one_spec_table_naming_every_family_the_parser_knows() {
    let rows = readme_spec_rows();
    // The families as the SPEC parser lists them when it meets an unknown one.
    let (code, _, stderr) = on_case("dissipation", &["--compliance", "nosuchfamily:x=1"]);
    assert_eq!(code, 2, "{stderr}");
    let known = stderr
        .split("(known: ")
        .nth(1)
        .and_then(|rest| rest.split(')').next())
        .unwrap_or_else(|| panic!("the parser's list of families: {stderr}"));
    let mut parser_families: Vec<&str> = known.split(", ").collect();
    let mut readme_families: Vec<&str> = rows
        .iter()
        .map(|row| row.template.split(':').next().unwrap_or(""))
        .collect();
    parser_families.sort_unstable();
    readme_families.sort_unstable();
    assert_eq!(readme_families, parser_families);
    // Each example fills in the template's parameters, named as the template names them.
    let keys = |spec: &str| -> Vec<String> {
        let (family, parameters) = spec.split_once(':').unwrap_or((spec, ""));
        let mut keys: Vec<String> = parameters
            .split(',')
            .filter_map(|p| p.split_once('=').map(|(k, _)| format!("{family}.{k}")))
            .collect();
        keys.sort();
        keys
    };
    for row in &rows {
        if row.template.starts_with("table:") {
            assert!(row.example.starts_with("table:"), "{}", row.example);
        } else {
            assert_eq!(
                keys(&row.template),
                keys(&row.example),
                "{} against {}",
                row.template,
                row.example
            );
        }
    }
    let poly = rows.iter().find(|row| row.template.starts_with("poly:")).expect("poly");
    assert!(
        poly.template.contains("p0=p0") && poly.slope.contains("(P − p0)"),
        "{}",
        poly.slope
    );
}

#[test]
fn the_compliance_range_is_named_and_reaches_down_to_the_permanent_stick_load() {
    // v'' = 0.5 − 0.2(P − 1) > 0: refused over [P_T, P0 + P1], P_T = 0.36718 < P0 − P1 = 0.6.
    let (code, stdout, stderr) = on_case("dissipation", &["--compliance", "poly:p0=1,coeffs=2;0.5;-0.1"]);
    assert_one_line_failure(
        (code, stdout, stderr.clone()),
        2,
        "v'' ≤ 0 is needed on [3.6718e-1, 1.4000e0] = [P_T, P0 + P1]",
    );
    assert!(stderr.contains("the slip loads of the cycle reach down to the permanent-stick load P_T"));
    assert!(!stderr.contains("the cycle reaches"), "{stderr}");
}

#[test]
fn hints_name_only_flags_that_can_help() {
    // The verified fallback of a default run runs out of time: no advice to use --digits.
    let near_separation = [
        "--p1",
        "0.999999",
        "--q1",
        "0.001",
        "--phi",
        "0.5pi",
        "--max-seconds",
        "0.001",
    ];
    let (_, _, stderr) = on_case("dissipation", &near_separation);
    assert!(
        stderr.contains("raise --max-seconds") && !stderr.contains("--digits"),
        "{stderr}"
    );
    let (_, _, stderr) = on_case("dissipation", &["--digits", "500", "--max-seconds", "0.001"]);
    assert!(
        stderr.contains("raise --max-seconds or ask for fewer --digits"),
        "{stderr}"
    );
    // No ratio printed as a division by infinity.
    let (_, stdout, stderr) = on_case("dissipation", &["--q1", "1e-320", "--json"]);
    assert!(!stdout.contains("/inf") && !stderr.contains("/inf"), "{stdout}{stderr}");
}

/// Running out of time is a failure (exit 1), not bad input, whichever notices it: the
/// library between attempts, or the command's watchdog when an attempt under way outlasts
/// the budget (near in phase, whose first attempt builds large node tables).
#[test]
fn running_out_of_time_exits_1_whichever_notices_it() {
    // Near in phase with Q1 < fP1 the first enclosure needs node tables at 2112 bits (about
    // a second).
    let slow = [
        "--p0",
        "1",
        "--p1",
        "0.4",
        "--q1",
        "0.2",
        "--phi",
        "1e-300",
        "--compliance",
        "persson:gamma=1,sigma=1",
    ];
    for budget in ["0.001", "0.05", "0.3"] {
        for digits in [None, Some("20")] {
            let mut args = slow.to_vec();
            args.extend(["--max-seconds", budget]);
            if let Some(digits) = digits {
                args.extend(["--digits", digits]);
            }
            assert_one_line_failure(on_case("dissipation", &args), 1, "raise --max-seconds");
        }
    }
    let (code, _, stderr) = on_case("dissipation", &["--digits", "500", "--max-seconds", "0.001"]);
    assert_eq!(code, 1, "{stderr}");
}

#[test]
fn output_paths_are_checked_before_computing_and_failures_are_one_human_line() {
    let directory = Scratch::new("paths");
    let in_dir = |name: &str| directory.join(name).display().to_string();
    assert_one_line_failure(
        on_case("simulate", &["--plot", &in_dir("x.eps")]),
        2,
        "x.eps: the file name must end in .svg or .png or .pdf",
    );
    assert_one_line_failure(
        on_case("simulate", &["--loop", &in_dir("x.txt")]),
        2,
        "x.txt: the file name must end in .csv",
    );
    assert_one_line_failure(
        on_case("simulate", &["--plot", &in_dir("missing/x.svg")]),
        2,
        "does not exist",
    );
    let (code, stdout, stderr) = on_case("simulate", &["--plot", "/proc/x.png"]);
    assert_one_line_failure(
        (code, stdout, stderr.clone()),
        2,
        "/proc/x.png: cannot create a file in /proc",
    );
    assert!(!stderr.contains("Os {") && !stderr.contains("Error("), "{stderr}");
    let file = in_dir("existing-file");
    std::fs::write(&file, "keep").unwrap();
    assert_one_line_failure(
        microslip(&["accuracy", "--out", &file]),
        2,
        "exists and is not a directory",
    );
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "keep");
    // Nothing but the files asked for is left in the directory (no temporaries).
    let (code, _, stderr) = on_case(
        "simulate",
        &[
            "--tolerance",
            "1e-3",
            "--elements",
            "100",
            "--steps",
            "200",
            "--loop",
            &in_dir("l.csv"),
            "--plot",
            &in_dir("p.svg"),
        ],
    );
    assert_eq!(code, 0, "{stderr}");
    let mut names: Vec<String> = std::fs::read_dir(&directory)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["existing-file", "l.csv", "p.svg"]);
    assert!(std::fs::read_to_string(in_dir("l.csv"))
        .unwrap()
        .starts_with("theta,P,Q,u\n"));
}

/// A catalogue of the first three committed cases, one stored value altered and one removed.
fn altered_catalogue(directory: &Path) -> (PathBuf, String) {
    let committed = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/catalogue.json")).unwrap();
    let mut entries: Vec<serde_json::Value> = serde_json::from_str(&committed).unwrap();
    entries.truncate(3);
    let original = entries[0]["reference"]["W"].as_str().unwrap().to_string();
    let altered = format!("9{}", &original[1..]);
    entries[0]["reference"]["W"] = serde_json::Value::String(altered);
    entries[1].as_object_mut().unwrap().remove("reference");
    let path = directory.join("catalogue.json");
    std::fs::write(&path, serde_json::to_string_pretty(&entries).unwrap()).unwrap();
    (path, original)
}

#[test]
fn reference_checks_by_default_reports_every_difference_and_writes_only_when_asked() {
    let directory = Scratch::new("catalogue");
    let (path, original) = altered_catalogue(&directory);
    let before = std::fs::read_to_string(&path).unwrap();
    let path_text = path.display().to_string();
    let (code, stdout, stderr) = microslip(&["reference", "--catalogue", &path_text]);
    assert_eq!(code, 1, "{stderr}");
    assert!(stdout.is_empty());
    assert!(stderr.contains("2 of 3 reference values"), "{stderr}");
    assert!(
        stderr.contains("power-ordinary: stored W = 9") && stderr.contains(&format!("computed W = {original}")),
        "{stderr}"
    );
    assert!(stderr.contains("no stored value"), "{stderr}");
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        before,
        "check mode must not write"
    );
    let (code, stdout, stderr) = microslip(&["reference", "--catalogue", &path_text, "--write"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stdout.contains("3 reference values to 50 verified digits written"),
        "{stdout}"
    );
    let (code, stdout, stderr) = microslip(&["reference", "--catalogue", &path_text]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("all 3 reference values"), "{stdout}");
    let rewritten: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    assert_eq!(rewritten[0]["reference"]["W"], original.as_str());
    assert_eq!(std::fs::read_dir(&directory).unwrap().count(), 1, "no temporary left");
}

#[test]
fn json_reports_share_one_vocabulary() {
    let (code, stdout, stderr) = on_case("dissipation", &["--json"]);
    assert_eq!(code, 0, "{stderr}");
    let f64_run = json(&stdout);
    let w_f64 = f64_run["W_f64"].as_f64().unwrap();
    let w: f64 = f64_run["W"].as_str().unwrap().parse().unwrap();
    assert!((w - w_f64).abs() <= 1e-12 * w, "{f64_run}");
    // The default is proven: an enclosure in f64 intervals, its 12 to 15 digits certified.
    assert!(
        f64_run["digits_verified"] == 13 && f64_run["precision_bits"] == 53 && f64_run["arithmetic"] == "f64 intervals",
        "{f64_run}"
    );
    let eb = f64_run["segments_f64"]["EB"].as_f64().unwrap();
    assert!((f64_run["segments"]["EB"].as_str().unwrap().parse::<f64>().unwrap() - eb).abs() < 1e-12);
    // W_f64 is the library's f64 value in shortest round-trip form: it parses back to itself.
    let text = stdout.split("\"W_f64\":").nth(1).unwrap().split(',').next().unwrap();
    assert_eq!(text.parse::<f64>().unwrap().to_string(), text);
    let (_, stdout, _) = on_case("dissipation", &["--json", "--digits", "20"]);
    let verified = json(&stdout);
    // The binary64 nearest the middle of the enclosure, with or without --digits.
    assert!(verified["W_f64"].is_number() && verified["segments_f64"]["EB"].is_number());
    assert_eq!(verified["digits_verified"], 20);
    assert_eq!(verified["inputs"]["p0"], "1");

    let (code, stdout, stderr) = on_case(
        "simulate",
        &["--json", "--elements", "100", "--steps", "200", "--tolerance", "1e-3"],
    );
    assert_eq!(code, 0, "{stderr}");
    let simulated = json(&stdout);
    assert_eq!(simulated["inputs"]["p1"], "0.4");
    assert_eq!(simulated["inputs"]["elements"], 100);
    assert_eq!(simulated["inputs"]["tolerance"], 1e-3);
    assert_eq!(simulated["method"], "history-simulation");
    assert_eq!(simulated["provenance"], "simulated");
    assert!(simulated["digits_verified"].is_null() && simulated["precision_bits"] == 53);
    assert!(simulated["W_f64"].as_f64().is_some() && simulated["W"].is_string());

    let (code, stdout, stderr) = microslip(&[
        "small-amplitude",
        "--rho",
        "1.25",
        "--phi",
        "0.4pi",
        "--json",
        "--digits",
        "20",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let coefficient = json(&stdout);
    assert_eq!(coefficient["digits_verified"], 20);
    assert_eq!(coefficient["inputs"]["rho"], "1.25");

    let (code, stdout, stderr) = microslip(&["verify", "--quick", "--json"]);
    assert_eq!(code, 0, "{stderr}");
    let gate = json(&stdout);
    for claim in gate["claims"].as_array().unwrap() {
        let bits = claim["precision_bits"].as_u64().unwrap();
        assert!(bits >= 53, "{claim}");
    }
}

#[test]
fn library_error_texts_name_no_command_line_flags() {
    use microslip::answer::DissipationAnswerError;
    use microslip::digits::agreement::OutOfBudget;
    use microslip::dissipation::DissipationError;
    let errors: Vec<String> = vec![
        DissipationError::NotConverged {
            points: 512,
            relative_error: 1e-3,
            requested: 1e-15,
        }
        .to_string(),
        DissipationError::IllConditioned {
            bits: 53,
            cause: "x".into(),
            expected: 1e-3,
            limit: 1e-12,
        }
        .to_string(),
        DissipationError::OutOfRange { scale: 1e-300 }.to_string(),
        DissipationAnswerError::DigitsOutOfRange(0).to_string(),
        DissipationAnswerError::Budget(OutOfBudget {
            digits_requested: 50,
            digits_agreed: 3,
            seconds: 1.0,
            precision_bits: 256,
        })
        .to_string(),
    ];
    for text in errors {
        assert!(!text.contains("--"), "{text}");
    }
}

#[test]
fn a_misspelt_command_flag_or_choice_keeps_clap_suggestion_and_usage() {
    for (args, expected) in [
        (
            &["disipation"][..],
            &[
                "microslip: unrecognized subcommand 'disipation'",
                "a similar subcommand exists: 'dissipation'",
                "Usage: microslip [OPTIONS] <COMMAND>",
                "--help",
            ][..],
        ),
        (
            &["dissipation", "--frictoin", "1"][..],
            &[
                "microslip: unexpected argument '--frictoin'",
                "a similar argument exists: '--friction'",
                "Usage: microslip dissipation",
            ][..],
        ),
        (
            &["batch", "--input", "in.csv", "--output", "out.csv", "--format", "xml"][..],
            &["invalid value 'xml' for '--format", "[possible values: csv, jsonl]"][..],
        ),
        (
            &["completions", "tcsh"][..],
            &[
                "possible values: bash, elvish, fish, powershell, zsh",
                "a similar value exists: 'zsh'",
            ][..],
        ),
    ] {
        let (code, stdout, stderr) = microslip(args);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stdout.is_empty(), "{args:?}: {stdout}");
        for text in expected {
            assert!(stderr.contains(text), "{args:?}: '{text}' in {stderr}");
        }
        assert!(!stderr.contains("error:"), "{args:?}: {stderr}");
    }
}

#[test]
fn completions_for_each_shell_know_the_commands_and_their_flags() {
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let (code, script, stderr) = microslip(&["completions", shell]);
        assert_eq!(code, 0, "{shell}: {stderr}");
        assert!(stderr.is_empty(), "{shell}: {stderr}");
        for word in [
            "dissipation",
            "small-amplitude",
            "batch",
            "friction",
            "compliance",
            "jobs",
        ] {
            assert!(script.contains(word), "{shell}: no '{word}'");
        }
    }
    // bash reads its script without complaint, where bash is installed.
    let (_, script, _) = microslip(&["completions", "bash"]);
    if let Ok(mut bash) = Command::new("bash")
        .args(["-n", "/dev/stdin"])
        .stdin(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
    {
        use std::io::Write;
        bash.stdin.take().expect("stdin").write_all(script.as_bytes()).unwrap();
        let output = bash.wait_with_output().unwrap();
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    }
}

#[test]
fn the_manual_pages_are_roff_for_the_program_and_each_command() {
    let (code, page, stderr) = microslip(&["man"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(page.contains(".TH microslip 1"), "{page}");
    assert!(
        page.contains(".SH SYNOPSIS") && page.contains(".SH SUBCOMMANDS"),
        "{page}"
    );
    assert!(page.contains(env!("CARGO_PKG_VERSION")), "{page}");
    for command in ["dissipation", "batch", "small-amplitude"] {
        let roff_name = command.replace('-', "\\-");
        assert!(
            page.contains(&format!("microslip\\-{roff_name}(1)")),
            "{command}: {page}"
        );
        let (code, page, stderr) = microslip(&["man", command]);
        assert_eq!(code, 0, "{command}: {stderr}");
        assert!(page.contains(&format!(".TH microslip-{command} 1")), "{page}");
        assert!(page.contains(env!("CARGO_PKG_VERSION")), "{page}");
    }
    let (_, page, _) = microslip(&["man", "dissipation"]);
    assert!(
        page.contains("\\-\\-friction") && page.contains("\\-\\-compliance"),
        "{page}"
    );
    assert_one_line_failure(
        microslip(&["man", "dissipasion"]),
        2,
        "no command 'dissipasion' to print a manual page for; the commands are dissipation,",
    );
}

#[test]
fn jobs_sets_the_worker_threads_and_refuses_what_is_not_a_thread_count() {
    let directory = Scratch::new("jobs");
    let input = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/batch-example.csv");
    let mut outputs = Vec::new();
    for jobs in [None, Some("1"), Some("3")] {
        let output = directory.join(format!("out-{}.csv", jobs.unwrap_or("default")));
        let output_text = output.display().to_string();
        let mut args = vec!["batch", "--input", input, "--output", &output_text];
        args.extend(jobs.iter().flat_map(|jobs| ["--jobs", *jobs]));
        let (code, _, stderr) = microslip(&args);
        assert_eq!(code, 0, "{jobs:?}: {stderr}");
        outputs.push(std::fs::read_to_string(output).unwrap());
    }
    assert!(outputs.iter().all(|output| *output == outputs[0]));
    let out = directory.join("figures").display().to_string();
    let (code, _, stderr) = microslip(&["figures", "--out", &out, "-j", "1"]);
    assert_eq!(code, 0, "{stderr}");
    for command in [
        &["batch", "--input", input, "--output", "-"][..],
        &["verify", "--quick"][..],
        &["figures", "--out", &out][..],
    ] {
        for jobs in ["0", "-2", "x", "1025"] {
            let mut args = command.to_vec();
            args.extend(["--jobs", jobs]);
            assert_one_line_failure(
                microslip(&args),
                2,
                &format!("--jobs must be a whole number of threads from 1 to 1024 (got '{jobs}')"),
            );
        }
    }
    for command in ["batch", "verify", "figures"] {
        let (_, help, _) = microslip(&[command, "--help"]);
        assert!(
            help.contains("-j, --jobs <JOBS>") && help.contains("RAYON_NUM_THREADS"),
            "{help}"
        );
    }
}

/// The files of `directory` (recursively) whose names end in one of `extensions`.
fn source_files(directory: &Path, extensions: &[&str], found: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(directory).unwrap().flatten() {
        let path = entry.path();
        if path.is_dir() {
            source_files(&path, extensions, found);
        } else if extensions.iter().any(|e| path.extension().is_some_and(|x| x == *e)) {
            found.push(path);
        }
    }
}

#[test]
fn comments_cite_no_tracker_numbers() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for directory in ["src", "tests", "benches"] {
        source_files(&root.join(directory), &["rs", "sh", "py"], &mut files);
    }
    assert!(files.len() > 20, "{files:?}");
    let word = ["iss", "ue"].concat();
    let mut citations = Vec::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        for (number, line) in text.lines().enumerate() {
            let lower = line.to_lowercase();
            let cites = lower.match_indices(&word).any(|(at, _)| {
                let rest = lower[at + word.len()..].trim_start_matches(['s', ' ', '#']);
                rest.starts_with(|c: char| c.is_ascii_digit())
            });
            if cites {
                citations.push(format!("{}:{}: {line}", file.display(), number + 1));
            }
        }
    }
    assert!(citations.is_empty(), "{}", citations.join("\n"));
}

/// `dissipation --json` with the acceptance case's flags replaced by `flags`.
fn dissipation_json(flags: &[&str]) -> serde_json::Value {
    let mut args = vec!["--json"];
    args.extend(flags);
    let (code, stdout, stderr) = on_case("dissipation", &args);
    assert_eq!(code, 0, "{stderr}");
    json(&stdout)
}

/// The case of the acceptance flags with `flags` replacing some, as decimal text.
fn case_text(flags: &[(&str, &str)]) -> microslip::case::CaseText {
    let value = |flag: &str| {
        flags
            .iter()
            .chain(CASE_FLAGS.iter())
            .find(|(f, _)| *f == flag)
            .map(|(_, v)| v.to_string())
    };
    microslip::case::CaseText {
        p0: value("--p0").unwrap(),
        p1: value("--p1").unwrap(),
        q0: value("--q0").unwrap_or_else(|| "0".into()),
        q1: value("--q1").unwrap(),
        phi: value("--phi").unwrap(),
        friction: value("--friction").unwrap(),
        lambda: value("--lambda"),
        nu: None,
        compliance: value("--compliance").unwrap(),
    }
}

/// Whether the JSON `enclosure` of `report` contains `reference` (a decimal string).
fn encloses(report: &serde_json::Value, reference: &str) -> bool {
    let end = |i: usize| {
        rug::Float::with_val(
            400,
            rug::Float::parse(report["enclosure"][i].as_str().unwrap()).unwrap(),
        )
    };
    let value = rug::Float::with_val(400, rug::Float::parse(reference).unwrap());
    end(0) <= value && value <= end(1)
}

#[test]
fn digits_asked_and_the_default_digits_are_proven_by_an_enclosure() {
    use microslip::answer::agreed::verified_dissipation;
    let budget = std::time::Duration::from_secs(120);
    for flags in [
        vec![],
        vec![("--compliance", "power:c=0.5,beta=-0.5"), ("--phi", "0.3pi")],
        vec![("--compliance", "hertz:r=2,estar=3"), ("--p1", "0.9"), ("--q1", "0.2")],
        vec![("--compliance", "poly:p0=1,coeffs=2;-0.5"), ("--q0", "0.1")],
    ] {
        let args: Vec<&str> = flags.iter().flat_map(|(f, v)| [*f, *v]).collect();
        let proven = dissipation_json(&[&args[..], &["--digits", "30"]].concat());
        assert_eq!(proven["provenance"], "certified", "{proven}");
        assert_eq!(proven["digits_certified"], 30, "{proven}");
        // An independent reference: 60 digits by agreement of two MPFR precisions.
        let reference = verified_dissipation(&case_text(&flags), 60, budget)
            .unwrap()
            .answer
            .value
            .decimal
            .to_string();
        assert!(encloses(&proven, &reference), "{proven} vs {reference}");
        let w = proven["W"].as_str().unwrap();
        let rounded = rug::Float::with_val(400, rug::Float::parse(&reference).unwrap()).to_string_radix(10, Some(30));
        assert_eq!(
            rug::Float::with_val(400, rug::Float::parse(w).unwrap()),
            rug::Float::with_val(400, rug::Float::parse(&rounded).unwrap()),
            "{w} vs {reference}"
        );
        let default = dissipation_json(&args);
        assert_eq!(default["provenance"], "certified", "{default}");
        assert!(default["digits_certified"].as_u64().unwrap() >= 12, "{default}");
        assert!(encloses(&default, &reference), "{default} vs {reference}");
    }
    let (_, stdout, _) = on_case("dissipation", &["--digits", "30"]);
    assert!(
        stdout
            .lines()
            .next()
            .unwrap()
            .contains("30 significant digits, proven (rigorous enclosure at "),
        "{stdout}"
    );
    let (_, stdout, _) = on_case("dissipation", &[]);
    assert!(
        stdout
            .lines()
            .next()
            .unwrap()
            .contains("13 significant digits, proven (rigorous enclosure in f64 interval arithmetic)"),
        "{stdout}"
    );
    assert!(!stdout.contains("not proven"), "{stdout}");
}

#[test]
fn a_phase_near_pi_gets_proven_relative_digits_without_digits_asked() {
    let near_pi = dissipation_json(&["--q1", "0.2", "--phi", "3.141592653589793"]);
    assert_eq!(near_pi["W"], "1.79304398627923e-33", "{near_pi}");
    assert_eq!(near_pi["provenance"], "certified", "{near_pi}");
}

#[test]
fn the_misrounded_f64_reproducers_print_only_digits_of_w() {
    use microslip::answer::agreed::verified_dissipation;
    for flags in common::MISROUNDED_F64_CASES {
        let args: Vec<&str> = flags.iter().flat_map(|(f, v)| [*f, *v]).collect();
        let printed = dissipation_json(&args);
        let digits = printed["digits"].as_u64().unwrap() as usize;
        let reference = verified_dissipation(&case_text(flags), 30, std::time::Duration::from_secs(120))
            .unwrap()
            .answer
            .value
            .decimal
            .to_string();
        let reference: f64 = reference.parse().unwrap();
        let w = printed["W"].as_str().unwrap();
        assert_eq!(w, format!("{:.*e}", digits - 1, reference), "{printed}");
    }
}

#[test]
fn an_exact_zero_is_one_answer_in_json_and_in_batch_rows() {
    let zero = dissipation_json(&["--compliance", "const:c=0.8", "--digits", "25"]);
    assert_eq!(zero["W"], "0");
    assert_eq!(zero["provenance"], "exact");
    assert_eq!(zero["method"], "exact");
    assert!(
        zero["precision_bits"].is_null() && zero["enclosure"].is_null(),
        "{zero}"
    );
    assert_eq!(zero["digits_certified"], 25);
    let directory = Scratch::new("exact-zero-batch");
    let input = directory.join("in.csv");
    std::fs::write(
        &input,
        "p0,p1,q1,phi,friction,lambda,compliance\n1,0.4,0.5,0.4pi,1,1,const:c=0.8\n",
    )
    .unwrap();
    let (code, stdout, stderr) = microslip(&[
        "batch",
        "--input",
        input.to_str().unwrap(),
        "--output",
        "-",
        "--format",
        "jsonl",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let row = json(&stdout);
    assert_eq!(
        (&row["W"], &row["method"], &row["provenance"], &row["exact"]),
        (&zero["W"], &zero["method"], &zero["provenance"], &zero["exact"])
    );
}
