//! Why a path's W could not be proven: the reason its answer rests on agreement instead.

use crate::digits::enclosure::CertifiedError;

/// Why W could not be proven: the reason the answer rests on agreement instead.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum NotProven {
    /// A path the proof does not reach, at any precision.
    #[error("proven W does not cover this path: {0}")]
    NotCovered(&'static str),
    /// Two enclosures overlapped at every precision tried (two turning values equal, a
    /// load on a boundary, half a range of u at gross slip).
    #[error("the path's turning points, events or rainflow cycles compare values that overlap up to {bits} bits")]
    Undecided {
        /// The highest working precision tried.
        bits: u32,
    },
    /// A cycle's enclosure was refused.
    #[error("{0}")]
    Refused(CertifiedError),
    /// The enclosure at the highest precision tried was too wide for the digits.
    #[error("the enclosure at {bits} bits settles {reached} of the {asked} digits asked")]
    TooWide {
        /// The digits asked for.
        asked: u32,
        /// The digits it settled.
        reached: u32,
        /// Its working precision.
        bits: u32,
    },
    /// The deadline came first.
    #[error("the time budget ran out before the enclosure settled {asked} digits")]
    OutOfTime {
        /// The digits asked for.
        asked: u32,
    },
}
