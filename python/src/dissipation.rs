//! `dissipation(case)`: W by the one policy ([`dissipation_report`]), off the GIL.

use microslip::answer::dissipation::dissipation_report;
use pyo3::prelude::*;

use crate::answer::PyAnswer;
use crate::case::PyCase;
use crate::errors;

/// W and its segments for one case, as `microslip dissipation` prints them.
#[pyfunction]
#[pyo3(signature = (case, digits=None, max_seconds=60.0))]
pub fn dissipation(
    py: Python<'_>,
    case: &Bound<'_, PyCase>,
    digits: Option<u32>,
    max_seconds: f64,
) -> PyResult<PyAnswer> {
    let budget = errors::budget(max_seconds)?;
    let text = case.get().text.clone();
    let report = py
        .detach(|| dissipation_report(&text, digits, budget))
        .map_err(errors::of)?;
    Ok(PyAnswer::of_report(report))
}
