//! The threads a batch's rows are computed on: as many as the batch has jobs, started once
//! per batch ([`TimedWorkers`]). A row that outlasts its budget fails alone, out of time, and
//! is left to finish on its thread while the batch goes on.

use std::sync::Arc;
use std::time::Duration;

use super::{failed_row, row_result, InputRow, RowResult};
use crate::workers::{TimedWorkers, Unanswered};

pub use crate::workers::Ticket;

/// What a row gets beyond its budget to return its own, more specific, answer: the
/// computation keeps its deadline itself, but a step already under way (one Arb
/// integration, a rule whose cost was predicted short) cannot be stopped.
const ROW_GRACE: Duration = Duration::from_millis(500);

/// The threads of a batch, each computing one row at a time within the batch's budget.
///
/// ```
/// use std::time::Duration;
/// use microslip::batch::{read_input, RowPool};
///
/// let text = "p0,p1,q1,phi,friction,lambda,compliance\n1,0.4,0.5,0.4pi,1,1,const:c=1\n1,0.4,9,0.4pi,1,1,const:c=1\n";
/// let rows: Vec<_> = read_input(text.as_bytes()).unwrap().map(Result::unwrap).collect();
/// let pool = RowPool::new(2, None, Duration::from_secs(10));
/// let ticket = pool.hand_in(rows.into());
/// let results = pool.collect(ticket, &mut |_answered| {});
/// assert!(results[0].succeeded());
/// assert!(results[1].error.starts_with("line 3: "));
/// ```
pub struct RowPool(TimedWorkers<InputRow, RowResult>);

impl RowPool {
    /// `threads` threads (at least one) computing rows to `digits` (as a single run
    /// without), each within `budget`.
    pub fn new(threads: usize, digits: Option<u32>, budget: Duration) -> Self {
        let unanswered = move |row: &InputRow, why: Unanswered| {
            let why = match why {
                Unanswered::Late => format!(
                    "the time budget of {} s per row ran out before the result was reached; raise --max-seconds",
                    budget.as_secs_f64()
                ),
                Unanswered::NoThread => "internal error: cannot start a thread".to_string(),
                Unanswered::Panicked => {
                    "internal error: the computation panicked (please report this case)".to_string()
                }
            };
            failed_row(row, &why)
        };
        RowPool(TimedWorkers::new(
            threads,
            budget.saturating_add(ROW_GRACE),
            move |row| row_result(row, digits, budget),
            unanswered,
        ))
    }

    /// Hands in `rows`, to be computed after those handed in before them.
    pub fn hand_in(&self, rows: Arc<[InputRow]>) -> Ticket {
        self.0.hand_in(rows)
    }

    /// The results of the rows handed in with `ticket`, in input order, once all are
    /// answered; meanwhile `progress` is told, a few times a second, how many rows the
    /// pool has answered.
    pub fn collect(&self, ticket: Ticket, progress: &mut dyn FnMut(usize)) -> Vec<RowResult> {
        self.0.collect(ticket, progress)
    }
}
