//! The paper's Figures 4–8: the facts each figure is read for, checked on the
//! computed values, and the `microslip figures` command (proofs/figures.md).

mod common;
use common::Scratch;

use std::sync::OnceLock;

use microslip::accuracy::Measurement;
use microslip::case::Case;
use microslip::compliance::Polynomial;
use microslip::cycle::{CycleError, LoadCycle};
use microslip::dissipation::{dissipation, Options};
use microslip::figures::cubic_law::{amplitudes, cubic_law_errors, cubic_law_figure};
use microslip::figures::draw::{curve_style, figure_picture, plotted, slope_guide, FIGURE_WIDTH};
use microslip::figures::evaluate::{
    fitted_log_slope, gross_slip_amplitude, gross_slip_amplitude_at_ratio, limit_slope, local_slope, resolved, Formula,
    Point,
};
use microslip::figures::{compute, Figure, Figures, Progress, Style};
use microslip::plot::layout::{Frame, Rect};
use microslip::plot::{accuracy_picture, cycle_picture, Format, Picture};
use microslip::real::{Precision, Real};
use microslip::simulate::{simulate, SimulationOptions, SimulationResult};
use microslip::verify::small_amplitude::coefficient;
use resvg::tiny_skia::Pixmap;
use rug::Float;

/// The figures, computed once for all the tests of this file.
fn figures() -> &'static Figures {
    static FIGURES: OnceLock<Figures> = OnceLock::new();
    FIGURES.get_or_init(|| compute(&Progress::new(0, &|_, _| {})).expect("the figures compute"))
}

/// Every figure `figures` draws: the paper's, then the cubic law's error.
fn drawn_figures() -> Vec<&'static Figure> {
    static CUBIC_LAW: OnceLock<Figure> = OnceLock::new();
    let cubic_law = CUBIC_LAW.get_or_init(|| {
        let points = cubic_law_errors(&amplitudes(), &Progress::new(0, &|_, _| {}));
        cubic_law_figure(&points.expect("the cubic law's error computes"))
    });
    figures().figures.iter().chain([cubic_law]).collect()
}

fn w_hat(normal: f64, tangential: f64, phase_over_pi: f64) -> f64 {
    resolved(
        Point {
            normal,
            tangential,
            phase_over_pi,
        },
        Formula::Chosen,
    )
    .expect("a point inside the theory")
    .w_hat
}

#[test]
fn fig4_four_segment_points_agree_with_the_constant_normal_load_closed_form() {
    let facts = &figures().facts;
    assert!(facts.fig4_max_rel_diff < 1e-12, "{}", facts.fig4_max_rel_diff);
    // Recomputed here, also where the loop is about to slip (Q̂1 = 0.999).
    for q in [0.05, 0.5, 0.9, 0.999] {
        let at = Point {
            normal: 0.0,
            tangential: q,
            phase_over_pi: 0.5,
        };
        let integrated = resolved(at, Formula::FourSegment).unwrap().w_hat;
        let closed = resolved(at, Formula::ConstantNormalLoad).unwrap().w_hat;
        assert!(
            ((integrated - closed) / closed).abs() < 1e-12,
            "Q̂1 = {q}: {integrated} vs {closed}"
        );
    }
    // The closed form for v' = 1/P: 4[(2 − q) ln(1/(1 − q)) − 2q], which grows without bound at gross slip.
    for q in [0.2_f64, 0.9, 0.999] {
        let exact = 4.0 * ((2.0 - q) * (-(-q).ln_1p()) - 2.0 * q);
        let closed = resolved(
            Point {
                normal: 0.0,
                tangential: q,
                phase_over_pi: 0.5,
            },
            Formula::ConstantNormalLoad,
        )
        .unwrap()
        .w_hat;
        assert!(
            ((closed - exact) / exact).abs() < 1e-11,
            "Q̂1 = {q}: {closed} vs {exact}"
        );
    }
}

#[test]
fn fig5_every_maximum_lies_near_0_4_pi_and_out_of_phase_loading_dissipates_more() {
    let facts = &figures().facts;
    for (key, expected) in [
        ("0.2", 0.423),
        ("0.3", 0.399),
        ("0.4", 0.390),
        ("0.5", 0.392),
        ("0.6", 0.400),
    ] {
        let located = facts.fig5_phi_max_over_pi[key];
        assert!((located - expected).abs() <= 0.002, "Q̂1 = {key}: maximum at {located}π");
        // A maximum: larger than its neighbours 0.002 away on either side.
        let q: f64 = key.parse().unwrap();
        let peak = w_hat(0.4, q, located);
        assert!(
            peak > w_hat(0.4, q, located - 0.002) && peak > w_hat(0.4, q, located + 0.002),
            "{key}"
        );
        // The paper: the dissipation increases with φ to a maximum near π/2.
        assert!(
            w_hat(0.4, q, 0.1) < w_hat(0.4, q, 0.3) && w_hat(0.4, q, 0.3) < peak,
            "{key}"
        );
    }
    // In phase Ŵ = 0 for Q̂1 ≤ P̂1, and Q̂1 = 0.6 reaches gross slip there: the gain is unbounded.
    for key in ["0.2", "0.3", "0.4", "0.6"] {
        assert_eq!(facts.fig5_out_of_phase_gain[key], None, "{key}");
    }
    let gain = facts.fig5_out_of_phase_gain["0.5"].unwrap();
    assert!(
        (gain - w_hat(0.4, 0.5, 0.392) / w_hat(0.4, 0.5, 0.0)).abs() < 1e-3 * gain,
        "{gain}"
    );
    assert!(gain > 6.0 && gain < 7.0, "{gain}");
}

#[test]
fn fig6_and_fig7_small_amplitude_slopes_are_cubic_for_every_ratio() {
    let facts = &figures().facts;
    assert_eq!(facts.fig6_small_amplitude_slope.len(), 5);
    assert_eq!(facts.fig7_small_amplitude_slope.len(), 8);
    for (ratio, limit) in facts
        .fig6_small_amplitude_slope
        .iter()
        .chain(&facts.fig7_small_amplitude_slope)
    {
        assert_eq!(limit.slope, 3.0, "ratio {ratio}: {limit:?}");
        let last = limit.samples.last().unwrap();
        assert!((last.slope - 3.0).abs() < 5e-4, "ratio {ratio}: {last:?}");
    }
    // Out of phase dissipates more than in phase at the same amplitudes (Fig. 7 against Fig. 6).
    for ratio in [0.25, 0.5, 0.75, 0.9] {
        for q in [1e-3, 0.1, 0.5] {
            assert!(
                w_hat(ratio * q, q, 0.5) > w_hat(ratio * q, q, 0.0),
                "ratio {ratio}, Q̂1 = {q}"
            );
        }
    }
    // In phase nothing slips once fP1 ≥ Q1.
    assert_eq!(w_hat(0.1, 0.1, 0.0), 0.0);
    assert_eq!(w_hat(0.15, 0.1, 0.0), 0.0);
}

#[test]
fn fig8_limit_slope_is_two_at_every_phase_not_2_2() {
    let facts = &figures().facts;
    assert_eq!(facts.fig8_limit_slope.len(), 2);
    for map in &facts.fig8_limit_slope {
        assert_eq!(map.len(), 3);
        for (normal, limit) in map {
            assert_eq!(limit.slope, 2.0, "P̂1 = {normal}: {limit:?}");
            assert!(
                limit.settled_at <= 1e-4,
                "P̂1 = {normal}: settled at {}",
                limit.settled_at
            );
        }
    }
    // The slope fitted over Q̂1 ∈ [0.01, 0.1] is near 2 too, not 2.2.
    for map in &facts.fig8_range_slope {
        for (normal, slope) in map {
            assert!(*slope > 1.85 && *slope < 2.1, "P̂1 = {normal}: {slope}");
        }
    }
    // Other phases: the same limit (the paper found no slope below 2.2 for any phase).
    for phase in [0.1, 0.25, 0.75, 0.9] {
        let at = move |q: f64| Point {
            normal: 0.1,
            tangential: q,
            phase_over_pi: phase,
        };
        assert_eq!(limit_slope(0.1, &at).unwrap().slope, 2.0, "φ = {phase}π");
    }
    // And in the crossover the local slope dips below 2 (P̂1 = 0.05, φ = π/2).
    let at = |q: f64| Point {
        normal: 0.05,
        tangential: q,
        phase_over_pi: 0.5,
    };
    let (dip, _) = local_slope(0.0366, &at).unwrap();
    assert!(dip < 1.83 && dip > 1.81, "{dip}");
}

#[test]
fn fig8_limit_is_the_rho_squared_term_of_the_small_amplitude_coefficient() {
    // I(ρ, φ)/ρ² → −(8/3) sin²φ as ρ → 0, with relative correction ρ cos φ: W ∝ P1 Q1².
    let bits = Precision::bits(200);
    for phase in [0.1, 0.25, 0.4, 0.5, 0.75] {
        let pi_phase = Float::with_val(200, phase) * Float::pi(bits);
        let sin2 = Real::sin(&pi_phase).square().to_f64();
        for rho in [1e-3, 1e-5] {
            let r = Float::with_val(200, rho);
            let i = coefficient(&r, &pi_phase).unwrap().to_f64() / (rho * rho);
            let leading = -8.0 / 3.0 * sin2;
            let correction = 1.0 + rho * (std::f64::consts::PI * phase).cos();
            assert!(
                (i / (leading * correction) - 1.0).abs() < 2.0 * rho * rho,
                "φ = {phase}π, ρ = {rho}: I/ρ² = {i}"
            );
        }
    }
    // The ρ² term comes from the long segments BC and CH: the short slip segments EB and HE,
    // 2ρ sin φ long in θ, carry a fraction O(ρ) of it.
    for phase in [0.25, 0.5] {
        let p = 200;
        let one = Float::with_val(p, 1);
        let amplitude = Float::with_val(p, 0.25);
        let rho = 1e-3;
        let cycle = LoadCycle {
            mean_normal_load: one.clone(),
            normal_amplitude: amplitude.clone(),
            mean_tangential_load: Float::with_val(p, 0),
            tangential_amplitude: Float::with_val(p, rho) * &amplitude,
            phase: Float::with_val(p, phase) * Float::pi(bits),
            friction: one.clone(),
            compliance_ratio: one.clone(),
        };
        let linear = Polynomial {
            reference: one.clone(),
            coefficients: vec![Float::with_val(p, 0), one],
        };
        let options = Options {
            check_compliance: false,
            ..Options::default()
        };
        let segments = dissipation(&cycle, &linear, &options).unwrap().segments;
        let short = (segments.eb.clone() + &segments.he).to_f64().abs();
        let total = segments.total().to_f64().abs();
        assert!(
            short < 2.0 * rho * total,
            "φ = {phase}π: EB + HE = {short:e} of {total:e}"
        );
    }
    // For Persson's compliance (v''(P0) = −1/P0²): Ŵ ≈ (8/3) P̂1 Q̂1² sin²φ when Q̂1 ≪ P̂1 ≪ 1
    // (measured 1.000001 times it here; the correction grows like P̂1²).
    let (p1, q1) = (1e-3, 1e-7);
    let ratio = w_hat(p1, q1, 0.5) / (8.0 / 3.0 * p1 * q1 * q1);
    assert!((ratio - 1.0).abs() < 1e-5, "{ratio}");
}

#[test]
fn gross_slip_limits_are_where_the_cycle_validation_starts_refusing() {
    let cycle = |normal: f64, tangential: f64, phase_over_pi: f64| LoadCycle {
        mean_normal_load: 1.0,
        normal_amplitude: normal,
        mean_tangential_load: 0.0,
        tangential_amplitude: tangential,
        phase: phase_over_pi * std::f64::consts::PI,
        friction: 1.0,
        compliance_ratio: 1.0,
    };
    for (normal, phase) in [(0.0, 0.5), (0.05, 0.5), (0.2, 0.4), (0.4, 0.1), (0.3, 0.0), (0.5, 0.8)] {
        let limit = gross_slip_amplitude(normal, phase);
        assert!(
            cycle(normal, limit * (1.0 - 1e-9), phase).validate().is_ok(),
            "{normal} {phase}"
        );
        assert!(matches!(
            cycle(normal, limit * (1.0 + 1e-9), phase).validate(),
            Err(CycleError::GrossSlip { .. })
        ));
    }
    for (ratio, phase) in [(0.0, 0.0), (0.9, 0.0), (2.0, 0.5), (0.75, 0.4)] {
        let limit = gross_slip_amplitude_at_ratio(ratio, phase);
        let below = limit * (1.0 - 1e-9);
        let above = limit * (1.0 + 1e-9);
        assert!(cycle(ratio * below, below, phase).validate().is_ok(), "{ratio} {phase}");
        assert!(matches!(
            cycle(ratio * above, above, phase).validate(),
            Err(CycleError::GrossSlip { .. })
        ));
    }
    // Every curve stops just inside its limit.
    for figure in &figures().figures {
        for panel in &figure.panels {
            for curve in &panel.curves {
                for limit in &curve.gross_slip_at {
                    let nearest = curve
                        .samples
                        .iter()
                        .map(|(x, _, _)| (x - limit).abs())
                        .fold(f64::INFINITY, f64::min);
                    assert!(
                        nearest <= 1.01e-3 * limit.max(1.0),
                        "Fig. {}: {}",
                        figure.number,
                        curve.key
                    );
                }
            }
        }
    }
}

#[test]
fn slope_helpers_recover_known_powers() {
    let points: Vec<(f64, f64)> = [0.01, 0.03, 0.1, 0.3]
        .iter()
        .map(|x: &f64| (*x, 5.0 * x.powf(2.5)))
        .collect();
    assert!((fitted_log_slope(&points) - 2.5).abs() < 1e-12);
    // Constant normal load: Ŵ = (2/3) Q̂1³ (1 + Q̂1 + …), so the local slope is 3 + Q̂1 + O(Q̂1²).
    let at = |q: f64| Point {
        normal: 0.0,
        tangential: q,
        phase_over_pi: 0.5,
    };
    let (slope, bits) = local_slope(1e-3, &at).unwrap();
    assert!((slope - 3.001).abs() < 1e-5, "{slope}");
    assert_eq!(bits, 53);
}

/// The names of the files in `dir`, sorted.
fn file_names_in(dir: &std::path::Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// The files `figures` writes with a file per figure in each of `extensions`, sorted.
fn expected_files(extensions: &[&str]) -> Vec<String> {
    let mut expected = vec!["facts.json".to_string(), "limit_slopes.csv".to_string()];
    for stem in ["fig4", "fig5", "fig6", "fig7", "fig8", "cubic_law_error"] {
        for ext in extensions {
            expected.push(format!("{stem}.{ext}"));
        }
    }
    expected.sort();
    expected
}

#[test]
fn figures_command_writes_every_file_atomically_with_numeric_facts() {
    let scratch = Scratch::new("out");
    let dir = scratch.join("figures");
    let output = common::run(["figures", "--out"]).arg(&dir).output();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert_eq!(
        file_names_in(&dir),
        expected_files(&["csv", "png", "svg"]),
        "no temporary file is left behind"
    );
    let facts: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("facts.json")).unwrap()).unwrap();
    assert!(facts["fig4_max_rel_diff"].as_f64().unwrap() < 1e-12);
    for key in ["0.2", "0.3", "0.4", "0.5", "0.6"] {
        assert!(facts["fig5_phi_max_over_pi"][key].is_f64(), "{key}");
    }
    assert!(facts["fig5_out_of_phase_gain"]["0.5"].is_f64());
    assert!(facts["fig5_out_of_phase_gain"].get("0.2").is_none());
    assert!(facts["fig5_out_of_phase_gain_unbounded"]["0.2"].is_string());
    for key in ["0", "0.25", "0.5", "0.75", "0.9"] {
        assert_eq!(facts["fig6_small_amplitude_slope"][key].as_f64(), Some(3.0), "{key}");
    }
    for key in ["1", "1.5", "2"] {
        assert_eq!(facts["fig7_small_amplitude_slope"][key].as_f64(), Some(3.0), "{key}");
    }
    for suffix in ["", "_phi_0.4pi"] {
        for key in ["0.05", "0.1", "0.2"] {
            assert_eq!(facts[format!("fig8_limit_slope{suffix}")][key].as_f64(), Some(2.0));
            assert!(facts[format!("fig8_range_slope{suffix}")][key].is_f64());
        }
    }
    // A CSV row per sample, with the gross-slip end marked.
    let fig7 = std::fs::read_to_string(dir.join("fig7.csv")).unwrap();
    assert!(fig7.starts_with("panel,P1_hat_over_Q1_hat,Q1_hat,W_hat,precision_bits,gross_slip_limit\n"));
    assert_eq!(fig7.lines().filter(|l| !l.ends_with(',')).count(), 1 + 8, "{fig7}");
    let png = std::fs::read(dir.join("fig8.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    // The cubic law's error: a row per panel, phase and amplitude, its band reported.
    let cubic_law = std::fs::read_to_string(dir.join("cubic_law_error.csv")).unwrap();
    assert!(cubic_law.starts_with("panel,phi_over_pi,p1_over_p0,true_relative_error,proven_relative_bound,"));
    assert_eq!(cubic_law.lines().count(), 1 + 2 * 3 * 31);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        stdout.contains("cubic law's error, hertz, φ = 0.9π: proven band / true error"),
        "{stdout}"
    );
}

#[test]
fn figures_command_refuses_an_unusable_directory_before_computing() {
    let scratch = Scratch::new("file");
    let file = scratch.join("figures");
    std::fs::write(&file, b"not a directory").unwrap();
    let output = common::run(["figures", "--out"]).arg(&file).output();
    assert_eq!(output.status.code(), Some(2));
    assert!(output.stdout.is_empty());
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("cannot write to the output directory"), "{stderr}");
}

/// Whether a line through `points` (pixels) touches `rect` (sampled finely along each piece).
fn line_touches(points: &[(f64, f64)], rect: &Rect) -> Option<(f64, f64)> {
    let inside = |(x, y): (f64, f64)| x >= rect.left && x <= rect.right && y >= rect.top && y <= rect.bottom;
    if let [single] = points {
        return inside(*single).then_some(*single);
    }
    points.windows(2).find_map(|w| {
        (0..=64).find_map(|k| {
            let t = f64::from(k) / 64.0;
            let p = (w[0].0 + t * (w[1].0 - w[0].0), w[0].1 + t * (w[1].1 - w[0].1));
            inside(p).then_some(p)
        })
    })
}

/// The pixel of a point in drawn coordinates, from the chart's area and ranges.
fn pixel(frame: &Frame, (x, y): (f64, f64)) -> (f64, f64) {
    let a = &frame.area;
    let fx = (x - frame.x.start) / (frame.x.end - frame.x.start);
    let fy = (y - frame.y.start) / (frame.y.end - frame.y.start);
    (a.left + fx * (a.right - a.left), a.bottom - fy * (a.bottom - a.top))
}

/// The legend's box is drawn in the SVG where the layout says.
fn assert_legend_drawn(svg: &str, legend: &Rect) {
    let (w, h) = (legend.right - legend.left, legend.bottom - legend.top);
    let drawn = format!(
        "<rect x=\"{}\" y=\"{}\" width=\"{w}\" height=\"{h}\"",
        legend.left, legend.top
    );
    assert!(svg.contains(&drawn), "{drawn}");
}

#[test]
fn no_figure_legend_covers_a_curve_point_line_or_marker() {
    for figure in drawn_figures() {
        let picture = figure_picture(figure).unwrap();
        assert_eq!(picture.charts.len(), figure.panels.len());
        for (chart, panel) in picture.charts.iter().zip(&figure.panels) {
            let legend = chart.legend.inflate(1.0);
            assert_legend_drawn(&picture.svg, &chart.legend);
            // Off the data: under every chart's plotting area, inside the picture.
            for other in &picture.charts {
                assert!(
                    chart.legend.top > other.frame.area.bottom,
                    "Fig. {}: the legend is not under the charts",
                    figure.number
                );
            }
            let whole = Rect::at(0.0, 0.0, (f64::from(picture.size.0), f64::from(picture.size.1)));
            assert!(whole.encloses(&chart.legend), "Fig. {}: legend cut off", figure.number);
            let drawn = |x: f64, w: f64| {
                if figure.log_log {
                    (x.log10(), w.log10())
                } else {
                    (x, w)
                }
            };
            for curve in &panel.curves {
                let points: Vec<(f64, f64)> = curve
                    .samples
                    .iter()
                    .filter(|(x, w, _)| !figure.log_log || (*x > 0.0 && *w > 0.0))
                    .map(|(x, w, _)| pixel(&chart.frame, drawn(*x, *w)))
                    .collect();
                let marker = match curve.style {
                    Style::Points => 6.0,
                    Style::Line => 0.0,
                };
                let hit = if marker > 0.0 {
                    points.iter().find(|p| legend.inflate(marker).contains(**p)).copied()
                } else {
                    line_touches(&points, &legend)
                };
                assert!(
                    hit.is_none(),
                    "Fig. {} {}: the legend {:?} covers {:?} of {}",
                    figure.number,
                    panel.name,
                    chart.legend,
                    hit,
                    curve.label
                );
                // The crosses at the ends (half-width 7).
                for end in [points.first(), points.last()].into_iter().flatten() {
                    assert!(!legend.inflate(7.0).contains(*end), "Fig. {}: a cross", figure.number);
                }
            }
            if figure.log_log {
                let (line, _) = slope_guide(panel, figure.guide_slope.unwrap()).unwrap();
                let guide: Vec<(f64, f64)> = line.iter().map(|p| pixel(&chart.frame, *p)).collect();
                assert!(
                    line_touches(&guide, &legend).is_none(),
                    "Fig. {}: slope guide",
                    figure.number
                );
            }
        }
    }
}

/// Simulated cycles of several shapes: the README's, a mean tangential load, φ past π.
fn simulated_cycles() -> Vec<(LoadCycle<f64>, SimulationResult)> {
    [
        common::case(),
        common::case().p1("0.3").q0("0.2").q1("0.3").phi("0.1pi"),
        common::case().p1("0.5").q0("-0.1").q1("0.4").phi("1.3pi"),
        common::case().p1("0.2").q1("0.7").phi("0.5pi"),
    ]
    .into_iter()
    .map(|case| {
        let Case { cycle, compliance } = case.text().read::<f64>(Precision::DOUBLE).unwrap();
        let options = SimulationOptions {
            elements: Some(100),
            steps: Some(400),
            extrapolate: false,
            ..SimulationOptions::default()
        };
        let result = simulate(&cycle, compliance.as_ref(), &options).unwrap();
        (cycle, result)
    })
    .collect()
}

#[test]
fn simulate_plot_legends_cover_no_data_and_labels_sit_beside_their_markers() {
    for (cycle, result) in simulated_cycles() {
        let picture = cycle_picture(&cycle, &result).unwrap();
        let [ellipse, hysteresis] = picture.charts.as_slice() else {
            panic!("two charts")
        };
        for chart in [ellipse, hysteresis] {
            assert_legend_drawn(&picture.svg, &chart.legend);
            assert!(chart.frame.area.encloses(&chart.legend));
        }
        let loads: Vec<(f64, f64)> = result
            .steady_loop
            .iter()
            .map(|s| pixel(&ellipse.frame, (s.normal_load, s.tangential_load)))
            .collect();
        assert_eq!(line_touches(&loads, &ellipse.legend.inflate(1.0)), None, "{cycle:?}");
        // The friction wedge |Q| = fP.
        let top = ellipse.frame.x.end;
        for sign in [1.0, -1.0] {
            let wedge = [(0.0, 0.0), (top, sign * cycle.friction * top)].map(|p| pixel(&ellipse.frame, p));
            assert_eq!(line_touches(&wedge, &ellipse.legend.inflate(1.0)), None, "{cycle:?}");
        }
        let loop_points: Vec<(f64, f64)> = result
            .steady_loop
            .iter()
            .map(|s| pixel(&hysteresis.frame, (s.displacement, s.tangential_load)))
            .collect();
        assert_eq!(
            line_touches(&loop_points, &hysteresis.legend.inflate(1.0)),
            None,
            "{cycle:?}"
        );
        // B, C, H, E: each label beside its marker, none on any marker or on the legend.
        let names: Vec<&str> = ellipse.labels.iter().map(|l| l.text.as_str()).collect();
        assert_eq!(names, ["E", "B", "C", "H"]);
        for label in &ellipse.labels {
            assert!(!label.rect.intersects(&ellipse.legend), "{}", label.text);
            for marker in &ellipse.labels {
                let (x, y) = pixel(&ellipse.frame, marker.at);
                let r = marker.radius;
                // The nearest point of the label's box to the marker's centre lies outside the disc.
                let dx = (label.rect.left - x).max(0.0).max(x - label.rect.right);
                let dy = (label.rect.top - y).max(0.0).max(y - label.rect.bottom);
                assert!(
                    dx.hypot(dy) > r,
                    "label {} on the marker of {}",
                    label.text,
                    marker.text
                );
            }
            let (x, y) = pixel(&ellipse.frame, label.at);
            let dx = (label.rect.left - x).max(0.0).max(x - label.rect.right);
            let dy = (label.rect.top - y).max(0.0).max(y - label.rect.bottom);
            assert!(
                dx.hypot(dy) < 3.0 * label.radius + 8.0,
                "label {} far from its marker",
                label.text
            );
            assert!(
                picture.svg.contains(&format!(">{}</text>", label.text)),
                "label {} drawn",
                label.text
            );
        }
    }
}

/// The texts of an SVG's text elements.
fn svg_texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|rest| {
            let start = rest.find('>')? + 1;
            let end = rest.find("</text>")?;
            Some(rest[start..end].trim().to_string())
        })
        .collect()
}

/// Whether `text` reads as a number written with a negative zero ("-0", "-0.0", "-0e0").
fn negative_zero(text: &str) -> bool {
    text.strip_prefix('-')
        .and_then(|rest| rest.parse::<f64>().ok())
        .is_some_and(|value| value == 0.0)
}

fn is_power_of_ten(text: &str) -> bool {
    text.strip_prefix("10").is_some_and(|exponent| {
        !exponent.is_empty()
            && exponent
                .chars()
                .enumerate()
                .all(|(i, c)| "⁰¹²³⁴⁵⁶⁷⁸⁹".contains(c) || (i == 0 && c == '⁻'))
    })
}

#[test]
fn no_tick_reads_negative_zero_and_log_axes_show_powers_of_ten() {
    let mut svgs: Vec<(String, bool)> = drawn_figures()
        .into_iter()
        .map(|f| (figure_picture(f).unwrap().svg, f.log_log))
        .collect();
    for (cycle, result) in simulated_cycles() {
        svgs.push((cycle_picture(&cycle, &result).unwrap().svg, false));
    }
    let measurements: Vec<Measurement> = (0..12)
        .map(|k| Measurement {
            rule: if k % 2 == 0 { "gauss-legendre" } else { "tanh-sinh" },
            precision_bits: 53,
            parameter: f64::from(k),
            evaluations: 10,
            seconds: 1e-6 * 3f64.powi(k),
            rel_error: 10f64.powi(-3 * k),
            case: "x".into(),
        })
        .collect();
    let accuracy = accuracy_picture(&measurements).unwrap().svg;
    svgs.push((accuracy.clone(), true));
    for (svg, log) in &svgs {
        let texts = svg_texts(svg);
        assert!(texts.len() > 10);
        for text in &texts {
            assert!(!negative_zero(text), "a tick reads {text}");
            assert!(!text.contains("-0.0"), "{text}");
        }
        if *log {
            // Every tick label is a power of ten; nothing is a bare log10 like "-10.0".
            let numeric: Vec<&String> = texts
                .iter()
                .filter(|t| t.starts_with(|c: char| c.is_ascii_digit() || c == '-'))
                .collect();
            assert!(numeric.len() >= 6, "{numeric:?}");
            for text in numeric {
                assert!(is_power_of_ten(text), "log tick {text}");
            }
        }
    }
    // The accuracy chart's error axis runs from 10⁰ to the references' 10⁻¹⁰⁰.
    let texts = svg_texts(&accuracy);
    assert!(texts.iter().any(|t| t == "10⁰"), "{texts:?}");
    assert!(texts.iter().any(|t| t == "10⁻¹⁰⁰"), "{texts:?}");
}

#[test]
fn pngs_are_rendered_at_twice_the_old_size_and_anti_aliased() {
    let fig5 = &figures().figures[1];
    assert_eq!(fig5.number, 5);
    let picture = figure_picture(fig5).unwrap();
    let png = picture.encode(Format::Png).unwrap();
    let pixmap = Pixmap::decode_png(&png).unwrap();
    assert_eq!(
        (pixmap.width(), pixmap.height()),
        (2 * picture.size.0, 2 * picture.size.1)
    );
    // Anti-aliasing: along the first curve (Okabe–Ito blue (0, 114, 178) on white) there
    // are pixels of intermediate coverage, a blend a·colour + (1 − a)·white with a in
    // (0.15, 0.85); a staircase of whole pixels has none.
    let colour = [0.0, 114.0, 178.0];
    let blends = pixmap
        .pixels()
        .iter()
        .filter(|p| {
            let rgb = [f64::from(p.red()), f64::from(p.green()), f64::from(p.blue())];
            let a = (255.0 - rgb[2]) / (255.0 - colour[2]);
            (0.15..0.85).contains(&a)
                && rgb
                    .iter()
                    .zip(colour)
                    .all(|(v, c)| (v - (a * c + (1.0 - a) * 255.0)).abs() <= 3.0)
        })
        .count();
    assert!(blends > 300, "{blends} blended pixels");
    // The simulate plot too.
    let (cycle, result) = &simulated_cycles()[0];
    let png = cycle_picture(cycle, result).unwrap().encode(Format::Png).unwrap();
    let pixmap = Pixmap::decode_png(&png).unwrap();
    assert_eq!((pixmap.width(), pixmap.height()), (2400, 1200));
    let greys = pixmap
        .pixels()
        .iter()
        .filter(|p| p.red() == p.green() && p.green() == p.blue() && (40..215).contains(&p.red()))
        .map(|p| p.red())
        .collect::<std::collections::BTreeSet<u8>>();
    // (Rendered with crisp edges, black text and lines on white leave a handful.)
    assert!(greys.len() > 40, "{} grey levels", greys.len());
}

#[test]
fn figures_that_cannot_be_written_exit_1_and_leave_no_file_of_the_run() {
    let dir = Scratch::new("full");
    // 100 KiB a file: Fig. 4's CSV and SVG fit, its PNG (over 300 KB) does not.
    let output = common::run(["figures", "--out"])
        .arg(&dir)
        .file_size_limit_kib(100)
        .output();
    let stderr = common::failed_with_one(&output);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("no file of this run was kept"), "{stderr}");
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert!(left.is_empty(), "{left:?}");
    // A name taken by a directory is refused before anything is computed.
    std::fs::create_dir_all(dir.join("fig6.png")).unwrap();
    let output = common::run(["figures", "--out"]).arg(&dir).output();
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("fig6.png") && stderr.contains("is a directory"),
        "{stderr}"
    );
}

/// The font sizes of an SVG's text elements.
fn font_sizes(svg: &str) -> Vec<f64> {
    svg.split("<text")
        .skip(1)
        .filter_map(|rest| {
            let tag = &rest[..rest.find('>')?];
            let start = tag.find("font-size=\"")? + "font-size=\"".len();
            let end = start + tag[start..].find('"')?;
            tag[start..end].parse().ok()
        })
        .collect()
}

/// Every picture the program draws: the figures, the simulate plots, an accuracy chart.
fn every_picture() -> Vec<(String, Picture)> {
    let mut pictures: Vec<(String, Picture)> = drawn_figures()
        .into_iter()
        .map(|f| (format!("Fig. {}", f.number), figure_picture(f).unwrap()))
        .collect();
    for (cycle, result) in simulated_cycles().iter().take(1) {
        pictures.push(("simulate plot".into(), cycle_picture(cycle, result).unwrap()));
    }
    pictures.push((
        "accuracy chart".into(),
        accuracy_picture(&clamped_measurements()).unwrap(),
    ));
    pictures
}

#[test]
fn every_text_prints_at_eight_points_or_more_at_column_width() {
    // A figure prints at a column width of 85 mm: 8 pt = 8 × 25.4/72 mm is then
    // 8 × 25.4/72 × (canvas width / 85) canvas units, 19.9 for the 600-unit figures.
    for figure in drawn_figures() {
        let picture = figure_picture(figure).unwrap();
        assert_eq!(picture.size.0, FIGURE_WIDTH);
        assert!((picture.print_width_mm() - 85.0).abs() < 1e-9);
    }
    for (name, picture) in every_picture() {
        let needed = 8.0 * 25.4 / 72.0 * f64::from(picture.size.0) / picture.print_width_mm();
        let sizes = font_sizes(&picture.svg);
        assert!(sizes.len() > 10, "{name}: {} texts", sizes.len());
        let smallest = sizes.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(
            smallest >= needed,
            "{name}: a text of {smallest} units, {:.2} pt in print, below 8 pt ({needed:.2} units)",
            smallest * picture.print_width_mm() / f64::from(picture.size.0) * 72.0 / 25.4
        );
        // The SVG names the embedded family, not a generic one.
        assert!(picture.svg.contains("font-family=\"DejaVu Sans\""), "{name}");
        assert!(!picture.svg.contains("sans-serif"), "{name}");
    }
}

#[test]
fn curves_of_a_panel_differ_in_dash_pattern_and_marker_not_only_colour() {
    for figure in drawn_figures() {
        let svg = figure_picture(figure).unwrap().svg;
        for panel in &figure.panels {
            let lines: Vec<usize> = (0..panel.curves.len())
                .filter(|&i| panel.curves[i].style == Style::Line)
                .collect();
            for (k, &a) in lines.iter().enumerate() {
                for &b in &lines[..k] {
                    let (sa, sb) = (curve_style(a), curve_style(b));
                    assert_ne!(sa.dash, sb.dash, "Fig. {}: curves {a} and {b}", figure.number);
                    assert_ne!(sa.marker, sb.marker, "Fig. {}: curves {a} and {b}", figure.number);
                }
                // Drawn so: a polyline with the curve's dash pattern (or none, solid).
                let style = curve_style(a);
                let dashes: Vec<String> = style.dash.iter().map(f64::to_string).collect();
                let drawn = if dashes.is_empty() {
                    svg.contains("stroke-linecap=\"butt\" points=")
                } else {
                    svg.contains(&format!("stroke-dasharray=\"{}\"", dashes.join(" ")))
                };
                assert!(drawn, "Fig. {}: curve {a} drawn with {:?}", figure.number, style.dash);
            }
        }
        if figure.number >= 5 {
            // Several lines: markers along them (white-filled polygons or circles).
            assert!(svg.matches("fill=\"#FFFFFF\"").count() > 10, "Fig. {}", figure.number);
        }
    }
}

#[test]
fn no_chord_of_a_line_rises_more_than_one_percent_of_its_axis() {
    for figure in &figures().figures {
        let picture = figure_picture(figure).unwrap();
        for (chart, panel) in picture.charts.iter().zip(&figure.panels) {
            let span = chart.frame.y.end - chart.frame.y.start;
            for curve in panel.curves.iter().filter(|c| c.style == Style::Line) {
                let points = plotted(curve, figure.log_log);
                let (worst, at) = points
                    .windows(2)
                    .map(|w| ((w[1].1 - w[0].1).abs(), w[0].0))
                    .fold((0.0, f64::NAN), |a, b| if b.0 > a.0 { b } else { a });
                assert!(
                    worst <= 0.01 * span,
                    "Fig. {} {}: a chord rises {:.3} % of the axis at {at}",
                    figure.number,
                    curve.label,
                    100.0 * worst / span
                );
            }
        }
    }
    // Near gross slip Fig. 6's ratio-0 curve now has samples between Q̂1 = 0.89 and 0.999
    // (before, one chord took Ŵ from 2.7 to 19.7).
    let fig6 = &figures().figures[2].panels[0].curves[0];
    let between = fig6.samples.iter().filter(|(q, _, _)| (0.9..0.998).contains(q)).count();
    assert!(between >= 10, "{between}");
}

/// Measurements of two cases, one error below what a 100-digit reference resolves
/// (clamped at 1e−300 as `accuracy` records it).
fn clamped_measurements() -> Vec<Measurement> {
    let mut list = Vec::new();
    for case in ["ordinary", "stiff"] {
        for (rule, bits) in [("gauss-legendre", 53), ("gauss-legendre", 256), ("tanh-sinh", 512)] {
            for k in 0..5 {
                let error = if bits == 512 && k == 4 {
                    1e-300
                } else {
                    10f64.powi(-(1 + k) * bits as i32 / 30)
                };
                list.push(Measurement {
                    rule,
                    precision_bits: bits,
                    parameter: f64::from(k),
                    evaluations: 10,
                    seconds: 1e-6 * 4f64.powi(k) * f64::from(bits) / 53.0,
                    rel_error: error,
                    case: case.into(),
                });
            }
        }
    }
    list
}

#[test]
fn the_accuracy_chart_has_a_panel_per_case_and_draws_the_clamp_as_a_floor_marker() {
    let measurements = clamped_measurements();
    let picture = accuracy_picture(&measurements).unwrap();
    assert_eq!(picture.charts.len(), 2, "a panel per case");
    for chart in &picture.charts {
        // The error axis ends at the references' precision, 10⁻¹⁰⁰, not at the clamp.
        assert_eq!(chart.frame.y, -100.0..0.0);
        assert!(
            chart.legend.top > chart.frame.area.bottom,
            "the legend under the panels"
        );
    }
    // The clamped measurement: a filled triangle on the floor, and no line reaches it.
    let chart = &picture.charts[0];
    let clamped = measurements
        .iter()
        .find(|m| m.rel_error == 1e-300 && m.case == "ordinary")
        .unwrap();
    let (x, y) = pixel(&chart.frame, (clamped.seconds.log10(), -100.0));
    assert!((y - chart.frame.area.bottom).abs() < 1e-9);
    let tip = format!("points=\"{x:.2},{y:.2} ");
    assert!(picture.svg.contains(&tip), "{tip}");
    let at = format!("{x:.2},{y:.2}");
    for line in picture.svg.lines().filter(|l| l.starts_with("<polyline")) {
        assert!(!line.contains(&at), "a line runs to the clamped value: {line}");
    }
    // Three series in a legend of rules and precisions (two keys), the floor, the front.
    let texts = svg_texts(&picture.svg);
    for label in [
        "gauss-legendre",
        "tanh-sinh",
        "f64",
        "256 bits",
        "512 bits",
        "Pareto front",
    ] {
        assert!(texts.iter().any(|t| t == label), "{label}: {texts:?}");
    }
}

#[test]
fn figures_command_writes_vector_pdfs_with_the_font_embedded() {
    let scratch = Scratch::new("pdf");
    let dir = scratch.join("figures");
    let output = common::run(["figures", "--format", "pdf", "--out"]).arg(&dir).output();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert_eq!(file_names_in(&dir), expected_files(&["csv", "pdf"]));
    for n in 4..=8 {
        let pdf = std::fs::read(dir.join(format!("fig{n}.pdf"))).unwrap();
        assert!(pdf.starts_with(b"%PDF-"), "fig{n}.pdf");
        let text = String::from_utf8_lossy(&pdf);
        // The TrueType font is in the file (subset), under its own name.
        assert!(text.contains("/FontFile2"), "fig{n}.pdf embeds no TrueType font");
        assert!(text.contains("DejaVuSans"), "fig{n}.pdf names no DejaVu Sans");
        // 85 mm wide: 240.9 pt.
        let width = text
            .split("/MediaBox [")
            .nth(1)
            .and_then(|rest| rest.split(']').next())
            .and_then(|numbers| numbers.split_whitespace().nth(2))
            .and_then(|w| w.parse::<f64>().ok())
            .unwrap();
        assert!(
            (width - 85.0 / 25.4 * 72.0).abs() < 0.5,
            "fig{n}.pdf is {width} pt wide"
        );
    }
}
