//! The former home of the case's text form, now [`crate::case`].
// For the lead at merge: once src/reference.rs, src/batch.rs, src/batch/input.rs,
// src/exact/printing.rs, src/catalogue.rs, src/cli/{case,json,series}.rs, the tests and
// benches import from `crate::case`, remove this module.

pub use crate::case::{parse_phase, Case, CaseText, InputError};
