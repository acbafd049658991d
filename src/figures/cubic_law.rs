//! The cubic law's error: how far the cubic law W₁ = λ f² P1³ v''(P0) I(ρ, φ)
//! lies from W, proven and true, against P̂1 = P1/P0, for Persson's compliance
//! v' = γσ/P (γ = σ = 1) and Hertz's (R = E* = 1), at φ = 0.1π, 0.5π and 0.9π, with
//! P0 = f = λ = 1 and ρ = Q1/(fP1) = 0.5 kept as P1 moves.
//!
//! - The **proven band** is the remainder bound of proofs/cubic-law-remainder.md on
//!   |W − W₁| (N = 1, enclosed in Arb balls), over the certified |W|: the upper end of
//!   that ratio, so it bounds the relative error.
//! - The **true error** is |W − W₁|/|W| with W certified to [`W_DIGITS`] digits and W₁
//!   enclosed at 128 bits: W − W₁ cancels only a factor ~P̂1, so its printed digits are
//!   all right.
//!
//! Each point is checked as it is made: every number the error's ball holds must lie
//! below every number the bound's ball holds, or the figure is not written.
//!
//! `cubic_law_error.csv` has one row per point, the curves in the order of the panels
//! and phases: `panel` (`persson`, `hertz`), `phi_over_pi`, `p1_over_p0`,
//! `true_relative_error` (|W − W₁|/|W|, to 6 digits), `proven_relative_bound` (the
//! proven bound on |W − W₁| over |W|, rounded up to 4 digits), `W_certified` (W to
//! [`W_DIGITS`] certified digits), `W1_cubic_law` (W₁ to 20 digits),
//! `remainder_bound` (the proven bound on |W − W₁|, rounded up to 4 digits),
//! `bound_over_true` (their ratio, 3 decimals) and `precision_bits` (the working
//! precision of certified W).

use super::{Curve, Figure, Panel, Progress, Style};

/// The figure's number after the paper's 4–8 (it is not one of the paper's).
pub const CUBIC_LAW_FIGURE: u32 = 9;
/// The stem of its files: `cubic_law_error.csv`, `.svg`, `.png`, `.pdf`.
pub const FILE_STEM: &str = "cubic_law_error";
/// The phases φ/π of the curves.
pub const PHASES: [f64; 3] = [0.1, 0.5, 0.9];
/// ρ = Q1/(fP1), kept as P1 moves.
pub const RHO: f64 = 0.5;
/// The certified significant digits of W.
pub const W_DIGITS: u32 = 30;
/// The range of P̂1 drawn: up to half of P0, inside the theory at every phase (no
/// separation, no gross slip: the load ellipse stays inside |Q| < fP), and down to
/// 10⁻³, where the true error has settled on its slope 1 also at φ = 0.9π (its local
/// slope there is still 1.10 at P̂1 = 0.01).
pub const AMPLITUDE_RANGE: (f64, f64) = (0.001, 0.5);
/// Samples per curve (11.5 a decade).
pub const AMPLITUDE_SAMPLES: usize = 31;
/// The largest P̂1 of the ratios bound/true the figure is read for (the issue's
/// "ordinary cases").
pub const RATIO_AMPLITUDE: f64 = 0.1;

/// A panel: a compliance.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CompliancePanel {
    /// The CSV's `panel`.
    pub name: &'static str,
    /// Its SPEC, as the command line reads it.
    pub spec: &'static str,
    /// The chart's caption.
    pub caption: &'static str,
}

/// Persson's panel, then Hertz's.
pub const PANELS: [CompliancePanel; 2] = [
    CompliancePanel {
        name: "persson",
        spec: "persson:gamma=1,sigma=1",
        caption: "Cubic law's error: Persson, v' = γσ/P, γ = σ = 1",
    },
    CompliancePanel {
        name: "hertz",
        spec: "hertz:r=1,estar=1",
        caption: "Cubic law's error: Hertz, R = E* = 1",
    },
];

/// One point: a compliance, a phase, an amplitude, and the errors of the cubic law there.
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorPoint {
    /// The panel's name.
    pub panel: &'static str,
    /// φ/π.
    pub phase_over_pi: f64,
    /// P̂1 = P1/P0.
    pub p1_over_p0: f64,
    /// |W − W₁|/|W|, the midpoint of its ball.
    pub true_relative_error: f64,
    /// The proven bound on |W − W₁| over |W|: the upper end of its ball.
    pub proven_relative_bound: f64,
    /// W to [`W_DIGITS`] certified digits.
    pub w: String,
    /// W₁ to 20 digits.
    pub cubic_law: String,
    /// The proven bound on |W − W₁|: the upper end of its ball.
    pub remainder_bound: f64,
    /// The working precision of certified W (W₁ and the bound are at 128 bits).
    pub precision_bits: u32,
}

impl ErrorPoint {
    /// How many times the true error the proven band is.
    pub fn band_over_true(&self) -> f64 {
        self.proven_relative_bound / self.true_relative_error
    }
}

/// Why the figure could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CubicLawError {
    /// W, W₁ or the bound could not be computed.
    #[error("the cubic law's error, {panel}, φ = {phase_over_pi}π, P1/P0 = {amplitude}: {message}")]
    Point {
        panel: &'static str,
        phase_over_pi: f64,
        amplitude: f64,
        message: String,
    },
    /// The true error is not below the proven bound: the bound is wrong.
    #[error("the cubic law's error, {panel}, φ = {phase_over_pi}π, P1/P0 = {amplitude}: |W − W₁| reaches {error:e}, not below its proven bound {bound:e}; the remainder bound is wrong there (proofs/cubic-law-remainder.md)")]
    OutsideBand {
        panel: &'static str,
        phase_over_pi: f64,
        amplitude: f64,
        /// The upper end of |W − W₁|.
        error: f64,
        /// The lower end of the bound.
        bound: f64,
    },
}

/// The figure's P̂1: [`AMPLITUDE_SAMPLES`] values equally spaced in ln over
/// [`AMPLITUDE_RANGE`], each rounded to 3 significant digits (a decimal to type back in).
pub fn amplitudes() -> Vec<f64> {
    let (low, high) = AMPLITUDE_RANGE;
    super::evaluate::log_spaced(low, high, AMPLITUDE_SAMPLES)
        .into_iter()
        .map(|p1| format!("{p1:.2e}").parse().unwrap_or(p1))
        .collect()
}

/// The points of every panel and phase at the normal amplitudes `amplitudes` (P̂1), in
/// parallel, one progress step each; in the order of [`PANELS`], [`PHASES`], `amplitudes`.
#[cfg(feature = "certified")]
pub fn cubic_law_errors(amplitudes: &[f64], progress: &Progress) -> Result<Vec<ErrorPoint>, CubicLawError> {
    use rayon::prelude::*;
    // The kernels depend on (ρ, φ) alone: one shape per phase serves every amplitude.
    let shapes = PHASES
        .par_iter()
        .map(|&phase| enclosed::shape(phase))
        .collect::<Result<Vec<_>, _>>()?;
    let points: Vec<(&CompliancePanel, f64, _, f64)> = PANELS
        .iter()
        .flat_map(|panel| {
            PHASES
                .iter()
                .zip(&shapes)
                .flat_map(move |(&phase, shape)| amplitudes.iter().map(move |&p1| (panel, phase, shape, p1)))
        })
        .collect();
    points
        .par_iter()
        .map(|&(panel, phase, shape, p1)| {
            let point = enclosed::error_point(panel, phase, shape, p1)?;
            progress.step();
            Ok(point)
        })
        .collect()
}

/// The points of the figure as `microslip figures` draws it: on [`amplitudes`] where
/// certified W is built, none otherwise.
pub fn figure_points(progress: &Progress) -> Result<Vec<ErrorPoint>, CubicLawError> {
    #[cfg(feature = "certified")]
    return cubic_law_errors(&amplitudes(), progress);
    #[cfg(not(feature = "certified"))]
    {
        let _ = progress;
        Ok(Vec::new())
    }
}

/// The progress steps of [`figure_points`].
pub fn step_count() -> usize {
    if cfg!(feature = "certified") {
        PANELS.len() * PHASES.len() * AMPLITUDE_SAMPLES
    } else {
        0
    }
}

#[cfg(feature = "certified")]
mod enclosed {
    use super::{CompliancePanel, CubicLawError, ErrorPoint, AMPLITUDE_RANGE, PANELS, RHO, W_DIGITS};
    use crate::ball::Ball;
    use crate::case::{Case, CaseSpec, CaseText};
    use crate::digits::enclosure::certified_dissipation;
    use crate::digits::enclosure::series::case_balls;
    use crate::exact::SeriesShape;
    use crate::real::{Precision, Real};

    /// The working precision of W₁ and its bound: W − W₁ is ~P̂1·W, so 128 bits leave
    /// W's 30 digits untouched.
    const SERIES_BITS: u32 = 128;

    /// The real interval of a ball (the whole line where it has none).
    fn span(x: &Ball) -> (f64, f64) {
        x.real_span().unwrap_or((f64::NEG_INFINITY, f64::INFINITY))
    }

    /// ρ as the decimal it is written as.
    fn rho_text() -> String {
        format!("{RHO:?}")
    }

    /// The case of a point, or why it is not one. Its P1 and Q1 are the shortest decimals
    /// of the f64 amplitudes, and Q1 must be exactly ρ·P1 in those decimals (as it is for
    /// P1 of a few digits and ρ = 1/2): the shape of the phase is then the case's.
    fn case(panel: &CompliancePanel, phase_over_pi: f64, amplitude: f64) -> Result<CaseSpec, CubicLawError> {
        let (p1, q1) = (format!("{amplitude:?}"), format!("{:?}", RHO * amplitude));
        let exact = |text: &str| crate::decimal::decimal(text);
        if let (Some(p1_exact), Some(q1_exact), Some(rho)) = (exact(&p1), exact(&q1), exact(&rho_text())) {
            if q1_exact != p1_exact * rho {
                let why = format!("Q1 = {RHO}·P1 is not the decimal {q1} of its f64: give P1 with fewer digits");
                return Err(failure(panel, phase_over_pi, amplitude, why));
            }
        }
        CaseText::builder()
            .p0(1)
            .p1(p1)
            .q1(q1)
            .phi(format!("{phase_over_pi:?}pi"))
            .friction(1)
            .lambda(1)
            .compliance(panel.spec)
            .build()
            .map_err(|e| failure(panel, phase_over_pi, amplitude, e))
    }

    /// The error of a point.
    fn failure(
        panel: &CompliancePanel,
        phase_over_pi: f64,
        amplitude: f64,
        error: impl std::fmt::Display,
    ) -> CubicLawError {
        CubicLawError::Point {
            panel: panel.name,
            phase_over_pi,
            amplitude,
            message: error.to_string(),
        }
    }

    /// The series' shape (ρ, φ) of the phase, its phase read as the cases read it.
    pub(super) fn shape(phase_over_pi: f64) -> Result<SeriesShape<Ball>, CubicLawError> {
        let (panel, amplitude) = (&PANELS[0], AMPLITUDE_RANGE.0);
        let precision = Precision::bits(SERIES_BITS);
        let fail = |e: &dyn std::fmt::Display| failure(panel, phase_over_pi, amplitude, e);
        let Case { cycle, .. } =
            case_balls(&case(panel, phase_over_pi, amplitude)?, precision).map_err(|e| fail(&e))?;
        let rho = Ball::parse_decimal(&rho_text(), precision).map_err(|e| fail(&e))?;
        SeriesShape::new(&rho, &cycle.phase, 1).map_err(|e| fail(&e))
    }

    /// W certified, W₁ and its proven bound at one point, checked against each other.
    pub(super) fn error_point(
        panel: &CompliancePanel,
        phase_over_pi: f64,
        shape: &SeriesShape<Ball>,
        amplitude: f64,
    ) -> Result<ErrorPoint, CubicLawError> {
        let fail = |e: &dyn std::fmt::Display| failure(panel, phase_over_pi, amplitude, e);
        let spec = case(panel, phase_over_pi, amplitude)?;
        let read = |precision| {
            spec.at::<Ball>(precision)
                .map(|Case { cycle, compliance }| (cycle, compliance))
                .map_err(|e| e.to_string())
        };
        let certified = certified_dissipation(read, W_DIGITS).map_err(|e| fail(&e))?;
        let Case { cycle, compliance } = case_balls(&spec, Precision::bits(SERIES_BITS)).map_err(|e| fail(&e))?;
        let (sums, remainders) = shape
            .at_amplitude(&cycle, compliance.as_ref(), &cycle.normal_amplitude)
            .map_err(|e| fail(&e))?;
        let (cubic_law, bound) = (&sums[0], &remainders[0].bound());
        let w = &certified.enclosure.total;
        let error = (w.clone() - cubic_law).abs();
        let size = w.abs();
        let (error_span, bound_span) = (span(&error), span(bound));
        if error_span.1 > bound_span.0 || !error_span.1.is_finite() {
            return Err(CubicLawError::OutsideBand {
                panel: panel.name,
                phase_over_pi,
                amplitude,
                error: error_span.1,
                bound: bound_span.0,
            });
        }
        Ok(ErrorPoint {
            panel: panel.name,
            phase_over_pi,
            p1_over_p0: amplitude,
            true_relative_error: (error / &size).to_f64_lossy(),
            proven_relative_bound: span(&(bound.clone() / &size)).1,
            w: certified.value.decimal.to_string(),
            cubic_law: cubic_law.to_scientific(20),
            remainder_bound: bound_span.1,
            precision_bits: certified.enclosure.precision.in_bits(),
        })
    }
}

/// The points of one curve, in the order given.
fn curve_points<'a>(
    points: &'a [ErrorPoint],
    panel: &'a str,
    phase_over_pi: f64,
) -> impl Iterator<Item = &'a ErrorPoint> + 'a {
    points
        .iter()
        .filter(move |p| p.panel == panel && p.phase_over_pi == phase_over_pi)
}

/// The figure: a panel per compliance, per phase a solid line for the true error and
/// one for the proven band, log–log, with a slope-1 guide (the error is ~P̂1).
pub fn cubic_law_figure(points: &[ErrorPoint]) -> Figure {
    let panels = PANELS
        .iter()
        .map(|panel| {
            let mut curves = Vec::new();
            for phase in PHASES {
                let samples = |value: fn(&ErrorPoint) -> f64| {
                    curve_points(points, panel.name, phase)
                        .map(|p| (p.p1_over_p0, value(p), p.precision_bits))
                        .collect()
                };
                for (kind, label, value) in [
                    ("true", "true", (|p| p.true_relative_error) as fn(&ErrorPoint) -> f64),
                    ("bound", "proven band", |p| p.proven_relative_bound),
                ] {
                    curves.push(Curve {
                        key: format!("{phase}pi {kind}"),
                        label: format!("φ = {phase}π, {label}"),
                        style: Style::Line,
                        samples: samples(value),
                        gross_slip_at: Vec::new(),
                    });
                }
            }
            Panel {
                name: panel.name.to_string(),
                caption: panel.caption.to_string(),
                curves,
            }
        })
        .collect();
    Figure {
        number: CUBIC_LAW_FIGURE,
        x_label: "P1/P0",
        y_label: "|W − W₁| / |W|",
        x_column: "p1_over_p0",
        curve_column: "phi_over_pi",
        log_log: true,
        guide_slope: Some(1.0),
        panels,
        // No-break spaces keep every number off the start of a wrapped line.
        notes: vec![
            format!("The cubic law W₁ = λ f² P1³ v''(P0) I(ρ, φ), with P0\u{a0}=\u{a0}f\u{a0}=\u{a0}λ\u{a0}=\u{a0}1 and ρ = Q1/(f P1) =\u{a0}{RHO}."),
            format!("True: |W − W₁|/|W|, W certified to\u{a0}{W_DIGITS}\u{a0}digits. Proven band: the remainder bound on |W − W₁| over |W|; the bands of the three phases nearly coincide."),
        ],
    }
}

/// The CSV header (see the module's documentation).
pub const CSV_HEADER: [&str; 10] = [
    "panel",
    "phi_over_pi",
    "p1_over_p0",
    "true_relative_error",
    "proven_relative_bound",
    "W_certified",
    "W1_cubic_law",
    "remainder_bound",
    "bound_over_true",
    "precision_bits",
];

/// `x` rounded up to 4 significant digits, so that a bound stays one.
fn rounded_up(x: f64) -> String {
    crate::decimal::rounding::DecimalEnd::directed(&x, 4, rug::float::Round::Up)
}

/// `cubic_law_error.csv`: one row per point.
pub fn cubic_law_csv(points: &[ErrorPoint]) -> Result<String, csv::Error> {
    let rows = points.iter().map(|p| {
        [
            p.panel.to_string(),
            p.phase_over_pi.to_string(),
            p.p1_over_p0.to_string(),
            format!("{:.5e}", p.true_relative_error),
            rounded_up(p.proven_relative_bound),
            p.w.clone(),
            p.cubic_law.clone(),
            rounded_up(p.remainder_bound),
            format!("{:.3}", p.band_over_true()),
            p.precision_bits.to_string(),
        ]
    });
    crate::files::csv_text(&CSV_HEADER, rows)
}

/// The proven band over the true error along one curve, up to P̂1 = [`RATIO_AMPLITUDE`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BandRatio {
    /// The panel's name.
    pub panel: &'static str,
    /// φ/π.
    pub phase_over_pi: f64,
    /// The median of bound/true over the curve's points with P̂1 ≤ [`RATIO_AMPLITUDE`].
    pub median: f64,
    /// Their largest.
    pub max: f64,
    /// How many points.
    pub points: usize,
}

/// The median of `values` (the mean of the middle two for an even count; NaN for none).
pub fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    match values.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => values[n / 2],
        n => 0.5 * (values[n / 2 - 1] + values[n / 2]),
    }
}

/// bound/true per panel and phase over P̂1 ≤ [`RATIO_AMPLITUDE`].
pub fn band_ratios(points: &[ErrorPoint]) -> Vec<BandRatio> {
    let mut ratios = Vec::new();
    for panel in PANELS {
        for phase in PHASES {
            let values: Vec<f64> = curve_points(points, panel.name, phase)
                .filter(|p| p.p1_over_p0 <= RATIO_AMPLITUDE)
                .map(ErrorPoint::band_over_true)
                .collect();
            if values.is_empty() {
                continue;
            }
            ratios.push(BandRatio {
                panel: panel.name,
                phase_over_pi: phase,
                max: values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                points: values.len(),
                median: median(values),
            });
        }
    }
    ratios
}

/// One line per curve: the median and largest bound/true up to P̂1 = [`RATIO_AMPLITUDE`].
pub fn band_report(points: &[ErrorPoint]) -> String {
    band_ratios(points)
        .iter()
        .map(|r| {
            format!(
                "cubic law's error, {}, φ = {}π: proven band / true error for P1/P0 ≤ {RATIO_AMPLITUDE}: median {:.2}, max {:.2} ({} points)",
                r.panel, r.phase_over_pi, r.median, r.max, r.points
            )
        })
        .collect::<Vec<_>>()
        .join("\n")
}
