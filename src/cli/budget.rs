//! The time budget as a promise to the user: whatever the library does inside one
//! attempt, the command answers within `--max-seconds` and a moment.
//!
//! The library keeps its deadline itself: no Gauss–Legendre rule or tanh–sinh level
//! starts whose predicted cost would end past it, and node tables check it at every
//! node. What it cannot stop is a step already under way: one Arb integration of a
//! certified attempt (started on a predicted cost, which is an estimate), or a prediction
//! that falls short. The command therefore runs its work on a thread of its own and, once
//! the budget and a short grace have passed without an answer, refuses with one line and
//! ends the process.

use std::sync::mpsc;
use std::time::Duration;

use super::report::{fail, Failure};

/// What the library gets beyond the budget to return its own, more specific, answer.
const GRACE: Duration = Duration::from_millis(300);

/// Stack of the worker thread: as large as the main thread's usual one.
const STACK_BYTES: usize = 64 << 20;

/// `work()`, or a failure (exit 1, as when the library itself runs out of time; the
/// input was fine) and the end of the process when it has not answered within `budget`
/// plus a short grace.
pub fn within<T: Send>(budget: Duration, work: impl FnOnce() -> Result<T, Failure> + Send) -> Result<T, Failure> {
    within_or(budget, work, || {
        Failure::failed(format!(
            "the time budget of {} s ran out before the result was reached; raise --max-seconds",
            budget.as_secs_f64()
        ))
    })
}

/// `work()`, or `timed_out()` reported (and the end of the process) when it has not
/// answered within `budget` plus a short grace.
pub fn within_or<T: Send>(
    budget: Duration,
    work: impl FnOnce() -> Result<T, Failure> + Send,
    timed_out: impl FnOnce() -> Failure,
) -> Result<T, Failure> {
    std::thread::scope(|scope| {
        let (sender, receiver) = mpsc::channel();
        let spawned = std::thread::Builder::new()
            .stack_size(STACK_BYTES)
            .spawn_scoped(scope, move || {
                let _ = sender.send(work());
            });
        if let Err(error) = spawned {
            return Err(Failure::failed(format!("cannot start the computation: {error}")));
        }
        match receiver.recv_timeout(budget.saturating_add(GRACE)) {
            Ok(outcome) => outcome,
            Err(mpsc::RecvTimeoutError::Disconnected) => Err(Failure::failed("the computation ended without a result")),
            Err(mpsc::RecvTimeoutError::Timeout) => {
                let failure = timed_out();
                let _ = fail(&failure);
                // The worker cannot be interrupted; ending the process is the answer.
                std::process::exit(i32::from(failure.code))
            }
        }
    })
}
