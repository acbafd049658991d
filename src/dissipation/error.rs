//! Why W could not be computed.

use crate::compliance::AdmissibilityError;
use crate::cycle::CycleError;
use crate::quad::QuadError;

/// Why W could not be computed.
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DissipationError {
    /// The load cycle is outside the theory.
    #[error(transparent)]
    Cycle(#[from] CycleError),
    /// The compliance is not physical over the cycle's loads.
    #[error("{0} = [P_T, P0 + P1]: the slip loads of the cycle reach down to the permanent-stick load P_T")]
    Compliance(#[from] AdmissibilityError),
    /// The quadrature did not reach the tolerance.
    #[error("the integrals did not converge: relative change {relative_error:.2e} at {points} points per segment, {requested:.2e} requested; the case is too stiff for this working precision (more precision may converge)")]
    NotConverged {
        /// The Gauss–Legendre rule reached on the piece that failed.
        points: usize,
        /// The error reached, relative to the sum of the integrals.
        relative_error: f64,
        /// The relative tolerance asked for.
        requested: f64,
    },
    /// The working precision cannot resolve the cycle: rounding alone moves W too much.
    #[error("the case is ill-conditioned at {bits} bits: {cause}, so rounding alone can change W by ~{expected:.1e} relative (limit {limit:.0e}); it needs more working precision")]
    IllConditioned {
        /// The working precision, in bits.
        bits: u32,
        /// What amplifies the rounding, with its size.
        cause: String,
        /// The relative change of W that rounding alone can cause.
        expected: f64,
        /// The largest such change accepted.
        limit: f64,
    },
    /// The segment values are so small that f64 would hold them with fewer digits.
    #[error("the segment contributions ({scale:e}) fall below the range the working precision holds in full; rescale the loads (W scales with the load scale) or compute with a wider exponent range (MPFR)")]
    OutOfRange {
        /// The size of the segment contributions.
        scale: f64,
    },
    /// W came out negative beyond its error estimate (a physical compliance dissipates).
    #[error("W = {total:e} is negative beyond its error estimate {error:e}; the compliance may violate v'' ≤ 0 between the sampled loads")]
    Negative {
        /// W as computed.
        total: f64,
        /// Its error estimate.
        error: f64,
    },
    /// The deadline passed before the integrals converged.
    #[error("the time budget ran out before the integrals converged")]
    OutOfTime,
    /// An integrand produced NaN or infinity (compliance undefined at some load).
    #[error("the {segment} integral is not finite: the compliance is undefined at some load the cycle reaches")]
    NotFinite {
        /// The integral that is not finite: a segment (`EB`, `BC`, `CH`, `HE`), a closed form's piece, or `total`.
        segment: &'static str,
    },
    /// A magnitude of the case lies where products of it would overflow or underflow.
    #[error("{quantity} = {value:e} is outside what {bits}-bit arithmetic carries through the integrals without overflow or underflow (magnitudes {low:.0e} to {high:.0e}); compute with more precision, whose exponent range is far wider")]
    OutsideRange {
        /// The magnitude's name.
        quantity: String,
        /// Its value.
        value: f64,
        /// The working precision, in bits.
        bits: u32,
        /// The smallest magnitude carried safely.
        low: f64,
        /// The largest magnitude carried safely.
        high: f64,
    },
}

impl From<QuadError> for DissipationError {
    fn from(error: QuadError) -> Self {
        match error {
            QuadError::NotConverged {
                points,
                relative_error,
                requested,
            } => DissipationError::NotConverged {
                points,
                relative_error,
                requested,
            },
            QuadError::OutOfTime => DissipationError::OutOfTime,
            QuadError::NotFinite { piece } => DissipationError::NotFinite { segment: piece },
        }
    }
}
