//! The library's errors as Python exceptions, split as the command line splits its exit
//! codes: input refused (exit 2) is a `ValueError`, a result that could not be vouched for
//! in time (exit 1) a `RuntimeError`; the message is the command line's, without its hint.

use std::time::Duration;

use microslip::answer::ExitStatus;
use microslip::messages::printable;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::PyErr;

/// Input refused: a `ValueError` with the message on one line.
pub fn refused(message: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(printable(&message.to_string()).into_owned())
}

/// A result not had in time (or at all) for valid input: a `RuntimeError`.
pub fn failed(message: impl std::fmt::Display) -> PyErr {
    PyRuntimeError::new_err(printable(&message.to_string()).into_owned())
}

/// A library error as the library maps it to an exit code: refused input a `ValueError`,
/// a failed run a `RuntimeError`. The message leaves out the command line's hint, which
/// names its flags.
pub fn of(error: impl ExitStatus) -> PyErr {
    if error.is_failure() {
        failed(error)
    } else {
        refused(error)
    }
}

/// The most seconds a computation may be given, as on the command line.
const MOST_SECONDS: f64 = 1e6;

/// A time budget from `max_seconds`, refused outside (0, 1e6].
pub fn budget(max_seconds: f64) -> Result<Duration, PyErr> {
    if !(max_seconds > 0.0 && max_seconds <= MOST_SECONDS) {
        return Err(refused(format!(
            "max_seconds = {max_seconds} is not a time budget: give seconds in (0, 1e6]"
        )));
    }
    Ok(Duration::from_secs_f64(max_seconds))
}
