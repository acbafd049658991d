//! `aft(U, h, …)`: the harmonic-balance friction element ([`microslip::aft`]), its force's
//! harmonics and their exact Jacobian as numpy arrays.

use std::sync::{Arc, Mutex};

use microslip::aft::{
    aft as force_of, aft_with_normal_load, AftForce, FrictionElement, NormalLoad, VaryingLoadElement, DEFAULT_ELEMENTS,
};
use microslip::cycle::compliance_ratio_from_poisson;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;

use crate::errors;

/// What an element is built from: a solver calls `aft` with the same contact at every
/// iteration, so the element last built is kept and reused. The normal load's harmonics,
/// the layout and the bed's size matter only under a varying load (empty or 0 otherwise).
#[derive(PartialEq)]
struct ElementKey {
    normal_load: u64,
    friction: u64,
    compliance_ratio: u64,
    compliance: String,
    normal_harmonics: Vec<u64>,
    harmonics: Vec<usize>,
    time_points: usize,
    elements: usize,
}

impl ElementKey {
    fn new(normal_load: f64, friction: f64, compliance_ratio: f64, compliance: &str) -> Self {
        ElementKey {
            normal_load: normal_load.to_bits(),
            friction: friction.to_bits(),
            compliance_ratio: compliance_ratio.to_bits(),
            compliance: compliance.to_string(),
            normal_harmonics: Vec::new(),
            harmonics: Vec::new(),
            time_points: 0,
            elements: 0,
        }
    }
}

/// The element last built of one kind, with what it was built from.
type LastElement<E> = Mutex<Option<(ElementKey, Arc<E>)>>;

static LAST_ELEMENT: LastElement<FrictionElement> = Mutex::new(None);
static LAST_VARYING_ELEMENT: LastElement<VaryingLoadElement> = Mutex::new(None);

/// The element of `key`: the one kept in `last` where it was built from the same, else
/// built (and validated) by `build` and kept.
fn cached<E>(last: &LastElement<E>, key: ElementKey, build: impl FnOnce() -> PyResult<E>) -> PyResult<Arc<E>> {
    let mut last = last.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some((cached, element)) = last.as_ref() {
        if *cached == key {
            return Ok(Arc::clone(element));
        }
    }
    let element = Arc::new(build()?);
    *last = Some((key, Arc::clone(&element)));
    Ok(element)
}

/// The element of this contact at constant normal load.
fn element(normal_load: f64, friction: f64, compliance_ratio: f64, compliance: &str) -> PyResult<Arc<FrictionElement>> {
    let key = ElementKey::new(normal_load, friction, compliance_ratio, compliance);
    cached(&LAST_ELEMENT, key, || {
        FrictionElement::from_spec(normal_load, friction, compliance_ratio, compliance).map_err(errors::refused)
    })
}

/// The element of this contact under the normal load `load`, with a bed of `elements`.
fn varying_element(
    load: &NormalLoad,
    friction: f64,
    compliance_ratio: f64,
    compliance: &str,
    elements: usize,
) -> PyResult<Arc<VaryingLoadElement>> {
    let key = ElementKey {
        normal_harmonics: load.coefficients.iter().map(|c| c.to_bits()).collect(),
        harmonics: load.harmonics.to_vec(),
        time_points: load.time_points,
        elements,
        ..ElementKey::new(load.mean, friction, compliance_ratio, compliance)
    };
    cached(&LAST_VARYING_ELEMENT, key, || {
        VaryingLoadElement::from_spec(load, friction, compliance_ratio, compliance, elements).map_err(errors::refused)
    })
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

/// Harmonic coefficients (the argument `name`) as a float64 vector, from any array-like.
fn coefficients<'py>(values: &Bound<'py, PyAny>, name: &str) -> PyResult<PyReadonlyArray1<'py, f64>> {
    if let Ok(array) = values.extract::<PyReadonlyArray1<'py, f64>>() {
        return Ok(array);
    }
    let numpy = values.py().import("numpy")?;
    let converted = numpy
        .call_method1("asarray", (values, "float64"))
        .map_err(|error| errors::refused(format!("{name} is not an array of numbers: {error}")))?;
    let dimensions: usize = converted.getattr("ndim")?.extract()?;
    if dimensions != 1 {
        return Err(errors::refused(format!(
            "{name} has {dimensions} dimensions: give a vector of harmonic coefficients [{name}_0, cos k1, sin k1, …]"
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
/// sin h2, …] as tmdsimpy's `aft`), at normal load `p0`, friction coefficient `friction`,
/// compliance ratio `lam` (or Poisson's ratio `nu`) and normal compliance SPEC
/// `compliance`, on `time_points` equal steps of one period. At constant load, Masing's
/// memory on the virgin curve λ f (v(P) − v(P − Q/f)), with gross slip at ±fP. With
/// `p_harmonics` (in U's order, added to p0; P must stay positive at every time point) the
/// normal load varies and the contact is the spring bed of `microslip simulate` with
/// `elements` elements (W within about 1e-3 at 256 and 128 time points; all-zero
/// `p_harmonics` is Masing's element). The Jacobian is the exact derivative of the sampled
/// map, computed with the GIL released. Bad input raises `ValueError`.
#[pyfunction]
#[pyo3(signature = (U, h, p0, friction, compliance, lam=None, nu=None, time_points=128, p_harmonics=None, elements=DEFAULT_ELEMENTS))]
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
    p_harmonics: Option<&Bound<'py, PyAny>>,
    elements: usize,
) -> PyResult<ForceAndJacobian<'py>> {
    let harmonics = harmonic_numbers(h)?;
    let compliance_ratio = compliance_ratio(lam, nu)?;
    let displacement = coefficients(U, "U")?;
    let displacement = displacement.as_slice()?;
    let force = match p_harmonics {
        None => {
            let element = element(p0, friction, compliance_ratio, compliance)?;
            py.detach(|| force_of(&element, &harmonics, displacement, time_points))
        }
        Some(normal) => {
            let normal = coefficients(normal, "p_harmonics")?;
            let load = NormalLoad {
                mean: p0,
                harmonics: &harmonics,
                coefficients: normal.as_slice()?,
                time_points,
            };
            let element = varying_element(&load, friction, compliance_ratio, compliance, elements)?;
            py.detach(|| aft_with_normal_load(&element, displacement))
        }
    };
    arrays(py, force.map_err(errors::refused)?)
}

/// F and dF/dU (n × n) as numpy arrays.
fn arrays(py: Python<'_>, force: AftForce) -> PyResult<ForceAndJacobian<'_>> {
    let width = force.coefficients();
    let jacobian = force.jacobian.into_pyarray(py).reshape([width, width])?;
    Ok((force.force.into_pyarray(py), jacobian))
}
