//! Drives a set of one-dimensional integrals ("pieces", e.g. the four segments)
//! to a common relative tolerance with Gauss–Legendre rules of doubling degree.

use super::DissipationError;
use crate::quad::gauss_legendre::node_table;
use crate::real::Real;

/// ∫ₛₜₐᵣₜ^ₑₙd integrand: one piece of a sum of integrals.
pub(crate) struct Piece<'a, R> {
    pub name: &'static str,
    pub integrand: Box<dyn Fn(&R) -> R + 'a>,
    pub start: R,
    pub end: R,
}

/// The converged pieces: values in the order given, the summed error estimate,
/// and the integrand evaluations spent.
pub(crate) struct Converged<R> {
    pub values: Vec<R>,
    pub error: R,
    pub evaluations: usize,
}

/// Doubles each piece's rule from 8 points until successive values differ by at
/// most `relative_tolerance` × Σ|pieces| (the scale of the sum, which is what a
/// cancelling sum can be trusted to), or fails with `NotConverged` past `max_points`.
pub(crate) fn converge<R: Real>(
    pieces: &[Piece<'_, R>],
    relative_tolerance: &R,
    max_points: usize,
) -> Result<Converged<R>, DissipationError> {
    let precision = relative_tolerance.precision();
    let zero = relative_tolerance.int(0);
    let mut points = 8usize;
    let mut evaluations = 0usize;
    let integrate = |piece: &Piece<'_, R>, points: usize| -> Result<R, DissipationError> {
        if piece.start == piece.end {
            return Ok(piece.start.int(0));
        }
        let value = node_table::<R>(points, precision).integrate(&piece.integrand, &piece.start, &piece.end);
        if value.is_finite() {
            Ok(value)
        } else {
            Err(DissipationError::NotFinite { segment: piece.name })
        }
    };
    let mut values = pieces
        .iter()
        .map(|p| integrate(p, points))
        .collect::<Result<Vec<_>, _>>()?;
    evaluations += points * pieces.len();
    let mut changes: Vec<Option<R>> = vec![None; pieces.len()];
    loop {
        let scale = values.iter().fold(zero.clone(), |acc, v| acc + &v.abs());
        let allowed = scale.clone() * relative_tolerance / &zero.int(pieces.len().max(1) as i64);
        let done = |change: &Option<R>| change.as_ref().is_some_and(|c| *c <= allowed);
        if changes.iter().all(done) {
            let error = changes.iter().flatten().fold(zero.clone(), |acc, c| acc + c);
            return Ok(Converged { values, error, evaluations });
        }
        if points * 2 > max_points {
            let error = changes.iter().flatten().fold(zero.clone(), |acc, c| acc + c);
            let total = values.iter().fold(zero.clone(), |acc, v| acc + v);
            return Err(DissipationError::NotConverged {
                points,
                relative_error: (error / &total.abs().max_of(&scale.max_of(&R::epsilon(precision)))).to_f64_lossy(),
                requested: relative_tolerance.to_f64_lossy(),
            });
        }
        points *= 2;
        for (i, piece) in pieces.iter().enumerate() {
            if done(&changes[i]) {
                continue;
            }
            let refined = integrate(piece, points)?;
            evaluations += points;
            changes[i] = Some((refined.clone() - &values[i]).abs());
            values[i] = refined;
        }
    }
}
