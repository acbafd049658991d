//! A directory for one test's files that goes away with the test.

use std::path::Path;

/// A fresh directory of its own under the system's temporary directory, removed with everything
/// in it when dropped: at the end of the test and also when the test fails, since a panic
/// unwinds through it. Its name, `microslip-TEST-NAME-XXXXXX` (TEST the test file, NAME the
/// test's word for it), tells whose it is should one outlive its process (a killed run).
#[allow(dead_code)] // not every test binary writes files
pub struct Scratch(tempfile::TempDir);

#[allow(dead_code)] // not every test binary writes files
impl Scratch {
    /// A new, empty directory named after `name`; tests running at once never share one.
    pub fn new(name: &str) -> Self {
        let prefix = format!("microslip-{}-{name}-", env!("CARGO_CRATE_NAME").replace('_', "-"));
        let directory = tempfile::Builder::new()
            .prefix(&prefix)
            .tempdir()
            .unwrap_or_else(|error| panic!("cannot make a scratch directory {prefix}…: {error}"));
        Scratch(directory)
    }
}

impl std::ops::Deref for Scratch {
    type Target = Path;

    fn deref(&self) -> &Path {
        self.0.path()
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        self.0.path()
    }
}

impl AsRef<std::ffi::OsStr> for Scratch {
    fn as_ref(&self) -> &std::ffi::OsStr {
        self.0.path().as_os_str()
    }
}
