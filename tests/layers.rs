//! The layers of `src/` as the README's Architecture section draws them: a number
//! followed from `--digits` down to the integrator never climbs back up. Each top-level
//! module has a layer; a file may name (`crate::module`) only modules of its own layer
//! or below. Comments and unit-test modules are not imports, and are left out.

use std::path::{Path, PathBuf};

/// The layers from the bottom: the number types and the quadrature engine; the physics;
/// the input read once and decided; the ladder; the answers; the tools.
const LAYERS: [&[&str]; 6] = [
    &[
        "real",
        "doubts",
        "quad",
        "arb",
        "ball",
        "ball_gauss",
        "interval",
        "decimal",
        "files",
        "messages",
    ],
    &[
        "cycle",
        "phase",
        "compliance",
        "dissipation",
        "exact",
        "simulate",
        "path",
        "aft",
    ],
    &["case", "boundaries", "admissibility"],
    &["digits"],
    &["answer"],
    &[
        "batch",
        "workers",
        "verify",
        "figures",
        "plot",
        "accuracy",
        "catalogue",
        "cli",
        "main",
        "lib",
    ],
];

fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|layer| layer.contains(&module))
}

fn rust_files(directory: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(directory).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|extension| extension == "rs") {
            out.push(path);
        }
    }
}

/// The text of a file without its comments and its unit-test module.
fn code_of(text: &str) -> String {
    let text = match text.find("#[cfg(test)]\nmod tests") {
        Some(at) => &text[..at],
        None => text,
    };
    text.lines()
        .map(|line| match line.find("//") {
            Some(at) => &line[..at],
            None => line,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The top-level modules a text names as `crate::module`.
fn named_modules(code: &str) -> Vec<String> {
    code.match_indices("crate::")
        .map(|(at, prefix)| {
            code[at + prefix.len()..]
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect()
        })
        .collect()
}

#[test]
fn no_file_imports_a_module_of_a_higher_layer() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    assert!(files.len() > 100, "{}", files.len());
    let mut upward = Vec::new();
    let mut unplaced = Vec::new();
    for file in &files {
        let relative = file.strip_prefix(root).unwrap().to_string_lossy().replace('\\', "/");
        let top = relative
            .trim_start_matches("src/")
            .split('/')
            .next()
            .unwrap()
            .trim_end_matches(".rs")
            .to_string();
        let Some(own) = layer_of(&top) else {
            unplaced.push(relative.clone());
            continue;
        };
        let code = code_of(&std::fs::read_to_string(file).unwrap());
        for module in named_modules(&code) {
            match layer_of(&module) {
                Some(layer) if layer > own => {
                    upward.push(format!("{relative} imports crate::{module}"));
                }
                Some(_) => {}
                None => unplaced.push(format!("crate::{module} (named in {relative})")),
            }
        }
    }
    unplaced.dedup();
    assert!(unplaced.is_empty(), "modules without a layer: {unplaced:?}");
    upward.sort();
    upward.dedup();
    assert!(upward.is_empty(), "imports that go up a layer:\n{}", upward.join("\n"));
}
