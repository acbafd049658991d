//! Every JSON output of the command line against its JSON Schema in docs/schema/: a
//! spread of cases per command (f64 by default, proven digits, exact zeros, tables,
//! a fallback from f64, agreement, a W beyond MPFR's exponents) and batch rows of every
//! kind, failed ones included. The schemas are strict (no key beyond those named, every
//! key required, one type per key), so an output that gains, loses or retypes a key
//! fails here until its schema says so.

mod common;

use common::{case_args, microslip, Scratch, PERSSON};
use serde_json::Value;

/// The schema of docs/schema/`name`.schema.json, checked against draft 2020-12's
/// meta-schema.
fn schema(name: &str) -> jsonschema::Validator {
    let path = format!("{}/docs/schema/{name}.schema.json", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let schema: Value = serde_json::from_str(&text).unwrap_or_else(|e| panic!("{path}: {e}"));
    if let Err(error) = jsonschema::meta::validate(&schema) {
        panic!("{path} is no valid JSON Schema: {error}");
    }
    jsonschema::draft202012::new(&schema).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The problems `validator` finds in `document` (empty where it conforms).
fn problems(validator: &jsonschema::Validator, document: &Value) -> Vec<String> {
    validator
        .iter_errors(document)
        .map(|error| format!("{} at {}", error, error.instance_path()))
        .collect()
}

/// Asserts that `document` conforms to `validator`.
fn assert_conforms(validator: &jsonschema::Validator, document: &Value, context: &str) {
    let found = problems(validator, document);
    assert!(found.is_empty(), "{context}: {found:#?}\n{document}");
}

/// `microslip args…`, which must succeed and print one JSON document, valid by the schema
/// of `name`.
fn conforming(name: &str, args: &[String]) -> Value {
    let (code, stdout, stderr) = microslip(args);
    assert_eq!(code, 0, "{args:?}: {stderr}");
    let document: Value = serde_json::from_str(stdout.trim()).unwrap_or_else(|e| panic!("{args:?}: {e}\n{stdout}"));
    assert_conforms(&schema(name), &document, &format!("{args:?}"));
    document
}

fn args(words: &[&str]) -> Vec<String> {
    words.iter().map(|word| word.to_string()).collect()
}

/// The acceptance case for `command` with `overrides`, and `--json` and `extra` after it.
fn case_json(command: &str, overrides: &[(&str, &str)], extra: &[&str]) -> Vec<String> {
    let mut args = case_args(command, overrides);
    args.push("--json".to_string());
    args.extend(extra.iter().map(|word| word.to_string()));
    args
}

fn data(file: &str) -> String {
    format!("{}/tests/data/{file}", env!("CARGO_MANIFEST_DIR"))
}

/// Flags and values that replace the acceptance case's or add to them.
type Overrides<'a> = &'a [(&'a str, &'a str)];

#[test]
fn dissipation_json_conforms_in_every_provenance() {
    let table = format!("table:{}", data("rough-surface.csv"));
    let cases: [(Overrides, &[&str], &str); 8] = [
        (&[], &[], "certified"),
        (&[], &["--digits", "20"], "certified"),
        (&[("--compliance", "const:c=0.8")], &["--digits", "25"], "exact"),
        (&[("--q1", "0")], &[], "exact"),
        // f64 cannot settle W this close to π: 15 digits by an enclosure, and why.
        (&[("--q1", "0.2"), ("--phi", "3.141592653589793")], &[], "certified"),
        (&[("--compliance", &table)], &[], "table_error"),
        (&[("--compliance", &table)], &["--digits", "12"], "certified"),
        // W = 1.1e-872038349839: an exponent beyond MPFR's, carried apart.
        (
            &[
                ("--p0", "1e13"),
                ("--p1", "5e12"),
                ("--q1", "5e11"),
                ("--compliance", "exp:a=2.204,c=2.486,d=0.3174"),
            ],
            &[],
            "certified",
        ),
    ];
    for (overrides, extra, provenance) in cases {
        let args = case_json("dissipation", overrides, extra);
        let report = conforming("dissipation", &args);
        assert_eq!(report["provenance"], provenance, "{args:?}: {report}");
    }
    // ν in place of λ: the inputs echo the one given.
    let mut with_nu = case_json("dissipation", &[("--nu", "0.3")], &[]);
    let at = with_nu.iter().position(|arg| arg == "--lambda").expect("--lambda");
    with_nu.drain(at..at + 2);
    let report = conforming("dissipation", &with_nu);
    assert_eq!(
        (&report["inputs"]["nu"], report["inputs"].get("lambda")),
        (&"0.3".into(), None)
    );
}

/// A table whose knot is the cycle's slip load at φ = π/2 only as a limit: no precision
/// decides which side of it the load lies, and two precisions agreeing give the digits.
#[test]
fn dissipation_json_conforms_where_digits_rest_on_agreement() {
    let dir = Scratch::new("agreement");
    let rows: String = (1..=16)
        .map(|k| 0.125 * f64::from(k))
        .map(|p| format!("{p:e},{:e}\n", 1.0 / p))
        .collect();
    let table = dir.join("persson.csv");
    std::fs::write(&table, format!("load,slope\n{rows}")).expect("table");
    let compliance = format!("table:{}", table.display());
    let args = case_json(
        "dissipation",
        &[("--q1", "0.3"), ("--phi", "0.5pi"), ("--compliance", &compliance)],
        &["--digits", "20"],
    );
    let report = conforming("dissipation", &args);
    assert_eq!(report["provenance"], "agreement", "{report}");
    assert!(report["no_enclosure"].is_string(), "{report}");
}

#[test]
fn small_amplitude_json_conforms() {
    for (rho, phi, digits, provenance) in [
        ("1.25", "0.4pi", None, "certified"),
        ("1.25", "0.4pi", Some("20"), "certified"),
        ("1", "pi", None, "exact"),
        ("1e103", "0.4pi", None, "certified"),
    ] {
        let mut words = vec!["small-amplitude", "--rho", rho, "--phi", phi, "--json"];
        words.extend(digits.iter().flat_map(|d| ["--digits", d]));
        let report = conforming("small-amplitude", &args(&words));
        assert_eq!(report["provenance"], provenance, "{report}");
    }
}

#[test]
fn series_json_conforms_for_coefficients_and_for_partial_sums() {
    for words in [
        &["series", "--rho", "0.5", "--phi", "0.3pi", "--order", "6", "--json"][..],
        &[
            "series", "--rho", "2", "--phi", "0.5pi", "--order", "4", "--digits", "35", "--json",
        ],
        &["series", "--rho", "1", "--phi", "pi", "--order", "2", "--json"],
    ] {
        let report = conforming("series", &args(words));
        assert!(report["values"][0]["exact"].is_string(), "I_0 is exactly 0: {report}");
    }
    for (overrides, extra) in [
        (&[("--p1", "0.2"), ("--q1", "0.15"), ("--order", "4")][..], &[][..]),
        (
            &[("--p1", "0.2"), ("--q1", "0.15"), ("--order", "3")],
            &["--digits", "20"],
        ),
        (&[("--compliance", "const:c=1"), ("--order", "3")], &[]),
        (
            &[("--compliance", "poly:p0=1,coeffs=2;-0.5;-0.1"), ("--order", "3")],
            &[],
        ),
    ] {
        let report = conforming("series", &case_json("series", overrides, extra));
        assert_eq!(
            report["partial_sums"].as_array().map(Vec::len),
            report["differences"].as_array().map(Vec::len)
        );
    }
}

#[test]
fn simulate_json_conforms_and_names_the_simulation_as_its_provenance() {
    let report = conforming(
        "simulate",
        &case_json(
            "simulate",
            &[],
            &["--elements", "100", "--steps", "200", "--tolerance", "1e-3"],
        ),
    );
    assert_eq!(report["provenance"], "simulated");
    // Its interval is W ± the estimated error, and each end rounds to the W printed.
    let w = report["W_f64"].as_f64().unwrap();
    let end = |i: usize| report["enclosure"][i].as_str().unwrap().parse::<f64>().unwrap();
    assert!(end(0) <= w && w <= end(1), "{report}");
    let digits = report["digits"].as_u64().unwrap() as usize;
    for i in [0, 1] {
        assert_eq!(
            format!("{:.*e}", digits - 1, end(i)),
            report["W"].as_str().unwrap(),
            "{report}"
        );
    }
}

#[test]
fn verify_json_conforms() {
    let report = conforming("verify", &args(&["verify", "--quick", "--json"]));
    assert_eq!(report["passed"], true);
}

#[test]
fn batch_rows_of_every_kind_conform_failed_rows_included() {
    let table = format!("table:{}", data("rough-surface.csv"));
    let input = format!(
        "id,p0,p1,q0,q1,phi,friction,lambda,nu,compliance,note\n\
         f64,1,0.4,0,0.5,0.4pi,1,1,,\"{PERSSON}\",a note\n\
         in-phase,2,0.5,0,0.9,0,0.8,1.2,,\"power:c=0.5,beta=-0.5\",\n\
         nu,1,0.4,0.1,0.3,0.3pi,0.5,,0.3,\"hertz:r=1,estar=1\",\n\
         zero,1,0.4,0,0.5,0.4pi,1,1,,const:c=0.8,\n\
         no-tangential,1,0.4,0,0,0.4pi,1,1,,\"{PERSSON}\",\n\
         table,1,0.4,0,0.5,0.4pi,1,1,,{table},\n\
         beyond-f64,1,0.4,0,0.5,1.2,1,1,,\"persson:gamma=1e-400,sigma=1\",\n\
         near-pi,1,0.4,0,0.2,3.141592653589793,1,1,,\"{PERSSON}\",\n\
         gross-slip,1,0.4,0,2,0.4pi,1,1,,\"{PERSSON}\",\n\
         bad-spec,1,0.4,0,0.5,0.4pi,1,1,,nonsense:c=1,\n\
         #7,,,,,,,,,,\n"
    );
    let validator = schema("batch-row");
    for digits in [None, Some("25")] {
        let mut words = vec!["batch", "--input", "-", "--output", "-", "--format", "jsonl"];
        words.extend(digits.iter().flat_map(|d| ["--digits", d]));
        let output = common::run(&words).stdin(&input).output();
        assert_eq!(
            output.status.code(),
            Some(1),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        let rows: Vec<Value> = String::from_utf8_lossy(&output.stdout)
            .lines()
            .map(|line| serde_json::from_str(line).expect("a JSON line"))
            .collect();
        assert_eq!(rows.len(), 11);
        for row in &rows {
            assert_conforms(&validator, row, &format!("--digits {digits:?}"));
        }
        let failed: Vec<&str> = rows
            .iter()
            .filter(|row| row["error"].is_string())
            .map(|row| row["inputs"]["id"].as_str().unwrap())
            .collect();
        assert_eq!(failed, ["gross-slip", "bad-spec", "#7"]);
        assert_eq!(rows[0]["inputs"]["note"], "a note");
    }
}

/// The schemas are strict: a key they do not name, a missing key, or a value of another
/// type is refused; and the pieces every report shares are the same in every schema.
#[test]
fn the_schemas_refuse_the_old_shapes_and_agree_on_the_shared_keys() {
    let report = conforming("dissipation", &case_json("dissipation", &[], &[]));
    let validator = schema("dissipation");
    let changed = |change: &dyn Fn(&mut serde_json::Map<String, Value>)| {
        let mut document = report.clone();
        change(document.as_object_mut().unwrap());
        problems(&validator, &document)
    };
    let w_f64 = report["W_f64"].clone();
    assert!(!changed(&|d| {
        d.insert("bound".into(), "estimate".into());
    })
    .is_empty());
    assert!(!changed(&|d| {
        d.remove("exact");
    })
    .is_empty());
    assert!(!changed(&|d| {
        d.insert("W".into(), w_f64.clone());
    })
    .is_empty());
    assert!(!changed(&|d| {
        d.insert("provenance".into(), "proven".into());
    })
    .is_empty());
    let definitions = |name: &str| -> Value {
        let path = format!("{}/docs/schema/{name}.schema.json", env!("CARGO_MANIFEST_DIR"));
        let schema: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        schema["$defs"].clone()
    };
    let shared = definitions("dissipation");
    for name in ["batch-row", "series", "simulate", "small-amplitude"] {
        let defs = definitions(name);
        for (key, definition) in shared.as_object().unwrap() {
            if let Some(other) = defs.get(key) {
                assert_eq!(other, definition, "$defs/{key} of {name} differs from dissipation's");
            }
        }
        for key in ["printed", "enclosure", "digits", "provenance", "exact", "f64"] {
            assert!(defs.get(key).is_some(), "{name} has no $defs/{key}");
        }
    }
}

/// A refused --json run prints nothing on standard output, so no half document either.
#[test]
fn a_refused_json_run_prints_no_json() {
    for args in [
        case_json("dissipation", &[("--phi", "0.4tau")], &[]),
        case_json("simulate", &[("--q1", "2")], &[]),
        case_json("series", &[("--order", "2"), ("--compliance", "nonsense:c=1")], &[]),
        args(&["small-amplitude", "--rho", "-1", "--phi", "0.4pi", "--json"]),
    ] {
        let (code, stdout, stderr) = microslip(&args);
        assert_eq!((code, stdout.as_str()), (2, ""), "{args:?}: {stderr}");
    }
}
