//! Ŵ at one point of a figure, the gross-slip limits that end each curve, and the
//! log–log slopes read off the curves.
//!
//! Every figure is for Persson's compliance v' = C/P (β = −1) in the paper's
//! dimensionless variables. With P0 = f = λ = C = 1 the loads are P̂1 = P1,
//! Q̂1 = Q1 and W itself is Ŵ = W/(Cλf²P0^(β+2)), so a point is one library call.

use rug::Float;

use crate::compliance::Persson;
use crate::cycle::{LoadCycle, ValidCycle};
use crate::dissipation::{constant_normal_load, dissipation, four_segment, Dissipation, DissipationError, Options};
use crate::real::{Precision, Real};

/// The relative error a value may carry for a figure: slopes are central differences
/// over a step of 2·10⁻³ in ln Q̂1, so this keeps them good to about 10⁻⁶.
pub const FIGURE_RELATIVE_ERROR: f64 = 1e-9;

/// The MPFR precisions tried, in turn, where f64 cannot vouch for `FIGURE_RELATIVE_ERROR`.
const MPFR_BITS: [u32; 2] = [128, 256];

/// Which library formula computes a point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Formula {
    /// `dissipation`: the closed forms where the cycle is degenerate, the four-segment
    /// integrals otherwise.
    Chosen,
    /// `four_segment`: the four-segment integrals whatever the cycle (Fig. 4's points).
    FourSegment,
    /// `constant_normal_load`: the P1 = 0 closed form (Fig. 4's line).
    ConstantNormalLoad,
}

/// One point (P̂1, Q̂1, φ/π) of a figure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// P̂1 = P1/P0.
    pub normal: f64,
    /// Q̂1 = Q1/(fP0).
    pub tangential: f64,
    /// φ/π.
    pub phase_over_pi: f64,
}

/// Ŵ at a point, and the working precision that resolved it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Value {
    /// Ŵ = W/(Cλf²P0^(β+2)).
    pub w_hat: f64,
    /// 53 for f64, otherwise the MPFR precision used.
    pub precision_bits: u32,
}

/// Ŵ at a point computed at the working precision of `R`, with the library's error estimate.
pub fn dimensionless_dissipation<R: Real>(
    point: Point,
    formula: Formula,
    precision: Precision,
) -> Result<Dissipation<R>, DissipationError> {
    let one = R::from_i64(1, precision);
    let cycle = LoadCycle {
        mean_normal_load: one.clone(),
        normal_amplitude: R::from_f64(point.normal, precision),
        mean_tangential_load: one.int(0),
        tangential_amplitude: R::from_f64(point.tangential, precision),
        phase: R::from_f64(point.phase_over_pi, precision) * &one.pi_like(),
        friction: one.clone(),
        compliance_ratio: one.clone(),
    };
    let persson = Persson {
        gamma: one.clone(),
        sigma: one,
    };
    let options = Options::default();
    match formula {
        Formula::Chosen => dissipation(&cycle, &persson, &options),
        Formula::FourSegment => four_segment(&cycle, &persson, &options),
        Formula::ConstantNormalLoad => constant_normal_load(&ValidCycle::new(cycle)?, &persson, &options),
    }
}

/// Ŵ to `FIGURE_RELATIVE_ERROR`: in f64 where its error estimate vouches for that
/// (or the formula gives an exact zero), otherwise in MPFR at 128 and then 256 bits.
/// Errors other than ill-conditioning or missed accuracy (gross slip, say) are returned
/// as they are.
pub fn resolved(point: Point, formula: Formula) -> Result<Value, DissipationError> {
    let mut last = match dimensionless_dissipation::<f64>(point, formula, Precision::DOUBLE) {
        Ok(result) if vouched(result.total, result.error_estimate) => {
            return Ok(Value {
                w_hat: result.total,
                precision_bits: 53,
            })
        }
        Ok(result) => DissipationError::NotConverged {
            points: result.points,
            relative_error: result.error_estimate / result.total.abs(),
            requested: FIGURE_RELATIVE_ERROR,
        },
        Err(error @ (DissipationError::IllConditioned { .. } | DissipationError::OutOfRange { .. })) => error,
        Err(other) => return Err(other),
    };
    for bits in MPFR_BITS {
        match dimensionless_dissipation::<Float>(point, formula, Precision::bits(bits)) {
            Ok(result) => {
                let (total, error) = (result.total.to_f64(), result.error_estimate.to_f64());
                if vouched(total, error) {
                    return Ok(Value {
                        w_hat: total,
                        precision_bits: bits,
                    });
                }
                last = DissipationError::NotConverged {
                    points: result.points,
                    relative_error: error / total.abs(),
                    requested: FIGURE_RELATIVE_ERROR,
                };
            }
            Err(error) => last = error,
        }
    }
    Err(last)
}

/// Whether an error estimate vouches for a value to `FIGURE_RELATIVE_ERROR` (an exact zero counts).
fn vouched(total: f64, error: f64) -> bool {
    (total == 0.0 && error == 0.0) || (total.is_finite() && error <= total.abs() * FIGURE_RELATIVE_ERROR)
}

/// The largest Q̂1 before gross slip at fixed P̂1 and φ (Q0 = 0): the ellipse touches
/// |Q| = fP when the larger amplitude of Q ± fP, √(Q̂1² + P̂1² + 2P̂1Q̂1|cos φ|), reaches 1:
/// Q̂1 = √(1 − P̂1² sin²φ) − P̂1|cos φ|.
pub fn gross_slip_amplitude(normal: f64, phase_over_pi: f64) -> f64 {
    let (sin, cos) = (std::f64::consts::PI * phase_over_pi).sin_cos();
    (1.0 - normal * normal * sin * sin).sqrt() - normal * cos.abs()
}

/// The largest Q̂1 before gross slip along the line P̂1 = ratio·Q̂1 at phase φ:
/// Q̂1 = 1/√(1 + r² + 2r|cos φ|).
pub fn gross_slip_amplitude_at_ratio(ratio: f64, phase_over_pi: f64) -> f64 {
    let cos = (std::f64::consts::PI * phase_over_pi).cos().abs();
    1.0 / (1.0 + ratio * ratio + 2.0 * ratio * cos).sqrt()
}

/// Half-width, in ln Q̂1, of the central difference a local slope is taken over.
const SLOPE_STEP: f64 = 1e-3;

/// The local log–log slope d ln Ŵ / d ln Q̂1 at `amplitude`, with the point's other
/// coordinates from `at(Q̂1)`; also the largest precision it needed.
pub fn local_slope(amplitude: f64, at: &dyn Fn(f64) -> Point) -> Result<(f64, u32), DissipationError> {
    let above = resolved(at(amplitude * SLOPE_STEP.exp()), Formula::Chosen)?;
    let below = resolved(at(amplitude * (-SLOPE_STEP).exp()), Formula::Chosen)?;
    let slope = (above.w_hat / below.w_hat).ln() / (2.0 * SLOPE_STEP);
    Ok((slope, above.precision_bits.max(below.precision_bits)))
}

/// One local slope of a limit sequence.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlopeSample {
    /// Q̂1 where the slope was taken.
    pub amplitude: f64,
    /// d ln Ŵ / d ln Q̂1 there.
    pub slope: f64,
    /// The working precision it needed.
    pub precision_bits: u32,
}

/// The limit of the local slope as Q̂1 → 0: local slopes at Q̂1 = `start`·10^(−k/2),
/// k = 0, 1, …, until three in a row differ pairwise by less than 10⁻⁴ (settled to 3
/// decimals; three, so that two samples straddling a turning point do not pass for a limit).
#[derive(Clone, Debug, PartialEq)]
pub struct LimitSlope {
    /// The settled slope, rounded to 3 decimals.
    pub slope: f64,
    /// The Q̂1 of the last sample, where it settled.
    pub settled_at: f64,
    /// Every local slope taken, largest Q̂1 first.
    pub samples: Vec<SlopeSample>,
}

/// Why a limit slope could not be found.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SlopeError {
    /// A value on the way failed.
    #[error("at Q̂1 = {amplitude:e}: {source}")]
    Dissipation {
        amplitude: f64,
        #[source]
        source: DissipationError,
    },
    /// The local slopes still moved at the smallest Q̂1 tried.
    #[error("the local slope had not settled to 3 decimals by Q̂1 = {smallest:e} (last {last})")]
    NotSettled { smallest: f64, last: f64 },
}

/// The smallest Q̂1 a limit sequence goes down to, relative to its start.
const SMALLEST_RELATIVE_AMPLITUDE: f64 = 1e-10;

/// Finds the limit slope as Q̂1 → 0 (see [`LimitSlope`]).
pub fn limit_slope(start: f64, at: &dyn Fn(f64) -> Point) -> Result<LimitSlope, SlopeError> {
    let mut samples: Vec<SlopeSample> = Vec::new();
    for k in 0.. {
        let amplitude = start * 10f64.powf(-f64::from(k) / 2.0);
        if amplitude < start * SMALLEST_RELATIVE_AMPLITUDE {
            break;
        }
        let (slope, precision_bits) =
            local_slope(amplitude, at).map_err(|source| SlopeError::Dissipation { amplitude, source })?;
        let close = |back: usize, other: f64| {
            samples
                .len()
                .checked_sub(back)
                .is_some_and(|i| (samples[i].slope - other).abs() < 1e-4)
        };
        let settled = close(1, slope) && samples.len() >= 2 && close(2, samples[samples.len() - 1].slope);
        samples.push(SlopeSample {
            amplitude,
            slope,
            precision_bits,
        });
        if settled {
            return Ok(LimitSlope {
                slope: (slope * 1000.0).round() / 1000.0,
                settled_at: amplitude,
                samples,
            });
        }
    }
    let last = samples.last().map_or(f64::NAN, |s| s.slope);
    Err(SlopeError::NotSettled {
        smallest: start * SMALLEST_RELATIVE_AMPLITUDE,
        last,
    })
}

/// The least-squares slope of ln y against ln x.
pub fn fitted_log_slope(points: &[(f64, f64)]) -> f64 {
    let logs: Vec<(f64, f64)> = points.iter().map(|(x, y)| (x.ln(), y.ln())).collect();
    let n = logs.len() as f64;
    let (mean_x, mean_y) = logs.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (covariance, variance) = logs.iter().fold((0.0, 0.0), |(c, v), (x, y)| {
        (c + (x - mean_x) * (y - mean_y), v + (x - mean_x) * (x - mean_x))
    });
    covariance / variance
}

/// `count` values from `low` to `high` equally spaced in ln.
pub fn log_spaced(low: f64, high: f64, count: usize) -> Vec<f64> {
    let (a, b) = (low.ln(), high.ln());
    (0..count)
        .map(|i| (a + (b - a) * i as f64 / (count - 1) as f64).exp())
        .collect()
}
