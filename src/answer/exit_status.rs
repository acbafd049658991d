//! How a failed answer ends a command: the one map from the errors of the library's
//! public entry points (W, I and the series, a path, the simulation) to an exit code and
//! a hint. The command line, batch rows and the Python binding read it; none of them
//! matches an error's variants to decide.

/// Exit code of a run whose result could not be vouched for, on valid input.
pub const FAILED: u8 = 1;
/// Exit code of refused input: a case outside the theory, a limit, a malformed value.
pub const REFUSED: u8 = 2;

/// An error as a command ends on it.
pub trait ExitStatus: std::fmt::Display {
    /// Whether the input was fine and the run could not vouch for its result (in time, or
    /// at all): a failure, rather than a refusal of the input.
    fn is_failure(&self) -> bool;

    /// [`FAILED`] for a failure, [`REFUSED`] for refused input.
    fn exit_code(&self) -> u8 {
        if self.is_failure() {
            FAILED
        } else {
            REFUSED
        }
    }

    /// What the user may change, as a clause to append to the message (empty where no
    /// flag helps); `digits_asked`: whether digits were asked for (`--digits`).
    fn hint(&self, _digits_asked: bool) -> &'static str {
        ""
    }

    /// The one line to print: the message and its hint.
    fn line(&self, digits_asked: bool) -> String {
        format!("{self}{}", self.hint(digits_asked))
    }
}
