//! `aft(U, h, …)`: the harmonic-balance friction element ([`microslip::aft`]), its force's
//! harmonics and their exact Jacobian as numpy arrays.

use std::sync::{Arc, Mutex};

use microslip::aft::{aft as force_of, FrictionElement};
use microslip::cycle::compliance_ratio_from_poisson;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;

use crate::errors;

/// What an element is built from: a solver calls `aft` with the same contact at every
/// iteration, so the element last built is kept and reused.
#[derive(PartialEq)]
struct ElementKey {
    normal_load: u64,
    friction: u64,
    compliance_ratio: u64,
    compliance: String,
}

static LAST_ELEMENT: Mutex<Option<(ElementKey, Arc<FrictionElement>)>> = Mutex::new(None);

/// The element of this contact, built (and validated) once for repeated calls.
fn element(normal_load: f64, friction: f64, compliance_ratio: f64, compliance: &str) -> PyResult<Arc<FrictionElement>> {
    let key = ElementKey {
        normal_load: normal_load.to_bits(),
        friction: friction.to_bits(),
        compliance_ratio: compliance_ratio.to_bits(),
        compliance: compliance.to_string(),
    };
    let mut last = LAST_ELEMENT.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some((cached, element)) = last.as_ref() {
        if *cached == key {
            return Ok(Arc::clone(element));
        }
    }
    let element = Arc::new(
        FrictionElement::from_spec(normal_load, friction, compliance_ratio, compliance).map_err(errors::refused)?,
    );
    *last = Some((key, Arc::clone(&element)));
    Ok(element)
}

/// λ from `lam` or from Poisson's ratio `nu`, exactly one of them given.
fn compliance_ratio(lam: Option<f64>, nu: Option<f64>) -> PyResult<f64> {
    match (lam, nu) {
        (Some(lam), None) => Ok(lam),
        (None, Some(nu)) => compliance_ratio_from_poisson(&nu).map_err(errors::refused),
        _ => Err(errors::refused(
            "give exactly one of the compliance ratio lam (λ) and Poisson's ratio nu (ν)",
        )),
    }
}

/// The displacement's harmonics as a float64 vector, from any array-like.
fn coefficients<'py>(displacement: &Bound<'py, PyAny>) -> PyResult<PyReadonlyArray1<'py, f64>> {
    if let Ok(array) = displacement.extract::<PyReadonlyArray1<'py, f64>>() {
        return Ok(array);
    }
    let numpy = displacement.py().import("numpy")?;
    let converted = numpy
        .call_method1("asarray", (displacement, "float64"))
        .map_err(|error| errors::refused(format!("U is not an array of numbers: {error}")))?;
    let dimensions: usize = converted.getattr("ndim")?.extract()?;
    if dimensions != 1 {
        return Err(errors::refused(format!(
            "U has {dimensions} dimensions: give a vector of harmonic coefficients [U_0, cos k1, sin k1, …]"
        )));
    }
    converted.extract()
}

/// The harmonic numbers as whole numbers ≥ 0.
fn harmonic_numbers(harmonics: Vec<i64>) -> PyResult<Vec<usize>> {
    harmonics
        .into_iter()
        .map(|k| {
            usize::try_from(k).map_err(|_| errors::refused(format!("harmonic {k} is negative: give k = 0, 1, 2, …")))
        })
        .collect()
}

/// The force's harmonics F and dF/dU.
type ForceAndJacobian<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray2<f64>>);

/// The friction force's harmonics F and their exact Jacobian dF/dU for a tangential
/// displacement with harmonics `U` (ordered [U_0 if `h` holds 0, cos h1, sin h1, cos h2,
/// sin h2, …] as tmdsimpy's `aft`), at constant normal load `p0`, friction coefficient
/// `friction`, compliance ratio `lam` (or Poisson's ratio `nu`) and normal compliance SPEC
/// `compliance`, on `time_points` equal steps of one period. Masing's memory on the virgin
/// curve λ f (v(P) − v(P − Q/f)), with gross slip at ±fP; the Jacobian is the exact
/// derivative of the sampled map, computed with the GIL released. Bad input raises
/// `ValueError`.
#[pyfunction]
#[pyo3(signature = (U, h, p0, friction, compliance, lam=None, nu=None, time_points=128))]
#[allow(non_snake_case, clippy::too_many_arguments)]
pub fn aft<'py>(
    py: Python<'py>,
    U: &Bound<'py, PyAny>,
    h: Vec<i64>,
    p0: f64,
    friction: f64,
    compliance: &str,
    lam: Option<f64>,
    nu: Option<f64>,
    time_points: usize,
) -> PyResult<ForceAndJacobian<'py>> {
    let harmonics = harmonic_numbers(h)?;
    let element = element(p0, friction, compliance_ratio(lam, nu)?, compliance)?;
    let displacement = coefficients(U)?;
    let displacement = displacement.as_slice()?;
    let force = py
        .detach(|| force_of(&element, &harmonics, displacement, time_points))
        .map_err(errors::refused)?;
    let width = force.coefficients();
    let jacobian = force.jacobian.into_pyarray(py).reshape([width, width])?;
    Ok((force.force.into_pyarray(py), jacobian))
}
