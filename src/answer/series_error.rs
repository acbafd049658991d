//! Why I(ρ, φ), the Iₙ or a case's partial sums could not be given: the one error of
//! their answers ([`super::series`], [`super::remainders`]).

use super::DissipationAnswerError;
use super::ExitStatus;
use crate::case::InputError;
use crate::digits::agreement::{OutOfBudget, VerifyError, GUARD_DIGITS, MAX_DIGITS};
use crate::exact::{RemainderError, SeriesError};
use crate::phase::PhaseError;
use crate::real::ParseRealError;

/// The highest order the series is computed to.
pub const MAX_ORDER: usize = 200;

/// Why I, the Iₙ or the partial sums could not be given.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExactAnswerError {
    /// ρ is not a number.
    #[error("{quantity} is not a number: {source}")]
    Number {
        /// Which input.
        quantity: &'static str,
        /// Why it does not read.
        #[source]
        source: ParseRealError,
    },
    /// φ is not a phase.
    #[error(transparent)]
    Phase(#[from] PhaseError),
    /// ρ ≤ 0 (the small-amplitude coefficient).
    #[error("ρ must be a positive number (and below MPFR's range, about 1e323228496), got {0}")]
    NonPositiveRatio(String),
    /// The digits asked for are out of range.
    #[error("the digits asked for must be between 1 and {MAX_DIGITS}, got {0}")]
    DigitsOutOfRange(u32),
    /// The order asked for is out of range.
    #[error("the order of the series must be between 1 and {MAX_ORDER}, got {0}")]
    OrderOutOfRange(usize),
    /// The series itself failed.
    #[error(transparent)]
    Series(#[from] SeriesError),
    /// The series' remainder could not be bounded.
    #[error(transparent)]
    Remainder(#[from] RemainderError),
    /// The case does not read.
    #[error(transparent)]
    Input(#[from] InputError),
    /// W failed.
    #[error(transparent)]
    Reference(#[from] DissipationAnswerError),
    /// The time budget ran out before the enclosures were narrow enough.
    #[error("only {reached} of the {asked} digits of {quantity} asked were certified within {seconds:.1} s; ask for fewer digits or a larger --max-seconds")]
    Unreached {
        /// What was being enclosed (`I`, `Iₙ`, `W_N`).
        quantity: &'static str,
        /// The digits asked for.
        asked: u32,
        /// The fewest digits reached.
        reached: u32,
        /// The time spent.
        seconds: f64,
    },
    /// A value lies beyond MPFR's exponents: the partial sums of an exponential at loads of
    /// about 10⁸ decay loads and more.
    #[error("{quantity} lies beyond 2^(±2^29) (about 10^(±1.6e8)), outside the exponents this command prints: `microslip dissipation` prints W at any size")]
    BeyondRange {
        /// What was being enclosed (`I`, `Iₙ`, `W_N`).
        quantity: &'static str,
    },
    /// No enclosure, and the agreement path ran out of time.
    #[error("only {} of the {} digits needed ({} asked for and {GUARD_DIGITS} guard digits) agreed between two precisions within {:.1} s, and no rigorous enclosure could be had; ask for fewer digits", .0.digits_agreed, .0.digits_required(), .0.digits_requested, .0.seconds)]
    OutOfTime(OutOfBudget),
}

impl ExitStatus for ExactAnswerError {
    fn is_failure(&self) -> bool {
        match self {
            ExactAnswerError::OutOfTime(_)
            | ExactAnswerError::Unreached { .. }
            | ExactAnswerError::BeyondRange { .. }
            | ExactAnswerError::Remainder(RemainderError::Kernel { .. }) => true,
            ExactAnswerError::Reference(error) => error.is_failure(),
            _ => false,
        }
    }
}

impl From<VerifyError<ExactAnswerError>> for ExactAnswerError {
    fn from(error: VerifyError<ExactAnswerError>) -> Self {
        error.into_error(ExactAnswerError::OutOfTime)
    }
}
