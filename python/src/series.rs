//! `series(case, order)` (partial sums W_N beside W) and `small_amplitude(rho, phi)`
//! (the coefficient I(ρ, φ)), as `microslip series` and `microslip small-amplitude`
//! print them.

use microslip::answer::remainders::{case_remainders, CaseRemainders};
use microslip::answer::series::{coefficient_answer, partial_sum_answers, PartialSums};
use microslip::answer::Provenance;
use pyo3::prelude::*;

use crate::answer::PyAnswer;
use crate::case::{decimal_text, PyCase};
use crate::errors;

/// A case's partial sums W_N (N = 1 … order) of the small-amplitude series beside W, with
/// their proven remainders.
#[pyclass(name = "Series", module = "microslip", frozen)]
pub struct PySeries {
    sums: PartialSums,
    /// `None` where W is exactly 0, and every W_N with it.
    remainders: Option<CaseRemainders>,
}

#[pymethods]
impl PySeries {
    /// W, as `dissipation(case, digits)` gives it.
    #[getter]
    fn dissipation(&self) -> PyAnswer {
        PyAnswer::of(self.sums.dissipation.clone())
    }

    /// W_N at index N − 1.
    #[getter]
    fn partial_sums(&self) -> Vec<PyAnswer> {
        self.sums.sums.iter().cloned().map(PyAnswer::of).collect()
    }

    /// W_N − W at index N − 1.
    #[getter]
    fn differences(&self) -> Vec<PyAnswer> {
        self.sums.differences.iter().cloned().map(PyAnswer::of).collect()
    }

    /// At index N − 1, a proven upper bound on |W − W_N| (0 where W is exactly 0).
    #[getter]
    fn remainder_bounds(&self) -> Vec<f64> {
        match &self.remainders {
            Some(remainders) => remainders.bounds.clone(),
            None => vec![0.0; self.sums.sums.len()],
        }
    }

    /// At index N − 1, whether W ≥ W_N is proven, so that W lies in [W_N, W_N + bound]
    /// (as for a completely monotone v' at even N).
    #[getter]
    fn lower_bound_of_w(&self) -> Vec<bool> {
        match &self.remainders {
            Some(remainders) => remainders.from_below.clone(),
            None => vec![true; self.sums.sums.len()],
        }
    }

    /// W enclosed by the series alone: the narrowest W_N with its remainder's enclosure.
    #[getter]
    fn series_w(&self) -> PyAnswer {
        PyAnswer::of(self.remainders.as_ref().map_or_else(
            || self.sums.dissipation.clone(),
            |remainders| remainders.series_w.clone(),
        ))
    }

    fn __repr__(&self) -> String {
        let sums: Vec<String> = self.sums.sums.iter().map(|s| s.value.decimal.to_string()).collect();
        format!(
            "Series(W={}, partial_sums=[{}])",
            self.sums.dissipation.value.decimal,
            sums.join(", ")
        )
    }
}

/// The partial sums W_1 … W_order of the case's small-amplitude series beside its W,
/// each to `digits` proven digits (15 without).
#[pyfunction]
#[pyo3(signature = (case, order, digits=None, max_seconds=60.0))]
pub fn series(
    py: Python<'_>,
    case: &Bound<'_, PyCase>,
    order: usize,
    digits: Option<u32>,
    max_seconds: f64,
) -> PyResult<PySeries> {
    let budget = errors::budget(max_seconds)?;
    let text = case.get().text.clone();
    let (sums, remainders) = py
        .detach(|| {
            let sums = partial_sum_answers(&text, order, digits, budget)?;
            let remainders = match sums.dissipation.provenance {
                Provenance::Exact(_) => None,
                _ => Some(case_remainders(&text, order, None)?),
            };
            Ok::<_, microslip::answer::series::ExactAnswerError>((sums, remainders))
        })
        .map_err(errors::of)?;
    Ok(PySeries { sums, remainders })
}

/// The small-amplitude coefficient I(ρ, φ), ρ = Q1/(f P1), to `digits` proven digits
/// (15 without).
#[pyfunction]
#[pyo3(signature = (rho, phi, digits=None, max_seconds=60.0))]
pub fn small_amplitude(
    py: Python<'_>,
    rho: &Bound<'_, PyAny>,
    phi: &Bound<'_, PyAny>,
    digits: Option<u32>,
    max_seconds: f64,
) -> PyResult<PyAnswer> {
    let budget = errors::budget(max_seconds)?;
    let (rho, phi) = (decimal_text(rho, "rho")?, decimal_text(phi, "phi")?);
    let answer = py
        .detach(|| coefficient_answer(&rho, &phi, digits, budget))
        .map_err(errors::of)?;
    Ok(PyAnswer::of(answer))
}
