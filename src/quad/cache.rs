//! The tables of nodes and weights (a Gauss–Legendre rule of n points, a tanh–sinh level),
//! computed once and shared by every thread.
//!
//! One entry per (table type, size) holds the table at the highest precision computed so
//! far; a lower precision is served by rounding that table's values once, and the last
//! rounded copy is kept beside it (a run asks for one precision many times). A request
//! above the entry's precision computes the table anew and replaces it, so the precision
//! ladder of verified digits holds one table per rule, not one per attempt.
//!
//! Each table is computed once under concurrency: the entry's lock is held while it is
//! computed, and a second thread asking for it waits and then rounds the result. A thread
//! already computing a table (whose rayon pool may hand it another job meanwhile) never
//! waits: where the entry is busy it computes a private copy instead, so that no thread
//! can wait for itself or for a thread waiting on it.
//!
//! Memory is bounded by [`MAX_BYTES`]: past it, the entries used least recently are
//! dropped (tables in use stay alive with their users).

use std::any::{Any, TypeId};
use std::cell::Cell;
use std::collections::HashMap;
use std::ops::RangeInclusive;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, OnceLock, TryLockError};

use crate::real::Precision;

/// A table of nodes and weights that can be rounded to a lower precision.
pub(crate) trait Table: Send + Sync + Sized + 'static {
    /// The precision of its values.
    fn precision(&self) -> Precision;
    /// The same table at `precision` (lower than its own), each value rounded once.
    fn rounded(&self, precision: Precision) -> Self;
    /// Bytes held, roughly (for the bound on the cache).
    fn bytes(&self) -> usize;
}

/// The most bytes the cached tables may hold: 64 MiB, the 4096-point rule at about
/// 7000 bits; a typical verified run at 100 digits holds well under 1 MiB.
pub(crate) const MAX_BYTES: usize = 64 << 20;

type Shared = Arc<dyn Any + Send + Sync>;

/// A table with its precision and size.
#[derive(Clone)]
struct Held {
    bits: u32,
    bytes: usize,
    table: Shared,
}

#[derive(Default)]
struct Slot {
    /// The table at the highest precision computed.
    best: Option<Held>,
    /// The last copy rounded from `best`.
    rounded: Option<Held>,
}

impl Slot {
    fn bytes(&self) -> usize {
        self.best.iter().chain(&self.rounded).map(|held| held.bytes).sum()
    }
}

#[derive(Default)]
struct Entry {
    slot: Mutex<Slot>,
    last_used: AtomicU64,
}

type Key = (TypeId, usize);

/// A set of tables within a bound on their bytes.
pub(crate) struct Cache {
    entries: Mutex<HashMap<Key, Arc<Entry>>>,
    clock: AtomicU64,
    max_bytes: usize,
}

/// The cache every computation shares.
fn shared() -> &'static Cache {
    static SHARED: OnceLock<Cache> = OnceLock::new();
    SHARED.get_or_init(|| Cache::new(MAX_BYTES))
}

fn lock<T>(mutex: &Mutex<T>) -> MutexGuard<'_, T> {
    mutex.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

thread_local! {
    /// How many tables this thread is computing (more than one where rayon has handed it
    /// another job while it waits for the parts of its own).
    static COMPUTING: Cell<u32> = const { Cell::new(0) };
}

/// `compute()` with this thread marked as computing a table.
fn computing<T>(compute: impl FnOnce() -> Option<T>) -> Option<T> {
    COMPUTING.with(|count| count.set(count.get() + 1));
    let table = compute();
    COMPUTING.with(|count| count.set(count.get() - 1));
    table
}

fn downcast<T: Table>(held: &Held) -> Option<Arc<T>> {
    Arc::clone(&held.table).downcast::<T>().ok()
}

fn held<T: Table>(table: Arc<T>) -> Held {
    Held {
        bits: table.precision().in_bits(),
        bytes: table.bytes(),
        table,
    }
}

/// The table of type `T` and `size` at `precision` from the shared cache: see [`Cache::get`].
pub(crate) fn cached<T: Table>(
    size: usize,
    precision: Precision,
    compute: impl FnOnce() -> Option<T>,
) -> Option<Arc<T>> {
    shared().get(size, precision, compute)
}

/// The least size in `sizes` whose table of type `T` the shared cache holds at `precision`
/// or above: see [`Cache::least_held`].
#[cfg(feature = "certified")]
pub(crate) fn least_held<T: Table>(sizes: RangeInclusive<usize>, precision: Precision) -> Option<usize> {
    shared().least_held::<T>(sizes, precision)
}

/// Forgets every table of the shared cache (for measuring the cold cost).
pub(crate) fn clear() {
    lock(&shared().entries).clear();
}

impl Cache {
    pub(crate) fn new(max_bytes: usize) -> Self {
        Cache {
            entries: Mutex::new(HashMap::new()),
            clock: AtomicU64::new(0),
            max_bytes,
        }
    }

    /// The table of type `T` and `size` at `precision`: from the cache (rounded down where
    /// it holds a higher precision), or computed by `compute`, which may give up (at a
    /// deadline) with `None`, leaving the cache as it was.
    pub(crate) fn get<T: Table>(
        &self,
        size: usize,
        precision: Precision,
        compute: impl FnOnce() -> Option<T>,
    ) -> Option<Arc<T>> {
        let entry = {
            let mut entries = lock(&self.entries);
            let entry = Arc::clone(entries.entry((TypeId::of::<T>(), size)).or_default());
            let now = self.clock.fetch_add(1, Ordering::Relaxed);
            entry.last_used.store(now, Ordering::Relaxed);
            entry
        };
        let mut slot = if COMPUTING.with(Cell::get) == 0 {
            lock(&entry.slot)
        } else {
            match entry.slot.try_lock() {
                Ok(slot) => slot,
                Err(TryLockError::Poisoned(poisoned)) => poisoned.into_inner(),
                Err(TryLockError::WouldBlock) => return computing(compute).map(Arc::new),
            }
        };
        let bits = precision.in_bits();
        if let Some(best) = slot.best.clone().filter(|best| best.bits >= bits) {
            if best.bits == bits {
                return downcast(&best);
            }
            if let Some(rounded) = slot.rounded.as_ref().filter(|rounded| rounded.bits == bits) {
                return downcast(rounded);
            }
            let table = Arc::new(downcast::<T>(&best)?.rounded(precision));
            slot.rounded = Some(held(Arc::clone(&table)));
            drop(slot);
            self.keep_within_bound(&entry);
            return Some(table);
        }
        let table = Arc::new(computing(compute)?);
        *slot = Slot {
            best: Some(held(Arc::clone(&table))),
            rounded: None,
        };
        drop(slot);
        self.keep_within_bound(&entry);
        Some(table)
    }

    /// The least size in `sizes` whose table of type `T` is held at `precision` or above
    /// (tables being computed are not counted): where a larger table than the one needed
    /// would serve, it may spare computing another. It may be dropped before it is asked
    /// for, and is then computed again. (Only the rules on Arb balls share tables.)
    #[cfg_attr(not(feature = "certified"), allow(dead_code))]
    pub(crate) fn least_held<T: Table>(&self, sizes: RangeInclusive<usize>, precision: Precision) -> Option<usize> {
        let bits = precision.in_bits();
        lock(&self.entries)
            .iter()
            .filter(|((kind, size), _)| *kind == TypeId::of::<T>() && sizes.contains(size))
            .filter(|(_, entry)| {
                entry
                    .slot
                    .try_lock()
                    .is_ok_and(|slot| slot.best.as_ref().is_some_and(|best| best.bits >= bits))
            })
            .map(|((_, size), _)| *size)
            .min()
    }

    /// Drops the entries used least recently, other than `keep`, until the cache holds at
    /// most its bound. Entries being computed are skipped (their size is not yet known).
    fn keep_within_bound(&self, keep: &Arc<Entry>) {
        let mut entries = lock(&self.entries);
        let mut sizes: Vec<(u64, Key, usize)> = entries
            .iter()
            .filter_map(|(key, entry)| {
                let bytes = entry.slot.try_lock().ok()?.bytes();
                Some((entry.last_used.load(Ordering::Relaxed), *key, bytes))
            })
            .collect();
        let mut total: usize = sizes.iter().map(|(_, _, bytes)| bytes).sum();
        sizes.sort_unstable_by_key(|(last_used, _, _)| *last_used);
        for (_, key, bytes) in sizes {
            if total <= self.max_bytes {
                break;
            }
            if entries.get(&key).is_some_and(|entry| !Arc::ptr_eq(entry, keep)) {
                entries.remove(&key);
                total -= bytes;
            }
        }
    }

    /// The bytes held (entries being computed excepted).
    #[cfg(test)]
    fn bytes_held(&self) -> usize {
        lock(&self.entries)
            .values()
            .filter_map(|entry| Some(entry.slot.try_lock().ok()?.bytes()))
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicUsize;
    use std::sync::Barrier;

    /// A table of `bytes` bytes at `bits`, its values the precision it was made at (so that
    /// rounding is visible).
    #[derive(Debug)]
    struct Fake {
        bits: u32,
        made_at: u32,
        bytes: usize,
    }

    impl Table for Fake {
        fn precision(&self) -> Precision {
            Precision::bits(self.bits)
        }
        fn rounded(&self, precision: Precision) -> Self {
            Fake {
                bits: precision.in_bits(),
                ..*self
            }
        }
        fn bytes(&self) -> usize {
            self.bytes
        }
    }

    fn fake(bits: u32, bytes: usize) -> impl FnOnce() -> Option<Fake> {
        move || {
            Some(Fake {
                bits,
                made_at: bits,
                bytes,
            })
        }
    }

    #[test]
    fn one_entry_per_size_rounds_down_and_recomputes_above() {
        let cache = Cache::new(1 << 20);
        let high = cache.get(7, Precision::bits(300), fake(300, 10)).unwrap();
        // Below the held precision: rounded from it, not computed.
        let low = cache.get(7, Precision::bits(100), || -> Option<Fake> { None }).unwrap();
        assert_eq!((low.bits, low.made_at), (100, 300));
        // The rounded copy is kept for the next request at its precision.
        let again = cache.get(7, Precision::bits(100), || -> Option<Fake> { None }).unwrap();
        assert!(Arc::ptr_eq(&low, &again));
        assert!(Arc::ptr_eq(
            &high,
            &cache.get(7, Precision::bits(300), fake(1, 1)).unwrap()
        ));
        // Above it: computed, and it replaces the entry.
        let higher = cache.get(7, Precision::bits(500), fake(500, 10)).unwrap();
        assert_eq!(higher.made_at, 500);
        let low = cache.get(7, Precision::bits(300), || -> Option<Fake> { None }).unwrap();
        assert_eq!((low.bits, low.made_at), (300, 500));
        // A computation that gives up leaves the cache as it was.
        assert!(cache
            .get(8, Precision::bits(100), || -> Option<Fake> { None })
            .is_none());
        assert_eq!(cache.get(8, Precision::bits(100), fake(100, 1)).unwrap().made_at, 100);
    }

    #[test]
    fn the_least_size_held_at_a_precision_is_found_in_a_range() {
        let cache = Cache::new(1 << 20);
        cache.get(40, Precision::bits(300), fake(300, 10)).unwrap();
        cache.get(36, Precision::bits(100), fake(100, 10)).unwrap();
        cache.get(48, Precision::bits(500), fake(500, 10)).unwrap();
        // 36 is held below 200 bits; 40 and 48 at or above it.
        assert_eq!(cache.least_held::<Fake>(32..=48, Precision::bits(200)), Some(40));
        assert_eq!(cache.least_held::<Fake>(32..=48, Precision::bits(100)), Some(36));
        assert_eq!(cache.least_held::<Fake>(41..=60, Precision::bits(400)), Some(48));
        assert_eq!(cache.least_held::<Fake>(32..=39, Precision::bits(200)), None);
        assert_eq!(cache.least_held::<Fake>(32..=48, Precision::bits(600)), None);
    }

    #[test]
    fn the_least_recently_used_entries_go_beyond_the_bound() {
        let cache = Cache::new(1000);
        for size in 0..10 {
            cache.get(size, Precision::bits(64), fake(64, 400)).unwrap();
            assert!(cache.bytes_held() <= 1000, "{} bytes", cache.bytes_held());
        }
        // The two most recent remain.
        let kept = |size| {
            cache
                .get(size, Precision::bits(64), || -> Option<Fake> { None })
                .is_some()
        };
        assert!(kept(9) && kept(8) && !kept(0));
        // A table beyond the bound by itself is still served (and kept while it is the newest).
        assert_eq!(cache.get(20, Precision::bits(64), fake(64, 5000)).unwrap().bytes, 5000);
    }

    #[test]
    fn concurrent_requests_compute_a_table_once() {
        let cache = Cache::new(1 << 20);
        let computations = AtomicUsize::new(0);
        let threads = 8;
        let barrier = Barrier::new(threads);
        let tables: Vec<Arc<Fake>> = std::thread::scope(|scope| {
            let handles: Vec<_> = (0..threads)
                .map(|_| {
                    scope.spawn(|| {
                        barrier.wait();
                        cache
                            .get(3, Precision::bits(200), || {
                                computations.fetch_add(1, Ordering::SeqCst);
                                // Long enough for every other thread to ask meanwhile.
                                std::thread::sleep(std::time::Duration::from_millis(50));
                                fake(200, 1)()
                            })
                            .unwrap()
                    })
                })
                .collect();
            handles.into_iter().map(|handle| handle.join().unwrap()).collect()
        });
        assert_eq!(computations.load(Ordering::SeqCst), 1);
        assert!(tables.iter().all(|table| Arc::ptr_eq(table, &tables[0])));
    }
}
