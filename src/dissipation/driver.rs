//! Drives a set of one-dimensional integrals ("pieces", e.g. the four segments)
//! to a common relative tolerance.
//!
//! Each piece starts with Gauss–Legendre rules of doubling degree, which converge
//! geometrically when the integrand is analytic well beyond the interval. Callers
//! split their intervals so that near-singularities (v' singular at P → 0 with the
//! cycle near separation, or P_T → 0 near gross slip) lie at ends, and map the narrow
//! ones away (`quad::sinh_map`). Where the doubling still stalls (the largest rule,
//! or two doublings without a tenfold gain) the piece falls back to tanh–sinh, whose
//! nodes crowd double-exponentially toward the ends; where that stalls too, the
//! piece has met the rounding noise of its integrand.

use std::time::Instant;

use super::{DissipationError, Options};
use crate::quad::gauss_legendre::node_table;
use crate::quad::tanh_sinh;
use crate::real::Real;

/// ∫ₛₜₐᵣₜ^ₑₙd integrand: one piece of a sum of integrals.
pub struct Integral<'a, R> {
    /// What the piece is (a segment name, or a closed form's term).
    pub name: &'static str,
    /// For segment pieces, the index of the segment (0 EB, 1 BC, 2 CH, 3 HE) it belongs to.
    pub segment: usize,
    /// The integrand.
    pub integrand: Box<dyn Fn(&R) -> R + 'a>,
    /// Lower limit.
    pub start: R,
    /// Upper limit.
    pub end: R,
}

/// The converged pieces: values in the order given, the summed error estimate,
/// the integrand evaluations spent and the largest Gauss–Legendre rule used.
pub(crate) struct Converged<R> {
    pub values: Vec<R>,
    pub error: R,
    pub evaluations: usize,
    pub points: usize,
    /// The Gauss–Legendre rule each piece ended with, in the order given (empty where the
    /// caller combined pieces of its own).
    pub piece_points: Vec<usize>,
}

impl<R: Real> Converged<R> {
    /// Pieces already combined by the caller: values with a common error estimate.
    pub fn combined(values: Vec<R>, error: R, evaluations: usize, points: usize) -> Self {
        Converged {
            values,
            error,
            evaluations,
            points,
            piece_points: Vec::new(),
        }
    }
}

/// Tanh–sinh levels allowed after Gauss–Legendre gives up (each doubles the nodes).
const MAX_TANH_SINH_LEVEL: u32 = 16;

/// How far above its share of the tolerance a piece may end when both rules have
/// reached its rounding noise, the noise then being its error estimate. Beyond this
/// the working precision is too low for the tolerance, and the piece is refused.
const NOISE_MARGIN: i64 = 100;

/// The piece by the `points`-point rule, with the rule applied to |f| (see
/// `NodeTable::integrate_with_magnitude`).
fn gauss<R: Real>(piece: &Integral<'_, R>, points: usize) -> Result<(R, R), DissipationError> {
    if piece.start == piece.end {
        return Ok((piece.start.int(0), piece.start.int(0)));
    }
    let precision = piece.start.precision();
    let table = node_table::<R>(points, precision);
    let (value, magnitude) = table.integrate_with_magnitude(&piece.integrand, &piece.start, &piece.end);
    Ok((finite(value, piece)?, magnitude))
}

/// The rounding floor of a rule's value: 64ε·∫|f|. Changes below it are noise, not error.
fn rounding_floor<R: Real>(magnitude: &R) -> R {
    magnitude.clone() * &magnitude.epsilon_like() * &magnitude.int(64)
}

fn finite<R: Real>(value: R, piece: &Integral<'_, R>) -> Result<R, DissipationError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(DissipationError::NotFinite { segment: piece.name })
    }
}

/// Each piece to an absolute accuracy of `relative_tolerance` × Σ|pieces| / (number of
/// pieces): the scale of the sum, which is what a cancelling sum can be trusted to.
/// Fails with `NotConverged` when neither rule gets there.
pub(crate) fn converge<R: Real>(
    pieces: &[Integral<'_, R>],
    relative_tolerance: &R,
    options: &Options<R>,
) -> Result<Converged<R>, DissipationError> {
    let zero = relative_tolerance.int(0);
    let first_points = match options.min_points {
        // Automatic: 16 points, where an ordinary case already has several digits in
        // f64; at higher precision a larger start would skip the small rules whose
        // changes let `predicted_error` stop a doubling early.
        0 => 16,
        points => points.max(2),
    };
    let max_points = options.max_points.max(first_points);
    if let Some(points) = options.fixed_points {
        // The rule of a quarter of the points sizes the error (generously, and at a quarter
        // of the cost): the rule alone cannot tell a converged piece from one whose peak
        // its nodes miss.
        let sizes: Vec<usize> = match &options.fixed_points_per_piece {
            Some(sizes) if sizes.len() == pieces.len() => sizes.clone(),
            _ => vec![points; pieces.len()],
        };
        let mut values = Vec::with_capacity(pieces.len());
        let mut error = zero.clone();
        let mut evaluations = 0;
        for (piece, &size) in pieces.iter().zip(&sizes) {
            let (value, magnitude) = gauss(piece, size)?;
            evaluations += size;
            let floor = rounding_floor(&magnitude);
            if options.fixed_rule_error {
                let coarse_points = (size / 4).max(1);
                let (coarse, _) = gauss(piece, coarse_points)?;
                evaluations += coarse_points;
                error += (value.clone() - &coarse).abs().max_of(&floor);
            } else {
                error += floor;
            }
            values.push(value);
        }
        return Ok(Converged {
            values,
            error,
            evaluations,
            points: sizes.iter().copied().max().unwrap_or(points),
            piece_points: sizes,
        });
    }
    let mut evaluations = 0;
    let mut largest_rule = first_points;
    // A first look at every piece sets the scale.
    let mut values = Vec::with_capacity(pieces.len());
    for piece in pieces {
        values.push(gauss(piece, first_points)?.0);
        evaluations += first_points;
    }
    let scale = |values: &[R]| values.iter().fold(zero.clone(), |acc, v| acc + &v.abs());
    let count = zero.int(pieces.len().max(1) as i64);
    let mut allowed = scale(&values) * relative_tolerance / &count;
    let mut errors = vec![zero.clone(); pieces.len()];
    // The rule each piece ends with; 0 for a piece tanh–sinh finished (the largest rule then stands in).
    let mut piece_points = vec![first_points; pieces.len()];
    for (i, piece) in pieces.iter().enumerate() {
        if piece.start == piece.end {
            continue;
        }
        let mut points = first_points;
        let mut previous_change: Option<R> = None;
        // Doublings running that failed to bring the change below a tenth of the smallest yet.
        let (mut smallest_change, mut stalled): (Option<R>, u32) = (None, 0);
        loop {
            if points * 2 > max_points || stalled >= 2 {
                // Gauss–Legendre stalled: a near-singularity at an end, or the rounding noise
                // of the integrand. Tanh–sinh resolves the first and tells the second.
                piece_points[i] = 0;
                let estimate = tanh_sinh::integrate(
                    &piece.integrand,
                    &piece.start,
                    &piece.end,
                    &allowed,
                    MAX_TANH_SINH_LEVEL,
                );
                evaluations += estimate.evaluations;
                let value = finite(estimate.value, piece)?;
                if estimate.converged {
                    values[i] = value;
                    errors[i] = estimate.error;
                    break;
                }
                // Neither rule got there. Where the two agree with each other and with
                // themselves to within NOISE_MARGIN × `allowed`, the piece has reached
                // the rounding noise of its integrand: that spread is its error.
                let last_change = previous_change.clone().unwrap_or_else(|| estimate.error.clone());
                let spread = (value - &values[i]).abs().max_of(&estimate.error).max_of(&last_change);
                if spread > allowed.clone() * &zero.int(NOISE_MARGIN) {
                    return Err(not_converged(&values, &spread, relative_tolerance, points));
                }
                errors[i] = spread;
                break;
            }
            if options.deadline.is_some_and(|deadline| Instant::now() >= deadline) {
                return Err(DissipationError::OutOfTime);
            }
            points *= 2;
            piece_points[i] = points;
            largest_rule = largest_rule.max(points);
            let (refined, magnitude) = gauss(piece, points)?;
            evaluations += points;
            let change = (refined.clone() - &values[i]).abs();
            values[i] = refined;
            // Converged to the tolerance, or to the rounding floor of a cancelling integrand.
            let floor = rounding_floor(&magnitude);
            if change <= allowed || change <= floor {
                errors[i] = change.max_of(&floor);
                break;
            }
            if let Some(predicted) = predicted_error(&change, previous_change.as_ref(), &allowed) {
                errors[i] = predicted;
                break;
            }
            let gained = smallest_change
                .as_ref()
                .is_none_or(|smallest| change.clone() * &change.int(10) <= *smallest);
            stalled = if gained { 0 } else { stalled + 1 };
            if gained {
                smallest_change = Some(change.clone());
            }
            previous_change = Some(change);
        }
        // Later pieces are held to the scale as now known.
        allowed = scale(&values) * relative_tolerance / &count;
    }
    let error = errors.iter().fold(zero.clone(), |acc, e| acc + e);
    for size in piece_points.iter_mut().filter(|size| **size == 0) {
        *size = largest_rule;
    }
    Ok(Converged {
        values,
        error,
        evaluations,
        points: largest_rule,
        piece_points,
    })
}

/// The error of the latest rule predicted from the last two changes, when the
/// prediction is safely below `allowed`.
///
/// With d = |I_2n − I_n| ≈ E(n) and d' = |I_n − I_{n/2}| ≈ E(n/2), the last doubling
/// gained a factor d'/d. Gauss–Legendre on an analytic integrand squares the error per
/// doubling once asymptotic (E(2n) ≈ d³/d'²), but while a nearby singularity still shapes
/// the convergence the gains grow more slowly, and nothing in the earlier changes shows it
/// (seen at 256 bits: gains of 10, 22, then 32 digits rather than 44, so that d³/d'²
/// claimed 1e−81 where the error was 4e−72, and W came out 3e−70 off with an estimate of
/// 5e−75). So the prediction assumes only that the next doubling gains as much as the
/// last, E(2n) ≈ d²/d'. It is trusted only when the last doubling gained at least three
/// digits (d < d'/1000) and 100× the prediction clears `allowed`; that is the error
/// reported. This saves the last doubling where it applies.
fn predicted_error<R: Real>(change: &R, previous: Option<&R>, allowed: &R) -> Option<R> {
    let previous = previous?;
    if change.clone() * &change.int(1000) >= *previous {
        return None;
    }
    let reported = change.clone() * change / previous * &change.int(100);
    (reported <= *allowed).then_some(reported)
}

fn not_converged<R: Real>(values: &[R], error: &R, relative_tolerance: &R, points: usize) -> DissipationError {
    let zero = relative_tolerance.int(0);
    let total = values.iter().fold(zero.clone(), |acc, v| acc + v).abs();
    let scale = total.max_of(&relative_tolerance.epsilon_like());
    DissipationError::NotConverged {
        points,
        relative_error: (error.clone() / &scale).to_f64_lossy(),
        requested: relative_tolerance.to_f64_lossy(),
    }
}
