//! `microslip batch`: rows in, results out in input order, every row as a single run
//! prints it; bad rows reported in their row, unreadable input refused.

use std::path::Path;
use std::process::Output;

mod common;

use common::{Draws, Scratch};

fn microslip(args: &[&str], stdin: Option<&str>) -> Output {
    common::run(args).stdin(stdin.unwrap_or("")).output()
}

/// `microslip batch` from the file `input` to the file `output`.
fn batch_files(input: &Path, output: &Path) -> common::Run {
    common::run(["batch", "--input", &path_text(input), "--output", &path_text(output)])
}

fn path_text(path: &Path) -> String {
    path.to_string_lossy().into_owned()
}

const HEADER: &str = "id,p0,p1,q0,q1,phi,friction,lambda,nu,compliance";

/// `rows` random cycles within the theory (most of them) over several compliances,
/// with the example table among them.
fn random_rows(seed: u64, rows: usize) -> Vec<[String; 10]> {
    let mut draws = Draws(seed);
    let table = format!("table:{}/tests/data/rough-surface.csv", env!("CARGO_MANIFEST_DIR"));
    let compliances = [
        "persson:gamma=1,sigma=1".to_string(),
        "power:c=0.5,beta=-0.5".to_string(),
        "hertz:r=2,estar=3".to_string(),
        "exp:a=1,c=0.5,d=0.2".to_string(),
        "rational:a=0.1,b=1,c=0.5".to_string(),
        table,
    ];
    (0..rows)
        .map(|i| {
            let p1 = 0.05 + 0.5 * draws.next();
            let q1 = (0.05 + 0.6 * draws.next()) * p1;
            let phase = draws.next();
            let compliance = compliances[i % compliances.len()].clone();
            let (lambda, nu) = if i % 3 == 0 {
                (String::new(), format!("{:.2}", 0.5 * draws.next()))
            } else {
                (format!("{:.3}", 1.0 + draws.next()), String::new())
            };
            [
                format!("row-{i}"),
                "1".to_string(),
                format!("{p1:.4}"),
                format!("{:.3}", 0.2 * (draws.next() - 0.5) * q1),
                format!("{q1:.4}"),
                format!("{phase:.3}pi"),
                format!("{:.2}", 0.3 + draws.next()),
                lambda,
                nu,
                compliance,
            ]
        })
        .collect()
}

fn to_csv(rows: &[[String; 10]]) -> String {
    let mut text = format!("{HEADER}\n");
    for row in rows {
        let cells: Vec<String> = row
            .iter()
            .map(|cell| {
                if cell.contains(',') {
                    format!("\"{cell}\"")
                } else {
                    cell.clone()
                }
            })
            .collect();
        text.push_str(&cells.join(","));
        text.push('\n');
    }
    text
}

/// The single run's JSON for one row.
fn single_run(row: &[String; 10], digits: Option<&str>) -> serde_json::Value {
    let names = ["p0", "p1", "q0", "q1", "phi", "friction", "lambda", "nu", "compliance"];
    let mut args: Vec<String> = vec!["dissipation".into(), "--json".into()];
    for (name, value) in names.iter().zip(&row[1..]) {
        if !value.is_empty() {
            args.push(format!("--{name}"));
            args.push(value.clone());
        }
    }
    if let Some(digits) = digits {
        args.extend(["--digits".to_string(), digits.to_string()]);
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let output = microslip(&args, None);
    if output.status.success() {
        serde_json::from_slice(&output.stdout).expect("json")
    } else {
        serde_json::json!({"error": String::from_utf8_lossy(&output.stderr).trim().to_string()})
    }
}

fn read_jsonl(bytes: &[u8]) -> Vec<serde_json::Value> {
    String::from_utf8_lossy(bytes)
        .lines()
        .map(|line| serde_json::from_str(line).expect("a JSON line"))
        .collect()
}

fn compare_with_single_runs(
    rows: &[[String; 10]],
    results: &[serde_json::Value],
    sample: &[usize],
    digits: Option<&str>,
) {
    for &i in sample {
        let single = single_run(&rows[i], digits);
        let batch = &results[i];
        assert_eq!(batch["inputs"]["id"], rows[i][0]);
        match single.get("error") {
            Some(error) => {
                let message = error.as_str().unwrap_or_default().trim_start_matches("microslip: ");
                let batch_error = batch["error"].as_str().expect("the batch row failed too");
                assert!(
                    batch_error.ends_with(message),
                    "row {i}: {batch_error} against {message}"
                );
            }
            None => {
                // Every result key of the row is the single run's, of the same value and type.
                assert!(batch["error"].is_null(), "row {i}: {}", batch["error"]);
                for (key, value) in batch.as_object().expect("a JSON object") {
                    if key != "inputs" && key != "error" {
                        assert_eq!(value, &single[key], "row {i}, {key}: {:?}", rows[i]);
                    }
                }
            }
        }
    }
}

#[test]
fn batch_output_equals_single_runs_row_by_row() {
    let rows = random_rows(14, 60);
    let output = microslip(
        &["batch", "--input", "-", "--output", "-", "--format", "jsonl"],
        Some(&to_csv(&rows)),
    );
    let code = output.status.code();
    assert!(
        code == Some(0) || code == Some(1),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let results = read_jsonl(&output.stdout);
    assert_eq!(results.len(), rows.len());
    for (row, result) in rows.iter().zip(&results) {
        assert_eq!(result["inputs"]["id"], row[0], "input order");
    }
    let succeeded = results.iter().filter(|r| r["error"].is_null()).count();
    assert!(succeeded >= 50, "{succeeded} of 60 rows succeeded");
    // A random sample of rows, each also run alone (the table rows included).
    let mut draws = Draws(2026);
    let mut sample: Vec<usize> = (0..16).map(|_| (draws.next() * rows.len() as f64) as usize).collect();
    sample.extend([5, 11]);
    compare_with_single_runs(&rows, &results, &sample, None);
}

#[test]
fn batch_with_verified_digits_equals_single_runs() {
    let rows: Vec<[String; 10]> = random_rows(7, 12)
        .into_iter()
        .filter(|row| !row[9].starts_with("table:"))
        .collect();
    let output = microslip(
        &[
            "batch", "--input", "-", "--output", "-", "--format", "jsonl", "--digits", "25",
        ],
        Some(&to_csv(&rows)),
    );
    let results = read_jsonl(&output.stdout);
    assert_eq!(results.len(), rows.len());
    let sample: Vec<usize> = (0..rows.len()).step_by(3).collect();
    compare_with_single_runs(&rows, &results, &sample, Some("25"));
    assert!(results
        .iter()
        .filter(|r| r["error"].is_null())
        .all(|r| r["digits"] == 25 && r["error_estimate"].is_null()));
}

#[test]
fn bad_rows_are_reported_in_their_row_and_the_others_computed() {
    let dir = Scratch::new("bad-rows");
    let table = format!("{}/tests/data/rough-surface.csv", env!("CARGO_MANIFEST_DIR"));
    let bad_table = dir.join("bad-table.csv");
    std::fs::write(&bad_table, "load,slope\n1,1\n2,0.5\n").expect("write");
    let input = format!(
        "{HEADER}\n\
         good-1,1,0.4,0,0.5,0.4pi,1,1,,\"persson:gamma=1,sigma=1\"\n\
         text,one,0.4,0,0.5,0.4pi,1,1,,\"persson:gamma=1,sigma=1\"\n\
         empty,1,,0,0.5,0.4pi,1,1,,\"persson:gamma=1,sigma=1\"\n\
         both,1,0.4,0,0.5,0.4pi,1,1,0.3,\"persson:gamma=1,sigma=1\"\n\
         unquoted,1,0.4,0,0.5,0.4pi,1,1,,persson:gamma=1,sigma=1\n\
         gross-slip,1,0.4,0,2,0.4pi,1,1,,\"persson:gamma=1,sigma=1\"\n\
         spec,1,0.4,0,0.5,0.4pi,1,1,,persson:gamma=1\n\
         range,1.5,0.7,0,0.3,0.4pi,1,1,,table:{table}\n\
         bad-table,1,0.4,0,0.5,0.4pi,1,1,,table:{}\n\
         good-2,1,0.4,0,0.5,0.2pi,1,1,,table:{table}\n",
        path_text(&bad_table)
    );
    let input_path = dir.join("input.csv");
    std::fs::write(&input_path, &input).expect("write");
    let output_path = dir.join("out.csv");
    let output = batch_files(&input_path, &output_path).output();
    let stderr = common::failed_with_one(&output);
    assert!(stderr.contains("8 failed"), "{stderr}");
    let mut reader = csv::Reader::from_path(&output_path).expect("output");
    let header = reader.headers().expect("header").clone();
    let column = |name: &str| header.iter().position(|h| h == name).expect(name);
    let records: Vec<csv::StringRecord> = reader.records().map(|r| r.expect("record")).collect();
    let ids: Vec<&str> = records.iter().map(|r| &r[column("id")]).collect();
    assert_eq!(
        ids,
        [
            "good-1",
            "text",
            "empty",
            "both",
            "unquoted",
            "gross-slip",
            "spec",
            "range",
            "bad-table",
            "good-2"
        ]
    );
    let error = |id: &str| records[ids.iter().position(|i| *i == id).expect(id)][column("error")].to_string();
    for (id, expected) in [
        ("text", "line 3: P0 (p0): 'one' is not a decimal number"),
        ("empty", "line 4: p1 is empty"),
        ("both", "line 5: give exactly one of lambda and nu"),
        ("unquoted", "line 6: the row has 11 fields, the header 10"),
        ("gross-slip", "line 7: gross slip"),
        ("spec", "line 8: compliance spec 'persson:gamma=1'"),
        ("range", "line 9: table"),
        ("bad-table", "line 10: table"),
    ] {
        assert!(error(id).starts_with(expected), "{id}: {}", error(id));
    }
    assert!(
        error("range").contains("covers loads [1e-1, 2e0]"),
        "{}",
        error("range")
    );
    assert!(error("bad-table").contains("has 2 data rows"), "{}", error("bad-table"));
    for id in ["good-1", "good-2"] {
        let record = &records[ids.iter().position(|i| *i == id).expect(id)];
        assert!(record[column("error")].is_empty(), "{id}");
        let w: f64 = record[column("W")].parse().expect("W");
        assert!(w > 0.1, "{id}: W = {w}");
    }
    let table_row = &records[9];
    assert!(!table_row[column("table_error")].is_empty());
}

#[test]
fn all_rows_computed_exits_0_and_replaces_the_output_whole() {
    let dir = Scratch::new("ok");
    let output_path = dir.join("result.jsonl");
    std::fs::write(&output_path, "old contents\n").expect("write");
    let example = format!("{}/tests/data/batch-example.csv", env!("CARGO_MANIFEST_DIR"));
    let good: String = std::fs::read_to_string(&example)
        .expect("example")
        .lines()
        .filter(|line| !line.starts_with("gross-slip"))
        .map(|line| format!("{line}\n"))
        .collect();
    let input_path = dir.join("good.csv");
    std::fs::write(&input_path, good).expect("write");
    let output = batch_files(&input_path, &output_path)
        .args(["--format", "jsonl"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output();
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let results = read_jsonl(&std::fs::read(&output_path).expect("output"));
    assert_eq!(results.len(), 7);
    assert!(results.iter().all(|r| r["error"].is_null() && r["W"].is_string()));
    // No temporary file left beside the output.
    let names: Vec<String> = std::fs::read_dir(&dir)
        .expect("dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
}

#[test]
fn an_unreadable_input_exits_2_and_writes_nothing() {
    let dir = Scratch::new("unreadable");
    let output_path = dir.join("out.csv");
    for (name, input) in [
        ("missing", None),
        (
            "no-columns",
            Some("id,p0,p1,q1,phi,friction,lambda\n1,1,0.4,0.5,0.4pi,1,1\n"),
        ),
        (
            "misspelled",
            Some("p0,p1,q1,phi,friction,lamda,compliance\n1,0.4,0.5,0.4pi,1,1,const:c=1\n"),
        ),
    ] {
        let input_path = dir.join(format!("{name}.csv"));
        if let Some(text) = input {
            std::fs::write(&input_path, text).expect("write");
        }
        let output = batch_files(&input_path, &output_path).output();
        assert_eq!(output.status.code(), Some(2), "{name}");
        assert!(output.stdout.is_empty(), "{name}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(stderr.trim_end().lines().count(), 1, "{name}: {stderr}");
        assert!(!output_path.exists(), "{name}: output written");
        match name {
            "missing" => assert!(stderr.contains("No such file"), "{stderr}"),
            "no-columns" => assert!(stderr.contains("no column compliance"), "{stderr}"),
            "digits" => assert!(
                stderr.contains("--digits must be between 1 and 1000, got 0"),
                "{stderr}"
            ),
            _ => assert!(stderr.contains("no column lambda (or nu)"), "{stderr}"),
        }
    }
}

#[test]
fn jsonl_gives_every_key_one_type_inputs_as_written_and_w_as_a_decimal_string() {
    let input = "id,p0,p1,q0,q1,phi,friction,lambda,nu,compliance\n\
                 007,1,0.4,-0.0500000000000000000001,0.5,0.4pi,1,,0.3,\"persson:gamma=1,sigma=1\"\n\
                 far,1e-400,0.4,0,0.5,1.2,1,1,,const:c=1\n\
                 tiny,1,0.4,0,0.5,0.4pi,1,1,,\"persson:gamma=1e-400,sigma=1\"\n";
    let typed = |digits: &[&str]| {
        let mut args = vec!["batch", "--input", "-", "--output", "-", "--format", "jsonl"];
        args.extend_from_slice(digits);
        read_jsonl(&microslip(&args, Some(input)).stdout)
    };
    let rows = typed(&[]);
    let first = &rows[0]["inputs"];
    // Every input cell is the text written, a decimal, a phase or an empty cell alike.
    assert_eq!(first["id"], "007");
    assert_eq!(first["p0"], "1");
    assert_eq!(first["p1"], "0.4");
    assert_eq!(first["q0"], "-0.0500000000000000000001");
    assert_eq!(first["phi"], "0.4pi");
    assert_eq!(first["lambda"], "");
    assert_eq!(first["nu"], "0.3");
    assert_eq!(first["compliance"], "persson:gamma=1,sigma=1");
    assert_eq!(rows[1]["inputs"]["p0"], "1e-400");
    assert_eq!(rows[1]["inputs"]["phi"], "1.2");
    // W is the single run's decimal string, with the binary64 computed beside it.
    let single = single_run(
        &[
            "007",
            "1",
            "0.4",
            "-0.0500000000000000000001",
            "0.5",
            "0.4pi",
            "1",
            "",
            "0.3",
            "persson:gamma=1,sigma=1",
        ]
        .map(String::from),
        None,
    );
    assert_eq!(rows[0]["W"], single["W"]);
    assert_eq!(rows[0]["W_f64"], single["W_f64"]);
    let printed: f64 = rows[0]["W"].as_str().unwrap().parse().unwrap();
    assert!((printed - rows[0]["W_f64"].as_f64().unwrap()).abs() <= 1e-12 * printed);
    assert!(rows[0]["error_estimate"].is_null() && rows[0]["table_error"].is_null());
    assert_eq!(rows[0]["provenance"], "certified", "{}", rows[0]);
    // A failed row (P0 < P1) has every result null, its inputs as written all the same.
    assert!(rows[1]["error"].is_string() && rows[1]["W"].is_null() && rows[1]["digits"].is_null());
    // A compliance f64 cannot hold: 15 digits by an enclosure, W text of the same kind, no W_f64
    // (the value lies below f64's range).
    assert_eq!(rows[2]["W"], "4.06247579245824e-401", "{}", rows[2]);
    assert!(rows[2]["W_f64"].is_null(), "{}", rows[2]);
    // Verified digits: text again, 25 of them, and the binary64 nearest their middle.
    let verified = typed(&["--digits", "25"]);
    let w = verified[0]["W"].as_str().expect("W is text");
    assert_eq!(w.split('e').next().unwrap().replace(['.', '-'], "").len(), 25, "{w}");
    assert!(w.starts_with(&single["W"].as_str().unwrap()[..8]), "{w}");
    assert!(verified[0]["W_f64"].is_number(), "{}", verified[0]);
}

/// W of a row's case at 400 bits by the library's quadrature to a 1e-100 tolerance: an
/// independent value for the enclosures of f64 and 30-digit rows.
fn reference_w(cells: &csv::StringRecord) -> rug::Float {
    use microslip::dissipation::{dissipation, Options};
    use microslip::real::Precision;
    let text = common::case()
        .p0(&cells[1])
        .p1(&cells[2])
        .q0(&cells[3])
        .q1(&cells[4])
        .phi(&cells[5])
        .friction(&cells[6])
        .lambda(&cells[7])
        .compliance(&cells[9])
        .text();
    let case = text.read::<rug::Float>(Precision::bits(400)).expect("the case reads");
    let tolerance = rug::Float::with_val(400, rug::Float::parse("1e-100").unwrap());
    let options = Options::default().with_tolerance(tolerance).with_max_points(4096);
    dissipation(&case.cycle, case.compliance.as_ref(), &options)
        .unwrap_or_else(|e| panic!("{text:?}: {e}"))
        .total
}

/// The CSV output appends `provenance`, `digits_certified`, `enclosure_lower` and
/// `enclosure_upper` after the columns it has always had, as JSON lines give them: every
/// point of the enclosure rounds to the W printed, and it holds an independent 400-bit W.
#[test]
fn csv_rows_carry_their_provenance_and_an_enclosure_that_rounds_to_w() {
    let table = format!("table:{}/tests/data/rough-surface.csv", env!("CARGO_MANIFEST_DIR"));
    let input = format!(
        "{HEADER}\n\
         persson,1,0.4,0,0.5,0.4pi,1,1,,\"persson:gamma=1,sigma=1\"\n\
         hertz,1,0.3,0.1,0.35,1.1,0.9,1.4,,\"hertz:r=2,estar=3\"\n\
         in-phase,2,0.5,0,0.9,0,0.8,1.2,,\"power:c=0.5,beta=-0.5\"\n\
         constant,1,0.4,0,0.5,0.4pi,1,1,,const:c=2\n\
         table,1,0.4,0,0.5,0.4pi,1,1,,{table}\n\
         gross,1,0.4,0,2,0.4pi,1,1,,\"persson:gamma=1,sigma=1\"\n"
    );
    for digits in [None, Some("30")] {
        let mut args = vec!["batch", "--input", "-", "--output", "-"];
        args.extend(digits.iter().flat_map(|d| ["--digits", d]));
        let csv_out = microslip(&args, Some(&input));
        args.extend(["--format", "jsonl"]);
        let lines = read_jsonl(&microslip(&args, Some(&input)).stdout);
        let mut reader = csv::Reader::from_reader(csv_out.stdout.as_slice());
        let header: Vec<String> = reader.headers().expect("header").iter().map(String::from).collect();
        assert_eq!(
            header.join(","),
            format!("{HEADER},W,digits,error_estimate,table_error,method,error,provenance,digits_certified,enclosure_lower,enclosure_upper")
        );
        let rows: Vec<csv::StringRecord> = reader.records().map(|r| r.expect("a row")).collect();
        assert_eq!(rows.len(), 6);
        for (row, line) in rows.iter().zip(&lines) {
            let cell = |name: &str| &row[header.iter().position(|h| h == name).unwrap()];
            let (id, w, provenance) = (cell("id"), cell("W"), cell("provenance"));
            let (lower, upper) = (cell("enclosure_lower"), cell("enclosure_upper"));
            let context = format!("{id} with --digits {digits:?}: {row:?}");
            // The CSV says what the JSON line says.
            assert_eq!(line["provenance"].as_str().unwrap_or(""), provenance, "{context}");
            assert_eq!(
                line["digits_certified"]
                    .as_u64()
                    .map(|d| d.to_string())
                    .unwrap_or_default(),
                cell("digits_certified"),
                "{context}"
            );
            let enclosure = line["enclosure"].as_array();
            let ends = enclosure.map(|e| (e[0].as_str().unwrap(), e[1].as_str().unwrap()));
            assert_eq!(ends.unwrap_or(("", "")), (lower, upper), "{context}");
            match (id, digits) {
                ("gross", _) => {
                    assert!(
                        !cell("error").is_empty() && w.is_empty() && provenance.is_empty(),
                        "{context}"
                    );
                    assert!(lower.is_empty() && cell("digits_certified").is_empty(), "{context}");
                    continue;
                }
                ("constant", _) => {
                    assert_eq!((provenance, lower, upper), ("exact", "", ""), "{context}");
                    assert_eq!(cell("digits_certified"), cell("digits"), "{context}");
                    continue;
                }
                ("table", None) => assert_eq!(provenance, "table_error", "{context}"),
                // Proven for the interpolant; the table's own error stays beside it.
                ("table", Some(_)) => {
                    assert_eq!((provenance, cell("digits_certified")), ("certified", "30"), "{context}");
                    assert!(!cell("table_error").is_empty(), "{context}");
                }
                // The default is proven too, to the 12 to 15 digits of its enclosure.
                (_, None) => {
                    let proven: u32 = cell("digits_certified").parse().unwrap_or(0);
                    assert!(provenance == "certified" && (12..=15).contains(&proven), "{context}");
                }
                (_, Some(_)) => {
                    assert_eq!((provenance, cell("digits_certified")), ("certified", "30"), "{context}");
                }
            }
            let printed_digits = w
                .split('e')
                .next()
                .unwrap()
                .chars()
                .filter(char::is_ascii_digit)
                .count();
            assert_eq!(cell("digits"), printed_digits.to_string(), "{context}");
            let (low, high) = (
                common::read_decimal(lower).unwrap(),
                common::read_decimal(upper).unwrap(),
            );
            common::every_point_rounds_to(w, &low, &high).unwrap_or_else(|e| panic!("{context}: {e}"));
            if id != "table" {
                let exact = reference_w(row);
                assert!(low <= exact && exact <= high, "{context}: {exact:.40}");
            }
        }
    }
}

/// Rows near in phase leave f64 for enclosures at a few hundred bits, whose node tables
/// are large enough to be computed on the worker pool. When the rows were dealt out by
/// the pool's own workers, each waiting for its row's thread, no worker was left for the
/// tables: with as many such rows as workers, every row ran out of its budget.
#[test]
fn rows_whose_node_tables_are_computed_on_the_pool_finish_within_their_budget() {
    let near_in_phase = [
        ("persson", "4.6953780618937086e-32", "persson:gamma=0.4542,sigma=1.728"),
        (
            "sum",
            "6.2548301364665267e-38",
            "power:c=1,beta=-0.5+persson:gamma=1,sigma=0.86",
        ),
        ("power", "1e-35", "power:c=1,beta=-1.5"),
        ("hertz", "3e-33", "hertz:r=1,estar=1"),
    ];
    let rows: Vec<[String; 10]> = near_in_phase
        .iter()
        .map(|(id, phi, spec)| [*id, "1", "0.4", "0", "0.1", phi, "1", "1.2", "", spec].map(String::from))
        .collect();
    let args: Vec<&str> = "batch --input - --output - --format jsonl --jobs 2 --max-seconds 30"
        .split(' ')
        .collect();
    let output = microslip(&args, Some(&to_csv(&rows)));
    let results = read_jsonl(&output.stdout);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    for result in &results {
        assert_eq!(result["provenance"], "certified", "{result}");
    }
    compare_with_single_runs(&rows, &results, &[0, 1, 2, 3], None);
}

#[test]
fn a_path_column_names_a_path_file_relative_to_the_csv_and_a_bad_file_fails_its_row_alone() {
    let dir = Scratch::new("path-column");
    let paths = dir.join("paths");
    std::fs::create_dir_all(&paths).unwrap();
    let force = "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0.05,0\n1,0.25,0.05,0.2,-0.3\n2,0.08,-0.04,0.1,0.06\n";
    let displacement = "k,P_cos,P_sin,u_cos,u_sin\n0,1.2,0,0.01,0\n1,0,0,0.2,-0.1\n2,0,0,0.04,0.05\n";
    std::fs::write(paths.join("force.csv"), force).unwrap();
    std::fs::write(paths.join("u.csv"), displacement).unwrap();
    std::fs::write(paths.join("bad.csv"), "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0,zero\n").unwrap();
    // Q constant under a varying P: W is exactly 0.
    std::fs::write(
        paths.join("still-q.csv"),
        "k,P_cos,P_sin,Q_cos,Q_sin\n0,1,0,0.1,0\n1,0.3,0.1,0,0\n",
    )
    .unwrap();
    let input = dir.join("in.csv");
    std::fs::write(
        &input,
        "id,p0,p1,q0,q1,phi,friction,lambda,nu,compliance,path,drive\n\
         cycle,1,0.4,0,0.5,0.4pi,1,1,,persson:gamma=1,sigma=1,,\n\
         force,,,,,,0.8,1.2,,persson:gamma=1,sigma=1,paths/force.csv,\n\
         missing,,,,,,0.8,1.2,,persson:gamma=1,sigma=1,paths/none.csv,\n\
         bad,,,,,,0.8,1.2,,persson:gamma=1,sigma=1,paths/bad.csv,force\n\
         both,1,0.4,,,,0.8,1.2,,persson:gamma=1,sigma=1,paths/force.csv,\n\
         displacement,,,,,,0.8,1.2,,persson:gamma=1,sigma=1,paths/u.csv,displacement\n\
         no-drive,,,,,,0.8,1.2,,persson:gamma=1,sigma=1,paths/u.csv,sideways\n\
         still-q,,,,,,0.8,1.2,,persson:gamma=1,sigma=1,paths/still-q.csv,\n"
            .replace("persson:gamma=1,sigma=1", "\"persson:gamma=1,sigma=1\""),
    )
    .unwrap();
    let output = dir.join("out.csv");
    let done = batch_files(&input, &output).output();
    assert_eq!(done.status.code(), Some(1), "{}", String::from_utf8_lossy(&done.stderr));
    let text = std::fs::read_to_string(&output).unwrap();
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let header: Vec<String> = reader.headers().unwrap().iter().map(str::to_string).collect();
    let column = |name: &str| header.iter().position(|h| h == name).unwrap();
    let rows: Vec<Vec<String>> = reader
        .records()
        .map(|r| r.unwrap().iter().map(str::to_string).collect())
        .collect();
    assert_eq!(rows.len(), 8);
    let (w, error, method, provenance) = (column("W"), column("error"), column("method"), column("provenance"));
    // The cycle's row is as it always was.
    assert_eq!(rows[0][method], "four-segment");
    // A path row's W is `microslip path`'s, proven where P varies too.
    let single = |file: &str, drive: &str| -> String {
        let out = common::run([
            "path",
            "--harmonics",
            &path_text(&paths.join(file)),
            "--drive",
            drive,
            "--friction",
            "0.8",
            "--lambda",
            "1.2",
            "--compliance",
            "persson:gamma=1,sigma=1",
            "--json",
        ])
        .output();
        let document: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        document["W"].as_str().unwrap().to_string()
    };
    assert_eq!(rows[1][w], single("force.csv", "force"));
    assert_eq!(
        (rows[1][method].as_str(), rows[1][provenance].as_str()),
        ("path-force", "certified")
    );
    assert_eq!(rows[5][w], single("u.csv", "displacement"));
    assert_eq!(rows[5][method], "path-displacement");
    for (row, expected) in [
        (2, "cannot read the path file"),
        (3, "line 2"),
        (4, "give either a path or the cycle's columns"),
        (6, "neither force nor displacement"),
    ] {
        assert!(rows[row][w].is_empty(), "{:?}", rows[row]);
        assert!(rows[row][error].contains(expected), "{:?}", rows[row]);
    }
    // As JSON lines, against the row schema.
    let schema_path = format!("{}/docs/schema/batch-row.schema.json", env!("CARGO_MANIFEST_DIR"));
    let schema: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(schema_path).unwrap()).unwrap();
    let validator = jsonschema::draft202012::new(&schema).unwrap();
    let jsonl = dir.join("out.jsonl");
    let done = common::run([
        "batch",
        "--input",
        &path_text(&input),
        "--output",
        &path_text(&jsonl),
        "--format",
        "jsonl",
    ])
    .output();
    assert_eq!(done.status.code(), Some(1));
    let lines: Vec<serde_json::Value> = std::fs::read_to_string(&jsonl)
        .unwrap()
        .lines()
        .map(|line| serde_json::from_str(line).unwrap())
        .collect();
    for line in &lines {
        let problems: Vec<String> = validator.iter_errors(line).map(|e| e.to_string()).collect();
        assert!(problems.is_empty(), "{problems:?}\n{line}");
    }
    assert_eq!(lines[1]["W"].as_str(), Some(rows[1][w].as_str()));
    assert_eq!(lines[5]["method"], "path-displacement");
    assert_eq!(lines[5]["provenance"], "certified");
    // An exact W: every digit asked, the reason, no working precision.
    assert_eq!(
        (
            lines[7]["W"].as_str(),
            lines[7]["provenance"].as_str(),
            lines[7]["digits"].as_u64()
        ),
        (Some("0"), Some("exact"), Some(15)),
        "{}",
        lines[7]
    );
    assert!(lines[7]["exact"]
        .as_str()
        .is_some_and(|why| why.contains("Q is constant")));
    assert_eq!(rows[7][provenance], "exact");
}

/// A file's chunks of 256 rows are computed while the next is read, each thread taking the
/// next row as it finishes one: rows of very unequal cost (every 25th near separation,
/// about twenty times an ordinary row) over three chunks still come out in input order,
/// the same bytes on one thread as on two.
#[test]
fn rows_of_unequal_cost_over_several_chunks_come_out_in_order_the_same_on_one_or_two_threads() {
    let dir = Scratch::new("unequal");
    let mut rows = random_rows(36, 600);
    for (i, row) in rows.iter_mut().enumerate().step_by(25) {
        let spec = ["power:c=1,beta=-4", "persson:gamma=1,sigma=1"][i % 2];
        *row = [&row[0], "1", "0.999999999", "0", "5e-10", "0.5pi", "1", "1", "", spec].map(String::from);
    }
    let input = dir.join("rows.csv");
    std::fs::write(&input, to_csv(&rows)).expect("input");
    let outputs: Vec<Vec<u8>> = ["1", "2"]
        .iter()
        .map(|jobs| {
            let output = dir.join(format!("jobs-{jobs}.csv"));
            let run = batch_files(&input, &output).args(["--jobs", jobs]).output();
            assert!(
                matches!(run.status.code(), Some(0 | 1)),
                "{}",
                String::from_utf8_lossy(&run.stderr)
            );
            std::fs::read(&output).expect("output")
        })
        .collect();
    assert!(outputs[0] == outputs[1], "the outputs of --jobs 1 and --jobs 2 differ");
    let mut reader = csv::Reader::from_reader(outputs[1].as_slice());
    let ids: Vec<String> = reader
        .records()
        .map(|record| record.expect("record")[0].to_string())
        .collect();
    let expected: Vec<&String> = rows.iter().map(|row| &row[0]).collect();
    assert_eq!(ids.iter().collect::<Vec<_>>(), expected);
    let slow = &outputs[1]
        .split(|&b| b == b'\n')
        .nth(1 + 25)
        .map(String::from_utf8_lossy);
    assert!(
        slow.as_ref()
            .is_some_and(|line| line.contains("0.999999999") && line.contains("certified")),
        "{slow:?}"
    );
}
