//! Reading a batch CSV as a stream: comment lines before the header, the header checked
//! (required columns, no name twice), then one row per record, each read as it is
//! needed, so that an endless input costs no more memory than its longest record.

use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use super::BatchError;
use crate::case::CaseText;
use crate::compliance::column_name;
use crate::messages::printable;
use crate::path::Drive;

pub use crate::files::MAX_RECORD_BYTES;

/// One input row: its line in the file, its cells, and the case (or why there is none).
#[derive(Clone, Debug)]
pub struct InputRow {
    /// Line of the input file where the row starts (the header's line is before it).
    pub line: u64,
    /// The cells, one per header column (missing ones empty).
    pub cells: Vec<String>,
    /// The case, or what is wrong with the row (for a row that names a path, why it has
    /// no case).
    pub case: Result<CaseText, String>,
    /// For a row whose `path` cell names a path file: the path request, or what is wrong
    /// with the row.
    pub path: Option<Result<PathRow, String>>,
}

/// A row that names a path file in place of p0, p1, q0, q1, phi.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PathRow {
    /// The path file, relative to the batch input's directory when it was read from a file.
    pub file: PathBuf,
    /// What the file prescribes besides P (`drive`: force by default, or displacement).
    pub drive: Drive,
    /// f.
    pub friction: String,
    /// λ, where given.
    pub lambda: Option<String>,
    /// ν, where given.
    pub nu: Option<String>,
    /// The compliance spec.
    pub compliance: String,
}

/// The bytes of the input as they are read, refusing what cannot be a batch CSV before
/// it costs memory: a NUL byte (binary data, `/dev/zero`), or a record that runs past
/// [`MAX_RECORD_BYTES`] (a line without end, an unclosed quote).
struct Guarded<R> {
    inner: R,
    /// Bytes read so far.
    read: u64,
    /// Lines ended so far.
    lines: u64,
    /// Where the record being read starts, as its reader last said.
    record_start: Arc<AtomicU64>,
}

impl<R: Read> Read for Guarded<R> {
    fn read(&mut self, buffer: &mut [u8]) -> std::io::Result<usize> {
        let count = self.inner.read(buffer)?;
        let refuse = |message: String| Err(std::io::Error::new(std::io::ErrorKind::InvalidData, message));
        for &byte in &buffer[..count] {
            self.read += 1;
            match byte {
                0 => {
                    return refuse(format!(
                        "line {} holds a NUL byte: this is not CSV text (a batch input is a CSV file of cases)",
                        self.lines + 1
                    ))
                }
                b'\n' => self.lines += 1,
                _ => {}
            }
        }
        let start = self.record_start.load(Ordering::Relaxed);
        // The CSV reader reads ahead by at most its buffer, which is far below the limit.
        if self.read.saturating_sub(start) > MAX_RECORD_BYTES + (64 << 10) {
            return refuse(format!(
                "a record near line {} runs past {} MiB (a line without end, or an unclosed quote): this is not a batch CSV, whose rows are at most {} MiB",
                self.lines + 1,
                MAX_RECORD_BYTES >> 20,
                MAX_RECORD_BYTES >> 20
            ));
        }
        Ok(count)
    }
}

/// Indices of the columns of a case, in [`CaseText`]'s order.
const CASE_COLUMNS: [&str; 9] = ["p0", "p1", "q0", "q1", "phi", "friction", "lambda", "nu", "compliance"];

/// The CSV records after the comments: the header line handed back in front of the rest.
type Records<R> = csv::Reader<std::io::Chain<std::io::Cursor<Vec<u8>>, BufReader<Guarded<R>>>>;

/// A batch input: its header, then its rows as they are read (an [`Iterator`]).
pub struct BatchInput<R> {
    /// Column names as given (trimmed).
    pub header: Vec<String>,
    columns: [Option<usize>; 9],
    reader: Records<R>,
    record_start: Arc<AtomicU64>,
    /// Bytes before the header line.
    bytes_before_header: u64,
    /// Comment lines before the header.
    comment_lines: u64,
    /// The `path` and `drive` columns, where given.
    path_columns: (Option<usize>, Option<usize>),
    /// The directory a relative path file is taken from.
    directory: Option<PathBuf>,
}

/// Reads the comment lines and the header of a batch CSV and checks the header: every
/// required column present, no column named twice. Only whole lines that begin with `#`
/// before the header are comments; after it every record is a row.
pub fn read_input<R: Read>(source: R) -> Result<BatchInput<R>, BatchError> {
    let record_start = Arc::new(AtomicU64::new(0));
    let mut buffered = BufReader::new(Guarded {
        inner: source,
        read: 0,
        lines: 0,
        record_start: Arc::clone(&record_start),
    });
    let input_error = |e: &dyn std::fmt::Display| BatchError::Input(e.to_string());
    let mut comment_lines = 0u64;
    let mut bytes_before_header = 0u64;
    let header_line = loop {
        let mut line = Vec::new();
        let count = buffered.read_until(b'\n', &mut line).map_err(|e| input_error(&e))? as u64;
        if count > MAX_RECORD_BYTES {
            return Err(BatchError::Input(too_long(comment_lines + 1)));
        }
        if count == 0 || !line.starts_with(b"#") {
            break line;
        }
        comment_lines += 1;
        bytes_before_header += count;
        record_start.store(bytes_before_header, Ordering::Relaxed);
    };
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .flexible(true)
        .from_reader(std::io::Cursor::new(header_line).chain(buffered));
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| input_error(&e))?
        .iter()
        .map(str::to_string)
        .collect();
    check_header(&header)?;
    record_start.store(bytes_before_header + reader.position().byte(), Ordering::Relaxed);
    let find = |name: &str| header.iter().position(|h| column_name(h) == name);
    let columns = CASE_COLUMNS.map(find);
    let path_columns = (find("path"), find("drive"));
    Ok(BatchInput {
        header,
        columns,
        reader,
        record_start,
        bytes_before_header,
        comment_lines,
        path_columns,
        directory: None,
    })
}

/// Why a record longer than [`MAX_RECORD_BYTES`] is refused.
fn too_long(line: u64) -> String {
    format!(
        "line {line} is longer than {} MiB: this is not a batch CSV, whose rows are at most {} MiB",
        MAX_RECORD_BYTES >> 20,
        MAX_RECORD_BYTES >> 20
    )
}

/// Refuses a header that names a column twice (compared as the columns are found: by
/// [`column_name`], without case and units) or lacks a required one.
fn check_header(header: &[String]) -> Result<(), BatchError> {
    let shown = || printable(&header.join(",")).into_owned();
    for (i, name) in header.iter().enumerate() {
        if header[..i]
            .iter()
            .any(|earlier| column_name(earlier) == column_name(name))
        {
            return Err(BatchError::DuplicateColumn {
                name: printable(name).into_owned(),
                header: shown(),
            });
        }
    }
    let has = |name: &str| header.iter().any(|h| column_name(h) == name);
    // With a `path` column a row may name a path file in place of the cycle's columns.
    let required: &[&str] = if has("path") {
        &["friction", "compliance"]
    } else {
        &["p0", "p1", "q1", "phi", "friction", "compliance"]
    };
    let mut missing: Vec<&str> = required.iter().copied().filter(|name| !has(name)).collect();
    if !has("lambda") && !has("nu") {
        missing.push("lambda (or nu)");
    }
    if missing.is_empty() {
        Ok(())
    } else {
        Err(BatchError::MissingColumns {
            missing: missing.join(", "),
            header: shown(),
        })
    }
}

/// Reads a whole input for what would stop a batch part-way (a NUL byte, a record over
/// [`MAX_RECORD_BYTES`], an unclosed quote, a header without its columns) without
/// computing anything: the number of rows, or why the input is no batch CSV. For a file,
/// which can be read twice, before any row is computed or written.
pub fn check_input<R: Read>(source: R) -> Result<u64, BatchError> {
    let mut rows = 0;
    for row in read_input(source)? {
        row?;
        rows += 1;
    }
    Ok(rows)
}

impl<R: Read> Iterator for BatchInput<R> {
    type Item = Result<InputRow, BatchError>;

    /// The next row; an input that stops being a CSV ends the rows with why.
    fn next(&mut self) -> Option<Self::Item> {
        let mut record = csv::ByteRecord::new();
        let start = self.reader.position().byte();
        let more = self.reader.read_byte_record(&mut record);
        let end = self.reader.position().byte();
        if matches!(more, Ok(true)) && end.saturating_sub(start) > MAX_RECORD_BYTES {
            let line = self.comment_lines + record.position().map_or(0, |p| p.line());
            return Some(Err(BatchError::Input(too_long(line))));
        }
        self.record_start
            .store(self.bytes_before_header + end, Ordering::Relaxed);
        match more {
            Err(error) => Some(Err(BatchError::Input(error.to_string()))),
            Ok(false) => None,
            Ok(true) => {
                let line = self.comment_lines + record.position().map_or(0, |p| p.line());
                Some(Ok(self.row(line, &record)))
            }
        }
    }
}

impl<R> BatchInput<R> {
    /// Takes relative path files from `directory` (the input file's), as they are read.
    pub fn relative_to(mut self, directory: &Path) -> Self {
        self.directory = Some(directory.to_path_buf());
        self
    }

    fn row(&self, line: u64, record: &csv::ByteRecord) -> InputRow {
        let text: Vec<Option<String>> = record
            .iter()
            .map(|cell| std::str::from_utf8(cell).ok().map(str::to_string))
            .collect();
        let cells: Vec<String> = (0..self.header.len())
            .map(|i| text.get(i).cloned().flatten().unwrap_or_default())
            .collect();
        let empty = text.iter().all(|cell| cell.as_deref() == Some(""));
        let named_path = self
            .path_columns
            .0
            .and_then(|i| text.get(i).cloned().flatten())
            .filter(|cell| !cell.is_empty());
        let path = match (&named_path, empty) {
            (Some(file), false) => Some(self.path_row(file, &text)),
            _ => None,
        };
        let case = if empty {
            Err("every cell of the row is empty".to_string())
        } else if path.is_some() {
            Err("the row names a path file".to_string())
        } else {
            row_case(&self.header, &text, &self.columns)
        };
        InputRow {
            line,
            cells,
            case,
            path,
        }
    }

    /// The path request of a row whose `path` cell names `file`.
    fn path_row(&self, file: &str, text: &[Option<String>]) -> Result<PathRow, String> {
        check_fields(&self.header, text)?;
        let cell = |k: Option<usize>| -> Option<String> { k.and_then(|i| text[i].clone()).filter(|s| !s.is_empty()) };
        let given: Vec<&str> = [0, 1, 2, 3, 4]
            .into_iter()
            .filter(|&k| cell(self.columns[k]).is_some())
            .map(|k| CASE_COLUMNS[k])
            .collect();
        if !given.is_empty() {
            return Err(format!(
                "the row names the path file '{}' and gives {} too: give either a path or the cycle's columns",
                printable(file),
                given.join(", ")
            ));
        }
        let drive = match cell(self.path_columns.1).as_deref() {
            None | Some("force") => Drive::Force,
            Some("displacement") => Drive::Displacement,
            Some(other) => {
                return Err(format!(
                    "drive = '{}' is neither force nor displacement",
                    printable(other)
                ))
            }
        };
        let required = |k: usize| cell(self.columns[k]).ok_or_else(|| format!("{} is empty", CASE_COLUMNS[k]));
        let (lambda, nu) = (cell(self.columns[6]), cell(self.columns[7]));
        if lambda.is_some() == nu.is_some() {
            return Err("give exactly one of lambda and nu".to_string());
        }
        let file = Path::new(file);
        Ok(PathRow {
            file: match &self.directory {
                Some(directory) if file.is_relative() => directory.join(file),
                _ => file.to_path_buf(),
            },
            drive,
            friction: required(5)?,
            lambda,
            nu,
            compliance: required(8)?,
        })
    }
}

/// Refuses a row whose fields do not match the header, or that is not UTF-8.
fn check_fields(header: &[String], text: &[Option<String>]) -> Result<(), String> {
    if text.len() != header.len() {
        return Err(format!(
            "the row has {} fields, the header {} (a compliance SPEC with commas must be quoted: \"persson:gamma=1,sigma=1\")",
            text.len(),
            header.len()
        ));
    }
    if let Some(i) = text.iter().position(Option::is_none) {
        return Err(format!("{} is not UTF-8 text", printable(&header[i])));
    }
    Ok(())
}

fn row_case(header: &[String], text: &[Option<String>], columns: &[Option<usize>; 9]) -> Result<CaseText, String> {
    check_fields(header, text)?;
    let cell = |k: usize| -> Option<String> { columns[k].and_then(|i| text[i].clone()).filter(|s| !s.is_empty()) };
    let required = |k: usize| cell(k).ok_or_else(|| format!("{} is empty", CASE_COLUMNS[k]));
    let (lambda, nu) = (cell(6), cell(7));
    if lambda.is_some() == nu.is_some() {
        return Err("give exactly one of lambda and nu".to_string());
    }
    Ok(CaseText {
        p0: required(0)?,
        p1: required(1)?,
        q0: cell(2).unwrap_or_else(|| "0".to_string()),
        q1: required(3)?,
        phi: required(4)?,
        friction: required(5)?,
        lambda,
        nu,
        compliance: required(8)?,
    })
}
