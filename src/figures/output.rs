//! Writing the figures: per figure a CSV and a picture in each format asked for (SVG,
//! PNG, PDF), the cubic law's error (`cubic_law_error.csv` and its pictures, where
//! certified W is built), plus `limit_slopes.csv`
//! (every local slope of every limit sequence) and `facts.json`. Everything is rendered
//! in memory first; each file is then written to a temporary name in the output
//! directory and renamed into place, so a reader never sees a half-written file, and
//! a failed write removes the files of this run. The directory is checked before
//! anything is computed.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Serialize;

use super::cubic_law::{self, CubicLawError, ErrorPoint};
use super::draw::figure_picture;
use super::evaluate::{LimitSlope, FIGURE_RELATIVE_ERROR};
use super::sweeps::{compute, step_count, Facts, Figures, SweepError, FIG5_NORMAL, FIG8_PHASES};
use super::{Figure, Progress};
use crate::decimal::printing::decimal_f64;
use crate::files::csv_text;
use crate::plot::{write_all_or_none, Format, PlotError};

/// Why the figures could not be written.
#[derive(Debug, thiserror::Error)]
pub enum FiguresError {
    /// The output directory cannot be created or written to.
    #[error("cannot write to the output directory {path}: {message}")]
    Directory { path: String, message: String },
    /// A computation failed.
    #[error(transparent)]
    Sweep(#[from] SweepError),
    /// The cubic law's error could not be computed, or broke its proven band.
    #[error(transparent)]
    CubicLaw(#[from] CubicLawError),
    /// A file could not be written.
    #[error("writing {path}: {message}")]
    Write { path: String, message: String },
    /// Writing the files failed; those this run had written are removed.
    #[error("{0} (no file of this run was kept)")]
    Files(crate::files::OutputError),
    /// A picture could not be drawn.
    #[error(transparent)]
    Plot(#[from] PlotError),
}

/// Only an unusable directory is refused input; anything failing after it was checked is
/// a failed run.
impl crate::answer::ExitStatus for FiguresError {
    fn is_failure(&self) -> bool {
        !matches!(self, FiguresError::Directory { .. })
    }
}

/// What was written.
#[derive(Debug)]
pub struct Summary {
    /// The files, in the order written.
    pub files: Vec<PathBuf>,
    /// The computed figures and facts.
    pub figures: Figures,
    /// The points of the cubic law's error (none without certified W).
    pub cubic_law: Vec<ErrorPoint>,
}

/// The formats the pictures are written in unless others are asked for.
pub const DEFAULT_FORMATS: [Format; 2] = [Format::Svg, Format::Png];

/// The names of the files written with pictures in `formats`, in the order written.
pub fn file_names(formats: &[Format]) -> Vec<String> {
    let mut names = Vec::new();
    for number in 4..=8 {
        names.push(format!("fig{number}.csv"));
        for format in formats {
            names.push(format!("fig{number}.{}", format.extension()));
        }
    }
    if cubic_law::step_count() > 0 {
        names.push(format!("{}.csv", cubic_law::FILE_STEM));
        for format in formats {
            names.push(format!("{}.{}", cubic_law::FILE_STEM, format.extension()));
        }
    }
    names.extend(["limit_slopes.csv".to_string(), "facts.json".to_string()]);
    names
}

/// Checks `directory`, computes every figure (reporting (done, total) steps), renders
/// every file in memory, the pictures in each of `formats`, and then writes them all
/// into it, or none: a failed write removes the files this run had written.
pub fn regenerate(
    directory: &Path,
    formats: &[Format],
    report: &(dyn Fn(usize, usize) + Sync),
) -> Result<Summary, FiguresError> {
    check_directory(directory, formats)?;
    let progress = Progress::new(step_count() + cubic_law::step_count(), report);
    let figures = compute(&progress)?;
    let cubic_law = cubic_law::figure_points(&progress)?;
    let mut contents: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    let mut add = |stem: &str, csv: Vec<u8>, figure: &Figure| -> Result<(), FiguresError> {
        contents.push((directory.join(format!("{stem}.csv")), csv));
        let picture = figure_picture(figure)?;
        for format in formats {
            let name = format!("{stem}.{}", format.extension());
            contents.push((directory.join(name), picture.encode(*format)?));
        }
        Ok(())
    };
    for figure in &figures.figures {
        add(&format!("fig{}", figure.number), figure_csv(figure)?, figure)?;
    }
    if !cubic_law.is_empty() {
        let stem = cubic_law::FILE_STEM;
        let csv =
            cubic_law::cubic_law_csv(&cubic_law).map_err(|e| write_error(Path::new(&format!("{stem}.csv")), e))?;
        add(stem, csv.into_bytes(), &cubic_law::cubic_law_figure(&cubic_law))?;
    }
    contents.push((directory.join("limit_slopes.csv"), limit_slopes_csv(&figures.facts)?));
    let facts = directory.join("facts.json");
    let text = serde_json::to_string_pretty(&FactsJson::of(&figures.facts)).map_err(|e| write_error(&facts, e))?;
    contents.push((facts, format!("{text}\n").into_bytes()));
    write_all_or_none(&contents).map_err(FiguresError::Files)?;
    Ok(Summary {
        files: contents.into_iter().map(|(path, _)| path).collect(),
        figures,
        cubic_law,
    })
}

/// Creates `directory` if needed, proves a file can be written and renamed in it, and
/// that none of the names to be written is taken by a directory.
fn check_directory(directory: &Path, formats: &[Format]) -> Result<(), FiguresError> {
    let unusable = |message: String| FiguresError::Directory {
        path: directory.display().to_string(),
        message,
    };
    std::fs::create_dir_all(directory).map_err(|e| unusable(e.to_string()))?;
    for name in file_names(formats) {
        crate::files::check_writable(&directory.join(name), &[]).map_err(|e| unusable(e.to_string()))?;
    }
    Ok(())
}

fn write_error(path: &Path, error: impl std::fmt::Display) -> FiguresError {
    FiguresError::Write {
        path: path.display().to_string(),
        message: error.to_string(),
    }
}

/// One row per sample: panel, curve, abscissa, Ŵ, the precision used, and on the end
/// sample of a curve that stops at gross slip the abscissa of the limit. Ŵ is printed by
/// the one printing rule to the digits its bound determines: every sample is vouched for
/// to [`FIGURE_RELATIVE_ERROR`] by its error estimate (an estimate, not a proof).
pub fn figure_csv(figure: &Figure) -> Result<Vec<u8>, FiguresError> {
    let header = [
        "panel",
        figure.curve_column,
        figure.x_column,
        "W_hat",
        "precision_bits",
        "gross_slip_limit",
    ];
    let mut rows = Vec::new();
    for panel in &figure.panels {
        for curve in &panel.curves {
            let last = curve.samples.len().saturating_sub(1);
            for (index, (x, w, bits)) in curve.samples.iter().enumerate() {
                // The limit nearest this end sample, if the curve stops there.
                let limit = if index == 0 || index == last {
                    curve
                        .gross_slip_at
                        .iter()
                        .filter(|l| (index == last && **l >= *x) || (index == 0 && **l <= *x))
                        .map(|l| format!("{l:.10}"))
                        .next()
                        .unwrap_or_default()
                } else {
                    String::new()
                };
                rows.push([
                    panel.name.clone(),
                    curve.key.clone(),
                    format!("{x:.10e}"),
                    decimal_f64(*w, w.abs() * FIGURE_RELATIVE_ERROR).to_string(),
                    bits.to_string(),
                    limit,
                ]);
            }
        }
    }
    let path = format!("fig{}.csv", figure.number);
    csv_text(&header, rows)
        .map(String::into_bytes)
        .map_err(|e| write_error(Path::new(&path), e))
}

/// Every local slope of every limit sequence, with where each settled.
fn limit_slopes_csv(facts: &Facts) -> Result<Vec<u8>, FiguresError> {
    let header = [
        "figure",
        "phi_over_pi",
        "curve",
        "Q1_hat",
        "local_slope",
        "precision_bits",
        "settled",
    ];
    let mut sequences: Vec<(&str, f64, &BTreeMap<String, LimitSlope>)> = vec![
        ("6 (P1_hat/Q1_hat)", 0.0, &facts.fig6_small_amplitude_slope),
        ("7 (P1_hat/Q1_hat)", 0.5, &facts.fig7_small_amplitude_slope),
    ];
    for (phase, map) in FIG8_PHASES.iter().zip(&facts.fig8_limit_slope) {
        sequences.push(("8 (P1_hat)", *phase, map));
    }
    let mut rows = Vec::new();
    for (figure, phase, map) in sequences {
        for (curve, limit) in map {
            for sample in &limit.samples {
                let settled = if sample.amplitude == limit.settled_at {
                    format!("{:.3}", limit.slope)
                } else {
                    String::new()
                };
                rows.push([
                    figure.to_string(),
                    phase.to_string(),
                    curve.clone(),
                    format!("{:.6e}", sample.amplitude),
                    format!("{:.9}", sample.slope),
                    sample.precision_bits.to_string(),
                    settled,
                ]);
            }
        }
    }
    csv_text(&header, rows)
        .map(String::into_bytes)
        .map_err(|e| write_error(Path::new("limit_slopes.csv"), e))
}

/// facts.json: one key per number the paper states in words, every value a number, the keys
/// in alphabetical order. A gain that has no finite value is absent from
/// `fig5_out_of_phase_gain` and given its reason in `fig5_out_of_phase_gain_unbounded`.
#[derive(Debug, Serialize)]
pub struct FactsJson<'a> {
    pub fig4_max_rel_diff: f64,
    pub fig5_out_of_phase_gain: BTreeMap<&'a str, f64>,
    pub fig5_out_of_phase_gain_unbounded: BTreeMap<&'a str, &'static str>,
    pub fig5_phi_max_over_pi: &'a BTreeMap<String, f64>,
    pub fig6_small_amplitude_slope: BTreeMap<&'a str, f64>,
    pub fig7_small_amplitude_slope: BTreeMap<&'a str, f64>,
    /// `fig8_limit_slope` and `fig8_range_slope` at φ = π/2, and with a suffix
    /// `_phi_{φ/π}pi` at the other phases.
    #[serde(flatten)]
    pub fig8: BTreeMap<String, BTreeMap<&'a str, f64>>,
}

impl<'a> FactsJson<'a> {
    /// The numbers of `facts` (the limit slopes without their sample sequences).
    pub fn of(facts: &'a Facts) -> Self {
        let slopes = |map: &'a BTreeMap<String, LimitSlope>| map.iter().map(|(k, v)| (k.as_str(), v.slope)).collect();
        let numbers = |map: &'a BTreeMap<String, f64>| map.iter().map(|(k, v)| (k.as_str(), *v)).collect();
        let mut fig8 = BTreeMap::new();
        for ((phase, limit), range) in FIG8_PHASES
            .iter()
            .zip(&facts.fig8_limit_slope)
            .zip(&facts.fig8_range_slope)
        {
            let suffix = if *phase == 0.5 {
                String::new()
            } else {
                format!("_phi_{phase}pi")
            };
            fig8.insert(format!("fig8_limit_slope{suffix}"), slopes(limit));
            fig8.insert(format!("fig8_range_slope{suffix}"), numbers(range));
        }
        let gains = &facts.fig5_out_of_phase_gain;
        let unbounded = |q1_hat: &str| {
            if q1_hat.parse::<f64>().is_ok_and(|q| q <= FIG5_NORMAL) {
                "Ŵ(φ = 0) = 0: in phase with Q̂1 ≤ P̂1 nothing slips, so Ŵ_max/Ŵ(0) is unbounded"
            } else {
                "φ = 0 is gross slip: Ŵ(0) is not defined, so Ŵ_max/Ŵ(0) is unbounded"
            }
        };
        FactsJson {
            fig4_max_rel_diff: facts.fig4_max_rel_diff,
            fig5_out_of_phase_gain: gains
                .iter()
                .filter_map(|(key, gain)| Some((key.as_str(), (*gain)?)))
                .collect(),
            fig5_out_of_phase_gain_unbounded: gains
                .iter()
                .filter(|(_, gain)| gain.is_none())
                .map(|(key, _)| (key.as_str(), unbounded(key)))
                .collect(),
            fig5_phi_max_over_pi: &facts.fig5_phi_max_over_pi,
            fig6_small_amplitude_slope: slopes(&facts.fig6_small_amplitude_slope),
            fig7_small_amplitude_slope: slopes(&facts.fig7_small_amplitude_slope),
            fig8,
        }
    }
}
