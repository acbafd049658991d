//! `Answer`: a printed value with its digits, enclosure and provenance
//! ([`microslip::answer::Answer`]), and for W what the policy says beside it.

use microslip::answer::dissipation::DissipationAnswer;
use microslip::answer::{Answer, Decimal, Provenance, Value};
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A value as printed by the one rule, with what vouches for it.
#[pyclass(name = "Answer", module = "microslip", frozen)]
#[derive(Clone)]
pub struct PyAnswer {
    answer: Answer,
    /// Why W's digits rest on agreement of two precisions rather than an enclosure.
    no_enclosure: Option<String>,
    /// For a table compliance: the estimated error of W due to the table.
    table_error: Option<f64>,
    /// The absolute quadrature error estimate of an f64 W (or of a table's).
    error_estimate: Option<f64>,
}

impl PyAnswer {
    /// A value without a W's reports (a coefficient, a partial sum, a simulated W).
    pub fn of(answer: Answer) -> Self {
        let error_estimate = match answer.provenance {
            Provenance::Simulated { error_estimate } => Some(error_estimate),
            _ => None,
        };
        PyAnswer {
            answer,
            no_enclosure: None,
            table_error: None,
            error_estimate,
        }
    }

    /// W as the policy of [`microslip::answer::dissipation`] gave it.
    pub fn of_report(report: DissipationAnswer) -> Self {
        let table_error = report.table.as_ref().map(|table| table.error);
        let quadrature_error = report.table.as_ref().map(|table| table.quadrature_error);
        PyAnswer {
            no_enclosure: report.no_enclosure.as_ref().map(ToString::to_string),
            table_error,
            error_estimate: quadrature_error.or(PyAnswer::of(report.answer.clone()).error_estimate),
            answer: report.answer,
        }
    }
}

/// The digits as JSON prints them: None where not one digit is determined.
fn printed(value: &Value) -> Option<String> {
    (value.digits() > 0).then(|| value.decimal.to_string())
}

/// The nearest float to the printed digits (NaN where none is determined).
pub fn float_of(value: &Value) -> f64 {
    match &value.decimal {
        Decimal::Zero => 0.0,
        Decimal::Digits { text, .. } => text.parse().unwrap_or(f64::NAN),
        Decimal::Undetermined { .. } => f64::NAN,
    }
}

#[pymethods]
impl PyAnswer {
    /// The nearest float to the printed digits; NaN where not one digit is determined.
    #[getter]
    pub fn value(&self) -> f64 {
        float_of(&self.answer.value)
    }

    /// The significant digits printed.
    #[getter]
    fn digits(&self) -> u32 {
        self.answer.digits()
    }

    /// The digits proven (by an enclosure, or exactly); 0 where they are estimated.
    #[getter]
    fn digits_certified(&self) -> u32 {
        self.answer.digits_certified()
    }

    /// The value as printed (`"4.062475792458e-1"`, `"0"`); None where not one digit is
    /// determined.
    #[getter]
    fn text(&self) -> Option<String> {
        printed(&self.answer.value)
    }

    /// Decimal ends, rounded outwards, of an interval that contains the value (proven for
    /// a proven provenance); None for an exact value.
    #[getter]
    fn enclosure(&self) -> Option<(String, String)> {
        self.answer.value.enclosure.clone()
    }

    /// What vouches for the value: `exact`, `certified`, `agreement`, `estimate`,
    /// `table_error` or `simulated`.
    #[getter]
    fn provenance(&self) -> &'static str {
        self.answer.provenance.key()
    }

    /// The provenance as the command line words it.
    #[getter]
    fn provenance_text(&self) -> String {
        self.answer.provenance.to_string()
    }

    /// Whether the printed digits are proven.
    #[getter]
    fn proven(&self) -> bool {
        self.answer.provenance.is_proven()
    }

    /// The working precision in bits (53 for f64; None for an exact value).
    #[getter]
    fn precision_bits(&self) -> Option<u32> {
        self.answer.provenance.precision_bits()
    }

    /// The binary64 value computed, where the digits come from an f64 run.
    #[getter]
    fn value_f64(&self) -> Option<f64> {
        self.answer.value.binary64
    }

    /// W's segments EB, BC, CH, HE as printed (None for a value without segments; a
    /// segment None where not one of its digits is determined).
    #[getter]
    fn segments<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(segments) = &self.answer.segments else {
            return Ok(None);
        };
        let dict = PyDict::new(py);
        for (name, value) in segments.named() {
            dict.set_item(name, printed(value))?;
        }
        Ok(Some(dict))
    }

    /// How W was computed (`four-segment`, …), where the value is a W.
    #[getter]
    fn method(&self) -> Option<&'static str> {
        self.answer.method.map(microslip::dissipation::Method::key)
    }

    /// Why the digits rest on two precisions agreeing rather than an enclosure.
    #[getter]
    fn no_enclosure(&self) -> Option<String> {
        self.no_enclosure.clone()
    }

    /// The absolute error estimate of an f64 or simulated value.
    #[getter]
    fn error_estimate(&self) -> Option<f64> {
        self.error_estimate
    }

    /// For a table compliance: the estimated error of W due to the table.
    #[getter]
    fn table_error(&self) -> Option<f64> {
        self.table_error
    }

    /// The value as an `mpmath.mpf` carrying its printed digits, or with `interval=True`
    /// its enclosure as an `mpmath.iv.mpf`.
    #[pyo3(signature = (interval=false))]
    fn to_mpmath<'py>(slf: &Bound<'py, Self>, interval: bool) -> PyResult<Bound<'py, PyAny>> {
        convert(slf, "to_mpmath")?.call1((slf, interval))
    }

    /// The enclosure as a python-flint `arb` ball.
    fn to_arb<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyAny>> {
        convert(slf, "to_arb")?.call1((slf,))
    }

    fn __float__(&self) -> f64 {
        self.value()
    }

    fn __repr__(&self) -> String {
        let text = self.answer.value.decimal.to_string();
        format!(
            "Answer({text}, digits={}, provenance={:?})",
            self.digits(),
            self.provenance()
        )
    }
}

/// A conversion of `microslip._convert`, which imports the optional package it needs.
fn convert<'py>(slf: &Bound<'py, PyAnswer>, name: &str) -> PyResult<Bound<'py, PyAny>> {
    slf.py().import("microslip._convert")?.getattr(name)
}

/// A named column of rows: its name and how a row gives its value.
pub type Column<T> = (&'static str, fn(&T) -> f64);

/// Rows as a dict of float64 arrays, one per column, after what `dict` already holds.
pub fn columns<'py, T>(dict: Bound<'py, PyDict>, rows: &[T], named: &[Column<T>]) -> PyResult<Bound<'py, PyDict>> {
    for (name, of) in named {
        let values: Vec<f64> = rows.iter().map(of).collect();
        dict.set_item(*name, values.into_pyarray(dict.py()))?;
    }
    Ok(dict)
}
