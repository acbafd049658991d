//! `microslip reference`: check (or rewrite) a catalogue's reference values.

use std::path::PathBuf;
use std::time::Duration;

use clap::Args;

use microslip::catalogue;
use microslip::files::check_writable;

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
    /// Time budget per case, in seconds (up to 1e6).
    #[arg(long, allow_hyphen_values = true, value_parser = parse::seconds, default_value = "120")]
    pub max_seconds: Duration,
}

pub fn run(args: &ReferenceArgs) -> Result<String, Failure> {
    let entries = catalogue::load(&args.catalogue)?;
    let total = entries.len();
    let progress = Progress::new(total);
    let show = |index: usize, name: &str| progress.at(index, name);
    if args.write {
        check_writable(&args.catalogue, &[])?;
        let digits = args.digits.unwrap_or(50);
        let updated = catalogue::regenerate(&entries, digits, args.max_seconds, show);
        progress.finish();
        let updated = updated?;
        catalogue::save(&args.catalogue, &updated).map_err(|e| Failure::failed(e.to_string()))?;
        return Ok(format!(
            "{} reference values to {digits} verified digits written to {}",
            updated.len(),
            args.catalogue.display()
        ));
    }
    let differences = catalogue::check(&entries, args.digits.unwrap_or(50), args.max_seconds, show);
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
