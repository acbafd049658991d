//! The one way to integrate a list of one-dimensional integrals ("pieces", e.g. the
//! parts of the four segments) to a common relative tolerance.
//!
//! Each piece starts with Gauss–Legendre rules of doubling degree, which converge
//! geometrically when the integrand is analytic well beyond the interval. Callers
//! split their intervals so that near-singularities lie at ends, and map the narrow
//! ones away ([`super::sinh_map`]). Where the doubling still stalls (the largest rule,
//! or two doublings without a tenfold gain) the piece falls back to tanh–sinh, whose
//! nodes crowd double-exponentially toward the ends; where that stalls too, the
//! piece has met the rounding noise of its integrand.

use std::time::Instant;

use super::gauss_legendre::node_table;
use super::{tanh_sinh, Estimate};
use crate::real::Real;

/// ∫ₛₜₐᵣₜ^ₑₙd integrand: one piece of a sum of integrals.
pub struct Piece<'a, R> {
    /// What the piece is (a segment's name, or a closed form's term), for messages.
    pub label: &'static str,
    /// The integrand.
    pub integrand: Box<dyn Fn(&R) -> R + 'a>,
    /// Lower limit.
    pub start: R,
    /// Upper limit.
    pub end: R,
}

/// Every piece integrated once with a given Gauss–Legendre rule, no refinement: for
/// checking a converged result with another rule.
#[derive(Clone, Debug)]
pub struct FixedRule {
    /// The rule for every piece.
    pub points: usize,
    /// The rule of each piece in turn (as [`PieceEstimate::rule`] gives them for the same
    /// pieces); where the count differs, `points` for all.
    pub per_piece: Option<Vec<usize>>,
    /// Size each piece's error by the rule of a quarter of the points (otherwise only by
    /// its rounding floor): the rule alone cannot tell a converged piece from one whose
    /// peak its nodes miss.
    pub quarter_rule_error: bool,
}

/// How far to drive the pieces.
#[derive(Clone, Debug)]
pub struct Settings<R> {
    /// Target error relative to the scale Σ|pieces|.
    pub relative_tolerance: R,
    /// The first Gauss–Legendre rule of the doubling sequence.
    pub first_points: usize,
    /// The largest Gauss–Legendre rule before tanh–sinh takes over.
    pub max_points: usize,
    /// Integrate with fixed rules instead of converging.
    pub fixed: Option<FixedRule>,
    /// Give up with [`QuadError::OutOfTime`] once this instant has passed (checked between refinements).
    pub deadline: Option<Instant>,
}

impl<R> Settings<R> {
    /// Converge to `relative_tolerance` from 16 points up to 512, with no deadline.
    pub fn new(relative_tolerance: R) -> Self {
        Settings {
            relative_tolerance,
            first_points: 16,
            max_points: 512,
            fixed: None,
            deadline: None,
        }
    }
}

/// Why the pieces could not be integrated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum QuadError {
    /// Neither rule reached the tolerance on some piece.
    #[error("the integrals did not converge: relative change {relative_error:.2e} at {points} points per piece, {requested:.2e} requested")]
    NotConverged {
        /// The Gauss–Legendre rule reached on the piece.
        points: usize,
        /// The error reached, relative to the sum of the pieces.
        relative_error: f64,
        /// The relative tolerance asked for.
        requested: f64,
    },
    /// The deadline passed.
    #[error("the time budget ran out before the integrals converged")]
    OutOfTime,
    /// An integrand produced NaN or infinity.
    #[error("the {piece} integral is not finite")]
    NotFinite {
        /// The piece's label.
        piece: &'static str,
    },
}

/// One piece's result.
#[derive(Clone, Debug)]
pub struct PieceEstimate<R> {
    /// Its value, error estimate, evaluations, and whether it met its share of the tolerance.
    pub estimate: Estimate<R>,
    /// ∫|f| by the last Gauss–Legendre rule applied to it: the scale of its rounding.
    pub magnitude: R,
    /// The Gauss–Legendre rule it ended with (where tanh–sinh finished it, the largest rule used).
    pub rule: usize,
}

/// The pieces integrated.
#[derive(Clone, Debug)]
pub struct Integrated<R> {
    /// Each piece's result, in the order given.
    pub pieces: Vec<PieceEstimate<R>>,
    /// The sum of the pieces' error estimates.
    pub error: R,
    /// Integrand evaluations spent over all pieces.
    pub evaluations: usize,
    /// The largest Gauss–Legendre rule used on any piece.
    pub largest_rule: usize,
}

impl<R: Real> Integrated<R> {
    /// The pieces' values, in the order given.
    pub fn values(&self) -> impl Iterator<Item = &R> {
        self.pieces.iter().map(|piece| &piece.estimate.value)
    }

    /// The rule each piece ended with, in the order given.
    pub fn rules(&self) -> Vec<usize> {
        self.pieces.iter().map(|piece| piece.rule).collect()
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
fn gauss<R: Real>(piece: &Piece<'_, R>, points: usize) -> Result<(R, R), QuadError> {
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

fn finite<R: Real>(value: R, piece: &Piece<'_, R>) -> Result<R, QuadError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(QuadError::NotFinite { piece: piece.label })
    }
}

/// Each piece to an absolute accuracy of `relative_tolerance` × Σ|pieces| / (number of
/// pieces): the scale of the sum, which is what a cancelling sum can be trusted to.
/// Fails with `NotConverged` when neither rule gets there.
pub fn integrate<R: Real>(pieces: &[Piece<'_, R>], settings: &Settings<R>) -> Result<Integrated<R>, QuadError> {
    match &settings.fixed {
        Some(fixed) => integrate_fixed(pieces, fixed, &settings.relative_tolerance.int(0)),
        None => converge(pieces, settings),
    }
}

fn integrate_fixed<R: Real>(pieces: &[Piece<'_, R>], fixed: &FixedRule, zero: &R) -> Result<Integrated<R>, QuadError> {
    let sizes: Vec<usize> = match &fixed.per_piece {
        Some(sizes) if sizes.len() == pieces.len() => sizes.clone(),
        _ => vec![fixed.points; pieces.len()],
    };
    let mut results = Vec::with_capacity(pieces.len());
    let mut error = zero.clone();
    let mut evaluations = 0;
    for (piece, &size) in pieces.iter().zip(&sizes) {
        let (value, magnitude) = gauss(piece, size)?;
        let mut piece_evaluations = size;
        let floor = rounding_floor(&magnitude);
        let piece_error = if fixed.quarter_rule_error {
            let coarse_points = (size / 4).max(1);
            let (coarse, _) = gauss(piece, coarse_points)?;
            piece_evaluations += coarse_points;
            (value.clone() - &coarse).abs().max_of(&floor)
        } else {
            floor
        };
        error += &piece_error;
        evaluations += piece_evaluations;
        results.push(PieceEstimate {
            estimate: Estimate {
                value,
                error: piece_error,
                evaluations: piece_evaluations,
                converged: true,
            },
            magnitude,
            rule: size,
        });
    }
    Ok(Integrated {
        pieces: results,
        error,
        evaluations,
        largest_rule: sizes.iter().copied().max().unwrap_or(fixed.points),
    })
}

fn converge<R: Real>(pieces: &[Piece<'_, R>], settings: &Settings<R>) -> Result<Integrated<R>, QuadError> {
    let relative_tolerance = &settings.relative_tolerance;
    let zero = relative_tolerance.int(0);
    let first_points = settings.first_points.max(2);
    let max_points = settings.max_points.max(first_points);
    let mut evaluations = 0;
    let mut largest_rule = first_points;
    // A first look at every piece sets the scale.
    let mut results = Vec::with_capacity(pieces.len());
    for piece in pieces {
        let (value, magnitude) = gauss(piece, first_points)?;
        evaluations += first_points;
        results.push(PieceEstimate {
            estimate: Estimate {
                value,
                error: zero.clone(),
                evaluations: first_points,
                converged: true,
            },
            magnitude,
            rule: first_points,
        });
    }
    let scale = |results: &[PieceEstimate<R>]| {
        results
            .iter()
            .fold(zero.clone(), |acc, piece| acc + &piece.estimate.value.abs())
    };
    let count = zero.int(pieces.len().max(1) as i64);
    let mut allowed = scale(&results) * relative_tolerance / &count;
    // Whether tanh–sinh finished a piece (its rule is then the largest Gauss–Legendre rule used).
    let mut by_tanh_sinh = vec![false; pieces.len()];
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
                by_tanh_sinh[i] = true;
                let estimate = tanh_sinh::integrate(
                    &piece.integrand,
                    &piece.start,
                    &piece.end,
                    &allowed,
                    MAX_TANH_SINH_LEVEL,
                );
                evaluations += estimate.evaluations;
                results[i].estimate.evaluations += estimate.evaluations;
                let value = finite(estimate.value, piece)?;
                if estimate.converged {
                    results[i].estimate.value = value;
                    results[i].estimate.error = estimate.error;
                    break;
                }
                // Neither rule got there. Where the two agree with each other and with
                // themselves to within NOISE_MARGIN × `allowed`, the piece has reached
                // the rounding noise of its integrand: that spread is its error.
                let last_change = previous_change.clone().unwrap_or_else(|| estimate.error.clone());
                let spread = (value - &results[i].estimate.value)
                    .abs()
                    .max_of(&estimate.error)
                    .max_of(&last_change);
                if spread > allowed.clone() * &zero.int(NOISE_MARGIN) {
                    return Err(not_converged(&results, &spread, relative_tolerance, points));
                }
                results[i].estimate.error = spread;
                results[i].estimate.converged = false;
                break;
            }
            if settings.deadline.is_some_and(|deadline| Instant::now() >= deadline) {
                return Err(QuadError::OutOfTime);
            }
            points *= 2;
            largest_rule = largest_rule.max(points);
            let (refined, magnitude) = gauss(piece, points)?;
            evaluations += points;
            let result = &mut results[i];
            result.rule = points;
            result.estimate.evaluations += points;
            let change = (refined.clone() - &result.estimate.value).abs();
            result.estimate.value = refined;
            // Converged to the tolerance, or to the rounding floor of a cancelling integrand.
            let floor = rounding_floor(&magnitude);
            result.magnitude = magnitude;
            if change <= allowed || change <= floor {
                result.estimate.error = change.max_of(&floor);
                break;
            }
            if let Some(predicted) = predicted_error(&change, previous_change.as_ref(), &allowed) {
                result.estimate.error = predicted;
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
        allowed = scale(&results) * relative_tolerance / &count;
    }
    let error = results
        .iter()
        .fold(zero.clone(), |acc, piece| acc + &piece.estimate.error);
    for (result, _) in results.iter_mut().zip(by_tanh_sinh).filter(|(_, tanh_sinh)| *tanh_sinh) {
        result.rule = largest_rule;
    }
    Ok(Integrated {
        pieces: results,
        error,
        evaluations,
        largest_rule,
    })
}

/// The error of the latest rule predicted from the last two changes, when the
/// prediction is safely below `allowed`.
///
/// With d = |I_2n − I_n| ≈ E(n) and d' = |I_n − I_{n/2}| ≈ E(n/2), the last doubling
/// gained a factor d'/d. Gauss–Legendre on an analytic integrand squares the error per
/// doubling once asymptotic (E(2n) ≈ d³/d'²), but while a nearby singularity still shapes
/// the convergence the gains grow more slowly, which the earlier changes do not show
/// (proofs/quadrature.md, "The convergence driver's early stop"). So the prediction
/// assumes only that the next doubling gains as much as the last, E(2n) ≈ d²/d'. It is
/// trusted only when the last doubling gained at least three digits (d < d'/1000) and
/// 100× the prediction clears `allowed`; that is the error reported.
fn predicted_error<R: Real>(change: &R, previous: Option<&R>, allowed: &R) -> Option<R> {
    let previous = previous?;
    if change.clone() * &change.int(1000) >= *previous {
        return None;
    }
    let reported = change.clone() * change / previous * &change.int(100);
    (reported <= *allowed).then_some(reported)
}

fn not_converged<R: Real>(results: &[PieceEstimate<R>], error: &R, relative_tolerance: &R, points: usize) -> QuadError {
    let zero = relative_tolerance.int(0);
    let total = results
        .iter()
        .fold(zero.clone(), |acc, piece| acc + &piece.estimate.value)
        .abs();
    let scale = total.max_of(&relative_tolerance.epsilon_like());
    QuadError::NotConverged {
        points,
        relative_error: (error.clone() / &scale).to_f64_lossy(),
        requested: relative_tolerance.to_f64_lossy(),
    }
}
