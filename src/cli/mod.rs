//! Helpers of the command line: argument parsers shared by every subcommand, the
//! typed JSON reports, progress bars, and how results and failures reach the terminal.

pub mod budget;
pub mod json;
pub mod parse;
pub mod progress;
pub mod report;
