//! The tables of nodes and weights, computed once per (table type, size, precision) and
//! shared: a Gauss–Legendre rule of n points, a tanh–sinh level.

use std::any::{Any, TypeId};
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use crate::real::Precision;

type Key = (TypeId, usize, u32);
type Map = HashMap<Key, Arc<dyn Any + Send + Sync>>;

fn map() -> &'static Mutex<Map> {
    static CACHE: OnceLock<Mutex<Map>> = OnceLock::new();
    CACHE.get_or_init(|| Mutex::new(HashMap::new()))
}

/// The table of type `T` for `size` at `precision`, computed by `compute` on first use.
pub(crate) fn cached<T: Send + Sync + 'static>(
    size: usize,
    precision: Precision,
    compute: impl FnOnce() -> T,
) -> Arc<T> {
    let key = (TypeId::of::<T>(), size, precision.in_bits());
    if let Some(table) = map().lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
        if let Ok(table) = Arc::clone(table).downcast::<T>() {
            return table;
        }
    }
    let table = Arc::new(compute());
    map()
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .insert(key, Arc::clone(&table) as Arc<dyn Any + Send + Sync>);
    table
}

/// Forgets every cached table (for measuring the cold cost).
pub(crate) fn clear() {
    map().lock().unwrap_or_else(|e| e.into_inner()).clear();
}
