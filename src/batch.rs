//! W for many load cycles at once (parameter sweeps, design maps): a CSV of cases in,
//! one result per case out, in input order, every case on the path a single run takes.
//!
//! [`case_dissipation`] is that path: verified or f64 digits as
//! [`printable_dissipation`] gives them, and for a compliance from a table the f64
//! value with the error the table introduces beside the quadrature's.

use std::time::{Duration, Instant};

use std::sync::Arc;

use rayon::prelude::*;

use crate::compliance::{parse_spec_with, tables_in_spec, ComplianceTable, TableError, TableInterpolant};
use crate::cycle::LoadCycle;
use crate::dissipation::{dissipation, DissipationError, Method, Options};
use crate::inputs::{Case, CaseText};
use crate::real::Precision;
use crate::reference::{printable_dissipation, PrintedDissipation, ReferenceError};
use crate::verified::resolved_digits;

mod input;
mod output;

pub use input::{read_input, BatchInput, InputRow, MAX_RECORD_BYTES};
pub use output::{BatchRecord, JsonValue};

/// Relative quadrature tolerance of W from a table: far below any table's own error,
/// and reachable on the interpolant's piecewise-cubic v' in f64.
pub const TABLE_QUADRATURE_TOLERANCE: f64 = 1e-12;

/// What |W[half table] − W[table]| is divided by to estimate the error of W[table], for
/// a table of `rows` rows. For a construction of order p = [`TABLE_ORDER`] the quotient
/// tends to 2^p − 1 = 15, but before the data are asymptotic it is smaller: over the
/// scan of proofs/table-compliance.md it fell to 6 at 16 to 24 rows, to 1 at 9 rows,
/// and below 1 for tables of up to 5 rows (halves of three rows, one parabola of node
/// values, can be as close to the full table as its own error). The divisor keeps a
/// factor of about two below the least quotient measured at each size.
fn half_table_divisor(rows: usize) -> f64 {
    match rows {
        0..=5 => 0.25,
        6..=12 => 0.5,
        _ => 3.0,
    }
}

/// What a table compliance adds to a result.
#[derive(Clone, Debug, PartialEq)]
pub struct TableEstimate {
    /// Estimated absolute error of W due to the table: the larger |W\[half table\] − W\[table\]|
    /// of the two half tables (plus the quadrature errors of the difference), scaled by
    /// the order of the construction.
    pub error: f64,
    /// The largest relative change the smoothing fit made to the data (0 when none).
    pub smoothing_residual: f64,
    /// W before rounding to the printed digits.
    pub unrounded: f64,
}

/// W as a single run prints it, and for table compliances the table's error.
#[derive(Clone, Debug)]
pub struct CaseDissipation {
    /// W and its segments as printed.
    pub printed: PrintedDissipation,
    /// Present when the compliance has a table term.
    pub table: Option<TableEstimate>,
}

/// Why a case gives no W.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CaseError {
    /// The case, the precision, or the quadrature.
    #[error(transparent)]
    Reference(#[from] ReferenceError),
    /// A table of the compliance.
    #[error(transparent)]
    Table(#[from] TableError),
    /// Verified digits asked for a table compliance.
    #[error("verified digits are not computed for a table compliance: the table is measured data, known only to its error estimate, and the interpolant between its loads is one choice of many, so digits beyond the table error would not be digits of W (the f64 run reports W with that error)")]
    DigitsForTable,
    /// f64 cannot compute this cycle, and a table is not computed at other precisions.
    #[error("{source} — but a table compliance is computed in f64 only, so this cycle cannot be computed from a table (where its loads are extreme, rescale the cycle and the table's loads together: W scales with the load scale)")]
    TableInF64 { source: DissipationError },
}

impl From<DissipationError> for CaseError {
    fn from(error: DissipationError) -> Self {
        CaseError::Reference(ReferenceError::Dissipation(error))
    }
}

/// W for one case: [`printable_dissipation`], or for a compliance with a table term, W
/// in f64 from the table's interpolant, rounded to the digits that its quadrature
/// error plus the table's error leave. Where they leave none, W (and a segment likewise)
/// is the empty text and its digits 0: no digit of it is known.
pub fn case_dissipation(case: &CaseText, digits: Option<u32>, budget: Duration) -> Result<CaseDissipation, CaseError> {
    let tables = tables_in_spec(&case.compliance)?;
    if tables.is_empty() {
        return Ok(CaseDissipation {
            printed: printable_dissipation(case, digits, budget)?,
            table: None,
        });
    }
    if digits.is_some() {
        return Err(CaseError::DigitsForTable);
    }
    let deadline = Instant::now() + budget;
    let Case { cycle, compliance } = case.read::<f64>(Precision::DOUBLE).map_err(ReferenceError::from)?;
    cycle.validate().map_err(DissipationError::from)?;
    tables_cover(&tables, &cycle)?;
    let in_f64 = |error: DissipationError| match error {
        DissipationError::IllConditioned { .. }
        | DissipationError::NotConverged { .. }
        | DissipationError::OutOfRange { .. }
        | DissipationError::OutsideRange { .. } => CaseError::TableInF64 { source: error },
        other => other.into(),
    };
    let options = Options {
        relative_tolerance: Some(TABLE_QUADRATURE_TOLERANCE),
        deadline: Some(deadline),
        ..Options::default()
    };
    let result = dissipation(&cycle, compliance.as_ref(), &options).map_err(in_f64)?;
    let segments = result.segments.named().map(|(_, value)| *value);
    // The table error: how far W moves when the table loses its odd rows, or its even rows.
    let divisor = half_table_divisor(tables.iter().map(|t| t.loads.len()).min().unwrap_or(0));
    let (mut table_error, mut segment_shifts) = (0.0f64, [0.0f64; 4]);
    for interpolant in [TableInterpolant::HalfTable, TableInterpolant::OtherHalfTable] {
        let half = parse_spec_with::<f64>(&case.compliance, Precision::DOUBLE, interpolant)
            .map_err(|e| ReferenceError::Input(e.into()))?;
        let moved = dissipation(&cycle, half.as_ref(), &options).map_err(in_f64)?;
        let uncertainty = moved.error_estimate + result.error_estimate;
        table_error = table_error.max(((moved.total - result.total).abs() + uncertainty) / divisor);
        for ((shift, value), half_value) in segment_shifts.iter_mut().zip(segments).zip(moved.segments.named()) {
            *shift = shift.max(((half_value.1 - value).abs() + uncertainty) / divisor);
        }
    }
    let segment_errors = segment_shifts.map(|shift| result.error_estimate + shift);
    let mut printed = PrintedDissipation::within(&result, result.error_estimate + table_error, segment_errors);
    if printed.digits == 0 {
        printed.total = String::new();
    }
    for ((_, text), (value, error)) in printed
        .segments
        .iter_mut()
        .zip(segments.into_iter().zip(segment_errors))
    {
        if resolved_digits(value, error) == 0 {
            text.clear();
        }
    }
    Ok(CaseDissipation {
        printed,
        table: Some(TableEstimate {
            error: table_error,
            smoothing_residual: tables.iter().map(|t| t.smoothing_residual).fold(0.0, f64::max),
            unrounded: result.total,
        }),
    })
}

/// Refuses a valid cycle whose loads, from min(P_T, P0 − P1) to P0 + P1, leave a table.
fn tables_cover(tables: &[Arc<ComplianceTable>], cycle: &LoadCycle<f64>) -> Result<(), TableError> {
    let low = (cycle.mean_normal_load - cycle.normal_amplitude).min(cycle.permanent_stick_load());
    let high = cycle.mean_normal_load + cycle.normal_amplitude;
    tables.iter().try_for_each(|table| table.check_covers(low, high))
}

/// Refuses a cycle that leaves a table of the compliance SPEC, naming the table's range
/// (for computations that check the compliance themselves, as the simulation does). A
/// cycle outside the theory passes here: its own check says what is wrong.
pub fn check_table_range(spec: &str, cycle: &LoadCycle<f64>) -> Result<(), TableError> {
    if cycle.validate().is_err() {
        return Ok(());
    }
    tables_cover(&tables_in_spec(spec)?, cycle)
}

/// A short machine-readable name of a method.
pub fn method_key(method: Method) -> &'static str {
    match method {
        Method::FourSegment => "four-segment",
        Method::InPhase => "in-phase",
        Method::ConstantNormalLoad => "constant-normal-load",
        Method::NoTangentialOscillation => "no-tangential-oscillation",
        Method::Exact(_) => "exact",
    }
}

/// A batch input that cannot be used at all.
#[derive(Debug, thiserror::Error)]
pub enum BatchError {
    /// The input cannot be read, or is not a CSV.
    #[error("batch input: {0}")]
    Input(String),
    /// Required columns are missing.
    #[error("batch input has no column {missing} (its header is '{header}'); a batch needs p0, p1, q1, phi, friction, lambda or nu, compliance, and optionally q0 and id")]
    MissingColumns { missing: String, header: String },
    /// A column is named twice: which one a row's value came from would be a guess.
    #[error("batch input names the column '{name}' twice (its header is '{header}'); give each column once")]
    DuplicateColumn { name: String, header: String },
}

/// The columns a batch appends to its input's.
pub const RESULT_COLUMNS: [&str; 6] = ["W", "digits", "error_estimate", "table_error", "method", "error"];

/// The result of one row, as the output columns print it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RowResult {
    /// W as printed (empty on failure).
    pub total: String,
    /// Its significant digits.
    pub digits: Option<u32>,
    /// The absolute quadrature error estimate of an f64 W.
    pub error_estimate: Option<f64>,
    /// The estimated absolute error due to a table compliance.
    pub table_error: Option<f64>,
    /// How W was computed (with why MPFR, when f64 fell back to it).
    pub method: String,
    /// Why the row failed (empty when it succeeded).
    pub error: String,
}

impl RowResult {
    /// Did the row give a W?
    pub fn succeeded(&self) -> bool {
        self.error.is_empty()
    }
}

/// What a row gets beyond its budget to return its own, more specific, answer.
const ROW_GRACE: Duration = Duration::from_millis(500);

/// Stack of a row's thread: as large as a command's worker has.
const ROW_STACK_BYTES: usize = 64 << 20;

/// A unit of work for a row thread.
type Job = Box<dyn FnOnce() + Send>;

/// The threads rows run on, beside the pool that waits for them: a row that outlasts
/// its budget is left to finish on its thread, which then ends, while the batch goes on.
/// Idle threads are reused (a thread per row would cost more than an f64 row), and end
/// when the batch is over.
#[derive(Default)]
struct RowThreads {
    idle: std::sync::Mutex<Vec<std::sync::mpsc::Sender<Job>>>,
}

impl RowThreads {
    /// An idle thread, or a new one.
    fn take(&self) -> Option<std::sync::mpsc::Sender<Job>> {
        if let Some(idle) = self.idle.lock().ok().and_then(|mut idle| idle.pop()) {
            return Some(idle);
        }
        let (sender, receiver) = std::sync::mpsc::channel::<Job>();
        let thread = std::thread::Builder::new().stack_size(ROW_STACK_BYTES);
        thread
            .spawn(move || {
                // Until its sender is dropped: by the pool at the end, or by a row that gave up.
                while let Ok(job) = receiver.recv() {
                    job();
                }
            })
            .ok()?;
        Some(sender)
    }

    /// `work()` on a row thread, or None when it has not answered within `budget` and
    /// [`ROW_GRACE`]: the computation checks its deadline between steps, and a step that
    /// outlasts it is left to finish on its own rather than hold the batch.
    fn within_budget<T: Send + 'static>(
        &self,
        budget: Duration,
        work: impl FnOnce() -> T + Send + 'static,
    ) -> Option<std::thread::Result<T>> {
        let Some(thread) = self.take() else {
            return Some(Err(Box::new("cannot start a thread")));
        };
        let (sender, receiver) = std::sync::mpsc::channel();
        let job: Job = Box::new(move || {
            let _ = sender.send(std::panic::catch_unwind(std::panic::AssertUnwindSafe(work)));
        });
        if thread.send(job).is_err() {
            return Some(Err(Box::new("a row thread ended")));
        }
        let answer = receiver.recv_timeout(budget.saturating_add(ROW_GRACE)).ok()?;
        if let Ok(mut idle) = self.idle.lock() {
            idle.push(thread);
        }
        Some(answer)
    }
}

fn row_result(threads: &RowThreads, row: &InputRow, digits: Option<u32>, budget: Duration) -> RowResult {
    let failed = |error: String| RowResult {
        error: format!("line {}: {error}", row.line),
        ..RowResult::default()
    };
    let case = match &row.case {
        Ok(case) => case.clone(),
        Err(problem) => return failed(problem.clone()),
    };
    match threads.within_budget(budget, move || case_dissipation(&case, digits, budget)) {
        Some(Ok(Ok(result))) => {
            let printed = result.printed;
            let mut method = method_key(printed.method).to_string();
            if let Some(reason) = &printed.fallback {
                method.push_str(&format!(" (verified in MPFR: {reason})"));
            }
            RowResult {
                total: printed.total,
                digits: Some(printed.digits),
                error_estimate: printed.error_estimate,
                table_error: result.table.map(|t| t.error),
                method,
                error: String::new(),
            }
        }
        Some(Ok(Err(error))) => failed(error.to_string()),
        Some(Err(_)) => failed("internal error: the computation panicked (please report this case)".to_string()),
        None => failed(format!(
            "the time budget of {} s per row ran out before the result was reached; raise --max-seconds",
            budget.as_secs_f64()
        )),
    }
}

/// Every row on all cores, each within `budget`, in input order; `row_done` is called
/// as each row finishes.
pub fn run(rows: &[InputRow], digits: Option<u32>, budget: Duration, row_done: &(dyn Fn() + Sync)) -> Vec<RowResult> {
    let threads = RowThreads::default();
    rows.par_iter()
        .map(|row| {
            let result = row_result(&threads, row, digits, budget);
            row_done();
            result
        })
        .collect()
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
    csv_lines(rows.iter().zip(results).map(|(row, result)| {
        keep.iter().map(|&i| row.cells[i].clone()).chain([
            result.total.clone(),
            result.digits.map_or(String::new(), |d| d.to_string()),
            estimate_text(result.error_estimate),
            estimate_text(result.table_error),
            result.method.clone(),
            result.error.clone(),
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

/// The results as records, one per row in input order (the JSON lines output).
pub fn records<'a>(header: &'a [String], rows: &'a [InputRow], results: &'a [RowResult]) -> Vec<BatchRecord<'a>> {
    let keep = echoed(header);
    rows.iter()
        .zip(results)
        .map(|(row, result)| {
            BatchRecord::new(
                keep.iter().map(|&i| (header[i].as_str(), row.cells[i].as_str())),
                result,
            )
        })
        .collect()
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
    fn a_record_echoes_the_inputs_and_gives_absent_results_as_null() {
        let text = "id,p0,p1,q1,phi,friction,lambda,compliance,W\n\
                    a,1,0.4,0.5,0.4pi,1,1,\"persson:gamma=1,sigma=1\",old\n\
                    b,1,0.4,5,0.4pi,1,1,\"persson:gamma=1,sigma=1\",old\n";
        let (header, rows) = rows_of(text);
        let results = run(&rows, None, Duration::from_secs(10), &|| {});
        let lines: Vec<serde_json::Value> = records(&header, &rows, &results)
            .iter()
            .map(|record| serde_json::to_value(record).unwrap())
            .collect();
        // The input's own W column is not echoed: the result's W takes its place.
        assert_eq!(lines[0]["W"], 0.4062475792458);
        assert_eq!(lines[0]["id"], "a");
        assert_eq!(lines[0]["p1"], 0.4);
        assert_eq!(lines[0]["phi"], "0.4pi");
        assert_eq!(lines[0]["compliance"], "persson:gamma=1,sigma=1");
        assert_eq!(lines[0]["digits"], 13);
        assert!(lines[0]["error"].is_null() && lines[0]["table_error"].is_null());
        assert!(lines[1]["W"].is_null() && lines[1]["method"].is_null());
        assert!(lines[1]["error"].as_str().unwrap().contains("gross slip"));
        assert_eq!(lines[0].as_object().unwrap().len(), 14);
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
