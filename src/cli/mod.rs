//! The command line's subcommands, one file each (its flags and its run: parse, call
//! the library, print), and their helpers: argument parsers and the shared flags, the
//! typed JSON reports, the progress display, the time budget, and how results and
//! failures reach the terminal. `completions` and `man` describe the command tree itself.

pub mod accuracy;
pub mod batch;
pub mod budget;
pub mod case;
pub mod completions;
pub mod dissipation;
pub mod durations;
pub mod figures;
pub mod json;
pub mod man;
pub mod parse;
pub mod path;
pub mod progress;
pub mod reference;
pub mod report;
pub mod series;
pub mod series_remainder;
pub mod signals;
pub mod simulate;
pub mod small_amplitude;
pub mod table;
pub mod verify;
