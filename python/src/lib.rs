//! The Python module `microslip._microslip`: W, its series, the small-amplitude
//! coefficient, the simulation and any periodic load path, as the command line computes
//! and prints them, and the harmonic-balance friction element `aft`.
//!
//! Each concept is one module of conversion between Python and the library, so that the
//! binding follows the library's API by changing that module alone.

use pyo3::prelude::*;

mod aft;
mod answer;
mod case;
mod dissipation;
mod errors;
mod path;
mod series;
mod simulation;
mod sweep;

#[pymodule]
fn _microslip(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add("__version__", env!("CARGO_PKG_VERSION"))?;
    module.add_class::<case::PyCase>()?;
    module.add_class::<answer::PyAnswer>()?;
    module.add_class::<series::PySeries>()?;
    module.add_class::<simulation::PySimulation>()?;
    module.add_class::<path::PyPath>()?;
    module.add_function(wrap_pyfunction!(dissipation::dissipation, module)?)?;
    module.add_function(wrap_pyfunction!(sweep::sweep, module)?)?;
    module.add_function(wrap_pyfunction!(case::decimal_text_of, module)?)?;
    module.add_function(wrap_pyfunction!(series::series, module)?)?;
    module.add_function(wrap_pyfunction!(series::small_amplitude, module)?)?;
    module.add_function(wrap_pyfunction!(simulation::simulate, module)?)?;
    module.add_function(wrap_pyfunction!(aft::aft, module)?)?;
    module.add_function(wrap_pyfunction!(path::path_of_text, module)?)?;
    Ok(())
}
