//! Why W could not be given: the one error of every path to W ([`super::dissipation`],
//! [`super::agreed`]), with its exit code and hint.

use super::ExitStatus;
use crate::case::InputError;
use crate::compliance::TableError;
use crate::digits::agreement::{OutOfBudget, GUARD_DIGITS, MAX_DIGITS};
use crate::dissipation::DissipationError;

/// Why W could not be given, on any of its paths (enclosure, agreement, a table's
/// estimate, the checks before them).
#[non_exhaustive]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DissipationAnswerError {
    /// The case's text is wrong.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The case is outside the theory, or would not converge.
    #[error(transparent)]
    Dissipation(#[from] DissipationError),
    /// The digits asked for are out of range.
    #[error("the significant digits asked for must be between 1 and {MAX_DIGITS}, got {0}")]
    DigitsOutOfRange(u32),
    /// The budget ran out first.
    #[error("only {} of {} digits could be verified within {:.1} s (two precisions must agree to {GUARD_DIGITS} digits more; last attempt at {} bits)", .0.digits_reached(), .0.digits_requested, .0.seconds, .0.precision_bits)]
    Budget(OutOfBudget),
    /// The certified enclosure could not be had in time.
    #[cfg(feature = "certified")]
    #[error(transparent)]
    Certified(crate::digits::enclosure::CertifiedError),
    /// A table of the compliance.
    #[error(transparent)]
    Table(#[from] TableError),
    /// f64 cannot compute this cycle, and a table is not computed at other precisions.
    #[error("{source} — but a table compliance is computed in f64 only, so this cycle cannot be computed from a table (where its loads are extreme, rescale the cycle and the table's loads together: W scales with the load scale)")]
    TableInF64 {
        /// Why f64 cannot compute the cycle.
        source: DissipationError,
    },
}

impl ExitStatus for DissipationAnswerError {
    fn is_failure(&self) -> bool {
        match self {
            DissipationAnswerError::Budget(_) | DissipationAnswerError::Dissipation(DissipationError::OutOfTime) => {
                true
            }
            #[cfg(feature = "certified")]
            DissipationAnswerError::Certified(_) => true,
            _ => false,
        }
    }

    fn hint(&self, digits_asked: bool) -> &'static str {
        match self {
            // A table is computed in f64, where these end; any other W goes up to Arb.
            DissipationAnswerError::Dissipation(
                DissipationError::NotConverged { .. }
                | DissipationError::IllConditioned { .. }
                | DissipationError::OutOfRange { .. },
            ) if !digits_asked => "; try --digits N (digits in MPFR)",
            // More time helps an enclosure only where time is what it ran out of.
            #[cfg(feature = "certified")]
            DissipationAnswerError::Certified(error)
                if !matches!(error, crate::digits::enclosure::CertifiedError::OutOfTime { .. }) =>
            {
                ""
            }
            _ if !self.is_failure() => "",
            _ if digits_asked => "; raise --max-seconds or ask for fewer --digits",
            _ => "; raise --max-seconds",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_digits_hint_is_given_only_where_digits_were_not() {
        let out_of_range = || DissipationAnswerError::Dissipation(DissipationError::OutOfRange { scale: 1e-310 });
        assert_eq!(out_of_range().hint(false), "; try --digits N (digits in MPFR)");
        assert_eq!(out_of_range().hint(true), "");
        assert_eq!(out_of_range().exit_code(), 2);
        let budget = || {
            DissipationAnswerError::Budget(OutOfBudget {
                digits_requested: 30,
                digits_agreed: 3,
                seconds: 1.0,
                precision_bits: 256,
            })
        };
        assert!(budget().hint(true).contains("fewer --digits"));
        assert!(!budget().hint(false).contains("--digits"));
        assert_eq!(budget().exit_code(), 1);
    }

    #[test]
    fn the_budget_error_reads_as_before() {
        let budget = OutOfBudget {
            digits_requested: 1000,
            digits_agreed: 1002,
            seconds: 0.01,
            precision_bits: 3834,
        };
        assert_eq!(
            DissipationAnswerError::Budget(budget).to_string(),
            "only 1000 of 1000 digits could be verified within 0.0 s (two precisions must agree to 4 digits more; last attempt at 3834 bits)"
        );
    }
}
