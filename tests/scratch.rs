//! The tests' scratch directory: fresh for each use, and gone with everything in it when the
//! test ends, also when it fails.

use std::path::{Path, PathBuf};

mod common;
use common::Scratch;

/// A directory holding a file and a subdirectory with a file of its own.
fn filled(scratch: &Path) {
    std::fs::write(scratch.join("out.csv"), "id,w\n").unwrap();
    std::fs::create_dir(scratch.join("nested")).unwrap();
    std::fs::write(scratch.join("nested").join("loop.csv"), "t,x\n").unwrap();
}

#[test]
fn each_scratch_directory_is_new_and_named_for_its_test() {
    let (first, second) = (Scratch::new("twice"), Scratch::new("twice"));
    assert_ne!(&*first, &*second);
    for scratch in [&first, &second] {
        assert!(scratch.is_dir(), "{}", scratch.display());
        assert_eq!(std::fs::read_dir(scratch).unwrap().count(), 0, "{}", scratch.display());
        let name = scratch.file_name().unwrap().to_string_lossy().into_owned();
        assert!(name.starts_with("microslip-scratch-twice-"), "{name}");
        assert_eq!(scratch.parent(), Some(std::env::temp_dir().as_path()));
    }
}

#[test]
fn a_scratch_directory_goes_with_everything_in_it() {
    let scratch = Scratch::new("dropped");
    filled(&scratch);
    let path = scratch.to_path_buf();
    drop(scratch);
    assert!(!path.exists(), "{} is left behind", path.display());
}

#[test]
fn a_scratch_directory_goes_when_its_test_panics() {
    let mut used = PathBuf::new();
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let scratch = Scratch::new("panicked");
        filled(&scratch);
        used = scratch.to_path_buf();
        panic!("a failing assertion");
    }));
    assert!(outcome.is_err());
    assert!(used.starts_with(std::env::temp_dir()), "{}", used.display());
    assert!(!used.exists(), "{} is left behind", used.display());
}
