//! Pictures of a simulated cycle: the load ellipse in the (P, Q) plane with the
//! friction wedge |Q| = fP and the points B, C, H, E, beside the Q–u hysteresis
//! loop with its four segments coloured. SVG or PNG by the file name's extension
//! (others are refused); files are written atomically. Text is laid out with the
//! DejaVu Sans font built into the program (assets/, with its license), so plots do
//! not depend on the fonts installed.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::cycle::LoadCycle;
use crate::dissipation::{Segment, Segments};
use crate::files::OutputError;
use crate::simulate::SimulationResult;

/// The font text is drawn and measured with (plotters lays out text only with a
/// registered font); an SVG names its family, `sans-serif`.
const FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// Why a picture could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The cycle is outside the theory.
    #[error(transparent)]
    Cycle(#[from] crate::cycle::CycleError),
    /// The built-in font was not accepted by the drawing library.
    #[error("the built-in plot font cannot be read")]
    Font,
    /// The file could not be written, or has an extension other than .svg or .png.
    #[error(transparent)]
    Output(#[from] OutputError),
}

/// The extensions a plot can be written as.
pub const PLOT_EXTENSIONS: [&str; 2] = ["svg", "png"];

/// Draws into `path` atomically, as PNG or SVG by its extension (any other refused, the
/// font registered first): `$draw(root, args…)` with `$draw` generic over the plotters backend,
/// so that one expansion serves both. Evaluates to `Result<(), PlotError>`.
macro_rules! write_picture {
    ($path:expr, $size:expr, $draw:ident($($arg:expr),*)) => {{
        let path: &::std::path::Path = $path;
        let png = $crate::plot::is_png(path)?;
        $crate::plot::register_font()?;
        let size: (u32, u32) = $size;
        Ok($crate::files::write_atomically(path, |file: &::std::path::Path| {
            if png {
                $draw(::plotters::prelude::BitMapBackend::new(file, size).into_drawing_area(), $($arg),*)
                    .map_err($crate::plot::describe)
            } else {
                $draw(::plotters::prelude::SVGBackend::new(file, size).into_drawing_area(), $($arg),*)
                    .map_err($crate::plot::describe)
            }
        })?)
    }};
}
pub(crate) use write_picture;

/// Whether `path` names a PNG (otherwise an SVG); any other extension is refused.
pub(crate) fn is_png(path: &Path) -> Result<bool, PlotError> {
    match path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase()) {
        Some(e) if e == "png" => Ok(true),
        Some(e) if e == "svg" => Ok(false),
        _ => Err(OutputError::Extension {
            path: path.display().to_string(),
            expected: ".svg or .png".to_string(),
        }
        .into()),
    }
}

/// A drawing failure as one line: the underlying I/O error where there is one.
pub(crate) fn describe(error: Box<dyn std::error::Error>) -> String {
    let mut cause: Option<&(dyn std::error::Error + 'static)> = Some(error.as_ref());
    while let Some(current) = cause {
        if let Some(io) = current.downcast_ref::<std::io::Error>() {
            return io.to_string();
        }
        cause = current.source();
    }
    error.to_string()
}

const SEGMENT_COLOURS: [RGBColor; 4] = [
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(255, 127, 14),
];

/// What is drawn, computed once for either backend.
struct Scene {
    ellipse: Vec<(f64, f64)>,
    points: Vec<(&'static str, f64, f64)>,
    top_load: f64,
    tangential_extent: f64,
    segments: Segments<Vec<(f64, f64)>>,
    dissipation: f64,
}

/// Draws the ellipse and the loop side by side into `path` (.svg or .png).
pub fn plot_cycle(path: &Path, cycle: &LoadCycle<f64>, result: &SimulationResult) -> Result<(), PlotError> {
    let geometry = cycle.geometry()?;
    // The geometry is that of φ reduced to [0, π): an odd number of π removed mirrors Q − Q0.
    let turns = (cycle.phase / std::f64::consts::PI).floor() as i64;
    let mirror = if turns.rem_euclid(2) == 1 { -1.0 } else { 1.0 };
    let two_pi = 2.0 * std::f64::consts::PI;
    let starts = Segments {
        eb: geometry.theta_e,
        bc: geometry.theta_b,
        ch: geometry.theta_c,
        he: geometry.theta_h,
    };
    // The segment an angle lies in: the one whose start it passed most recently.
    let segment_of = |theta: f64| {
        Segment::ALL
            .into_iter()
            .min_by(|&a, &b| {
                (theta - starts.get(a))
                    .rem_euclid(two_pi)
                    .total_cmp(&(theta - starts.get(b)).rem_euclid(two_pi))
            })
            .unwrap_or(Segment::EB)
    };
    let mut segments = Segments::from_fn(|_| Vec::new());
    for pair in result.steady_loop.windows(2) {
        let points = segments.get_mut(segment_of(0.5 * (pair[0].theta + pair[1].theta)));
        points.push((pair[0].displacement, pair[0].tangential_load));
        points.push((pair[1].displacement, pair[1].tangential_load));
    }
    let top_load = cycle.mean_normal_load + cycle.normal_amplitude;
    let scene = Scene {
        ellipse: result
            .steady_loop
            .iter()
            .map(|s| (s.normal_load, s.tangential_load))
            .collect(),
        points: ["E", "B", "C", "H"]
            .iter()
            .zip(starts.iter())
            .map(|(name, (_, theta))| {
                (
                    *name,
                    cycle.mean_normal_load + geometry.normal_offset(theta),
                    cycle.mean_tangential_load + mirror * geometry.tangential_offset(theta),
                )
            })
            .collect(),
        top_load,
        tangential_extent: cycle.friction * top_load * 1.05,
        segments,
        dissipation: result.w_work,
    };
    write_picture!(path, (1200, 520), draw(&scene))
}

/// Registers the font once per process: text layout needs its metrics in SVG too.
pub(crate) fn register_font() -> Result<(), PlotError> {
    static REGISTERED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    let registered =
        REGISTERED.get_or_init(|| plotters::style::register_font("sans-serif", FontStyle::Normal, FONT).is_ok());
    if *registered {
        Ok(())
    } else {
        Err(PlotError::Font)
    }
}

fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, scene: &Scene) -> Result<(), Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let (left, right) = root.split_horizontally(root.dim_in_pixel().0 / 2);
    let (top, extent) = (scene.top_load * 1.05, scene.tangential_extent);
    let mut ellipse = ChartBuilder::on(&left)
        .caption("load cycle in the (P, Q) plane", ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(56)
        .build_cartesian_2d(0.0..top, -extent..extent)?;
    ellipse.configure_mesh().x_desc("P").y_desc("Q").draw()?;
    ellipse
        .draw_series(LineSeries::new([(0.0, 0.0), (top, extent)], BLACK.mix(0.5)))?
        .label("|Q| = fP")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK.mix(0.5)));
    ellipse.draw_series(LineSeries::new([(0.0, 0.0), (top, -extent)], BLACK.mix(0.5)))?;
    ellipse.draw_series(LineSeries::new(scene.ellipse.iter().copied(), &BLACK))?;
    for (name, p, q) in &scene.points {
        ellipse.draw_series(std::iter::once(Circle::new((*p, *q), 4, RED.filled())))?;
        ellipse.draw_series(std::iter::once(Text::new(
            name.to_string(),
            (*p, *q),
            ("sans-serif", 16),
        )))?;
    }
    ellipse
        .configure_series_labels()
        .border_style(BLACK)
        .background_style(WHITE)
        .draw()?;
    let all = scene.segments.iter().flat_map(|(_, points)| points);
    let (u_min, u_max, q_min, q_max) = all.fold(
        (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY),
        |(a, b, c, d), (u, q)| (a.min(*u), b.max(*u), c.min(*q), d.max(*q)),
    );
    let pad = |a: f64, b: f64| 0.05 * (b - a).abs().max(1e-300);
    let mut hysteresis = ChartBuilder::on(&right)
        .caption(
            format!("hysteresis loop, W = {:.6e}", scene.dissipation),
            ("sans-serif", 18),
        )
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(56)
        .build_cartesian_2d(
            (u_min - pad(u_min, u_max))..(u_max + pad(u_min, u_max)),
            (q_min - pad(q_min, q_max))..(q_max + pad(q_min, q_max)),
        )?;
    hysteresis.configure_mesh().x_desc("u").y_desc("Q").draw()?;
    for (segment, colour) in Segment::ALL.into_iter().zip(SEGMENT_COLOURS) {
        hysteresis
            .draw_series(
                scene
                    .segments
                    .get(segment)
                    .chunks(2)
                    .map(move |c| PathElement::new(c.to_vec(), colour.stroke_width(2))),
            )?
            .label(segment.name())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2)));
    }
    hysteresis
        .configure_series_labels()
        .border_style(BLACK)
        .background_style(WHITE)
        .draw()?;
    root.present()?;
    Ok(())
}

/// One curve per (rule, precision): log10 relative error against log10 seconds,
/// with the Pareto front circled, into `path` (.svg or .png).
pub fn plot_accuracy(path: &Path, measurements: &[crate::accuracy::Measurement]) -> Result<(), PlotError> {
    write_picture!(path, (1100, 700), draw_accuracy(measurements))
}

fn draw_accuracy<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    measurements: &[crate::accuracy::Measurement],
) -> Result<(), Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let point = |m: &crate::accuracy::Measurement| (m.seconds.max(1e-9).log10(), m.rel_error.max(1e-300).log10());
    let (x_min, x_max, y_min) = measurements.iter().map(point).fold(
        (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY),
        |(a, b, c), (x, y)| (a.min(x), b.max(x), c.min(y)),
    );
    let mut chart = ChartBuilder::on(&root)
        .caption("accuracy against cost (all cases)", ("sans-serif", 20))
        .margin(14)
        .x_label_area_size(40)
        .y_label_area_size(56)
        .build_cartesian_2d((x_min - 0.2)..(x_max + 0.2), (y_min - 5.0)..1.0)?;
    chart
        .configure_mesh()
        .x_desc("log10 seconds per W")
        .y_desc("log10 relative error")
        .draw()?;
    let mut curves: Vec<(String, Vec<&crate::accuracy::Measurement>)> = Vec::new();
    for m in measurements {
        let key = if m.precision_bits == 53 {
            format!("{} f64", m.rule)
        } else {
            format!("{} {} bits", m.rule, m.precision_bits)
        };
        match curves.iter_mut().find(|(k, _)| *k == key) {
            Some((_, list)) => list.push(m),
            None => curves.push((key, vec![m])),
        }
    }
    for (index, (key, mut list)) in curves.into_iter().enumerate() {
        list.sort_by(|a, b| a.case.cmp(&b.case).then(a.parameter.total_cmp(&b.parameter)));
        let colour = Palette99::pick(index).to_rgba();
        let mut by_case: Vec<Vec<(f64, f64)>> = Vec::new();
        let mut last_case = String::new();
        for m in list {
            if m.case != last_case {
                by_case.push(Vec::new());
                last_case = m.case.clone();
            }
            if let Some(curve) = by_case.last_mut() {
                curve.push(point(m));
            }
        }
        for (i, curve) in by_case.into_iter().enumerate() {
            let series = chart.draw_series(LineSeries::new(curve, colour.stroke_width(2)))?;
            if i == 0 {
                series
                    .label(key.clone())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], colour.stroke_width(2)));
            }
        }
    }
    let front = crate::accuracy::pareto_front(measurements);
    chart
        .draw_series(front.iter().map(|m| Circle::new(point(m), 6, BLACK.stroke_width(2))))?
        .label("Pareto front")
        .legend(|(x, y)| Circle::new((x + 9, y), 5, BLACK.stroke_width(2)));
    chart
        .configure_series_labels()
        .border_style(BLACK)
        .background_style(WHITE.mix(0.9))
        .position(SeriesLabelPosition::UpperRight)
        .draw()?;
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_built_in_font_is_a_truetype_font_the_drawing_library_accepts() {
        assert_eq!(FONT[..4], [0, 1, 0, 0], "TrueType version 1.0 header");
        assert!(register_font().is_ok());
    }
}
