//! `simulate(case)`: W by the independent history simulation, with its steady loop, as
//! `microslip simulate` computes it.

use std::time::Instant;

use microslip::answer::simulation::{simulated_answer, SimulatedAnswer};
use microslip::answer::Answer;
use microslip::simulate::SimulationOptions;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::answer::{columns, PyAnswer};
use crate::case::PyCase;
use crate::errors;

/// The simulation's W and steady loop.
#[pyclass(name = "Simulation", module = "microslip", frozen)]
pub struct PySimulation {
    simulated: SimulatedAnswer,
}

#[pymethods]
impl PySimulation {
    /// W as the work of the loads over the steady cycle.
    #[getter]
    #[allow(non_snake_case)]
    fn W(&self) -> PyAnswer {
        PyAnswer::of(self.simulated.answer.clone())
    }

    /// W as the frictional work of the slipping elements (agrees with `W`).
    #[getter]
    fn w_friction(&self) -> PyAnswer {
        PyAnswer::of(Answer {
            value: self.simulated.friction.clone(),
            ..self.simulated.answer.clone()
        })
    }

    /// The estimated relative error of W (an estimate from the refinements, not a proof).
    #[getter]
    fn estimated_rel_error(&self) -> f64 {
        self.simulated.result.estimated_rel_error
    }

    /// Elements of the finest run.
    #[getter]
    fn elements(&self) -> usize {
        self.simulated.result.elements
    }

    /// Load steps per cycle of the finest run.
    #[getter]
    fn steps(&self) -> usize {
        self.simulated.result.steps
    }

    /// The steady loop as arrays `theta`, `P`, `Q`, `u` (the columns of `--loop`).
    #[getter(r#loop)]
    fn steady_loop<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        columns(
            PyDict::new(py),
            &self.simulated.result.steady_loop,
            &[
                ("theta", |s| s.theta),
                ("P", |s| s.normal_load),
                ("Q", |s| s.tangential_load),
                ("u", |s| s.displacement),
            ],
        )
    }

    fn __repr__(&self) -> String {
        format!(
            "Simulation(W={}, estimated_rel_error={:.1e}, elements={}, steps={})",
            self.W().value(),
            self.simulated.result.estimated_rel_error,
            self.simulated.result.elements,
            self.simulated.result.steps
        )
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
    let options = SimulationOptions {
        elements,
        steps,
        deadline: Some(Instant::now() + budget),
        tolerance: Some(tolerance),
        ..SimulationOptions::default()
    };
    // The library decides what the command line decides (the f64 cycle, the tables, a W
    // that underflows), with the same exit code: refused input or a failed run.
    let simulated = py.detach(|| simulated_answer(&spec, &options)).map_err(errors::of)?;
    Ok(PySimulation { simulated })
}
