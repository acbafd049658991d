//! The catalogue of hard cases with committed reference values
//! (`tests/data/catalogue.json`): ordinary cases of every compliance family and
//! the corners users ask for first — phases near 0 and π, ellipses at the
//! gross-slip lines, near separation, tiny amplitudes, steep and flat compliance,
//! extreme friction, P_T near 0. [`check`] recomputes the stored values and reports
//! every difference; [`regenerate`] and [`save`] replace them. A reference value is a
//! verified decimal, so a compliance from a table (known only to its table error) has
//! none.

use std::path::Path;
use std::time::{Duration, Instant};

use serde::{Deserialize, Serialize};

use crate::answer::dissipation::dissipation_answer;
use crate::answer::DissipationAnswerError;
use crate::case::CaseText;
use crate::files::{write_text_atomically, OutputError};

/// One catalogue case and, once computed, its reference value.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CatalogueEntry {
    /// A short unique name, e.g. `near-separation`.
    pub name: String,
    /// What makes the case interesting.
    pub description: String,
    /// The loads and compliance.
    pub case: CaseText,
    /// W to `digits` verified significant digits.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference: Option<ReferenceValue>,
}

/// A verified reference value.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ReferenceValue {
    /// Verified significant digits.
    pub digits: u32,
    /// W, as a decimal string with `digits` significant digits.
    #[serde(rename = "W")]
    pub w: String,
}

/// Reading, writing or computing the catalogue failed.
#[derive(Debug, thiserror::Error)]
pub enum CatalogueError {
    /// The file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The catalogue file.
        path: String,
        /// The system's error.
        #[source]
        source: std::io::Error,
    },
    /// The file could not be written.
    #[error(transparent)]
    Output(#[from] OutputError),
    /// The file is not a catalogue.
    #[error("{path}: not a catalogue ({source})")]
    Format {
        /// The catalogue file.
        path: String,
        /// Where and why the JSON does not read as a catalogue.
        #[source]
        source: serde_json::Error,
    },
    /// A case could not be computed.
    #[error("case '{name}': {source}")]
    Case {
        /// The case's name in the catalogue.
        name: String,
        /// Why it could not be computed.
        #[source]
        source: EntryError,
    },
}

/// Why a case has no reference value.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EntryError {
    /// Its computation failed, or its compliance has a table.
    #[error(transparent)]
    Case(#[from] DissipationAnswerError),
    /// The run's time budget ran out before the case was started.
    #[error("not computed: the time budget of {0:.1} s for the whole run ran out before this case")]
    NotReached(f64),
}

/// The reference value of `case` to `digits` digits, by `deadline`, as
/// [`dissipation_answer`] gives them (certified where an enclosure can be had): for a
/// compliance with a table, the digits of its interpolant's W.
pub fn reference_value(
    case: &CaseText,
    digits: u32,
    deadline: Instant,
) -> Result<ReferenceValue, DissipationAnswerError> {
    let budget = deadline.saturating_duration_since(Instant::now());
    let answer = dissipation_answer(case, Some(digits), budget)?;
    Ok(ReferenceValue {
        digits: answer.digits(),
        w: answer.value.decimal.to_string(),
    })
}

/// [`reference_value`] within a run that started at `started` with `budget`.
fn value_within(
    case: &CaseText,
    digits: u32,
    started: Instant,
    budget: Duration,
) -> Result<ReferenceValue, EntryError> {
    let deadline = started + budget;
    if Instant::now() >= deadline {
        return Err(EntryError::NotReached(budget.as_secs_f64()));
    }
    Ok(reference_value(case, digits, deadline)?)
}

/// Reads a catalogue file.
pub fn load(path: &Path) -> Result<Vec<CatalogueEntry>, CatalogueError> {
    let text = std::fs::read_to_string(path).map_err(|source| CatalogueError::Io {
        path: path.display().to_string(),
        source,
    })?;
    serde_json::from_str(&text).map_err(|source| CatalogueError::Format {
        path: path.display().to_string(),
        source,
    })
}

/// Writes a catalogue file (pretty JSON, one case per block) atomically: a failed
/// write leaves the old file whole.
pub fn save(path: &Path, entries: &[CatalogueEntry]) -> Result<(), CatalogueError> {
    let mut text = serde_json::to_string_pretty(entries).map_err(|source| CatalogueError::Format {
        path: path.display().to_string(),
        source,
    })?;
    text.push('\n');
    Ok(write_text_atomically(path, &text)?)
}

/// A stored reference value that a fresh computation does not reproduce.
#[derive(Clone, Debug)]
pub struct Difference {
    /// The case's name.
    pub name: String,
    /// The stored value, if any.
    pub stored: Option<ReferenceValue>,
    /// The value computed now, to the stored digits, or why it could not be.
    pub computed: Result<ReferenceValue, EntryError>,
}

impl std::fmt::Display for Difference {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let stored = match &self.stored {
            Some(value) => format!("stored W = {} ({} digits)", value.w, value.digits),
            None => "no stored value".to_string(),
        };
        match &self.computed {
            Ok(value) => write!(f, "{}: {stored}, computed W = {}", self.name, value.w),
            Err(error) => write!(f, "{}: {stored}, cannot be computed: {error}", self.name),
        }
    }
}

/// Recomputes every case to its stored number of digits (`default_digits` where none
/// is stored), all within `budget`, and returns every case whose stored value is
/// missing or differs, or which could not be computed (a failure is never a match);
/// `progress` is told each case's name as it starts.
pub fn check(
    entries: &[CatalogueEntry],
    default_digits: u32,
    budget: Duration,
    mut progress: impl FnMut(usize, &str),
) -> Vec<Difference> {
    let started = Instant::now();
    let mut differences = Vec::new();
    for (index, entry) in entries.iter().enumerate() {
        progress(index, &entry.name);
        let digits = entry.reference.as_ref().map_or(default_digits, |r| r.digits);
        let computed = value_within(&entry.case, digits, started, budget);
        let reproduced = matches!((&computed, &entry.reference), (Ok(now), Some(stored)) if now == stored);
        if !reproduced {
            differences.push(Difference {
                name: entry.name.clone(),
                stored: entry.reference.clone(),
                computed,
            });
        }
    }
    differences
}

/// Computes every case's reference value to `digits` verified digits, all within
/// `budget`; the first case that fails ends it. `progress` is told each case's name as
/// it starts.
pub fn regenerate(
    entries: &[CatalogueEntry],
    digits: u32,
    budget: Duration,
    mut progress: impl FnMut(usize, &str),
) -> Result<Vec<CatalogueEntry>, CatalogueError> {
    let started = Instant::now();
    entries
        .iter()
        .enumerate()
        .map(|(index, entry)| {
            progress(index, &entry.name);
            let value = value_within(&entry.case, digits, started, budget).map_err(|source| CatalogueError::Case {
                name: entry.name.clone(),
                source,
            })?;
            Ok(CatalogueEntry {
                reference: Some(value),
                ..entry.clone()
            })
        })
        .collect()
}
