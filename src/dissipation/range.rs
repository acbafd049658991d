//! Whether the magnitudes of a case fit the working precision's exponent range.
//!
//! The integrands multiply up to four magnitudes of the case — (Q − Q0), f, the change
//! of v' and a load rate — and the error estimate multiplies W by ε². In f64 an
//! intermediate that overflows or underflows does not stop the computation: it turns
//! into ∞, 0 or a subnormal, and a product such as d/(x(x + d)) with x(x + d) = ∞ makes
//! W a clean, wrong 0. Rather than trust every formula, the computation is refused
//! up front when one of these magnitudes lies outside a band in which no product of
//! five of them can leave the range held at full precision: [m^(1/5), m^(−1/5)] with
//! m the smallest full-precision magnitude — about 1e±58 in f64, and beyond anything
//! physical in MPFR, whose exponent range is some 2^28 bits wide.
//!
//! The change of v' is also checked against itself: the compliance's own formula for
//! v'(P0 + x) − v'(P0) must agree with the plain difference wherever that difference
//! is resolved, which it cannot if either overflowed or underflowed inside.

use super::error::DissipationError;
use super::options::Options;
use super::slope::slope_at;
use crate::compliance::Compliance;
use crate::cycle::LoadCycle;
use crate::real::Real;

/// Intervals into which the loads the cycle reaches are cut to sample v' (ends included):
/// for an admissible v' (monotone) the largest change is at an end; the rest is for any v'.
const SAMPLES: i64 = 4;

/// Refuses a case with a magnitude outside the band, or whose change of v' about P0
/// comes out differently by its own formula and by subtraction.
pub(crate) fn check_magnitudes<R: Real>(
    cycle: &LoadCycle<R>,
    compliance: &dyn Compliance<R>,
    options: &Options<R>,
    low: &R,
    high: &R,
) -> Result<(), DissipationError> {
    let p0 = &cycle.mean_normal_load;
    let precision = p0.precision();
    let zero = p0.int(0);
    let smallest = R::smallest_full_precision(precision).powr(&p0.ratio(1, 5));
    let largest = p0.int(1) / &smallest;
    let outside = |quantity: &str, value: &R| {
        let magnitude = value.abs();
        (magnitude != zero && (magnitude < smallest || magnitude > largest || !magnitude.is_finite())).then(|| {
            DissipationError::OutsideRange {
                quantity: quantity.to_string(),
                value: value.to_f64_lossy(),
                bits: precision.in_bits(),
                low: smallest.to_f64_lossy(),
                high: largest.to_f64_lossy(),
            }
        })
    };
    let loads = [
        ("P0", p0.clone()),
        ("P1", cycle.normal_amplitude.clone()),
        ("Q1", cycle.tangential_amplitude.clone()),
        ("the friction coefficient f", cycle.friction.clone()),
        ("fP0", cycle.friction.clone() * p0),
    ];
    if let Some(error) = loads.iter().find_map(|(quantity, value)| outside(quantity, value)) {
        return Err(error);
    }
    let slope_at_mean = compliance.slope(p0);
    if options.check_compliance || !options.remove_constant_slope {
        if let Some(error) = outside("v'(P0)", &slope_at_mean) {
            return Err(error);
        }
    }
    let change = slope_at(compliance, p0, true);
    let (from, to) = (low.clone() - p0, high.clone() - p0);
    let mut largest_change = zero.clone();
    for i in 0..=SAMPLES {
        let offset = from.clone() + &((to.clone() - &from) * &zero.ratio(i, SAMPLES));
        let value = change(&offset);
        if !value.is_finite() {
            // Left to the integrals, which say where the compliance is not finite.
            continue;
        }
        largest_change = largest_change.max_of(&value.abs());
        let (at, reference) = (compliance.slope(&(p0.clone() + &offset)), slope_at_mean.clone());
        let plain = at.clone() - &reference;
        let rounding = at.abs().max_of(&reference.abs()) * &zero.epsilon_like() * &zero.int(1 << 20);
        if plain.is_finite() && plain.abs() > rounding {
            let disagreement = (value.clone() - &plain).abs();
            if disagreement > plain.abs() * &zero.ratio(1, 1000) {
                let load = (p0.clone() + &offset).to_f64_lossy();
                return Err(DissipationError::OutsideRange {
                    quantity: format!(
                        "v'(P) − v'(P0) at P = {load:e} by the compliance's formula, against {:e} by subtraction,",
                        plain.to_f64_lossy()
                    ),
                    value: value.to_f64_lossy(),
                    bits: precision.in_bits(),
                    low: smallest.to_f64_lossy(),
                    high: largest.to_f64_lossy(),
                });
            }
        }
    }
    if let Some(error) = outside("the largest change of v' over the cycle's loads", &largest_change) {
        return Err(error);
    }
    Ok(())
}
