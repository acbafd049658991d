//! Output files that are never half-written: each is written to a temporary file in
//! its own directory and renamed over the target once complete, and a target can be
//! checked for writability before any work is spent on its contents.

use std::path::{Path, PathBuf};

/// Why an output file cannot be (or could not be) written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The name does not end in one of the extensions the content can be written as.
    #[error("{path}: the file name must end in {expected}")]
    Extension {
        /// The file asked for.
        path: String,
        /// The extensions admitted.
        expected: String,
    },
    /// The directory the file would go in does not exist or is not a directory.
    #[error("{path}: the directory {directory} does not exist")]
    NoDirectory {
        /// The file asked for.
        path: String,
        /// Its directory.
        directory: String,
    },
    /// No file can be created in the directory.
    #[error("{path}: cannot create a file in {directory}: {source}")]
    NotWritable {
        /// The file asked for.
        path: String,
        /// Its directory.
        directory: String,
        /// Why the trial file could not be created.
        #[source]
        source: std::io::Error,
    },
    /// The target exists and is a directory.
    #[error("{path}: is a directory")]
    IsDirectory {
        /// The file asked for.
        path: String,
    },
    /// Writing failed (permissions, a full disk, ...).
    #[error("{path}: {source}")]
    Io {
        /// The file being written.
        path: String,
        /// The system's error.
        #[source]
        source: std::io::Error,
    },
    /// The content could not be produced (e.g. the drawing library failed).
    #[error("{path}: {message}")]
    Content {
        /// The file being written.
        path: String,
        /// What went wrong.
        message: String,
    },
}

/// The CSV text of a header and rows, quoted where a cell needs it (by the csv crate).
pub fn csv_text<Row, Cell>(header: &[&str], rows: impl IntoIterator<Item = Row>) -> Result<String, csv::Error>
where
    Row: IntoIterator<Item = Cell>,
    Cell: AsRef<[u8]>,
{
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(header)?;
    for row in rows {
        writer.write_record(row)?;
    }
    let bytes = writer
        .into_inner()
        .map_err(|error| csv::Error::from(error.into_error()))?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

/// The directory a file goes in (`.` for a bare file name).
fn directory_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// A temporary name beside `path` with the same extension (some writers pick the
/// format by extension), unique to this process.
fn temporary_beside(path: &Path) -> PathBuf {
    static COUNTER: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let count = COUNTER.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let stem = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut name = format!(".{stem}.{}-{count}.tmp", std::process::id());
    if let Some(extension) = path.extension() {
        name.push('.');
        name.push_str(&extension.to_string_lossy());
    }
    directory_of(path).join(name)
}

/// Checks, before anything is computed, that `path` ends in one of `extensions` (any
/// when empty, compared without case), is not a directory, and that its directory
/// exists and accepts a new file (by creating and removing a temporary one).
pub fn check_writable(path: &Path, extensions: &[&str]) -> Result<(), OutputError> {
    let shown = path.display().to_string();
    if !extensions.is_empty() {
        let matches = path
            .extension()
            .is_some_and(|e| extensions.iter().any(|x| e.eq_ignore_ascii_case(x)));
        if !matches {
            let listed: Vec<String> = extensions.iter().map(|e| format!(".{e}")).collect();
            return Err(OutputError::Extension {
                path: shown,
                expected: listed.join(" or "),
            });
        }
    }
    if path.is_dir() {
        return Err(OutputError::IsDirectory { path: shown });
    }
    let directory = directory_of(path);
    if !directory.is_dir() {
        return Err(OutputError::NoDirectory {
            path: shown,
            directory: directory.display().to_string(),
        });
    }
    let probe = temporary_beside(path);
    std::fs::File::create(&probe).map_err(|source| OutputError::NotWritable {
        path: shown.clone(),
        directory: directory.display().to_string(),
        source,
    })?;
    std::fs::remove_file(&probe).map_err(|source| OutputError::Io { path: shown, source })
}

/// Writes `path` atomically: `write` fills a temporary file beside it (same directory,
/// same extension), which then replaces `path` in one rename. On any failure the
/// temporary file is removed and `path` is left as it was.
pub fn write_atomically<E: std::fmt::Display>(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), E>,
) -> Result<(), OutputError> {
    let shown = path.display().to_string();
    let temporary = temporary_beside(path);
    let outcome = write(&temporary)
        .map_err(|error| OutputError::Content {
            path: shown.clone(),
            message: error.to_string(),
        })
        .and_then(|()| {
            // The content must be on disk before the rename makes it visible.
            std::fs::File::open(&temporary)
                .and_then(|file| file.sync_all())
                .and_then(|()| std::fs::rename(&temporary, path))
                .map_err(|source| OutputError::Io {
                    path: shown.clone(),
                    source,
                })
        });
    if outcome.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    outcome
}

/// Writes `contents` to `path` atomically.
pub fn write_text_atomically(path: &Path, contents: &str) -> Result<(), OutputError> {
    write_atomically(path, |temporary| std::fs::write(temporary, contents))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let directory = std::env::temp_dir().join(format!("microslip-files-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&directory).unwrap();
        directory
    }

    #[test]
    fn a_failed_write_leaves_the_old_file_and_no_temporary() {
        let directory = scratch("failed");
        let target = directory.join("out.csv");
        std::fs::write(&target, "old").unwrap();
        let outcome = write_atomically(&target, |temporary| {
            std::fs::write(temporary, "half")?;
            Err(std::io::Error::other("the writer failed"))
        });
        assert!(matches!(outcome, Err(OutputError::Content { .. })), "{outcome:?}");
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "old");
        assert_eq!(std::fs::read_dir(&directory).unwrap().count(), 1);
        write_text_atomically(&target, "new").unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "new");
        assert_eq!(std::fs::read_dir(&directory).unwrap().count(), 1);
        std::fs::remove_dir_all(&directory).unwrap();
    }

    #[test]
    fn targets_are_checked_for_extension_directory_and_writability() {
        let directory = scratch("check");
        assert!(check_writable(&directory.join("a.svg"), &["svg", "png"]).is_ok());
        assert!(check_writable(&directory.join("a.PNG"), &["svg", "png"]).is_ok());
        let wrong = check_writable(&directory.join("a.pdf"), &["svg", "png"]).unwrap_err();
        assert!(wrong.to_string().ends_with("must end in .svg or .png"), "{wrong}");
        let missing = check_writable(&directory.join("nowhere/a.svg"), &["svg"]).unwrap_err();
        assert!(matches!(missing, OutputError::NoDirectory { .. }), "{missing}");
        assert!(matches!(
            check_writable(&directory, &[]),
            Err(OutputError::IsDirectory { .. })
        ));
        assert_eq!(std::fs::read_dir(&directory).unwrap().count(), 0);
        std::fs::remove_dir_all(&directory).unwrap();
    }

    #[test]
    fn csv_text_quotes_only_the_cells_that_need_it() {
        let rows = [["1.5e-3", "persson:gamma=1,sigma=1", ""], ["-2", "say \"hi\"", "x"]];
        let text = csv_text(&["a", "b", "c"], rows).unwrap();
        assert_eq!(
            text,
            "a,b,c\n1.5e-3,\"persson:gamma=1,sigma=1\",\n-2,\"say \"\"hi\"\"\",x\n"
        );
    }
}
