//! Independent items of work on threads of their own: a fixed number at a time
//! ([`each_on_own_threads`]), or handed in chunk after chunk to threads that live as long
//! as their pool, each item within a time limit ([`TimedWorkers`]).
//!
//! The gate's steps and a batch's rows are dealt out by plain threads, not by rayon's
//! workers: a row given up at its time limit is left running on its thread, and an item
//! may itself run parallel work on the pool (a large node table is computed on it). Were
//! the pool's workers the ones running the items, that work could wait for a pool whose
//! every worker is busy with an item, until the budget ran out.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;

mod timed;

pub use timed::{Ticket, TimedWorkers, Unanswered};

/// `work(i)` for every i in 0..`count`, on `threads` threads (at least one), and
/// `finished(i, &result)` on the caller's thread as each ends, in the order they end.
/// Returns the results in index order.
pub(crate) fn each_on_own_threads<T: Send>(
    count: usize,
    threads: usize,
    work: impl Fn(usize) -> T + Sync,
    mut finished: impl FnMut(usize, &T),
) -> Vec<T> {
    let next = AtomicUsize::new(0);
    let (sender, receiver) = mpsc::channel();
    let mut results: Vec<Option<T>> = std::iter::repeat_with(|| None).take(count).collect();
    std::thread::scope(|scope| {
        for _ in 0..threads.clamp(1, count.max(1)) {
            let (sender, next, work) = (sender.clone(), &next, &work);
            scope.spawn(move || loop {
                let index = next.fetch_add(1, Ordering::Relaxed);
                if index >= count || sender.send((index, work(index))).is_err() {
                    break;
                }
            });
        }
        drop(sender);
        for (index, result) in receiver {
            finished(index, &result);
            results[index] = Some(result);
        }
    });
    // Every index was sent once: a thread ends only past the last index, and a panic in
    // `work` ends the scope with it.
    results.into_iter().flatten().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_item_is_done_once_and_returned_in_order() {
        let mut seen = Vec::new();
        let squares = each_on_own_threads(100, 3, |i| i * i, |i, &square| seen.push((i, square)));
        assert_eq!(squares, (0..100).map(|i| i * i).collect::<Vec<_>>());
        seen.sort_unstable();
        assert_eq!(seen, (0..100).map(|i| (i, i * i)).collect::<Vec<_>>());
        assert!(each_on_own_threads(0, 4, |i| i, |_, _| {}).is_empty());
    }
}
