//! The friction element whose normal load varies over the period with the displacement's
//! harmonics: the spring bed graded to the load's range, or Masing's exact element where
//! the load is constant.

use crate::compliance::{check_admissible, parse_spec, Compliance};
use crate::real::Precision;

use super::fourier::Layout;
use super::spring_bed::SpringBed;
use super::varying_load::LoadedBed;
use super::{check_contact, sampled_displacement, AftError, AftForce, FrictionElement, ADMISSIBLE_FROM};

/// The elements of the bed unless asked otherwise: at 128 time points W within about 1e−3
/// of the converged map's (3e−3 in the deepest microslip, whose slip annulus few elements
/// span), measured in proofs/aft.md.
pub const DEFAULT_ELEMENTS: usize = 256;

/// The fewest and the most elements of a bed.
const ELEMENT_RANGE: std::ops::RangeInclusive<usize> = 16..=1 << 20;

/// A periodic normal load P(t) = p0 + Σ_j C_j b_j(t) in the displacement's harmonic layout
/// (the coefficients ordered as U: [C_0 if `harmonics` holds 0, cos k₁, sin k₁, …]),
/// sampled at `time_points` equal steps of one period.
#[derive(Clone, Copy, Debug)]
pub struct NormalLoad<'a> {
    /// p0, the mean normal load (C_0, where given, adds to it).
    pub mean: f64,
    /// The harmonic numbers, strictly increasing: those of the displacement.
    pub harmonics: &'a [usize],
    /// The normal load's harmonic coefficients, in the displacement's order.
    pub coefficients: &'a [f64],
    /// The time points per period.
    pub time_points: usize,
}

/// A contact with friction coefficient f, compliance ratio λ and normal compliance v(P)
/// under the periodic normal load P(t) > 0, for [`aft_with_normal_load`].
#[derive(Debug)]
pub struct VaryingLoadElement {
    harmonics: Vec<usize>,
    time_points: usize,
    kind: Kind,
}

#[derive(Debug)]
enum Kind {
    /// P constant: Masing's relation, exact.
    Constant(FrictionElement),
    /// P varying: the spring bed.
    Varying(Box<Varying>),
}

/// The bed and what its elements hold at each sample of P.
#[derive(Debug)]
struct Varying {
    bed: SpringBed,
    normal_load: Vec<f64>,
    approach: Vec<f64>,
    base_capacity: Vec<f64>,
    touching: Vec<usize>,
    scale: f64,
    compliance_ratio: f64,
}

/// The normal load's coefficients checked: as many as the layout has, and finite.
fn check_coefficients(load: &NormalLoad, layout: &Layout) -> Result<(), AftError> {
    if load.coefficients.len() != layout.coefficients() {
        return Err(AftError::NormalLoadLength {
            given: load.coefficients.len(),
            expected: layout.coefficients(),
            harmonics: load.harmonics.to_vec(),
        });
    }
    if let Some((index, &value)) = load.coefficients.iter().enumerate().find(|(_, c)| !c.is_finite()) {
        return Err(AftError::NormalLoadNotFinite { index, value });
    }
    Ok(())
}

impl VaryingLoadElement {
    /// The element for the normal load `load`, f = `friction` > 0, λ = `compliance_ratio`
    /// in [1, 2], a compliance admissible (v' > 0, v'' ≤ 0) up to the highest P, and a bed of
    /// `elements` spring elements (at least 16; [`DEFAULT_ELEMENTS`] is a fair default).
    /// Where the load's coefficients are all zero the element is Masing's
    /// ([`FrictionElement`]), exact and without a bed. Refused where P(t_n) ≤ 0 at a time
    /// point (naming it).
    pub fn new(
        load: &NormalLoad,
        friction: f64,
        compliance_ratio: f64,
        compliance: Box<dyn Compliance<f64>>,
        elements: usize,
    ) -> Result<Self, AftError> {
        let layout = Layout::cached(load.harmonics, load.time_points)?;
        check_coefficients(load, &layout)?;
        let element = |kind| VaryingLoadElement {
            harmonics: load.harmonics.to_vec(),
            time_points: load.time_points,
            kind,
        };
        // C_0 (where k = 0 is among the harmonics, it comes first) only shifts the mean.
        let start = usize::from(load.harmonics.first() == Some(&0));
        if load.coefficients[start..].iter().all(|&c| c == 0.0) {
            let mean = load.mean + load.coefficients[..start].iter().sum::<f64>();
            let masing = FrictionElement::new(mean, friction, compliance_ratio, compliance)?;
            return Ok(element(Kind::Constant(masing)));
        }
        check_contact(friction, compliance_ratio)?;
        if !ELEMENT_RANGE.contains(&elements) {
            return Err(AftError::Parameter {
                quantity: "the number of elements",
                value: elements as f64,
                requirement: "must lie in [16, 1048576]",
            });
        }
        let normal_load: Vec<f64> = layout
            .synthesize(load.coefficients)
            .iter()
            .map(|p| load.mean + p)
            .collect();
        if let Some((time_point, &load)) = normal_load
            .iter()
            .enumerate()
            .find(|(_, p)| !(**p > 0.0 && p.is_finite()))
        {
            return Err(AftError::Separation { time_point, load });
        }
        let lowest = normal_load.iter().copied().fold(f64::INFINITY, f64::min);
        let highest = normal_load.iter().copied().fold(0.0, f64::max);
        check_admissible(compliance.as_ref(), &(highest * ADMISSIBLE_FROM), &highest)?;
        let approach: Vec<f64> = normal_load.iter().map(|p| compliance.approach(p)).collect();
        if let Some(&bad) = approach.iter().find(|v| !v.is_finite()) {
            return Err(AftError::UndefinedApproach { approach: bad });
        }
        let bed = SpringBed::new(compliance.as_ref(), lowest, highest, elements);
        let scale = compliance_ratio * friction;
        let base_capacity = normal_load
            .iter()
            .zip(&approach)
            .map(|(&p, &v)| {
                if bed.base_stiffness() > 0.0 {
                    scale * bed.base_normal_load(p, v).max(0.0) / bed.base_stiffness()
                } else {
                    0.0
                }
            })
            .collect();
        let touching = normal_load.iter().map(|&p| bed.touching(p)).collect();
        Ok(element(Kind::Varying(Box::new(Varying {
            bed,
            normal_load,
            approach,
            base_capacity,
            touching,
            scale,
            compliance_ratio,
        }))))
    }

    /// The element with the compliance given as a SPEC (`hertz:r=1,estar=1`, …).
    pub fn from_spec(
        load: &NormalLoad,
        friction: f64,
        compliance_ratio: f64,
        spec: &str,
        elements: usize,
    ) -> Result<Self, AftError> {
        let compliance = parse_spec::<f64>(spec, Precision::DOUBLE)?;
        VaryingLoadElement::new(load, friction, compliance_ratio, compliance, elements)
    }

    /// P(t_n) at the time points (empty where the load is constant).
    pub fn normal_load_samples(&self) -> &[f64] {
        match &self.kind {
            Kind::Constant(_) => &[],
            Kind::Varying(varying) => &varying.normal_load,
        }
    }

    /// The spring elements of the bed, the base element among them where K(0) > 0 (none
    /// where the load is constant: Masing's element needs none).
    pub fn elements(&self) -> usize {
        match &self.kind {
            Kind::Constant(_) => 0,
            Kind::Varying(varying) => varying.bed.entry.len() - varying.bed.first(),
        }
    }
}

impl Varying {
    fn loaded(&self) -> LoadedBed<'_> {
        LoadedBed {
            bed: &self.bed,
            normal_load: &self.normal_load,
            approach: &self.approach,
            base_capacity: &self.base_capacity,
            touching: &self.touching,
            scale: self.scale,
            compliance_ratio: self.compliance_ratio,
        }
    }
}

/// The friction force's harmonics and their exact Jacobian (of the sampled map) for the
/// tangential displacement with harmonics `displacement`, in the layout (harmonics, time
/// points) the element's normal load was given in.
pub fn aft_with_normal_load(element: &VaryingLoadElement, displacement: &[f64]) -> Result<AftForce, AftError> {
    let varying = match &element.kind {
        Kind::Constant(masing) => return super::aft(masing, &element.harmonics, displacement, element.time_points),
        Kind::Varying(varying) => varying,
    };
    let layout = Layout::cached(&element.harmonics, element.time_points)?;
    let samples = sampled_displacement(&layout, &element.harmonics, displacement)?;
    let steady = varying.loaded().steady_period(&samples, &layout);
    Ok(AftForce {
        harmonics: element.harmonics.clone(),
        displacement: displacement.to_vec(),
        force: layout.analyze(&steady.load),
        jacobian: layout.analyze_gradients(&steady.gradient),
        displacement_samples: samples,
        load_samples: steady.load,
    })
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::aft::varying_load::SteadyPeriod;

    /// The steady period of a Hertz contact (P = 1 + the load's harmonics, f = 0.5, λ = 1.2,
    /// 256 elements, h = [0, 1, 3], 128 time points) under the displacement's harmonics.
    pub(in crate::aft) fn loaded_period(normal: &[f64], displacement: &[f64]) -> SteadyPeriod {
        let harmonics = [0, 1, 3];
        let load = NormalLoad {
            mean: 1.0,
            harmonics: &harmonics,
            coefficients: normal,
            time_points: 128,
        };
        let element = VaryingLoadElement::from_spec(&load, 0.5, 1.2, "hertz:r=1,estar=100", DEFAULT_ELEMENTS).unwrap();
        let Kind::Varying(varying) = &element.kind else {
            panic!("the load {normal:?} varies");
        };
        let layout = Layout::cached(&harmonics, 128).unwrap();
        let samples = sampled_displacement(&layout, &harmonics, displacement).unwrap();
        varying.loaded().steady_period(&samples, &layout)
    }
}
