//! The catalogue of hard cases with committed reference values
//! (`tests/data/catalogue.json`): ordinary cases of every compliance family and
//! the corners users ask for first — phases near 0 and π, ellipses at the
//! gross-slip lines, near separation, tiny amplitudes, steep and flat compliance,
//! extreme friction, P_T near 0.

use std::path::Path;
use std::time::Duration;

use serde::{Deserialize, Serialize};

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
    /// The file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    /// The file is not a catalogue.
    #[error("{path}: not a catalogue ({source})")]
    Format {
        path: String,
        #[source]
        source: serde_json::Error,
    },
    /// A case could not be computed.
    #[error("case '{name}': {source}")]
    Case {
        name: String,
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

/// Writes a catalogue file (pretty JSON, one case per block).
pub fn save(path: &Path, entries: &[CatalogueEntry]) -> Result<(), CatalogueError> {
    let mut text = serde_json::to_string_pretty(entries).map_err(|source| CatalogueError::Format {
        path: path.display().to_string(),
        source,
    })?;
    text.push('\n');
    std::fs::write(path, text).map_err(|source| CatalogueError::Io {
        path: path.display().to_string(),
        source,
    })
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
