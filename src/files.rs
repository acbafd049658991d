//! Output files that are never half-written, and outputs that are not files at all.
//!
//! What a name refers to decides how it is written ([`destination`]): a regular file
//! (new, existing, or the target of a symbolic link) is written to a temporary file in
//! its own directory and renamed over the target once complete; a device, a FIFO, a
//! socket, a descriptor (`/dev/fd/N`) or standard output (`-`, `/dev/stdout`) is written
//! in place and never replaced. Every target can be checked before any work is spent on
//! its contents ([`check_writable`]).
//!
//! Every temporary file is listed while it exists, so that a process ended by a signal
//! removes them first ([`abandon_temporaries`]): no temporary file outlives the process.

use std::fs::{File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError};

/// The temporary files of this process that exist (or are about to).
static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// `work` with the list of temporary files held: the cleanup on a signal waits for it, so
/// a temporary file is never made unlisted, nor renamed over its target once removed.
fn with_temporaries<T>(work: impl FnOnce(&mut Vec<PathBuf>) -> T) -> T {
    let mut list = TEMPORARIES.lock().unwrap_or_else(PoisonError::into_inner);
    work(&mut list)
}

/// Removes every temporary file of the process and keeps the list held for good, so that
/// none is made or renamed afterwards: for a process about to end on a signal (its
/// outputs are then left as they were, never half-written).
pub fn abandon_temporaries() {
    let mut list = TEMPORARIES.lock().unwrap_or_else(PoisonError::into_inner);
    for temporary in list.drain(..) {
        let _ = std::fs::remove_file(temporary);
    }
    std::mem::forget(list);
}

/// The longest record (a line of a CSV input: a batch row, its header, a comment, a row
/// of a table) read, in bytes: a row of numbers and a SPEC is well under a kilobyte.
pub const MAX_RECORD_BYTES: u64 = 1 << 20;

/// Why an output file cannot be (or could not be) written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The name is empty.
    #[error("the output name is empty: give a file name, or - for standard output")]
    EmptyName,
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
    /// Symbolic links that do not end (a loop, or a chain longer than the system allows).
    #[error("{path}: too many levels of symbolic links")]
    LinkLoop {
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

/// Where the bytes of an output go.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Destination {
    /// A regular file, new or existing, after following symbolic links: replaced whole
    /// by a rename, so that a reader never sees it half-written.
    File(PathBuf),
    /// A device, a FIFO, a socket or a descriptor: written in place, never replaced.
    InPlace(PathBuf),
    /// Standard output: `-`, `/dev/stdout`, `/dev/fd/1`, `/proc/self/fd/1`.
    StandardOutput,
}

/// Symbolic links followed before a name is refused as a loop (Linux's own limit).
const MAX_LINKS: usize = 40;

/// A name of an open descriptor (`/dev/fd/N`, `/proc/PID/fd/N`): its link target is a
/// description (`pipe:[…]`), not a path, so it is written through the name itself.
fn descriptor_number(path: &Path) -> Option<&str> {
    let text = path.to_str()?;
    let rest = text.strip_prefix("/dev/fd/").or_else(|| {
        text.strip_prefix("/proc/")
            .and_then(|r| r.split_once("/fd/").map(|(_, n)| n))
    })?;
    rest.bytes().all(|b| b.is_ascii_digit()).then_some(rest)
}

/// What `path` refers to, following symbolic links: see [`Destination`].
pub fn destination(path: &Path) -> Result<Destination, OutputError> {
    let shown = || path.display().to_string();
    if path.as_os_str().is_empty() {
        return Err(OutputError::EmptyName);
    }
    if path == Path::new("-") || path == Path::new("/dev/stdout") {
        return Ok(Destination::StandardOutput);
    }
    let mut current = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        if let Some(number) = descriptor_number(&current) {
            let own = current.starts_with("/dev/fd") || current.starts_with("/proc/self") || {
                current.starts_with(format!("/proc/{}", std::process::id()))
            };
            return Ok(if own && number == "1" {
                Destination::StandardOutput
            } else {
                Destination::InPlace(current)
            });
        }
        match std::fs::symlink_metadata(&current) {
            Err(error) if error.kind() == std::io::ErrorKind::NotFound => return Ok(Destination::File(current)),
            Err(source) => return Err(OutputError::Io { path: shown(), source }),
            Ok(metadata) if metadata.file_type().is_symlink() => {
                let target =
                    std::fs::read_link(&current).map_err(|source| OutputError::Io { path: shown(), source })?;
                current = directory_of(&current).join(target);
            }
            Ok(metadata) if metadata.is_dir() => return Err(OutputError::IsDirectory { path: shown() }),
            Ok(metadata) if metadata.is_file() => return Ok(Destination::File(current)),
            Ok(_) => return Ok(Destination::InPlace(current)),
        }
    }
    Err(OutputError::LinkLoop { path: shown() })
}

/// The directory a file goes in (`.` for a bare file name).
fn directory_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// A temporary name in `directory`, after `name` and with `name`'s extension (some
/// writers pick the format by extension), unique to this process.
fn temporary_in(directory: &Path, name: &Path) -> PathBuf {
    static COUNTER: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let count = COUNTER.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let stem = name
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let mut temporary = format!(".{stem}.{}-{count}.tmp", std::process::id());
    if let Some(extension) = name.extension() {
        temporary.push('.');
        temporary.push_str(&extension.to_string_lossy());
    }
    directory.join(temporary)
}

/// Where the content for `path` is written first: beside its target file, or for an
/// output written in place, in the system's temporary directory.
fn temporary_for(path: &Path, destination: &Destination) -> PathBuf {
    match destination {
        Destination::File(target) => temporary_in(&directory_of(target), path),
        _ => temporary_in(&std::env::temp_dir(), path),
    }
}

/// Checks, before anything is computed, that `path` ends in one of `extensions` (any
/// when empty, compared without case; standard output, `-`, is taken for a content of a
/// single extension) and can be written: a file's directory exists and
/// accepts a new file (by creating and removing a temporary one), a device opens for
/// writing (a FIFO is not opened: that would wait for its reader).
pub fn check_writable(path: &Path, extensions: &[&str]) -> Result<(), OutputError> {
    let shown = path.display().to_string();
    // Standard output has no name to tell the format by: it takes a content of one format.
    let single_format_to_standard_output =
        extensions.len() == 1 && matches!(destination(path), Ok(Destination::StandardOutput));
    if !extensions.is_empty() && !single_format_to_standard_output {
        let matches = path
            .extension()
            .is_some_and(|e| extensions.iter().any(|x| e.eq_ignore_ascii_case(x)));
        if !matches {
            let listed: Vec<String> = extensions.iter().map(|e| format!(".{e}")).collect();
            if matches!(destination(path), Ok(Destination::StandardOutput)) {
                return Err(OutputError::Content {
                    path: shown,
                    message: format!(
                        "standard output has no name to choose the format by: write to a file ending in {}",
                        listed.join(" or ")
                    ),
                });
            }
            return Err(OutputError::Extension {
                path: shown,
                expected: listed.join(" or "),
            });
        }
    }
    let destination = destination(path)?;
    let io = |source| OutputError::Io {
        path: path.display().to_string(),
        source,
    };
    match &destination {
        Destination::StandardOutput => Ok(()),
        Destination::InPlace(target) => {
            use std::os::unix::fs::FileTypeExt;
            if std::fs::metadata(target).map_err(io)?.file_type().is_fifo() {
                return Ok(());
            }
            open_in_place(target).map(drop).map_err(io)
        }
        Destination::File(target) => {
            let directory = directory_of(target);
            if !directory.is_dir() {
                return Err(OutputError::NoDirectory {
                    path: shown,
                    directory: directory.display().to_string(),
                });
            }
            let probe = temporary_for(path, &destination);
            with_temporaries(|_| {
                File::create(&probe).map_err(|source| OutputError::NotWritable {
                    path: shown,
                    directory: directory.display().to_string(),
                    source,
                })?;
                std::fs::remove_file(&probe).map_err(io)
            })
        }
    }
}

/// Opens an output written in place: never created, truncated or replaced.
fn open_in_place(target: &Path) -> std::io::Result<File> {
    OpenOptions::new().append(true).open(target)
}

/// Copies a finished temporary file to an output written in place. A reader of
/// standard output that has gone is not an error of ours.
fn copy_in_place(temporary: &Path, destination: &Destination) -> std::io::Result<()> {
    let mut content = File::open(temporary)?;
    let copied = match destination {
        Destination::InPlace(target) => {
            let mut sink = open_in_place(target)?;
            std::io::copy(&mut content, &mut sink).and_then(|_| sink.flush())
        }
        _ => {
            let mut sink = std::io::stdout().lock();
            std::io::copy(&mut content, &mut sink).and_then(|_| sink.flush())
        }
    };
    match copied {
        Err(error) if error.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => other,
    }
}

/// Makes a complete temporary file the target: on disk first, then renamed over it.
fn replace(temporary: &Path, target: &Path) -> std::io::Result<()> {
    File::open(temporary)
        .and_then(|file| file.sync_all())
        .and_then(|()| std::fs::rename(temporary, target))
}

/// Writes `path` whole or not at all: `write` fills a temporary file (same extension),
/// which then replaces a regular file in one rename, or is copied to a device, FIFO or
/// standard output. On any failure the temporary file is removed and a regular file is
/// left as it was.
pub fn write_atomically<E: std::fmt::Display>(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), E>,
) -> Result<(), OutputError> {
    let shown = path.display().to_string();
    let destination = destination(path)?;
    let temporary = temporary_for(path, &destination);
    with_temporaries(|list| list.push(temporary.clone()));
    let outcome = write(&temporary)
        .map_err(|error| OutputError::Content {
            path: shown.clone(),
            message: error.to_string(),
        })
        .and_then(|()| {
            match &destination {
                Destination::File(target) => with_temporaries(|_| replace(&temporary, target)),
                _ => copy_in_place(&temporary, &destination),
            }
            .map_err(|source| OutputError::Io {
                path: shown.clone(),
                source,
            })
        });
    with_temporaries(|list| {
        if outcome.is_err() || !matches!(destination, Destination::File(_)) {
            let _ = std::fs::remove_file(&temporary);
        }
        list.retain(|listed| *listed != temporary);
    });
    outcome
}

/// Writes `contents` to `path` whole or not at all ([`write_atomically`]).
pub fn write_text_atomically(path: &Path, contents: &str) -> Result<(), OutputError> {
    write_atomically(path, |temporary| std::fs::write(temporary, contents))
}

/// An output written as its content is produced: a regular file through a temporary
/// file that [`StreamedOutput::finish`] renames over it (dropped unfinished, the
/// temporary file is removed and the file left as it was); a device, FIFO or standard
/// output directly, in place.
pub struct StreamedOutput {
    sink: std::io::BufWriter<Box<dyn Write + Send>>,
    /// The temporary file and the file it will replace, for a regular file.
    replacing: Option<(PathBuf, PathBuf)>,
    shown: String,
}

impl StreamedOutput {
    /// Opens `path` for writing (see [`destination`]).
    pub fn create(path: &Path) -> Result<Self, OutputError> {
        let shown = path.display().to_string();
        let destination = destination(path)?;
        let io = |source| OutputError::Io {
            path: shown.clone(),
            source,
        };
        let (sink, replacing): (Box<dyn Write + Send>, _) = match &destination {
            Destination::StandardOutput => (Box::new(std::io::stdout()), None),
            Destination::InPlace(target) => (Box::new(open_in_place(target).map_err(io)?), None),
            Destination::File(target) => {
                let temporary = temporary_for(path, &destination);
                let file = with_temporaries(|list| {
                    let file = File::create(&temporary)?;
                    list.push(temporary.clone());
                    Ok(file)
                })
                .map_err(io)?;
                (Box::new(file), Some((temporary, target.clone())))
            }
        };
        Ok(StreamedOutput {
            sink: std::io::BufWriter::new(sink),
            replacing,
            shown,
        })
    }

    /// Completes the output: flushed, and a regular file replaced by what was written.
    pub fn finish(mut self) -> Result<(), OutputError> {
        let shown = self.shown.clone();
        let io = |source| OutputError::Io {
            path: shown.clone(),
            source,
        };
        self.sink.flush().map_err(io)?;
        if let Some((temporary, target)) = self.replacing.take() {
            let replaced = with_temporaries(|list| {
                let replaced = replace(&temporary, &target);
                if replaced.is_err() {
                    let _ = std::fs::remove_file(&temporary);
                }
                list.retain(|listed| *listed != temporary);
                replaced
            });
            replaced.map_err(io)?;
        }
        Ok(())
    }
}

impl Write for StreamedOutput {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        self.sink.write(bytes)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.sink.flush()
    }
}

impl Drop for StreamedOutput {
    fn drop(&mut self) {
        if let Some((temporary, _)) = &self.replacing {
            with_temporaries(|list| {
                let _ = std::fs::remove_file(temporary);
                list.retain(|listed| listed != temporary);
            });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::os::unix::fs::FileTypeExt;

    /// A fresh directory, removed with everything in it when the test ends (also on a
    /// failure).
    fn scratch(name: &str) -> tempfile::TempDir {
        tempfile::Builder::new()
            .prefix(&format!("microslip-files-{name}-"))
            .tempdir()
            .unwrap()
    }

    #[test]
    fn a_failed_write_leaves_the_old_file_and_no_temporary() {
        let scratch = scratch("failed");
        let directory = scratch.path();
        let target = directory.join("out.csv");
        std::fs::write(&target, "old").unwrap();
        let outcome = write_atomically(&target, |temporary| {
            std::fs::write(temporary, "half")?;
            Err(std::io::Error::other("the writer failed"))
        });
        assert!(matches!(outcome, Err(OutputError::Content { .. })), "{outcome:?}");
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "old");
        assert_eq!(std::fs::read_dir(directory).unwrap().count(), 1);
        write_text_atomically(&target, "new").unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "new");
        assert_eq!(std::fs::read_dir(directory).unwrap().count(), 1);
    }

    #[test]
    fn targets_are_checked_for_extension_directory_and_writability() {
        let scratch = scratch("check");
        let directory = scratch.path();
        assert!(check_writable(&directory.join("a.svg"), &["svg", "png"]).is_ok());
        assert!(check_writable(&directory.join("a.PNG"), &["svg", "png"]).is_ok());
        let wrong = check_writable(&directory.join("a.pdf"), &["svg", "png"]).unwrap_err();
        assert!(wrong.to_string().ends_with("must end in .svg or .png"), "{wrong}");
        let missing = check_writable(&directory.join("nowhere/a.svg"), &["svg"]).unwrap_err();
        assert!(matches!(missing, OutputError::NoDirectory { .. }), "{missing}");
        assert!(matches!(
            check_writable(directory, &[]),
            Err(OutputError::IsDirectory { .. })
        ));
        assert_eq!(std::fs::read_dir(directory).unwrap().count(), 0);
    }

    #[test]
    fn a_link_is_followed_and_its_target_replaced_and_devices_are_written_in_place() {
        let scratch = scratch("links");
        let directory = scratch.path();
        let target = directory.join("target.csv");
        let link = directory.join("link.csv");
        std::fs::write(&target, "old").unwrap();
        std::os::unix::fs::symlink("target.csv", &link).unwrap();
        assert_eq!(
            destination(&link).unwrap(),
            Destination::File(directory.join("target.csv"))
        );
        check_writable(&link, &["csv"]).unwrap();
        write_text_atomically(&link, "new").unwrap();
        assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "new");
        // A dangling link is followed too: its target is created.
        std::fs::remove_file(&target).unwrap();
        let mut streamed = StreamedOutput::create(&link).unwrap();
        streamed.write_all(b"streamed").unwrap();
        streamed.finish().unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "streamed");
        assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        let null = Path::new("/dev/null");
        assert_eq!(destination(null).unwrap(), Destination::InPlace(null.to_path_buf()));
        write_text_atomically(null, "nothing").unwrap();
        assert!(std::fs::metadata(null).unwrap().file_type().is_char_device());
        for stdout in ["-", "/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"] {
            assert_eq!(destination(Path::new(stdout)).unwrap(), Destination::StandardOutput);
        }
        let looped = directory.join("loop");
        std::os::unix::fs::symlink("loop", &looped).unwrap();
        assert!(matches!(destination(&looped), Err(OutputError::LinkLoop { .. })));
        assert!(matches!(destination(Path::new("")), Err(OutputError::EmptyName)));
        assert!(matches!(
            check_writable(Path::new(""), &[]),
            Err(OutputError::EmptyName)
        ));
    }

    #[test]
    fn an_unfinished_stream_leaves_the_old_file_and_no_temporary() {
        let scratch = scratch("unfinished");
        let directory = scratch.path();
        let target = directory.join("out.csv");
        std::fs::write(&target, "old").unwrap();
        let mut streamed = StreamedOutput::create(&target).unwrap();
        streamed.write_all(b"half").unwrap();
        drop(streamed);
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "old");
        assert_eq!(std::fs::read_dir(directory).unwrap().count(), 1);
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
