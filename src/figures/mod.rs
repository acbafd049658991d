//! The paper's Figures 4–8 regenerated, and the facts its Section 4 states in words
//! checked: Persson's compliance v' = C/P (β = −1), in the variables
//! P̂1 = P1/P0, Q̂1 = Q1/(fP0), Ŵ = W/(Cλf²P0^(β+2)) and φ/π.
//!
//! - [`evaluate`]: Ŵ at a point to the accuracy a figure needs (f64, or MPFR where f64
//!   cannot vouch for it), the gross-slip limits, local and fitted log–log slopes;
//! - [`sweeps`]: the curves of each figure and the facts;
//! - [`output`]: the CSV files, `facts.json`, written atomically;
//! - [`draw`]: the pictures (SVG, PNG and PDF);
//! - [`cubic_law`]: the cubic law's proven error band beside its true error, for
//!   Persson's and Hertz's compliances.
//!
//! What the numbers show against the paper's words is in proofs/figures.md.

pub mod cubic_law;
pub mod draw;
pub mod evaluate;
pub mod output;
pub mod sweeps;

use std::sync::atomic::{AtomicUsize, Ordering};

pub use output::{regenerate, FiguresError, Summary};
pub use sweeps::{compute, Facts, Figures};

/// How a curve is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Style {
    /// A line through the samples.
    Line,
    /// Markers only (Fig. 4's integrated points).
    Points,
}

/// One curve: Ŵ against the figure's abscissa, with where it meets gross slip.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// The curve's parameter as the issue writes it ("0.25", "0.4pi"), the key of its facts.
    pub key: String,
    /// The legend text.
    pub label: String,
    /// Line or points.
    pub style: Style,
    /// (abscissa, Ŵ, precision bits) in increasing abscissa.
    pub samples: Vec<(f64, f64, u32)>,
    /// The abscissae at which the cycle reaches gross slip, where the curve stops
    /// (its first and/or last sample lies just inside).
    pub gross_slip_at: Vec<f64>,
}

/// One chart of a figure (Fig. 8 has two, one per phase).
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// Short name, also the CSV's `panel` column ("phi=0.5pi").
    pub name: String,
    /// The chart's caption.
    pub caption: String,
    /// Its curves.
    pub curves: Vec<Curve>,
}

/// One of the paper's figures, or the cubic law's error band.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// 4 to 8, the paper's numbers; 9, [`cubic_law::CUBIC_LAW_FIGURE`], the cubic law's error.
    pub number: u32,
    /// The abscissa's axis label, in the paper's variables.
    pub x_label: &'static str,
    /// The ordinate's axis label.
    pub y_label: &'static str,
    /// The abscissa's CSV column name.
    pub x_column: &'static str,
    /// The name of the parameter that tells the curves apart (CSV column).
    pub curve_column: &'static str,
    /// Logarithmic axes (Figs. 6–8).
    pub log_log: bool,
    /// The slope of the dashed reference line on a log–log figure (the small-amplitude limit).
    pub guide_slope: Option<f64>,
    /// Its charts.
    pub panels: Vec<Panel>,
    /// What the figure states rather than draws (e.g. W = 0 for P̂1/Q̂1 ≥ 1).
    pub notes: Vec<String>,
}

/// Counts finished evaluations for a progress display.
pub struct Progress<'a> {
    done: AtomicUsize,
    total: usize,
    report: &'a (dyn Fn(usize, usize) + Sync),
}

impl<'a> Progress<'a> {
    /// A counter towards `total`, reporting (done, total) after each step.
    pub fn new(total: usize, report: &'a (dyn Fn(usize, usize) + Sync)) -> Self {
        Progress {
            done: AtomicUsize::new(0),
            total,
            report,
        }
    }

    /// One more step done.
    pub fn step(&self) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        (self.report)(done.min(self.total), self.total);
    }
}
