//! What a computation on enclosures (Arb balls, f64 intervals) could not decide, counted
//! per thread: comparisons of overlapping values, and functions asked for an analytic
//! continuation where they have none. Both number types share these counters, so that one
//! [`watch`] covers a computation whichever type it runs on.

use std::cell::{Cell, RefCell};

thread_local! {
    static UNDECIDED: Cell<u64> = const { Cell::new(0) };
    static NOT_ANALYTIC: Cell<u64> = const { Cell::new(0) };
    static ANALYTIC_MODE: Cell<bool> = const { Cell::new(false) };
    static SITES: RefCell<Option<Vec<String>>> = const { RefCell::new(None) };
}

/// What a computation on enclosures could not decide.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Doubts {
    /// Comparisons of overlapping enclosures (each answered `false`).
    pub undecided_comparisons: u64,
    /// Functions asked for an analytic continuation across a branch cut or a sign change.
    pub not_analytic: u64,
}

impl Doubts {
    /// Whether the computation decided everything it branched on.
    pub fn none(&self) -> bool {
        self.undecided_comparisons == 0 && self.not_analytic == 0
    }
}

/// Runs `computation` and reports what it could not decide (on this thread).
pub fn watch<T>(computation: impl FnOnce() -> T) -> (T, Doubts) {
    let before = (UNDECIDED.get(), NOT_ANALYTIC.get());
    let value = computation();
    let doubts = Doubts {
        undecided_comparisons: UNDECIDED.get() - before.0,
        not_analytic: NOT_ANALYTIC.get() - before.1,
    };
    (value, doubts)
}

/// Runs `computation` and gives its value where it decided everything it branched on,
/// `None` otherwise; what it could not decide is not counted against an enclosing
/// [`watch`]: for a question whose undecided answer the caller handles itself (a finer
/// subdivision, a bracket that stops shrinking).
pub fn if_decided<T>(computation: impl FnOnce() -> T) -> Option<T> {
    let before = (UNDECIDED.get(), NOT_ANALYTIC.get());
    let located = SITES.with_borrow(|sites| sites.as_ref().map(Vec::len));
    let value = computation();
    let decided = (UNDECIDED.get(), NOT_ANALYTIC.get()) == before;
    UNDECIDED.set(before.0);
    NOT_ANALYTIC.set(before.1);
    SITES.with_borrow_mut(|sites| {
        if let (Some(sites), Some(length)) = (sites.as_mut(), located) {
            sites.truncate(length);
        }
    });
    decided.then_some(value)
}

/// Runs `computation` with every function required (`true`) to be analytic on its
/// complex argument, as Arb's integration asks when it bounds an integrand on a ball.
pub fn with_analytic<T>(required: bool, computation: impl FnOnce() -> T) -> T {
    let before = ANALYTIC_MODE.replace(required);
    let value = computation();
    ANALYTIC_MODE.set(before);
    value
}

pub(crate) fn undecided() {
    UNDECIDED.set(UNDECIDED.get() + 1);
    SITES.with_borrow_mut(|sites| {
        if let Some(sites) = sites {
            sites.push(call_site());
        }
    });
}

/// Runs `computation` as [`watch`] does, and also names where each undecided comparison
/// was asked: per comparison, the frames of this crate's code that led to it, innermost
/// first (outside the number types' modules). For locating a tie that no precision resolves; the
/// frames' names need the debug information the release profile keeps.
pub fn locate_doubts<T>(computation: impl FnOnce() -> T) -> (T, Doubts, Vec<String>) {
    let outer = SITES.replace(Some(Vec::new()));
    let (value, doubts) = watch(computation);
    let sites = SITES.replace(outer).unwrap_or_default();
    (value, doubts, sites)
}

/// The modules whose frames a located doubt leaves out: the number types and this one.
const NUMBER_MODULES: [&str; 3] = ["microslip::ball::", "microslip::interval::", "microslip::doubts::"];

/// The frames of this crate (outside the number types' modules) on the current stack,
/// innermost first.
fn call_site() -> String {
    let trace = std::backtrace::Backtrace::force_capture().to_string();
    let mut frames = Vec::new();
    let mut lines = trace.lines().map(str::trim).peekable();
    while let Some(line) = lines.next() {
        let Some((_, function)) = line.split_once(": ") else {
            continue;
        };
        let location = lines.peek().and_then(|next| next.strip_prefix("at ")).unwrap_or("");
        let inside_numbers = NUMBER_MODULES.iter().any(|module| function.starts_with(module));
        if function.starts_with("microslip::") && !inside_numbers {
            let short = location.rsplit_once("/src/").map_or(location, |(_, file)| file);
            frames.push(format!("{function} (src/{short})"));
        }
    }
    frames.join(" <- ")
}

pub(crate) fn not_analytic() {
    NOT_ANALYTIC.set(NOT_ANALYTIC.get() + 1);
}

pub(crate) fn analytic_required() -> bool {
    ANALYTIC_MODE.get()
}
