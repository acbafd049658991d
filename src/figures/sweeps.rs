//! The curves of Figures 4–8 and the facts Section 4 states in words.

use std::collections::BTreeMap;

use rayon::prelude::*;

use super::evaluate::{
    fitted_log_slope, gross_slip_amplitude, gross_slip_amplitude_at_ratio, limit_slope, log_spaced, resolved, Formula,
    LimitSlope, Point, SlopeError,
};
use super::{Curve, Figure, Panel, Progress, Style};
use crate::dissipation::DissipationError;

/// The ordinate of Figs. 4–8.
const W_HAT_LABEL: &str = "Ŵ = W/(C λ f² P0)";
/// Fig. 5's normal amplitude and tangential amplitudes.
pub const FIG5_NORMAL: f64 = 0.4;
/// Fig. 5's curves, as the issue writes them.
pub const FIG5_AMPLITUDES: [&str; 5] = ["0.2", "0.3", "0.4", "0.5", "0.6"];
/// Fig. 6's ratios P̂1/Q̂1 (in phase; W = 0 for ratios ≥ 1).
pub const FIG6_RATIOS: [&str; 5] = ["0", "0.25", "0.5", "0.75", "0.9"];
/// Fig. 7's ratios P̂1/Q̂1 (φ = π/2).
pub const FIG7_RATIOS: [&str; 8] = ["0", "0.25", "0.5", "0.75", "0.9", "1", "1.5", "2"];
/// Fig. 8's fixed normal amplitudes.
pub const FIG8_NORMALS: [&str; 3] = ["0.05", "0.1", "0.2"];
/// Fig. 8's phases φ/π: out of phase, and near the largest dissipation of Fig. 5.
pub const FIG8_PHASES: [f64; 2] = [0.5, 0.4];
/// The smallest Q̂1 drawn in Figs. 6 and 7.
pub const RATIO_FIGURES_LOW: f64 = 1e-3;
/// The smallest Q̂1 drawn in Fig. 8 (its Q̂1² régime starts near Q̂1 ≈ P̂1/10).
pub const FIG8_LOW: f64 = 1e-4;
/// The range of Q̂1 over which `fig8_range_slope` fits a line: the initial straight
/// portion of a figure drawn from Q̂1 = 0.01, as the paper's log–log figures are.
pub const FIG8_RANGE: (f64, f64) = (0.01, 0.1);
/// Where a curve's last sample lies, relative to the gross-slip limit (10⁻³ inside): where
/// the permanent-stick load P_T tends to 0 there (P1 = 0, or φ = π/2), W grows like ln(1/P_T).
const GROSS_SLIP_MARGIN: f64 = 1e-3;
/// The Q̂1 from which every limit-slope sequence starts.
const LIMIT_START: f64 = 0.1;
/// Samples per curve in Figs. 6–8.
const CURVE_SAMPLES: usize = 61;
/// Samples of φ/π in Fig. 5 (step 0.01).
const PHASE_SAMPLES: usize = 101;

/// Everything regenerated: the five figures and the facts.
#[derive(Clone, Debug)]
pub struct Figures {
    /// Figures 4 to 8, in order.
    pub figures: Vec<Figure>,
    /// The numbers of facts.json.
    pub facts: Facts,
}

/// The numbers the paper states in words (the keys of facts.json).
#[derive(Clone, Debug, PartialEq)]
pub struct Facts {
    /// Worst relative difference of the four-segment points from the closed form (Fig. 4).
    pub fig4_max_rel_diff: f64,
    /// By Q̂1: φ/π of the (interior) maximum of Ŵ(φ), to 3 decimals.
    pub fig5_phi_max_over_pi: BTreeMap<String, f64>,
    /// By Q̂1: Ŵ at that maximum over Ŵ at φ = 0; None where Ŵ(0) = 0 (P̂1 ≥ Q̂1) or
    /// φ = 0 is gross slip (Q̂1 = 0.6), the gain then being unbounded.
    pub fig5_out_of_phase_gain: BTreeMap<String, Option<f64>>,
    /// By ratio P̂1/Q̂1: limit slope of Ŵ against Q̂1 as Q̂1 → 0, φ = 0.
    pub fig6_small_amplitude_slope: BTreeMap<String, LimitSlope>,
    /// By ratio: the same at φ = π/2.
    pub fig7_small_amplitude_slope: BTreeMap<String, LimitSlope>,
    /// By P̂1, per phase φ/π of `FIG8_PHASES`: the limit slope as Q̂1 → 0.
    pub fig8_limit_slope: Vec<BTreeMap<String, LimitSlope>>,
    /// By P̂1, per phase: the slope fitted over `FIG8_RANGE`.
    pub fig8_range_slope: Vec<BTreeMap<String, f64>>,
}

impl Facts {
    /// One line per limit slope: its value and the Q̂1 at which it settled.
    pub fn settling_report(&self) -> String {
        let mut sequences: Vec<(String, &BTreeMap<String, LimitSlope>)> = vec![
            (
                "fig6_small_amplitude_slope, P̂1/Q̂1 =".into(),
                &self.fig6_small_amplitude_slope,
            ),
            (
                "fig7_small_amplitude_slope, P̂1/Q̂1 =".into(),
                &self.fig7_small_amplitude_slope,
            ),
        ];
        for (phase, map) in FIG8_PHASES.iter().zip(&self.fig8_limit_slope) {
            sequences.push((format!("fig8_limit_slope at φ = {phase}π, P̂1 ="), map));
        }
        let mut out = String::new();
        for (name, map) in sequences {
            for (key, limit) in map {
                out.push_str(&format!(
                    "{name} {key}: {:.3}, settled at Q̂1 = {:.2e}\n",
                    limit.slope, limit.settled_at
                ));
            }
        }
        out.trim_end().to_string()
    }
}

/// Why the figures could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SweepError {
    /// A point of a curve failed.
    #[error("Fig. {figure}, P̂1 = {normal}, Q̂1 = {tangential}, φ/π = {phase}: {source}")]
    Point {
        figure: u32,
        normal: f64,
        tangential: f64,
        phase: f64,
        #[source]
        source: DissipationError,
    },
    /// A limit slope failed.
    #[error("Fig. {figure}, curve {curve}: {source}")]
    Slope {
        figure: u32,
        curve: String,
        #[source]
        source: SlopeError,
    },
}

fn parse(key: &str) -> f64 {
    key.parse().unwrap_or(f64::NAN)
}

/// Ŵ at a point, or the error naming the figure and point.
fn value(figure: u32, point: Point, formula: Formula) -> Result<(f64, u32), SweepError> {
    resolved(point, formula)
        .map(|v| (v.w_hat, v.precision_bits))
        .map_err(|source| SweepError::Point {
            figure,
            normal: point.normal,
            tangential: point.tangential,
            phase: point.phase_over_pi,
            source,
        })
}

/// Evaluates `points` in parallel, one progress step each, as (abscissa, Ŵ, bits).
fn sweep(
    figure: u32,
    points: &[(f64, Point)],
    formula: Formula,
    progress: &Progress,
) -> Result<Vec<(f64, f64, u32)>, SweepError> {
    points
        .par_iter()
        .map(|(x, point)| {
            let (w, bits) = value(figure, *point, formula)?;
            progress.step();
            Ok((*x, w, bits))
        })
        .collect()
}

/// The largest rise or fall of a drawn chord between consecutive samples of a line, as
/// a fraction of the curve's own span of drawn ordinates (log10 Ŵ on log–log figures,
/// Ŵ from 0 on linear ones); the axis spans every curve, so no chord rises more than
/// this fraction of it.
pub const CHORD_FRACTION: f64 = 0.01;

/// The most samples refinement lets a curve have.
const REFINED_SAMPLES_CAP: usize = 4000;

/// The drawn ordinate of a sample: log10 Ŵ on log–log figures (None where Ŵ ≤ 0), Ŵ otherwise.
fn drawn_ordinate(w: f64, log_log: bool) -> Option<f64> {
    if log_log {
        (w > 0.0).then(|| w.log10())
    } else {
        Some(w)
    }
}

/// The chords of `samples` that rise or fall more than [`CHORD_FRACTION`] of the
/// curve's span, by the index of their left end.
fn steep_chords(samples: &[(f64, f64, u32)], log_log: bool) -> Vec<usize> {
    let drawn: Vec<Option<f64>> = samples.iter().map(|(_, w, _)| drawn_ordinate(*w, log_log)).collect();
    let (low, high) = drawn
        .iter()
        .flatten()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| (a.min(*y), b.max(*y)));
    // A linear axis starts at 0.
    let (low, high) = if log_log {
        (low, high)
    } else {
        (low.min(0.0), high.max(0.0))
    };
    let limit = CHORD_FRACTION * (high - low);
    (0..samples.len().saturating_sub(1))
        .filter(|&i| match (drawn[i], drawn[i + 1]) {
            (Some(a), Some(b)) => (b - a).abs() > limit && samples[i].0 < samples[i + 1].0,
            _ => false,
        })
        .collect()
}

/// The samples of a line with more added where the curve is steep: every chord that
/// rises or falls more than [`CHORD_FRACTION`] of the curve's span is bisected (at the
/// geometric middle on log–log figures), round after round, until none does (or the
/// curve holds [`REFINED_SAMPLES_CAP`] samples). Near gross slip, where Ŵ grows like
/// ln(1/P_T), this puts the samples where the curve turns up.
fn refined(
    figure: u32,
    mut samples: Vec<(f64, f64, u32)>,
    log_log: bool,
    at: &(dyn Fn(f64) -> Point + Sync),
    formula: Formula,
) -> Result<Vec<(f64, f64, u32)>, SweepError> {
    loop {
        let steep = steep_chords(&samples, log_log);
        if steep.is_empty() || samples.len() + steep.len() > REFINED_SAMPLES_CAP {
            return Ok(samples);
        }
        let middles: Vec<(f64, Point)> = steep
            .iter()
            .map(|&i| {
                let (a, b) = (samples[i].0, samples[i + 1].0);
                let x = if log_log { (a * b).sqrt() } else { 0.5 * (a + b) };
                (x, at(x))
            })
            .collect();
        samples.extend(sweep(figure, &middles, formula, &Progress::new(0, &|_, _| {}))?);
        samples.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
}

/// The number of progress steps [`compute`] reports.
pub fn step_count() -> usize {
    let fig4 = FIG4_POINTS.len() * 2 + FIG4_LINE_SAMPLES;
    let fig5 = FIG5_AMPLITUDES.len() * (PHASE_SAMPLES + 1);
    let fig6 = FIG6_RATIOS.len() * (CURVE_SAMPLES + 1);
    let fig7 = FIG7_RATIOS.len() * (CURVE_SAMPLES + 1);
    let fig8 = FIG8_PHASES.len() * FIG8_NORMALS.len() * (CURVE_SAMPLES + 2);
    fig4 + fig5 + fig6 + fig7 + fig8
}

/// Fig. 4's integrated points: Q̂1 = 0.05, 0.10, …, 0.95 and 0.99.
const FIG4_POINTS: [f64; 20] = [
    0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5, 0.55, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9, 0.95, 0.99,
];
/// Samples of Fig. 4's closed-form line.
const FIG4_LINE_SAMPLES: usize = 200;

/// Computes the five figures and the facts, reporting progress.
pub fn compute(progress: &Progress) -> Result<Figures, SweepError> {
    let (fig4, fig4_max_rel_diff) = figure4(progress)?;
    let (fig5, fig5_phi_max_over_pi, fig5_out_of_phase_gain) = figure5(progress)?;
    let (fig6, fig6_small_amplitude_slope) = ratio_figure(6, 0.0, &FIG6_RATIOS, progress)?;
    let (fig7, fig7_small_amplitude_slope) = ratio_figure(7, 0.5, &FIG7_RATIOS, progress)?;
    let (fig8, fig8_limit_slope, fig8_range_slope) = figure8(progress)?;
    Ok(Figures {
        figures: vec![fig4, fig5, fig6, fig7, fig8],
        facts: Facts {
            fig4_max_rel_diff,
            fig5_phi_max_over_pi,
            fig5_out_of_phase_gain,
            fig6_small_amplitude_slope,
            fig7_small_amplitude_slope,
            fig8_limit_slope,
            fig8_range_slope,
        },
    })
}

/// Fig. 4: P̂1 = 0, the four-segment integrals (points) against the constant-normal-load
/// closed form (line), up to gross slip at Q̂1 = 1.
fn figure4(progress: &Progress) -> Result<(Figure, f64), SweepError> {
    // The phase is immaterial at P1 = 0; π/2 keeps the integrator away from the in-phase degeneracy.
    let at = |q: f64| {
        (
            q,
            Point {
                normal: 0.0,
                tangential: q,
                phase_over_pi: 0.5,
            },
        )
    };
    let points: Vec<_> = FIG4_POINTS.iter().map(|&q| at(q)).collect();
    let integrated = sweep(4, &points, Formula::FourSegment, progress)?;
    let closed = sweep(4, &points, Formula::ConstantNormalLoad, progress)?;
    let max_rel_diff = integrated
        .iter()
        .zip(&closed)
        .map(|((_, a, _), (_, b, _))| ((a - b) / b).abs())
        .fold(0.0, f64::max);
    let limit = gross_slip_amplitude(0.0, 0.5);
    let line_points: Vec<_> = (1..=FIG4_LINE_SAMPLES)
        .map(|i| at(limit * (1.0 - GROSS_SLIP_MARGIN) * i as f64 / FIG4_LINE_SAMPLES as f64))
        .collect();
    let line = sweep(4, &line_points, Formula::ConstantNormalLoad, progress)?;
    let line = refined(4, line, false, &|q| at(q).1, Formula::ConstantNormalLoad)?;
    let figure = Figure {
        number: 4,
        x_label: "Q1/(f P0)",
        y_label: W_HAT_LABEL,
        x_column: "Q1_hat",
        curve_column: "method",
        log_log: false,
        guide_slope: None,
        panels: vec![Panel {
            name: "P1_hat=0".into(),
            caption: "Fig. 4: constant normal load, P1 = 0".into(),
            curves: vec![
                Curve {
                    key: "closed form".into(),
                    label: "closed form (constant normal load)".into(),
                    style: Style::Line,
                    samples: line,
                    gross_slip_at: vec![limit],
                },
                Curve {
                    key: "four-segment".into(),
                    label: "four-segment integration, P1 = 0".into(),
                    style: Style::Points,
                    samples: integrated,
                    gross_slip_at: vec![],
                },
            ],
        }],
        notes: vec![format!(
            "gross slip at Q1 = f P0; worst relative difference of the points from the line {max_rel_diff:.1e}"
        )],
    };
    Ok((figure, max_rel_diff))
}

/// Golden-section refinement of a maximum of `w` inside [low, high] to `width`.
fn golden_maximum(
    mut low: f64,
    mut high: f64,
    width: f64,
    w: &dyn Fn(f64) -> Result<f64, SweepError>,
) -> Result<(f64, f64), SweepError> {
    let ratio = (5f64.sqrt() - 1.0) / 2.0;
    let (mut a, mut b) = (high - ratio * (high - low), low + ratio * (high - low));
    let (mut wa, mut wb) = (w(a)?, w(b)?);
    while high - low > width {
        if wa > wb {
            high = b;
            (b, wb) = (a, wa);
            a = high - ratio * (high - low);
            wa = w(a)?;
        } else {
            low = a;
            (a, wa) = (b, wb);
            b = low + ratio * (high - low);
            wb = w(b)?;
        }
    }
    let x = 0.5 * (low + high);
    Ok((x, w(x)?))
}

type Fig5Facts = (Figure, BTreeMap<String, f64>, BTreeMap<String, Option<f64>>);

/// Fig. 5: P̂1 = 0.4, Ŵ against φ/π for each Q̂1; the location of each maximum and the gain over φ = 0.
fn figure5(progress: &Progress) -> Result<Fig5Facts, SweepError> {
    let mut curves = Vec::new();
    let mut located = BTreeMap::new();
    let mut gains = BTreeMap::new();
    for key in FIG5_AMPLITUDES {
        let q = parse(key);
        let at = |phase: f64| Point {
            normal: FIG5_NORMAL,
            tangential: q,
            phase_over_pi: phase,
        };
        // Gross slip where √(Q̂1² + P̂1² + 2P̂1Q̂1|cos φ|) ≥ 1, i.e. |cos φ| ≥ (1 − Q̂1² − P̂1²)/(2P̂1Q̂1).
        let bound = (1.0 - q * q - FIG5_NORMAL * FIG5_NORMAL) / (2.0 * FIG5_NORMAL * q);
        // (Rounding of the bound must not hide a limit that lies exactly at φ = 0, as Q̂1 = 0.6's does.)
        let (first, gross_slip_at) = if bound < 1.0 + 1e-12 {
            let edge = bound.min(1.0).acos() / std::f64::consts::PI;
            (edge + GROSS_SLIP_MARGIN, vec![edge, 1.0 - edge])
        } else {
            (0.0, vec![])
        };
        let phases: Vec<(f64, Point)> = (0..PHASE_SAMPLES)
            .map(|i| i as f64 / (PHASE_SAMPLES - 1) as f64)
            .map(|phase| phase.clamp(first, 1.0 - first))
            .map(|phase| (phase, at(phase)))
            .collect();
        let samples = sweep(5, &phases, Formula::Chosen, progress)?;
        // The interior local maximum of the samples, refined to ±5·10⁻⁵ in φ/π.
        let peak = (1..samples.len() - 1)
            .filter(|&i| samples[i].1 >= samples[i - 1].1 && samples[i].1 >= samples[i + 1].1)
            .max_by(|&i, &j| samples[i].1.total_cmp(&samples[j].1))
            .unwrap_or(samples.len() / 2);
        let w = |phase: f64| value(5, at(phase), Formula::Chosen).map(|(w, _)| w);
        let (phase_max, w_max) = golden_maximum(samples[peak - 1].0, samples[peak + 1].0, 1e-4, &w)?;
        progress.step();
        located.insert(key.to_string(), (phase_max * 1000.0).round() / 1000.0);
        let in_phase = samples[0].1;
        let gain = (gross_slip_at.is_empty() && in_phase > 0.0).then(|| w_max / in_phase);
        gains.insert(key.to_string(), gain);
        let samples = refined(5, samples, false, &at, Formula::Chosen)?;
        curves.push(Curve {
            key: key.to_string(),
            label: format!("Q1/(f P0) = {key}"),
            style: Style::Line,
            samples,
            gross_slip_at,
        });
    }
    let figure = Figure {
        number: 5,
        x_label: "φ/π",
        y_label: W_HAT_LABEL,
        x_column: "phi_over_pi",
        curve_column: "Q1_hat",
        log_log: false,
        guide_slope: None,
        panels: vec![Panel {
            name: "P1_hat=0.4".into(),
            caption: "Fig. 5: effect of the phase, P1/P0 = 0.4".into(),
            curves,
        }],
        notes: vec!["Ŵ = 0 at φ = 0 and π for Q1 ≤ f P1; Q1/(f P0) = 0.6 touches gross slip at φ = 0 and π (the curve ends there)".into()],
    };
    Ok((figure, located, gains))
}

/// The sampled curve Ŵ(Q̂1) at fixed `normal_of(Q̂1)` and phase, from `low` to the gross-slip limit.
fn amplitude_curve(
    figure: u32,
    low: f64,
    limit: f64,
    at: &(dyn Fn(f64) -> Point + Sync),
    progress: &Progress,
) -> Result<Vec<(f64, f64, u32)>, SweepError> {
    let points: Vec<(f64, Point)> = log_spaced(low, limit * (1.0 - GROSS_SLIP_MARGIN), CURVE_SAMPLES)
        .into_iter()
        .map(|q| (q, at(q)))
        .collect();
    sweep(figure, &points, Formula::Chosen, progress)
}

fn slope_of(figure: u32, curve: &str, at: &dyn Fn(f64) -> Point) -> Result<LimitSlope, SweepError> {
    limit_slope(LIMIT_START, at).map_err(|source| SweepError::Slope {
        figure,
        curve: curve.to_string(),
        source,
    })
}

/// The curve of Ŵ against Q̂1 from `low` up to the gross-slip `limit` (where it stops),
/// with its small-amplitude limit slope.
fn curve_to_gross_slip(
    figure: u32,
    key: &str,
    label: String,
    low: f64,
    limit: f64,
    at: &(dyn Fn(f64) -> Point + Sync),
    progress: &Progress,
) -> Result<(Curve, LimitSlope), SweepError> {
    let samples = amplitude_curve(figure, low, limit, at, progress)?;
    let samples = refined(figure, samples, true, at, Formula::Chosen)?;
    let slope = slope_of(figure, key, at)?;
    progress.step();
    let curve = Curve {
        key: key.to_string(),
        label,
        style: Style::Line,
        samples,
        gross_slip_at: vec![limit],
    };
    Ok((curve, slope))
}

/// Figs. 6 and 7: Ŵ against Q̂1 at fixed ratios P̂1/Q̂1, and the small-amplitude slope of each.
fn ratio_figure(
    number: u32,
    phase_over_pi: f64,
    ratios: &[&str],
    progress: &Progress,
) -> Result<(Figure, BTreeMap<String, LimitSlope>), SweepError> {
    let mut curves = Vec::new();
    let mut slopes = BTreeMap::new();
    for key in ratios {
        let ratio = parse(key);
        let at = move |q: f64| Point {
            normal: ratio * q,
            tangential: q,
            phase_over_pi,
        };
        let limit = gross_slip_amplitude_at_ratio(ratio, phase_over_pi);
        let label = format!("f P1/Q1 = {key}");
        let (curve, slope) = curve_to_gross_slip(number, key, label, RATIO_FIGURES_LOW, limit, &at, progress)?;
        slopes.insert(key.to_string(), slope);
        curves.push(curve);
    }
    let (caption, notes) = if phase_over_pi == 0.0 {
        (
            "Fig. 6: in-phase loading, φ = 0 (closed form)",
            vec!["Ŵ = 0 for f P1/Q1 ≥ 1 (not drawn): the load line stays inside the friction cone".to_string()],
        )
    } else {
        ("Fig. 7: out-of-phase loading, φ = π/2", vec![])
    };
    let figure = Figure {
        number,
        x_label: "Q1/(f P0)",
        y_label: W_HAT_LABEL,
        x_column: "Q1_hat",
        curve_column: "P1_hat_over_Q1_hat",
        log_log: true,
        guide_slope: Some(3.0),
        panels: vec![Panel {
            name: format!("phi={phase_over_pi}pi"),
            caption: caption.into(),
            curves,
        }],
        notes,
    };
    Ok((figure, slopes))
}

type Fig8Facts = (Figure, Vec<BTreeMap<String, LimitSlope>>, Vec<BTreeMap<String, f64>>);

/// Fig. 8: Ŵ against Q̂1 at fixed P̂1, at φ = π/2 and 0.4π; limit and fitted slopes.
fn figure8(progress: &Progress) -> Result<Fig8Facts, SweepError> {
    let mut panels = Vec::new();
    let (mut limits, mut ranges) = (Vec::new(), Vec::new());
    for phase_over_pi in FIG8_PHASES {
        let mut curves = Vec::new();
        let (mut limit_slopes, mut range_slopes) = (BTreeMap::new(), BTreeMap::new());
        for key in FIG8_NORMALS {
            let normal = parse(key);
            let at = move |q: f64| Point {
                normal,
                tangential: q,
                phase_over_pi,
            };
            let limit = gross_slip_amplitude(normal, phase_over_pi);
            let label = format!("P1/P0 = {key}");
            let (curve, slope) = curve_to_gross_slip(8, key, label, FIG8_LOW, limit, &at, progress)?;
            limit_slopes.insert(key.to_string(), slope);
            let fit_points: Vec<(f64, Point)> = log_spaced(FIG8_RANGE.0, FIG8_RANGE.1, 21)
                .into_iter()
                .map(|q| (q, at(q)))
                .collect();
            let fitted = sweep(8, &fit_points, Formula::Chosen, &Progress::new(0, &|_, _| {}))?;
            let pairs: Vec<(f64, f64)> = fitted.iter().map(|(q, w, _)| (*q, *w)).collect();
            range_slopes.insert(key.to_string(), fitted_log_slope(&pairs));
            progress.step();
            curves.push(curve);
        }
        panels.push(Panel {
            name: format!("phi={phase_over_pi}pi"),
            caption: format!("Fig. 8: fixed P1/P0, φ = {phase_over_pi}π"),
            curves,
        });
        limits.push(limit_slopes);
        ranges.push(range_slopes);
    }
    let figure = Figure {
        number: 8,
        x_label: "Q1/(f P0)",
        y_label: W_HAT_LABEL,
        x_column: "Q1_hat",
        curve_column: "P1_hat",
        log_log: true,
        guide_slope: Some(2.0),
        panels,
        notes: vec![format!(
            "grey dashes: slope 2, the limit as Q1 → 0 at fixed P1; facts.json fits the slope over Q1/(f P0) ∈ [{},\u{a0}{}]",
            FIG8_RANGE.0, FIG8_RANGE.1
        )],
    };
    Ok((figure, limits, ranges))
}
