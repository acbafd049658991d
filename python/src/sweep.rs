//! The sweep under `dissipation_many`: one W per row of broadcast columns, by the batch's
//! row pool ([`microslip::batch::RowPool`], every row on the path a single run takes):
//! its threads started once per sweep, the next chunk handed in while the last is
//! computed, the GIL released while waiting.

use std::sync::Arc;

use microslip::batch::{InputRow, RowPool, RowResult, Ticket};
use microslip::case::CaseText;
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;

use crate::answer::float_of;
use crate::errors;

/// One input column: a value for every row, a value per row as text, or floats.
#[derive(FromPyObject)]
pub enum Column<'py> {
    Same(String),
    Floats(PyReadonlyArray1<'py, f64>),
    Texts(Vec<String>),
}

impl Column<'_> {
    /// The column's decimal text in row `row`; a float as the shortest decimal that reads
    /// back to it.
    fn cell(&self, row: usize) -> String {
        match self {
            Column::Same(text) => text.clone(),
            Column::Floats(values) => format!("{:e}", values.as_array()[row]),
            Column::Texts(texts) => texts[row].clone(),
        }
    }
}

/// The most worker threads, as on the command line (`--jobs`).
const MOST_JOBS: usize = 1024;

/// Rows handed to the pool at once: two chunks' cases are all the text held at a time.
const ROWS_PER_CHUNK: usize = 1024;

/// The columns of a case, by the names of `Case`'s arguments (`lam` and `nu` None where
/// not given).
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub struct Columns<'py> {
    p0: Column<'py>,
    p1: Column<'py>,
    q0: Column<'py>,
    q1: Column<'py>,
    phi: Column<'py>,
    friction: Column<'py>,
    lam: Option<Column<'py>>,
    nu: Option<Column<'py>>,
    compliance: Column<'py>,
}

impl Columns<'_> {
    fn row(&self, row: usize) -> InputRow {
        let case = CaseText {
            p0: self.p0.cell(row),
            p1: self.p1.cell(row),
            q0: self.q0.cell(row),
            q1: self.q1.cell(row),
            phi: self.phi.cell(row),
            friction: self.friction.cell(row),
            lambda: self.lam.as_ref().map(|c| c.cell(row)),
            nu: self.nu.as_ref().map(|c| c.cell(row)),
            compliance: self.compliance.cell(row),
        };
        InputRow {
            line: row as u64 + 1,
            cells: Vec::new(),
            case: Ok(case),
            path: None,
        }
    }
}

/// W per row, and (row, reason) for each row that gave none.
type Swept<'py> = (Bound<'py, PyArray1<f64>>, Vec<(usize, String)>);

/// W of rows `0..rows` of the columns (each a float array or list of `rows`, or one
/// text for all), and (row, reason) for the rows that gave none.
#[pyfunction]
pub fn sweep<'py>(
    py: Python<'py>,
    columns: Columns<'py>,
    rows: usize,
    digits: Option<u32>,
    max_seconds: f64,
    jobs: Option<usize>,
) -> PyResult<Swept<'py>> {
    let budget = errors::budget(max_seconds)?;
    let threads = match jobs {
        None => rayon::current_num_threads(),
        Some(jobs @ 1..=MOST_JOBS) => jobs,
        Some(jobs) => {
            return Err(errors::refused(format!(
                "jobs = {jobs}: give a whole number of threads from 1 to {MOST_JOBS}, or None for one per core"
            )))
        }
    };
    let pool = RowPool::new(threads, digits, budget);
    let chunk_from = |start: usize| -> Arc<[InputRow]> {
        (start..rows.min(start + ROWS_PER_CHUNK))
            .map(|row| columns.row(row))
            .collect()
    };
    let mut values = Vec::with_capacity(rows);
    let mut failures = Vec::new();
    let mut computing: Option<(Arc<[InputRow]>, Ticket)> = None;
    for start in (0..rows).step_by(ROWS_PER_CHUNK).map(Some).chain([None]) {
        // The next chunk is read (with the GIL) and handed in before the last is awaited.
        let next = start.map(|start| {
            let chunk = chunk_from(start);
            let ticket = pool.hand_in(Arc::clone(&chunk));
            (chunk, ticket)
        });
        if let Some((chunk, ticket)) = computing.take() {
            let results = py.detach(|| pool.collect(ticket, &mut |_| {}));
            record(&chunk, results, &mut values, &mut failures);
            py.check_signals()?;
        }
        computing = next;
    }
    Ok((values.into_pyarray(py), failures))
}

/// Each row's printed W as a float into `values` (NaN where it failed, with its row and
/// reason into `failures`).
fn record(rows: &[InputRow], results: Vec<RowResult>, values: &mut Vec<f64>, failures: &mut Vec<(usize, String)>) {
    for (row, result) in rows.iter().zip(results) {
        match &result.answer {
            Some(report) if result.succeeded() => values.push(float_of(&report.answer.value)),
            _ => {
                values.push(f64::NAN);
                let prefix = format!("line {}: ", row.line);
                let reason = result
                    .error
                    .strip_prefix(&prefix)
                    .map(str::to_string)
                    .unwrap_or(result.error);
                failures.push((row.line as usize - 1, reason));
            }
        }
    }
}
