//! A path's boundaries decided on enclosures of its decimals as written, never on their
//! f64 copies: the contact (f > 0, λ ∈ [1, 2], from ν where ν is given), separation
//! (P > 0 throughout) and, under force driving, gross slip (|Q| < fP throughout), for
//! `microslip path` and the simulation of a path file alike, each by
//! the path's own checks run on f64 intervals, then on Arb balls at rising precision,
//! until every comparison they make is decided (proofs/boundaries.md, "Paths").
//!
//! A decided refusal quotes the enclosure's middle; a path no precision up to
//! [`MAX_BITS`] decides is refused as undecidable. A path decided inside whose f64 copy
//! crosses a boundary is left to [`super::path_answer`], which says so.

use crate::doubts::watch;
use crate::interval::Interval;
use crate::path::events::{check_contact_and_separation, check_path};
use crate::path::{Drive, PathRequest, PathRequestError};
use crate::real::{Precision, Real};

/// The most bits a path's boundaries are decided at.
pub const MAX_BITS: u32 = 1 << 13;

/// The bits the balls start with.
#[cfg(feature = "certified")]
const FIRST_BITS: u32 = 128;

/// Whether the path of `request` is inside the theory, decided exactly: `Ok` where it is,
/// its refusal where it is not, and "undecidable" where no precision settles it. A file
/// that is not read in f64 is refused as that read says; a rung is not started after the
/// request's deadline (a failure: the input was fine).
pub(crate) fn decide_boundaries(request: &PathRequest) -> Result<(), PathRequestError> {
    request.read_path::<f64>(Precision::DOUBLE)?;
    match decided_at::<Interval>(request, Precision::DOUBLE) {
        Some(Ok(())) => return Ok(()),
        // The margin quoted from balls, whose middle is the exact one to far below f64's
        // rounding (the intervals' is off by their width); the intervals' where balls
        // do not decide.
        #[cfg(feature = "certified")]
        Some(Err(refusal)) => {
            let precise = decided_at::<crate::ball::Ball>(request, Precision::bits(FIRST_BITS));
            return Err(precise.and_then(Result::err).unwrap_or(refusal));
        }
        #[cfg(not(feature = "certified"))]
        Some(Err(refusal)) => return Err(refusal),
        None => {}
    }
    // The one ladder: balls at four times the bits each rung, none started past the deadline.
    #[cfg(feature = "certified")]
    {
        use crate::digits::{Ladder, Rung, Stop};
        let ladder = Ladder::new(Precision::bits(FIRST_BITS), Precision::bits(MAX_BITS)).until(Some(request.deadline));
        let rung = |precision| match decided_at::<crate::ball::Ball>(request, precision) {
            Some(decided) => Rung::Reached(decided),
            None => Rung::Short(()),
        };
        match ladder.climb(rung, |precision, _| Precision::bits(precision.in_bits() * 4)) {
            Ok((decided, _)) => return decided,
            Err(Stop::OutOfTime { .. }) => {
                return Err(PathRequestError::failed(
                    "the time budget ran out before the path's boundaries were decided; raise --max-seconds",
                ))
            }
            Err(Stop::Final(()) | Stop::Exhausted(())) => {}
        }
    }
    Err(PathRequestError::refused(format!(
        "undecidable at this precision: whether the path separates, reaches gross slip or has λ outside [1, 2] \
         is not settled at {MAX_BITS} bits; move the inputs off the boundary"
    )))
}

/// The checks on the path read at `precision`; `None` where a comparison they made is
/// undecided there, or where the path is not read there (the caller read it in f64: a
/// failure here comes from the enclosures' width, as of a sum of many samples' cosines).
fn decided_at<R: Real>(request: &PathRequest, precision: Precision) -> Option<Result<(), PathRequestError>> {
    let path = request.read_path::<R>(precision).ok()?;
    let (result, doubts) = watch(|| -> Result<(), PathRequestError> {
        let contact = request.read_contact::<R>(precision)?;
        match request.drive {
            Drive::Force => check_path(&path, &contact)?,
            // Gross slip is allowed under displacement driving.
            Drive::Displacement => check_contact_and_separation(&path, &contact)?,
        }
        Ok(())
    });
    doubts.none().then_some(result)
}
