//! W for many load cycles at once (parameter sweeps, design maps): a CSV of cases in,
//! one result per case out, in input order, every case on the path a single run takes.
//!
//! [`case_dissipation`] is that path: verified or f64 digits as
//! [`printable_dissipation`] gives them, and for a compliance from a table the f64
//! value with the error the table introduces beside the quadrature's.

use std::collections::BTreeMap;
use std::io::Read;
use std::time::Duration;

use std::sync::Arc;

use rayon::prelude::*;
use serde::Serialize;

use crate::compliance::{
    parse_spec_with, tables_in_spec, ComplianceTable, Difference, TableError, TableInterpolant, TABLE_ORDER,
};
use crate::cycle::LoadCycle;
use crate::dissipation::{dissipation, DissipationError, Method, Options};
use crate::inputs::{Case, CaseText};
use crate::real::{Precision, Real};
use crate::reference::{printable_dissipation, PrintedDissipation, ReferenceError};
use crate::verified::resolved_digits;

/// Relative quadrature tolerance of W from a table: far below any table's own error,
/// and reachable on the interpolant's piecewise-cubic v' in f64.
pub const TABLE_QUADRATURE_TOLERANCE: f64 = 1e-12;

/// Relative quadrature tolerance of the table-error integral (only its size matters).
const TABLE_ERROR_TOLERANCE: f64 = 1e-3;

/// W[half table] − W[table] ≈ (2^p − 1)·(error of W[table]) for a construction of order
/// p. The divisor takes one order less than the construction has (2^(p−1) − 1 = 3 for
/// p = 3): where the data are not yet asymptotic (a cycle on a few rows, say) the ratio
/// falls below 2^p − 1, and a short estimate would print a wrong digit.
fn half_table_divisor() -> f64 {
    f64::from((1u32 << (TABLE_ORDER - 1)) - 1)
}

/// What a table compliance adds to a result.
#[derive(Clone, Debug, PartialEq)]
pub struct TableEstimate {
    /// Estimated absolute error of W due to the table: |W[half table] − W[table]| (plus
    /// the quadrature error of that difference) over 2^(p−1) − 1, p = [`TABLE_ORDER`].
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
    #[error("{source}; a table compliance is computed in f64 only, so this cycle cannot be computed from a table")]
    TableInF64 { source: DissipationError },
}

impl From<DissipationError> for CaseError {
    fn from(error: DissipationError) -> Self {
        CaseError::Reference(ReferenceError::Dissipation(error))
    }
}

/// W for one case: [`printable_dissipation`], or for a compliance with a table term, W
/// in f64 from the table's cubic interpolant, rounded to the digits that its quadrature
/// error plus the table's error leave.
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
    let Case { cycle, compliance } = case.read::<f64>(Precision::DOUBLE).map_err(ReferenceError::from)?;
    cycle.validate().map_err(DissipationError::from)?;
    tables_cover(&tables, &cycle)?;
    let in_f64 = |error: DissipationError| match error {
        DissipationError::IllConditioned { .. } | DissipationError::NotConverged { .. } => {
            CaseError::TableInF64 { source: error }
        }
        other => other.into(),
    };
    let options = Options {
        relative_tolerance: Some(TABLE_QUADRATURE_TOLERANCE),
        ..Options::default()
    };
    let result = dissipation(&cycle, compliance.as_ref(), &options).map_err(in_f64)?;
    let half = parse_spec_with::<f64>(&case.compliance, Precision::DOUBLE, TableInterpolant::HalfTable)
        .map_err(|e| ReferenceError::Input(e.into()))?;
    let difference = Difference {
        minuend: half,
        subtrahend: compliance,
    };
    let error_options = Options {
        relative_tolerance: Some(TABLE_ERROR_TOLERANCE),
        check_compliance: false,
        ..Options::default()
    };
    let change = dissipation(&cycle, &difference, &error_options).map_err(in_f64)?;
    let table_error = (change.total.abs() + change.error_estimate) / half_table_divisor();
    // At least one digit: a table is f64 only, and its W is printed whatever it resolves.
    let digits = resolved_digits(result.total, result.error_estimate + table_error).max(1);
    let shifts = change.segments.named().map(|(_, shift)| shift.abs());
    let segment_errors =
        shifts.map(|shift| result.error_estimate + (change.error_estimate + shift) / half_table_divisor());
    Ok(CaseDissipation {
        printed: PrintedDissipation::from_f64(&result, digits, segment_errors),
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
    /// The input cannot be read or has no usable header.
    #[error("batch input: {0}")]
    Input(String),
    /// Required columns are missing.
    #[error("batch input has no column {missing} (its header is '{header}'); a batch needs p0, p1, q1, phi, friction, lambda or nu, compliance, and optionally q0 and id")]
    MissingColumns { missing: String, header: String },
}

/// The columns a batch appends to its input's.
pub const RESULT_COLUMNS: [&str; 6] = ["W", "digits", "error_estimate", "table_error", "method", "error"];

/// One input row: its line in the file, its cells, and the case (or why there is none).
#[derive(Clone, Debug)]
pub struct InputRow {
    /// Line of the input file (1 is the header).
    pub line: u64,
    /// The cells, one per header column (missing ones empty).
    pub cells: Vec<String>,
    /// The case, or what is wrong with the row.
    pub case: Result<CaseText, String>,
}

/// A batch input: the header and the rows.
#[derive(Clone, Debug)]
pub struct BatchInput {
    /// Column names as given.
    pub header: Vec<String>,
    /// The rows in input order.
    pub rows: Vec<InputRow>,
}

/// Reads a batch CSV (header, `#` comments, cells trimmed). Only a missing column or an
/// unreadable file is an error; a bad row becomes a row whose case says why.
pub fn read_input(source: impl Read) -> Result<BatchInput, BatchError> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .flexible(true)
        .from_reader(source);
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| BatchError::Input(e.to_string()))?
        .iter()
        .map(str::to_string)
        .collect();
    let find = |name: &str| header.iter().position(|h| h.eq_ignore_ascii_case(name));
    let required = ["p0", "p1", "q1", "phi", "friction", "compliance"];
    let mut missing: Vec<&str> = required.iter().copied().filter(|name| find(name).is_none()).collect();
    if find("lambda").is_none() && find("nu").is_none() {
        missing.push("lambda (or nu)");
    }
    if !missing.is_empty() {
        return Err(BatchError::MissingColumns {
            missing: missing.join(", "),
            header: header.join(","),
        });
    }
    let index = |name: &str| find(name);
    let columns = [
        index("p0"),
        index("p1"),
        index("q0"),
        index("q1"),
        index("phi"),
        index("friction"),
        index("lambda"),
        index("nu"),
        index("compliance"),
    ];
    let mut rows = Vec::new();
    for record in reader.byte_records() {
        let record = record.map_err(|e| BatchError::Input(e.to_string()))?;
        let line = record.position().map_or(0, |p| p.line());
        let text: Vec<Option<String>> = record
            .iter()
            .map(|cell| std::str::from_utf8(cell).ok().map(|s| s.to_string()))
            .collect();
        if text.iter().all(|cell| cell.as_deref() == Some("")) {
            continue;
        }
        let cells: Vec<String> = (0..header.len())
            .map(|i| text.get(i).cloned().flatten().unwrap_or_default())
            .collect();
        let case = row_case(&header, &text, &columns);
        rows.push(InputRow { line, cells, case });
    }
    Ok(BatchInput { header, rows })
}

fn row_case(header: &[String], text: &[Option<String>], columns: &[Option<usize>; 9]) -> Result<CaseText, String> {
    if text.len() != header.len() {
        return Err(format!(
            "the row has {} fields, the header {} (a compliance SPEC with commas must be quoted: \"persson:gamma=1,sigma=1\")",
            text.len(),
            header.len()
        ));
    }
    if let Some(i) = text.iter().position(Option::is_none) {
        return Err(format!("{} is not UTF-8 text", header[i]));
    }
    let cell = |k: usize| -> Option<String> { columns[k].and_then(|i| text[i].clone()).filter(|s| !s.is_empty()) };
    let required = |k: usize, name: &str| cell(k).ok_or_else(|| format!("{name} is empty"));
    let (lambda, nu) = (cell(6), cell(7));
    if lambda.is_some() == nu.is_some() {
        return Err("give exactly one of lambda and nu".to_string());
    }
    Ok(CaseText {
        p0: required(0, "p0")?,
        p1: required(1, "p1")?,
        q0: cell(2).unwrap_or_else(|| "0".to_string()),
        q1: required(3, "q1")?,
        phi: required(4, "phi")?,
        friction: required(5, "friction")?,
        lambda,
        nu,
        compliance: required(8, "compliance")?,
    })
}

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

fn row_result(row: &InputRow, digits: Option<u32>, budget: Duration) -> RowResult {
    let failed = |error: String| RowResult {
        error: format!("line {}: {error}", row.line),
        ..RowResult::default()
    };
    let case = match &row.case {
        Ok(case) => case,
        Err(problem) => return failed(problem.clone()),
    };
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| case_dissipation(case, digits, budget)));
    match outcome {
        Ok(Ok(result)) => {
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
        Ok(Err(error)) => failed(error.to_string()),
        Err(_) => failed("internal error: the computation panicked (please report this case)".to_string()),
    }
}

/// Every row on all cores, in input order; `row_done` is called as each row finishes.
pub fn run(input: &BatchInput, digits: Option<u32>, budget: Duration, row_done: &(dyn Fn() + Sync)) -> Vec<RowResult> {
    input
        .rows
        .par_iter()
        .map(|row| {
            let result = row_result(row, digits, budget);
            row_done();
            result
        })
        .collect()
}

/// The input columns that are echoed (all but those named like a result column).
fn echoed(input: &BatchInput) -> Vec<usize> {
    (0..input.header.len())
        .filter(|&i| !RESULT_COLUMNS.contains(&input.header[i].as_str()))
        .collect()
}

fn estimate_text(value: Option<f64>) -> String {
    value.map_or(String::new(), |v| format!("{v:.2e}"))
}

/// The results as CSV: the input columns, then [`RESULT_COLUMNS`].
pub fn to_csv(input: &BatchInput, results: &[RowResult]) -> Result<Vec<u8>, BatchError> {
    let keep = echoed(input);
    let mut writer = csv::Writer::from_writer(Vec::new());
    let header = keep.iter().map(|&i| input.header[i].as_str()).chain(RESULT_COLUMNS);
    let io = |e: csv::Error| BatchError::Input(e.to_string());
    writer.write_record(header).map_err(io)?;
    for (row, result) in input.rows.iter().zip(results) {
        let cells = keep.iter().map(|&i| row.cells[i].clone()).chain([
            result.total.clone(),
            result.digits.map_or(String::new(), |d| d.to_string()),
            estimate_text(result.error_estimate),
            estimate_text(result.table_error),
            result.method.clone(),
            result.error.clone(),
        ]);
        writer.write_record(cells).map_err(io)?;
    }
    writer.into_inner().map_err(|e| BatchError::Input(e.to_string()))
}

/// One output row of a batch as a JSON object: the echoed input columns (as text,
/// the last of equally named ones kept) and the result fields (null where absent).
#[derive(Debug, Serialize)]
pub struct BatchRecord<'a> {
    #[serde(flatten)]
    pub inputs: BTreeMap<&'a str, &'a str>,
    #[serde(rename = "W")]
    pub w: Option<&'a str>,
    pub digits: Option<u32>,
    pub error_estimate: Option<f64>,
    pub table_error: Option<f64>,
    pub method: Option<&'a str>,
    pub error: Option<&'a str>,
}

/// The results as records, one per row in input order (the JSON lines output).
pub fn records<'a>(input: &'a BatchInput, results: &'a [RowResult]) -> Vec<BatchRecord<'a>> {
    let keep = echoed(input);
    let text = |s: &'a str| (!s.is_empty()).then_some(s);
    input
        .rows
        .iter()
        .zip(results)
        .map(|(row, result)| BatchRecord {
            inputs: keep
                .iter()
                .map(|&i| (input.header[i].as_str(), row.cells[i].as_str()))
                .collect(),
            w: text(&result.total),
            digits: result.digits,
            error_estimate: result.error_estimate,
            table_error: result.table_error,
            method: text(&result.method),
            error: text(&result.error),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_record_echoes_the_inputs_and_gives_absent_results_as_null() {
        let text = "id,p0,p1,q1,phi,friction,lambda,compliance,W\n\
                    a,1,0.4,0.5,0.4pi,1,1,\"persson:gamma=1,sigma=1\",old\n\
                    b,1,0.4,5,0.4pi,1,1,\"persson:gamma=1,sigma=1\",old\n";
        let input = read_input(text.as_bytes()).unwrap();
        let results = run(&input, None, Duration::from_secs(10), &|| {});
        let lines: Vec<serde_json::Value> = records(&input, &results)
            .iter()
            .map(|record| serde_json::to_value(record).unwrap())
            .collect();
        // The input's own W column is not echoed: the result's W takes its place.
        assert_eq!(lines[0]["W"], "4.062475792458e-1");
        assert_eq!(lines[0]["id"], "a");
        assert_eq!(lines[0]["compliance"], "persson:gamma=1,sigma=1");
        assert_eq!(lines[0]["digits"], 13);
        assert!(lines[0]["error"].is_null() && lines[0]["table_error"].is_null());
        assert!(lines[1]["W"].is_null() && lines[1]["method"].is_null());
        assert!(lines[1]["error"].as_str().unwrap().contains("gross slip"));
        assert_eq!(lines[0].as_object().unwrap().len(), 14);
    }
}
