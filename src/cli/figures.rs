//! `microslip figures`: the paper's Figures 4–8 and facts.json.

use std::path::PathBuf;

use clap::Args;
use microslip::figures::FiguresError;

use super::case::Jobs;
use super::progress::Progress;
use super::report::Failure;

#[derive(Args)]
pub struct FiguresArgs {
    /// Directory for fig4…fig8 (.csv, .svg, .png), limit_slopes.csv and facts.json.
    #[arg(long)]
    pub out: PathBuf,
    #[command(flatten)]
    pub jobs: Jobs,
}

pub fn run(args: &FiguresArgs) -> Result<String, Failure> {
    let progress = Progress::new(0);
    let summary = microslip::figures::regenerate(&args.out, &|done, total| progress.at_of(done, total, "steps"));
    progress.finish();
    // Only an unusable directory is refused input; anything failing after it was checked
    // is a failed run.
    let summary = summary.map_err(|error| match error {
        FiguresError::Directory { .. } => Failure::refused(error.to_string()),
        _ => Failure::failed(error.to_string()),
    })?;
    let facts = microslip::figures::output::FactsJson::of(&summary.figures.facts);
    Ok(format!(
        "{} files written to {}\n{}\n{}",
        summary.files.len(),
        args.out.display(),
        serde_json::to_string_pretty(&facts)?,
        summary.figures.facts.settling_report()
    ))
}
