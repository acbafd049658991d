//! `path(...)`: W, the amplitudes, the damping, the harmonics of Q and u and the steady
//! loop of a contact under any periodic load path, as `microslip path` computes them
//! (`microslip::answer::path`). The Python side writes the path as the CSV text the
//! command reads; this module only converts the request and the answer.

use std::time::Instant;

use microslip::answer::path::{path_answer, PathAnswer};
use microslip::path::input::Drive;
use microslip::path::{PathFormat, PathRequest, RatioText};
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::answer::columns;
use crate::errors;

/// The samples of the steady loop returned.
const LOOP_POINTS: usize = 1024;

/// A path's W and its outputs.
#[pyclass(name = "PathResult", module = "microslip", frozen)]
pub struct PyPath {
    answer: PathAnswer,
}

#[pymethods]
impl PyPath {
    /// W per cycle as the nearest float to the digits printed.
    #[getter]
    #[allow(non_snake_case)]
    fn W(&self) -> f64 {
        self.answer.w.value
    }

    /// W as printed: the digits its enclosure proves, or that two working precisions agree on.
    #[getter]
    fn text(&self) -> &str {
        &self.answer.w.text
    }

    /// How many significant digits `text` has.
    #[getter]
    fn digits(&self) -> usize {
        let mantissa = self.answer.w.text.split(['e', 'E']).next().unwrap_or_default();
        mantissa.chars().filter(char::is_ascii_digit).count()
    }

    /// How many significant digits the two working precisions agreed on (at least `digits`;
    /// for a proven W, the digits printed).
    #[getter]
    fn digits_agreed(&self) -> u32 {
        self.answer.w.digits_agreed
    }

    /// How many significant digits of W are proven: all printed ones for a proven W, else 0.
    #[getter]
    fn digits_certified(&self) -> u32 {
        self.answer.w.digits_certified
    }

    /// What vouches for W: ``"certified"`` (a rigorous enclosure), ``"exact"`` (a constant Q
    /// dissipates nothing) or ``"agreement"`` (two working precisions agree; not a proof,
    /// with the reason in the text).
    #[getter]
    fn provenance(&self) -> &str {
        self.answer.w.provenance
    }

    /// ``"force"`` or ``"displacement"``: what the path prescribed besides P.
    #[getter]
    fn drive(&self) -> &str {
        match self.answer.drive {
            Drive::Force => "force",
            Drive::Displacement => "displacement",
        }
    }

    /// Half the peak-to-peak of Q (f64, an estimate).
    #[getter]
    fn q_amplitude(&self) -> f64 {
        self.answer.outputs.q_amplitude
    }

    /// Half the peak-to-peak of u (f64, an estimate).
    #[getter]
    fn u_amplitude(&self) -> f64 {
        self.answer.outputs.u_amplitude
    }

    /// q_amplitude / u_amplitude.
    #[getter]
    fn secant_stiffness(&self) -> f64 {
        self.answer.outputs.secant_stiffness
    }

    /// η = W / (π q_amplitude u_amplitude).
    #[getter]
    fn loss_factor(&self) -> f64 {
        self.answer.outputs.loss_factor
    }

    /// ζ = η / 2, the equivalent viscous damping ratio.
    #[getter]
    fn damping_ratio(&self) -> f64 {
        self.answer.outputs.damping_ratio
    }

    /// The harmonics k = 0 … K of Q and u as arrays ``k``, ``Q_cos``, ``Q_sin``, ``u_cos``,
    /// ``u_sin`` (the joint's force in harmonic-balance form).
    #[getter]
    fn harmonics<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let rows = &self.answer.outputs.harmonics;
        let dict = PyDict::new(py);
        let orders: Vec<u64> = rows.iter().map(|row| row.k as u64).collect();
        dict.set_item("k", orders.into_pyarray(py))?;
        columns(
            dict,
            rows,
            &[
                ("Q_cos", |row| row.q_cos),
                ("Q_sin", |row| row.q_sin),
                ("u_cos", |row| row.u_cos),
                ("u_sin", |row| row.u_sin),
            ],
        )
    }

    /// The steady loop as arrays ``theta``, ``P``, ``Q``, ``u`` (the columns of ``--loop``).
    #[getter(r#loop)]
    fn steady_loop<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        columns(
            PyDict::new(py),
            &self.answer.outputs.steady_loop,
            &[
                ("theta", |p| p.theta),
                ("P", |p| p.normal_load),
                ("Q", |p| p.tangential_load),
                ("u", |p| p.displacement),
            ],
        )
    }

    fn __repr__(&self) -> String {
        format!(
            "PathResult(W={}, drive={:?}, loss_factor={:.6e})",
            self.answer.w.text,
            self.drive(),
            self.answer.outputs.loss_factor
        )
    }
}

/// The path whose CSV text is `contents` (harmonics when it has a column ``k``), driven by
/// `drive`, on the contact and compliance given as exact decimal text.
#[pyfunction(name = "_path_of_text")]
#[pyo3(signature = (contents, drive, friction, compliance, lam=None, nu=None, digits=None, max_seconds=60.0, harmonics_out=3))]
#[allow(clippy::too_many_arguments)]
pub fn path_of_text(
    py: Python<'_>,
    contents: String,
    drive: &str,
    friction: String,
    compliance: String,
    lam: Option<String>,
    nu: Option<String>,
    digits: Option<u32>,
    max_seconds: f64,
    harmonics_out: usize,
) -> PyResult<PyPath> {
    let budget = errors::budget(max_seconds)?;
    let drive = match drive {
        "force" => Drive::Force,
        "displacement" => Drive::Displacement,
        other => {
            return Err(errors::refused(format!(
                "drive '{other}' is neither 'force' nor 'displacement'"
            )))
        }
    };
    let ratio = match (lam, nu) {
        (Some(lambda), None) => RatioText::Lambda(lambda),
        (None, Some(nu)) => RatioText::Poisson(nu),
        _ => return Err(errors::refused("give exactly one of lam and nu")),
    };
    if digits.is_some_and(|d| d == 0 || d > 1000) {
        return Err(errors::refused("digits must lie in 1 … 1000"));
    }
    if harmonics_out > 64 {
        return Err(errors::refused("harmonics_out must lie in 0 … 64"));
    }
    let request = PathRequest {
        file: "the path".to_string(),
        format: PathFormat::of_contents(&contents),
        contents,
        drive,
        friction,
        ratio,
        compliance,
        digits,
        deadline: Instant::now() + budget,
        harmonics_out,
        loop_points: LOOP_POINTS,
    };
    let answer = py.detach(|| path_answer(&request)).map_err(errors::of)?;
    Ok(PyPath { answer })
}
