//! `simulate(case)`: W by the independent history simulation, with its steady loop, as
//! `microslip simulate` computes it.

use std::time::Instant;

use microslip::answer::{Answer, Provenance, Value};
use microslip::batch;
use microslip::case::Case;
use microslip::real::Precision;
use microslip::simulate::{simulate as simulate_cycle, SimulationError, SimulationOptions, SimulationResult};
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::answer::PyAnswer;
use crate::case::PyCase;
use crate::errors;

/// The simulation's W and steady loop.
#[pyclass(name = "Simulation", module = "microslip", frozen)]
pub struct PySimulation {
    result: SimulationResult,
}

impl PySimulation {
    /// A measure of W with the absolute bound the estimated relative error gives it.
    fn answer(&self, w: f64) -> PyAnswer {
        let bound = self.result.estimated_rel_error * self.result.w_work.abs();
        PyAnswer::of(Answer {
            value: Value::from_f64(w, bound),
            segments: None,
            digits_requested: None,
            provenance: Provenance::Simulated { error_estimate: bound },
            method: None,
        })
    }
}

#[pymethods]
impl PySimulation {
    /// W as the work of the loads over the steady cycle.
    #[getter]
    #[allow(non_snake_case)]
    fn W(&self) -> PyAnswer {
        self.answer(self.result.w_work)
    }

    /// W as the frictional work of the slipping elements (agrees with `W`).
    #[getter]
    fn w_friction(&self) -> PyAnswer {
        self.answer(self.result.w_friction)
    }

    /// The estimated relative error of W (an estimate from the refinements, not a proof).
    #[getter]
    fn estimated_rel_error(&self) -> f64 {
        self.result.estimated_rel_error
    }

    /// Elements of the finest run.
    #[getter]
    fn elements(&self) -> usize {
        self.result.elements
    }

    /// Load steps per cycle of the finest run.
    #[getter]
    fn steps(&self) -> usize {
        self.result.steps
    }

    /// The steady loop as arrays `theta`, `P`, `Q`, `u` (the columns of `--loop`).
    #[getter(r#loop)]
    fn steady_loop<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let samples = &self.result.steady_loop;
        let column = |of: fn(&microslip::simulate::LoopSample) -> f64| samples.iter().map(of).collect::<Vec<f64>>();
        let dict = PyDict::new(py);
        dict.set_item("theta", column(|s| s.theta).into_pyarray(py))?;
        dict.set_item("P", column(|s| s.normal_load).into_pyarray(py))?;
        dict.set_item("Q", column(|s| s.tangential_load).into_pyarray(py))?;
        dict.set_item("u", column(|s| s.displacement).into_pyarray(py))?;
        Ok(dict)
    }

    fn __repr__(&self) -> String {
        format!(
            "Simulation(W={}, estimated_rel_error={:.1e}, elements={}, steps={})",
            self.W().value(),
            self.result.estimated_rel_error,
            self.result.elements,
            self.result.steps
        )
    }
}

/// The simulation's failures, split as the command line splits them.
fn simulation_error(error: SimulationError) -> PyErr {
    match error {
        SimulationError::ToleranceNotReached { .. } | SimulationError::OutOfTime { .. } => errors::failed(error),
        other => errors::refused(other),
    }
}

/// W of the case by the time-stepped history simulation (an independent estimate, not a
/// proof), from `elements` and `steps` (defaults 400 and 1200) doubled twice, failing
/// where its estimated relative error exceeds `tolerance`.
#[pyfunction]
#[pyo3(signature = (case, elements=None, steps=None, tolerance=1e-6, max_seconds=60.0))]
pub fn simulate(
    py: Python<'_>,
    case: &Bound<'_, PyCase>,
    elements: Option<usize>,
    steps: Option<usize>,
    tolerance: f64,
    max_seconds: f64,
) -> PyResult<PySimulation> {
    let budget = errors::budget(max_seconds)?;
    let spec = case.get().text.spec().map_err(errors::refused)?;
    let Case { mut cycle, compliance } = spec.at::<f64>(Precision::DOUBLE).map_err(errors::refused)?;
    if let Err(error) = cycle.validate() {
        return Err(errors::failed(format!(
            "rounded to f64 the inputs cross a boundary that the exact cycle keeps off (in f64: {error}); the simulation runs in f64, `dissipation` computes this cycle"
        )));
    }
    // The simulation follows the loads in time: the mirror image a phase near an odd
    // multiple of π is read as is turned back.
    if spec.phase().is_mirror_image() {
        cycle.phase += std::f64::consts::PI;
        cycle.mean_tangential_load = -cycle.mean_tangential_load;
    }
    batch::check_table_range(spec.compliance(), &cycle).map_err(errors::refused)?;
    let options = SimulationOptions {
        elements,
        steps,
        deadline: Some(Instant::now() + budget),
        tolerance: Some(tolerance),
        ..SimulationOptions::default()
    };
    let result = py
        .detach(|| simulate_cycle(&cycle, compliance.as_ref(), &options))
        .map_err(simulation_error)?;
    if result.w_work == 0.0 && result.w_friction == 0.0 && spec.exact_zero().is_none() {
        return Err(errors::failed(
            "the simulation's W rounds to 0 in f64 (the changes of v' over the cycle's loads underflow), though nothing in the input makes W exactly 0; `dissipation` gives W at any size",
        ));
    }
    Ok(PySimulation { result })
}
