//! `microslip accuracy`: accuracy against cost of every rule, as CSV, pictures and a table.

use std::path::PathBuf;

use clap::Args;

use microslip::accuracy;
use microslip::files::check_writable;
use microslip::plot::{accuracy_picture, write_all_or_none, Format};

use super::durations::ACCURACY_QUICK;
use super::progress::Progress;
use super::report::Failure;

#[derive(Args)]
pub struct AccuracyArgs {
    /// Directory for accuracy.csv, accuracy.svg and accuracy.png (created if missing).
    #[arg(long)]
    pub out: PathBuf,
    #[arg(long, help = format!("Fewer cases, precisions and repeats ({ACCURACY_QUICK})"))]
    pub quick: bool,
}

pub fn run(args: &AccuracyArgs) -> Result<String, Failure> {
    // The directory and its three files are checked before the (long) measurement.
    if args.out.exists() && !args.out.is_dir() {
        return Err(Failure::refused(format!(
            "--out {}: exists and is not a directory",
            args.out.display()
        )));
    }
    std::fs::create_dir_all(&args.out).map_err(|e| Failure::refused(format!("{}: {e}", args.out.display())))?;
    let csv = args.out.join("accuracy.csv");
    let (svg, png) = (args.out.join("accuracy.svg"), args.out.join("accuracy.png"));
    for path in [&csv, &svg, &png] {
        check_writable(path, &[])?;
    }
    let cases = accuracy::standard_cases(args.quick);
    let progress = Progress::new(cases.len());
    let mut measurements = Vec::new();
    for (index, case) in cases.iter().enumerate() {
        progress.at(index, &format!("{}: 100-digit reference", case.name));
        let reference = accuracy::reference_value(&case.text);
        let reference = match reference {
            Ok(reference) => reference,
            Err(error) => {
                progress.finish();
                return Err(error.into());
            }
        };
        measurements.extend(accuracy::measure_case(case, &reference, args.quick, |stage| {
            progress.at(index, &format!("{}: {stage}", case.name));
        }));
    }
    progress.finish();
    // All three files are rendered in memory, then written all or none.
    let rendered = accuracy_picture(&measurements)
        .and_then(|picture| Ok([(svg, picture.encode(Format::Svg)?), (png, picture.encode(Format::Png)?)]));
    let [svg, png] = rendered.map_err(|e| Failure::failed(e.to_string()))?;
    let text = accuracy::to_csv(&measurements).map_err(|e| Failure::failed(e.to_string()))?;
    write_all_or_none(&[(csv, text.into_bytes()), svg, png])
        .map_err(|e| Failure::failed(format!("{e} (no file of this run was kept)")))?;
    let mut out = format!(
        "{:>8}  {:<28} {:>9} {:>9}  {:>12}  {}\n",
        "target", "cheapest rule", "bits", "parameter", "seconds", "case"
    );
    for case in &cases {
        let of_case: Vec<_> = measurements.iter().filter(|m| m.case == case.name).cloned().collect();
        for target in [1e-8, 1e-13, 1e-30, 1e-50, 1e-100] {
            match accuracy::cheapest_for(&of_case, target) {
                Some(m) => out.push_str(&format!(
                    "{target:>8.0e}  {:<28} {:>9} {:>9} {:>12.3e}  {}\n",
                    m.rule, m.precision_bits, m.parameter, m.seconds, m.case
                )),
                None => out.push_str(&format!(
                    "{target:>8.0e}  {:<28} {:>9} {:>9} {:>12}  {}\n",
                    "(none reached it)", "", "", "", case.name
                )),
            }
        }
    }
    out.push_str(&format!(
        "{} measurements written to {}",
        measurements.len(),
        args.out.display()
    ));
    Ok(out)
}
