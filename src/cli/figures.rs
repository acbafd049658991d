//! `microslip figures`: the paper's Figures 4–8, the cubic law's error and facts.json.

use std::path::PathBuf;

use clap::{Args, ValueEnum};
use microslip::figures::output::DEFAULT_FORMATS;
use microslip::plot::Format;

use super::case::Jobs;
use super::progress::Progress;
use super::report::Failure;

#[derive(Args)]
pub struct FiguresArgs {
    /// Directory for fig4…fig8 and cubic_law_error (.csv and the pictures), limit_slopes.csv
    /// and facts.json.
    #[arg(long)]
    pub out: PathBuf,
    /// The picture formats, comma-separated or repeated: svg, png (at 2×) and pdf
    /// (vector, the font embedded, 85 mm wide). Default: svg,png.
    #[arg(long, value_enum, value_delimiter = ',')]
    pub format: Vec<PictureFormat>,
    #[command(flatten)]
    pub jobs: Jobs,
}

/// A picture format of `--format`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum PictureFormat {
    Svg,
    Png,
    Pdf,
}

impl From<PictureFormat> for Format {
    fn from(format: PictureFormat) -> Self {
        match format {
            PictureFormat::Svg => Format::Svg,
            PictureFormat::Png => Format::Png,
            PictureFormat::Pdf => Format::Pdf,
        }
    }
}

pub fn run(args: &FiguresArgs) -> Result<String, Failure> {
    let mut formats: Vec<Format> = Vec::new();
    for format in args.format.iter().map(|&f| Format::from(f)) {
        if !formats.contains(&format) {
            formats.push(format);
        }
    }
    if formats.is_empty() {
        formats = DEFAULT_FORMATS.to_vec();
    }
    let progress = Progress::new(0);
    let summary =
        microslip::figures::regenerate(&args.out, &formats, &|done, total| progress.at_of(done, total, "steps"));
    progress.finish();
    let summary = summary.map_err(|error| Failure::of(&error, false))?;
    let facts = microslip::figures::output::FactsJson::of(&summary.figures.facts);
    let mut text = format!(
        "{} files written to {}\n{}\n{}",
        summary.files.len(),
        args.out.display(),
        serde_json::to_string_pretty(&facts)?,
        summary.figures.facts.settling_report()
    );
    if !summary.cubic_law.is_empty() {
        text.push('\n');
        text.push_str(&microslip::figures::cubic_law::band_report(&summary.cubic_law));
    }
    Ok(text)
}
