//! `microslip reference`: check (or rewrite) a catalogue's reference values.

use std::path::PathBuf;
use std::sync::Mutex;
use std::time::Duration;

use clap::Args;

use microslip::catalogue::{self, CatalogueEntry};
use microslip::files::check_writable;

use super::budget::within_or;
use super::parse;
use super::progress::Progress;
use super::report::Failure;

#[derive(Args)]
pub struct ReferenceArgs {
    /// The catalogue file (JSON).
    #[arg(long)]
    pub catalogue: PathBuf,
    /// Replace the stored values with freshly computed ones (atomically) instead of checking them.
    #[arg(long)]
    pub write: bool,
    /// Verified significant digits per case (1–1000): with --write, for every case (default 50);
    /// when checking, for cases without a stored value (the others are checked to their stored digits).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::digits)]
    pub digits: Option<u32>,
    /// Time budget of the whole run (all cases together), in seconds (up to 1e6).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::seconds, default_value = "120")]
    pub max_seconds: Duration,
}

/// Checks (or with --write rewrites) the catalogue within --max-seconds for the whole
/// run: a case that fails or runs out of time is a failure, named.
pub fn run(args: &ReferenceArgs) -> Result<String, Failure> {
    let entries = catalogue::load(&args.catalogue)?;
    if args.write {
        check_writable(&args.catalogue, &[])?;
    }
    let current = Mutex::new(String::new());
    let timed_out = || {
        let name = current.lock().map(|name| name.clone()).unwrap_or_default();
        Failure::failed(format!(
            "the time budget of {} s for the whole run ran out while case '{name}' was computed (nothing written); raise --max-seconds",
            args.max_seconds.as_secs_f64()
        ))
    };
    within_or(args.max_seconds, || check_or_write(args, &entries, &current), timed_out)
}

fn check_or_write(
    args: &ReferenceArgs,
    entries: &[CatalogueEntry],
    current: &Mutex<String>,
) -> Result<String, Failure> {
    let total = entries.len();
    let progress = Progress::new(total);
    let show = |index: usize, name: &str| {
        if let Ok(mut current) = current.lock() {
            name.clone_into(&mut current);
        }
        progress.at(index, name);
    };
    if args.write {
        let digits = args.digits.unwrap_or(50);
        let updated = catalogue::regenerate(entries, digits, args.max_seconds, show);
        progress.finish();
        let updated = updated.map_err(|error| Failure::failed(format!("{error} (nothing written)")))?;
        catalogue::save(&args.catalogue, &updated).map_err(|e| Failure::failed(e.to_string()))?;
        return Ok(format!(
            "{} reference values to {digits} verified digits written to {}",
            updated.len(),
            args.catalogue.display()
        ));
    }
    let differences = catalogue::check(entries, args.digits.unwrap_or(50), args.max_seconds, show);
    progress.finish();
    if differences.is_empty() {
        return Ok(format!(
            "all {total} reference values in {} reproduce to their stored digits",
            args.catalogue.display()
        ));
    }
    let mut message = format!(
        "{} of {total} reference values in {} are not reproduced (nothing written; --write replaces them):",
        differences.len(),
        args.catalogue.display()
    );
    for difference in &differences {
        message.push_str(&format!("\n  {difference}"));
    }
    Err(Failure::failed(message))
}
