//! `Case`: one load cycle on a contact as exact decimal text ([`CaseText`]), read and
//! validated once on construction.

use microslip::case::CaseText;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyFloat, PyInt, PyString};

use crate::errors;

/// The decimal text of a number given from Python: a string as written (`"0.4pi"`,
/// `"1e-300"`), an integer exactly, a float as the shortest decimal that reads back to it
/// (its `repr`), a `decimal.Decimal` exactly.
pub fn decimal_text(value: &Bound<'_, PyAny>, field: &str) -> PyResult<String> {
    if let Ok(text) = value.cast::<PyString>() {
        return Ok(text.to_str()?.to_string());
    }
    let type_name = value.get_type().name()?;
    if value.is_instance_of::<PyBool>() || matches!(type_name.to_str()?, "bool" | "bool_") {
        return Err(PyTypeError::new_err(format!(
            "{field}: a boolean is not a number; give a number or a decimal string"
        )));
    }
    if value.is_instance_of::<PyInt>() {
        return Ok(value.str()?.to_str()?.to_string());
    }
    // Integers of other types (numpy's) convert exactly through `__index__`.
    if let Ok(index) = value.call_method0("__index__") {
        return Ok(index.str()?.to_str()?.to_string());
    }
    let py = value.py();
    let decimal = py.import("decimal")?.getattr("Decimal")?;
    if value.is_instance(&decimal)? {
        return Ok(value.str()?.to_str()?.to_string());
    }
    // Python's float, numpy's floats and anything else that converts to one.
    if let Ok(float) = value.extract::<f64>() {
        return Ok(PyFloat::new(py, float).repr()?.to_str()?.to_string());
    }
    Err(PyTypeError::new_err(format!(
        "{field}: {} is not a number; give a number or a decimal string",
        type_name
    )))
}

/// One load cycle P = P0 + P1 cos θ, Q = Q0 + Q1 cos(θ − φ) on a contact of friction
/// coefficient f, compliance ratio λ (or Poisson's ratio ν) and normal compliance SPEC.
#[pyclass(name = "Case", module = "microslip", frozen)]
pub struct PyCase {
    pub text: CaseText,
}

#[pymethods]
impl PyCase {
    #[new]
    #[pyo3(signature = (p0, p1, q1, phi, friction, compliance, lam=None, nu=None, q0=None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        p0: &Bound<'_, PyAny>,
        p1: &Bound<'_, PyAny>,
        q1: &Bound<'_, PyAny>,
        phi: &Bound<'_, PyAny>,
        friction: &Bound<'_, PyAny>,
        compliance: &str,
        lam: Option<&Bound<'_, PyAny>>,
        nu: Option<&Bound<'_, PyAny>>,
        q0: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let optional = |value: Option<&Bound<'_, PyAny>>, field| value.map(|v| decimal_text(v, field)).transpose();
        let text = CaseText {
            p0: decimal_text(p0, "p0")?,
            p1: decimal_text(p1, "p1")?,
            q0: optional(q0, "q0")?.unwrap_or_else(|| "0".to_string()),
            q1: decimal_text(q1, "q1")?,
            phi: decimal_text(phi, "phi")?,
            friction: decimal_text(friction, "friction")?,
            lambda: optional(lam, "lam")?,
            nu: optional(nu, "nu")?,
            compliance: compliance.to_string(),
        };
        text.spec().map_err(errors::refused)?;
        Ok(PyCase { text })
    }

    #[getter]
    fn p0(&self) -> &str {
        &self.text.p0
    }

    #[getter]
    fn p1(&self) -> &str {
        &self.text.p1
    }

    #[getter]
    fn q0(&self) -> &str {
        &self.text.q0
    }

    #[getter]
    fn q1(&self) -> &str {
        &self.text.q1
    }

    #[getter]
    fn phi(&self) -> &str {
        &self.text.phi
    }

    #[getter]
    fn friction(&self) -> &str {
        &self.text.friction
    }

    #[getter]
    fn lam(&self) -> Option<&str> {
        self.text.lambda.as_deref()
    }

    #[getter]
    fn nu(&self) -> Option<&str> {
        self.text.nu.as_deref()
    }

    #[getter]
    fn compliance(&self) -> &str {
        &self.text.compliance
    }

    fn __repr__(&self) -> String {
        let t = &self.text;
        let ratio = match (&t.lambda, &t.nu) {
            (Some(lambda), _) => format!("lam={lambda:?}"),
            (None, Some(nu)) => format!("nu={nu:?}"),
            (None, None) => String::new(),
        };
        format!(
            "Case(p0={:?}, p1={:?}, q1={:?}, phi={:?}, friction={:?}, compliance={:?}, {ratio}, q0={:?})",
            t.p0, t.p1, t.q1, t.phi, t.friction, t.compliance, t.q0
        )
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other.cast::<PyCase>().is_ok_and(|other| other.get().text == self.text)
    }
}

/// The decimal text `Case` reads from a number or a string (for the sweep's columns).
#[pyfunction(name = "_decimal_text")]
pub fn decimal_text_of(value: &Bound<'_, PyAny>, field: &str) -> PyResult<String> {
    decimal_text(value, field)
}
