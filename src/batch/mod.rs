//! W for many load cycles at once (parameter sweeps, design maps): a CSV of cases in,
//! one result per case out, in input order, every case on the path a single run takes
//! ([`dissipation_report`]).

use std::time::Duration;

use crate::answer::dissipation::{dissipation_report, DissipationAnswer};
use crate::answer::path::{path_answer, AgreedW, PathAnswer};
use crate::answer::ExitStatus;
use crate::answer::{Answer, Provenance};
use crate::messages::printable;
use crate::path::{PathFormat, PathRequest, RatioText};

mod input;
mod pool;

pub use input::{check_input, read_input, BatchInput, InputRow, PathRow, MAX_RECORD_BYTES};
pub use pool::{RowPool, Ticket};

pub use crate::answer::dissipation::{TableEstimate, TABLE_QUADRATURE_TOLERANCE};

/// A batch input that cannot be used at all.
#[derive(Debug, thiserror::Error)]
pub enum BatchError {
    /// The input cannot be read, or is not a CSV.
    #[error("batch input: {0}")]
    Input(String),
    /// Required columns are missing.
    #[error("batch input has no column {missing} (its header is '{header}'); a batch needs p0, p1, q1, phi, friction, lambda or nu, compliance, and optionally q0 and id (or a column path naming a path file in place of p0, p1, q0, q1, phi, with an optional drive)")]
    MissingColumns {
        /// The first required column the header lacks.
        missing: String,
        /// The header as read.
        header: String,
    },
    /// A column is named twice: which one a row's value came from would be a guess.
    #[error("batch input names the column '{name}' twice (its header is '{header}'); give each column once")]
    DuplicateColumn {
        /// The column named twice.
        name: String,
        /// The header as read.
        header: String,
    },
}

/// The columns a batch appends to its input's: the first six as they have always been,
/// then what vouches for W (`provenance`, `digits_certified`) and the decimal ends of an
/// interval that contains it (empty for an exact W).
pub const RESULT_COLUMNS: [&str; 10] = [
    "W",
    "digits",
    "error_estimate",
    "table_error",
    "method",
    "error",
    "provenance",
    "digits_certified",
    "enclosure_lower",
    "enclosure_upper",
];

/// The result of one row, as the output columns print it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RowResult {
    /// W as printed (empty on failure, and where not one digit is determined).
    pub total: String,
    /// Its significant digits.
    pub digits: Option<u32>,
    /// The digits proven (by an enclosure, or exact); 0 for estimated digits.
    pub digits_certified: Option<u32>,
    /// Decimal ends of an interval that contains W (none for an exact value).
    pub enclosure: Option<(String, String)>,
    /// What vouches for W ([`crate::answer::Provenance::key`]; empty on failure).
    pub provenance: String,
    /// The absolute quadrature error estimate of an f64 W.
    pub error_estimate: Option<f64>,
    /// The estimated absolute error due to a table compliance.
    pub table_error: Option<f64>,
    /// How W was computed (with why not f64, or why no enclosure, where it applies).
    pub method: String,
    /// Why the row failed (empty when it succeeded).
    pub error: String,
    /// W and what vouches for it, as a single run reports it (none for a failed row).
    pub answer: Option<DissipationAnswer>,
    /// W of a row that names a path file, as `microslip path` prints it.
    pub path: Option<AgreedW>,
}

impl RowResult {
    /// Did the row give a W?
    pub fn succeeded(&self) -> bool {
        self.error.is_empty()
    }

    /// The result of a row that gave `report`.
    fn of(report: DissipationAnswer) -> Self {
        let DissipationAnswer {
            answer,
            no_enclosure,
            table,
        } = &report;
        let Answer { value, provenance, .. } = answer;
        let mut method = answer.method.map_or("", crate::dissipation::Method::key).to_string();
        if let Some(why) = no_enclosure {
            method.push_str(&format!(" (no enclosure: {why})"));
        }
        let error_estimate = match provenance {
            Provenance::Table { .. } => table.as_ref().map(|t| t.quadrature_error),
            _ => None,
        };
        RowResult {
            total: report.total(),
            digits: Some(answer.digits()),
            digits_certified: Some(answer.digits_certified()),
            enclosure: value.enclosure.clone(),
            provenance: provenance.key().to_string(),
            error_estimate,
            table_error: table.as_ref().map(|t| t.error),
            method,
            error: String::new(),
            answer: Some(report),
            path: None,
        }
    }

    /// The result of a row whose path gave `answer`.
    fn of_path(answer: PathAnswer) -> Self {
        let w = answer.w;
        RowResult {
            total: w.text.clone(),
            // An exact 0 shows every digit asked.
            digits: Some(match w.exact {
                Some(_) => w.digits_certified,
                None => significant_digits(&w.text),
            }),
            digits_certified: Some(w.digits_certified),
            enclosure: w.enclosure.clone(),
            provenance: w.provenance.to_string(),
            method: format!("path-{}", answer.drive.name()),
            path: Some(w),
            ..RowResult::default()
        }
    }
}

/// The significant digits of a decimal as printed (`-1.2300e-4` has 5).
fn significant_digits(text: &str) -> u32 {
    let mantissa = text.split(['e', 'E']).next().unwrap_or("");
    let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
    digits.trim_start_matches('0').len() as u32
}

/// W of a row that names a path file: read, then answered as `microslip path` answers it.
fn path_result(row: &PathRow, digits: Option<u32>, budget: Duration) -> Result<PathAnswer, String> {
    let contents = std::fs::read_to_string(&row.file)
        .map_err(|error| format!("cannot read the path file {}: {error}", row.file.display()))?;
    let ratio = match (&row.lambda, &row.nu) {
        (Some(lambda), _) => RatioText::Lambda(lambda.clone()),
        (None, Some(nu)) => RatioText::Poisson(nu.clone()),
        (None, None) => return Err("give exactly one of lambda and nu".to_string()),
    };
    let request = PathRequest {
        file: row.file.display().to_string(),
        format: PathFormat::of_contents(&contents),
        contents,
        drive: row.drive,
        friction: row.friction.clone(),
        ratio,
        compliance: row.compliance.clone(),
        digits,
        deadline: std::time::Instant::now() + budget,
        harmonics_out: 0,
        loop_points: 1,
    };
    path_answer(&request).map_err(|error| error.line(digits.is_some()))
}

/// The result of a row that failed with `error`, naming the row's line.
fn failed_row(row: &InputRow, error: &str) -> RowResult {
    RowResult {
        error: format!("line {}: {}", row.line, printable(error)),
        ..RowResult::default()
    }
}

/// The result of a row, computed on this thread.
fn row_result(row: &InputRow, digits: Option<u32>, budget: Duration) -> RowResult {
    let outcome = match (&row.path, &row.case) {
        (Some(Err(problem)), _) | (None, Err(problem)) => Err(problem.clone()),
        (Some(Ok(path)), _) => path_result(path, digits, budget).map(RowResult::of_path),
        (None, Ok(case)) => dissipation_report(case, digits, budget)
            .map(RowResult::of)
            .map_err(|error| error.line(digits.is_some())),
    };
    outcome.unwrap_or_else(|error| failed_row(row, &error))
}

/// Every row on as many threads as rayon's pool has, each within `budget`, in input
/// order (a [`RowPool`] for these rows alone).
pub fn run(rows: &[InputRow], digits: Option<u32>, budget: Duration) -> Vec<RowResult> {
    let pool = RowPool::new(rayon::current_num_threads(), digits, budget);
    let ticket = pool.hand_in(rows.into());
    pool.collect(ticket, &mut |_| {})
}

/// The input columns that are echoed (all but those named like a result column).
fn echoed(header: &[String]) -> Vec<usize> {
    (0..header.len())
        .filter(|&i| !RESULT_COLUMNS.contains(&header[i].as_str()))
        .collect()
}

fn estimate_text(value: Option<f64>) -> String {
    value.map_or(String::new(), |v| format!("{v:.2e}"))
}

/// The header line of the CSV output: the input columns, then [`RESULT_COLUMNS`].
pub fn csv_header(header: &[String]) -> Result<Vec<u8>, BatchError> {
    let names = echoed(header)
        .into_iter()
        .map(|i| header[i].as_str())
        .chain(RESULT_COLUMNS);
    csv_lines([names])
}

/// The CSV lines of rows and their results.
pub fn csv_rows(header: &[String], rows: &[InputRow], results: &[RowResult]) -> Result<Vec<u8>, BatchError> {
    let keep = echoed(header);
    let count = |digits: Option<u32>| digits.map_or(String::new(), |d| d.to_string());
    csv_lines(rows.iter().zip(results).map(|(row, result)| {
        let (lower, upper) = result.enclosure.clone().unwrap_or_default();
        keep.iter().map(|&i| row.cells[i].clone()).chain([
            result.total.clone(),
            count(result.digits),
            estimate_text(result.error_estimate),
            estimate_text(result.table_error),
            result.method.clone(),
            result.error.clone(),
            result.provenance.clone(),
            count(result.digits_certified),
            lower,
            upper,
        ])
    }))
}

fn csv_lines<Row, Cell>(rows: impl IntoIterator<Item = Row>) -> Result<Vec<u8>, BatchError>
where
    Row: IntoIterator<Item = Cell>,
    Cell: AsRef<[u8]>,
{
    let io = |e: &dyn std::fmt::Display| BatchError::Input(e.to_string());
    let mut writer = csv::Writer::from_writer(Vec::new());
    for row in rows {
        writer.write_record(row).map_err(|e| io(&e))?;
    }
    writer.into_inner().map_err(|e| io(&e))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Read;

    fn rows_of(text: &str) -> (Vec<String>, Vec<InputRow>) {
        let input = read_input(text.as_bytes()).unwrap();
        let header = input.header.clone();
        (header, input.map(Result::unwrap).collect())
    }

    #[test]
    fn comments_are_whole_lines_before_the_header_and_every_row_is_a_row() {
        let text = "# a comment\n#another, with \"a quote\n\
                    id,p0,p1,q1,phi,friction,lambda,compliance\n\
                    #1,1,0.4,0.5,0.4pi,1,1,const:c=1\n\
                    ,,,,,,,\n\
                    # not a comment,1,0.4,0.5,0.4pi,1,1,const:c=1\n";
        let (_, rows) = rows_of(text);
        let ids: Vec<&str> = rows.iter().map(|row| row.cells[0].as_str()).collect();
        assert_eq!(ids, ["#1", "", "# not a comment"]);
        assert_eq!(rows.iter().map(|row| row.line).collect::<Vec<_>>(), [4, 5, 6]);
        assert!(rows[0].case.is_ok());
        assert_eq!(rows[1].case.as_ref().unwrap_err(), "every cell of the row is empty");
    }

    #[test]
    fn a_column_named_twice_and_input_that_is_no_csv_are_refused() {
        let twice = "p0,p1,q1,phi,friction,lambda,compliance,P0\n1,0.4,0.5,1,1,1,const:c=1,2\n";
        let error = read_input(twice.as_bytes()).err().unwrap();
        assert!(error.to_string().contains("names the column 'P0' twice"), "{error}");
        let zeros = std::io::repeat(0).take(1 << 30);
        let error = read_input(zeros).err().unwrap();
        assert!(error.to_string().contains("NUL byte"), "{error}");
        let endless = std::io::repeat(b'x').take(1 << 30);
        let error = read_input(endless).err().unwrap();
        assert!(error.to_string().contains("runs past 1 MiB"), "{error}");
        let header = "p0,p1,q1,phi,friction,lambda,compliance\n\"";
        let open_quote = header.as_bytes().chain(std::io::repeat(b'\n').take(1 << 30));
        let mut input = read_input(open_quote).unwrap();
        let error = input.next().unwrap().unwrap_err();
        assert!(error.to_string().contains("unclosed quote"), "{error}");
    }
}
