//! Items handed in chunk after chunk to a fixed number of threads that live as long as
//! their pool, each thread taking the next item as soon as it has finished one: no item
//! waits for a thread to hand it over, and no thread for the rest of a chunk, so that
//! every core stays busy across chunks.
//!
//! An item that outlasts the time limit is given up (its result says so) and left to
//! finish on its thread, which then ends; a new thread takes its place.
//!
//! Written here because no pool crate gives up on a running item: rayon's and
//! threadpool's tasks cannot be abandoned, so one late row would hold a core and the
//! batch's order until it ended, however long past its budget.

use std::collections::VecDeque;
use std::sync::{Arc, Condvar, Mutex, MutexGuard, PoisonError};
use std::time::{Duration, Instant};

/// Stack of a worker thread: as large as a command's worker has.
const STACK_BYTES: usize = 64 << 20;

/// How often a caller waiting for a chunk is told how many items have finished.
const PROGRESS_INTERVAL: Duration = Duration::from_millis(100);

/// Why an item has no result of its own.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unanswered {
    /// It outlasted the time limit.
    Late,
    /// No thread could be started to compute it.
    NoThread,
    /// Its computation panicked.
    Panicked,
}

/// What an item that has no result of its own gets instead.
type Unanswering<T, R> = Box<dyn Fn(&T, Unanswered) -> R + Send + Sync>;

/// Items handed in together, and their results in order as they come.
struct Chunk<T, R> {
    ticket: u64,
    items: Arc<[T]>,
    /// The first item no thread has taken.
    next: usize,
    results: Vec<Option<R>>,
    /// Items without a result yet.
    unanswered: usize,
}

/// What a worker thread is doing.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Worker {
    /// Waiting for items.
    Idle,
    /// Computing item `index` of chunk `ticket` since `started`.
    Busy {
        ticket: u64,
        index: usize,
        started: Instant,
    },
    /// Given up at its item's time limit (or never started): it takes no more items.
    Gone,
}

struct State<T, R> {
    /// Chunks handed in and not yet collected, in the order they were handed in.
    chunks: VecDeque<Chunk<T, R>>,
    workers: Vec<Worker>,
    next_ticket: u64,
    /// Items finished since the pool started.
    finished: usize,
    /// The pool has been dropped: idle threads end.
    closed: bool,
}

impl<T, R> State<T, R> {
    /// The first item no thread has taken: its chunk's ticket, its index and the chunk's items.
    fn take(&mut self) -> Option<(u64, usize, Arc<[T]>)> {
        let chunk = self.chunks.iter_mut().find(|chunk| chunk.next < chunk.items.len())?;
        chunk.next += 1;
        Some((chunk.ticket, chunk.next - 1, Arc::clone(&chunk.items)))
    }

    /// Records the result of an item; true when it was its chunk's last.
    fn answer(&mut self, ticket: u64, index: usize, result: R) -> bool {
        let Some(chunk) = self.chunks.iter_mut().find(|chunk| chunk.ticket == ticket) else {
            return false;
        };
        if chunk.results[index].is_some() {
            return false;
        }
        chunk.results[index] = Some(result);
        chunk.unanswered -= 1;
        self.finished += 1;
        chunk.unanswered == 0
    }
}

/// What the pool's threads share: the state, and what they compute.
struct Shared<T, R> {
    state: Mutex<State<T, R>>,
    /// Items to take have been handed in, or the pool closed.
    work: Condvar,
    /// A chunk has been answered whole.
    chunk_answered: Condvar,
    compute: Box<dyn Fn(&T) -> R + Send + Sync>,
    unanswered: Unanswering<T, R>,
    limit: Duration,
}

impl<T, R> Shared<T, R> {
    fn lock(&self) -> MutexGuard<'_, State<T, R>> {
        // The state is changed only by code that cannot panic part-way.
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

/// Items handed in, to be collected with the pool's `collect`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Ticket(u64);

/// Threads of their own computing items one at a time, each within a time limit.
pub struct TimedWorkers<T, R> {
    shared: Arc<Shared<T, R>>,
}

impl<T: Send + Sync + 'static, R: Send + 'static> TimedWorkers<T, R> {
    /// `threads` threads (at least one) computing `compute(item)`; an item that runs past
    /// `limit`, finds no thread or panics gets `unanswered(item, why)` instead.
    pub fn new(
        threads: usize,
        limit: Duration,
        compute: impl Fn(&T) -> R + Send + Sync + 'static,
        unanswered: impl Fn(&T, Unanswered) -> R + Send + Sync + 'static,
    ) -> Self {
        let workers = TimedWorkers {
            shared: Arc::new(Shared {
                state: Mutex::new(State {
                    chunks: VecDeque::new(),
                    workers: Vec::new(),
                    next_ticket: 0,
                    finished: 0,
                    closed: false,
                }),
                work: Condvar::new(),
                chunk_answered: Condvar::new(),
                compute: Box::new(compute),
                unanswered: Box::new(unanswered),
                limit,
            }),
        };
        let mut state = workers.shared.lock();
        for _ in 0..threads.max(1) {
            start_worker(&workers.shared, &mut state);
        }
        drop(state);
        workers
    }

    /// Hands in `items`, to be computed after those handed in before them.
    pub fn hand_in(&self, items: Arc<[T]>) -> Ticket {
        let mut state = self.shared.lock();
        let ticket = state.next_ticket;
        state.next_ticket += 1;
        state.chunks.push_back(Chunk {
            ticket,
            results: std::iter::repeat_with(|| None).take(items.len()).collect(),
            unanswered: items.len(),
            next: 0,
            items,
        });
        drop(state);
        self.shared.work.notify_all();
        Ticket(ticket)
    }

    /// The results of the items handed in with `ticket`, in their order, once all are
    /// finished (none for a ticket already collected); meanwhile `progress` is told every
    /// [`PROGRESS_INTERVAL`] how many items the pool has finished, and items past the
    /// time limit are given up.
    pub fn collect(&self, ticket: Ticket, progress: &mut dyn FnMut(usize)) -> Vec<R> {
        let mut state = self.shared.lock();
        loop {
            let wait = self.give_up_late_items(&mut state);
            let position = state.chunks.iter().position(|chunk| chunk.ticket == ticket.0);
            let Some(position) = position else {
                return Vec::new();
            };
            if state.chunks[position].unanswered == 0 {
                let chunk = state.chunks.remove(position);
                return chunk.map_or_else(Vec::new, |chunk| chunk.results.into_iter().flatten().collect());
            }
            state = self
                .shared
                .chunk_answered
                .wait_timeout(state, wait.min(PROGRESS_INTERVAL))
                .unwrap_or_else(PoisonError::into_inner)
                .0;
            let finished = state.finished;
            drop(state);
            progress(finished);
            state = self.shared.lock();
        }
    }

    /// Gives up the items that have outlasted the limit, each thread replaced by a new
    /// one, and the items no thread can take; the time until the next item would run out.
    fn give_up_late_items(&self, state: &mut State<T, R>) -> Duration {
        let now = Instant::now();
        let limit = self.shared.limit;
        let mut wait = limit;
        for slot in 0..state.workers.len() {
            let Worker::Busy { ticket, index, started } = state.workers[slot] else {
                continue;
            };
            let left = limit.saturating_sub(now.saturating_duration_since(started));
            if !left.is_zero() {
                wait = wait.min(left);
                continue;
            }
            state.workers[slot] = Worker::Gone;
            self.give_up(state, ticket, index, Unanswered::Late);
            start_worker(&self.shared, state);
        }
        if state.workers.iter().all(|worker| *worker == Worker::Gone) {
            while let Some((ticket, index, _)) = state.take() {
                self.give_up(state, ticket, index, Unanswered::NoThread);
            }
        }
        wait
    }

    /// Answers item `index` of chunk `ticket` as unanswered for `why`.
    fn give_up(&self, state: &mut State<T, R>, ticket: u64, index: usize, why: Unanswered) {
        let items = state.chunks.iter().find(|chunk| chunk.ticket == ticket);
        if let Some(result) = items.map(|chunk| (self.shared.unanswered)(&chunk.items[index], why)) {
            state.answer(ticket, index, result);
        }
    }
}

impl<T, R> Drop for TimedWorkers<T, R> {
    fn drop(&mut self) {
        self.shared.lock().closed = true;
        self.shared.work.notify_all();
    }
}

/// Starts a worker thread (marked gone if it cannot be started).
fn start_worker<T: Send + Sync + 'static, R: Send + 'static>(shared: &Arc<Shared<T, R>>, state: &mut State<T, R>) {
    let slot = state.workers.len();
    state.workers.push(Worker::Idle);
    let shared = Arc::clone(shared);
    let started = std::thread::Builder::new()
        .stack_size(STACK_BYTES)
        .spawn(move || work(&shared, slot));
    if started.is_err() {
        state.workers[slot] = Worker::Gone;
    }
}

/// The life of worker `slot`: the next item untaken, until the pool closes or its item
/// is given up.
fn work<T, R>(shared: &Shared<T, R>, slot: usize) {
    let mut state = shared.lock();
    loop {
        if state.closed || state.workers[slot] == Worker::Gone {
            return;
        }
        let Some((ticket, index, items)) = state.take() else {
            state = shared.work.wait(state).unwrap_or_else(PoisonError::into_inner);
            continue;
        };
        state.workers[slot] = Worker::Busy {
            ticket,
            index,
            started: Instant::now(),
        };
        drop(state);
        let item = &items[index];
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| (shared.compute)(item)))
            .unwrap_or_else(|_| (shared.unanswered)(item, Unanswered::Panicked));
        state = shared.lock();
        if state.workers[slot] == Worker::Gone {
            // Given up at the limit: the item has its result, and another thread this one's place.
            return;
        }
        state.workers[slot] = Worker::Idle;
        if state.answer(ticket, index, result) {
            shared.chunk_answered.notify_all();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The ids of the items, as they finish.
    type Finished = Arc<Mutex<Vec<u64>>>;

    /// Workers on items (id, milliseconds).
    type Sleepers = TimedWorkers<(u64, u64), Result<u64, Unanswered>>;

    /// Items (id, milliseconds) that sleep for their milliseconds, note their id as they
    /// finish, and answer it; an item of u64::MAX milliseconds panics.
    fn sleepers(threads: usize, limit_ms: u64) -> (Sleepers, Finished) {
        let finished = Finished::default();
        let noted = Arc::clone(&finished);
        let workers = TimedWorkers::new(
            threads,
            Duration::from_millis(limit_ms),
            move |&(id, ms)| {
                assert!(ms < u64::MAX, "item {id} panics");
                std::thread::sleep(Duration::from_millis(ms));
                noted.lock().unwrap().push(id);
                Ok(id)
            },
            |_, why| Err(why),
        );
        (workers, finished)
    }

    #[test]
    fn items_of_very_unequal_cost_come_back_in_order_while_the_other_thread_goes_on_across_chunks() {
        let (workers, finished) = sleepers(2, 60_000);
        // A slow item first: the other thread computes every other item, of both chunks, meanwhile.
        let first: Vec<(u64, u64)> = std::iter::once((0, 1_000)).chain((1..40).map(|id| (id, 0))).collect();
        let second: Vec<(u64, u64)> = (40..80).map(|id| (id, 0)).collect();
        let tickets = [workers.hand_in(first.into()), workers.hand_in(second.into())];
        let mut told = Vec::new();
        let results = tickets.map(|ticket| workers.collect(ticket, &mut |count| told.push(count)));
        assert_eq!(results[0], (0..40).map(Ok).collect::<Vec<_>>());
        assert_eq!(results[1], (40..80).map(Ok).collect::<Vec<_>>());
        assert_eq!(finished.lock().unwrap().last(), Some(&0));
        assert!(told.windows(2).all(|pair| pair[0] <= pair[1]), "{told:?}");
        assert!(workers.collect(tickets[0], &mut |_| {}).is_empty());
    }

    #[test]
    fn an_item_past_the_limit_fails_alone_and_its_thread_is_replaced() {
        let (workers, finished) = sleepers(1, 200);
        let started = Instant::now();
        let ticket = workers.hand_in(vec![(0, 5), (1, 5_000), (2, 5)].into());
        let results = workers.collect(ticket, &mut |_| {});
        assert_eq!(results, [Ok(0), Err(Unanswered::Late), Ok(2)]);
        let elapsed = started.elapsed();
        assert!(elapsed < Duration::from_millis(2_000), "{elapsed:?}");
        // The new thread goes on with the next chunk while the late item still sleeps.
        let ticket = workers.hand_in(vec![(3, 1), (4, 1)].into());
        assert_eq!(workers.collect(ticket, &mut |_| {}), [Ok(3), Ok(4)]);
        assert_eq!(*finished.lock().unwrap(), [0, 2, 3, 4]);
    }

    #[test]
    fn an_item_that_panics_fails_alone_and_its_thread_goes_on() {
        let (workers, finished) = sleepers(1, 60_000);
        let ticket = workers.hand_in(vec![(0, 1), (1, u64::MAX), (2, 1)].into());
        let results = workers.collect(ticket, &mut |_| {});
        assert_eq!(results, [Ok(0), Err(Unanswered::Panicked), Ok(2)]);
        assert_eq!(*finished.lock().unwrap(), [0, 2]);
    }

    #[test]
    fn an_empty_chunk_is_answered_at_once() {
        let (workers, _) = sleepers(2, 100);
        let ticket = workers.hand_in(Vec::new().into());
        assert!(workers.collect(ticket, &mut |_| {}).is_empty());
    }
}
