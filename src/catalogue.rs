//! The catalogue of hard cases with committed reference values
//! (`tests/data/catalogue.json`): ordinary cases of every compliance family and
//! the corners users ask for first — phases near 0 and π, ellipses at the
//! gross-slip lines, near separation, tiny amplitudes, steep and flat compliance,
//! extreme friction, P_T near 0. [`check`] recomputes the stored values and reports
//! every difference; [`regenerate`] and [`save`] replace them.

use std::path::Path;
use std::time::Duration;

use serde::{Deserialize, Serialize};

use crate::files::{write_text_atomically, OutputError};
use crate::inputs::CaseText;
use crate::reference::{verified_dissipation, ReferenceError};

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
        source: ReferenceError,
    },
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
    pub computed: Result<ReferenceValue, ReferenceError>,
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
/// is stored), each within `budget`, and returns every case whose stored value is
/// missing or differs, or which could not be computed; `progress` is told each case's
/// name as it starts.
pub fn check(
    entries: &[CatalogueEntry],
    default_digits: u32,
    budget: Duration,
    mut progress: impl FnMut(usize, &str),
) -> Vec<Difference> {
    let mut differences = Vec::new();
    for (index, entry) in entries.iter().enumerate() {
        progress(index, &entry.name);
        let digits = entry.reference.as_ref().map_or(default_digits, |r| r.digits);
        let computed = verified_dissipation(&entry.case, digits, budget).map(|verified| ReferenceValue {
            digits: verified.digits_verified,
            w: verified.total,
        });
        if computed.as_ref().ok() != entry.reference.as_ref() {
            differences.push(Difference {
                name: entry.name.clone(),
                stored: entry.reference.clone(),
                computed,
            });
        }
    }
    differences
}

/// Computes every case's reference value to `digits` verified digits, each within `budget`;
/// `progress` is told each case's name as it starts.
pub fn regenerate(
    entries: &[CatalogueEntry],
    digits: u32,
    budget: Duration,
    mut progress: impl FnMut(usize, &str),
) -> Result<Vec<CatalogueEntry>, CatalogueError> {
    entries
        .iter()
        .enumerate()
        .map(|(index, entry)| {
            progress(index, &entry.name);
            let verified =
                verified_dissipation(&entry.case, digits, budget).map_err(|source| CatalogueError::Case {
                    name: entry.name.clone(),
                    source,
                })?;
            Ok(CatalogueEntry {
                reference: Some(ReferenceValue {
                    digits: verified.digits_verified,
                    w: verified.total,
                }),
                ..entry.clone()
            })
        })
        .collect()
}
