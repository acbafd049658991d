//! The library as a Rust user meets it: the README shows the crate's first example.

/// The README's "Library use" block is `examples/library_use.rs` verbatim (which the
/// crate documentation includes and runs as a doctest), so the README cannot drift.
#[test]
fn readme_library_example_is_the_crate_example() {
    let root = env!("CARGO_MANIFEST_DIR");
    let readme = std::fs::read_to_string(format!("{root}/README.md")).unwrap();
    let example = std::fs::read_to_string(format!("{root}/examples/library_use.rs")).unwrap();
    let section = readme.split("## Library use\n").nth(1).expect("a Library use section");
    let block = section
        .split("```rust\n")
        .nth(1)
        .and_then(|rest| rest.split("```\n").next());
    assert_eq!(block, Some(example.as_str()));
}
