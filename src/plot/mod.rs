//! Pictures of a simulated cycle: the load ellipse in the (P, Q) plane with the
//! friction wedge |Q| = fP and the points B, C, H, E, beside the Q–u hysteresis
//! loop with its four segments told apart by colour and dash. SVG, PNG or PDF by the
//! file name's extension (others are refused).
//!
//! Every chart is drawn once, as SVG; a PNG is that SVG rendered anti-aliased at
//! [`RASTER_SCALE`] times its size, a PDF the same SVG as vector graphics. Text is laid
//! out and rendered with the DejaVu Sans font built into the program (assets/, with its
//! license), named in the SVG and embedded in the PDF, so pictures do not depend on the
//! fonts installed; its size prints at 8 pt or more ([`style`]). Legends and labels are
//! placed from the data where they cover none of it, and each picture comes with that
//! geometry ([`ChartLayout`]).

pub mod accuracy;
pub mod layout;
pub(crate) mod overlay;
mod rect;
mod render;
pub mod style;
pub mod ticks;

use std::ops::Range;
use std::path::{Path, PathBuf};

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

pub use self::accuracy::{accuracy_picture, plot_accuracy};
use self::layout::{
    beside, draw_legend, free_place, legend_size, text_size, Frame, Label, LegendEntry, Obstacles, Rect, Swatch,
};
use self::overlay::{Overlay, Stroke};
pub use self::render::RASTER_SCALE;
use self::style::{series, FAMILY, LINE_WIDTH, TEXT, TITLE, UNITS_PER_MM};
use crate::cycle::LoadCycle;
use crate::dissipation::{Segment, Segments};
use crate::files::OutputError;
use crate::simulate::SimulationResult;

/// The font text is drawn, measured and rendered with; an SVG names its family,
/// [`FAMILY`], and a PDF embeds it.
const FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Why a picture could not be drawn.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The cycle is outside the theory.
    #[error(transparent)]
    Cycle(#[from] crate::cycle::CycleError),
    /// The built-in font was not accepted by the drawing library.
    #[error("the built-in plot font cannot be read")]
    Font,
    /// The drawing or rendering library failed.
    #[error("drawing the picture: {0}")]
    Draw(String),
    /// The file could not be written, or has an extension other than .svg, .png or .pdf.
    #[error(transparent)]
    Output(#[from] OutputError),
}

/// The extensions a plot can be written as.
pub const PLOT_EXTENSIONS: [&str; 3] = ["svg", "png", "pdf"];

/// What a picture is written as.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// The SVG text, naming the font family.
    Svg,
    /// Rendered anti-aliased at [`RASTER_SCALE`].
    Png,
    /// Vector PDF with the font embedded, the page as wide as the picture prints.
    Pdf,
}

impl Format {
    /// Every format, in the order of [`PLOT_EXTENSIONS`].
    pub const ALL: [Format; 3] = [Format::Svg, Format::Png, Format::Pdf];

    /// The file extension, without its dot.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Svg => "svg",
            Format::Png => "png",
            Format::Pdf => "pdf",
        }
    }

    /// The format `path` names by its extension (.svg, .png or .pdf, any case); others are refused.
    pub fn of(path: &Path) -> Result<Format, PlotError> {
        let extension = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
        Format::ALL
            .into_iter()
            .find(|format| extension.as_deref() == Some(format.extension()))
            .ok_or_else(|| {
                OutputError::Extension {
                    path: path.display().to_string(),
                    expected: ".svg, .png or .pdf".to_string(),
                }
                .into()
            })
    }
}

/// The geometry of one chart as drawn, in the picture's (SVG) pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct ChartLayout {
    /// The plotting area and the ranges it spans.
    pub frame: Frame,
    /// The legend's box.
    pub legend: Rect,
    /// The labels beside markers.
    pub labels: Vec<Label>,
}

/// A picture drawn as SVG text, with the layout of its charts.
#[derive(Clone, Debug)]
pub struct Picture {
    /// The SVG document.
    pub svg: String,
    /// Each chart's geometry, left to right and top to bottom.
    pub charts: Vec<ChartLayout>,
    /// The width and height in drawing units.
    pub size: (u32, u32),
}

impl Picture {
    /// The file's bytes in `format`: the SVG text, or the PNG or PDF rendered from it.
    pub fn encode(&self, format: Format) -> Result<Vec<u8>, PlotError> {
        match format {
            Format::Svg => Ok(self.svg.clone().into_bytes()),
            Format::Png => render::png(&self.svg),
            Format::Pdf => render::pdf(&self.svg),
        }
    }

    /// The width it prints at, in millimetres ([`UNITS_PER_MM`]).
    pub fn print_width_mm(&self) -> f64 {
        f64::from(self.size.0) / UNITS_PER_MM
    }

    /// Writes the picture to `path` atomically, as SVG, PNG or PDF by its extension.
    pub fn write(&self, path: &Path) -> Result<(), PlotError> {
        let bytes = self.encode(Format::of(path)?)?;
        Ok(write_all_or_none(&[(path.to_path_buf(), bytes)])?)
    }
}

/// A drawing area on an SVG held in memory.
pub(crate) type Canvas<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// A chart of two linear coordinates (log10 of the values on logarithmic axes).
pub(crate) type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// What a drawing returns: the layout of its charts.
pub(crate) type Drawn = Result<Vec<ChartLayout>, Box<dyn std::error::Error>>;

/// Draws an SVG of `size` pixels on a white background with `draw`, which draws the axes
/// on the canvas and the data, legends and labels into the overlay (drawn last), and
/// returns the layout of its charts.
pub(crate) fn draw_svg(
    size: (u32, u32),
    draw: impl FnOnce(&Canvas<'_>, &mut Overlay) -> Drawn,
) -> Result<Picture, PlotError> {
    register_font()?;
    let mut svg = String::new();
    let mut overlay = Overlay::default();
    let charts = {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(|e| PlotError::Draw(e.to_string()))?;
        let charts = draw(&root, &mut overlay).map_err(|e| PlotError::Draw(e.to_string()))?;
        root.present().map_err(|e| PlotError::Draw(e.to_string()))?;
        charts
    };
    let end = svg
        .rfind("</svg>")
        .ok_or_else(|| PlotError::Draw("the SVG has no end tag".to_string()))?;
    svg.insert_str(end, &overlay.into_svg());
    Ok(Picture { svg, charts, size })
}

/// Writes every file, each atomically, or none: on a failure the files this call has
/// already written are removed and the error returned.
pub fn write_all_or_none(files: &[(PathBuf, Vec<u8>)]) -> Result<(), OutputError> {
    for (index, (path, bytes)) in files.iter().enumerate() {
        let written = crate::files::write_atomically(path, |temporary| std::fs::write(temporary, bytes));
        if let Err(error) = written {
            for (earlier, _) in &files[..index] {
                let _ = std::fs::remove_file(earlier);
            }
            return Err(error);
        }
    }
    Ok(())
}

/// Registers the font once per process: text layout needs its metrics.
pub(crate) fn register_font() -> Result<(), PlotError> {
    static REGISTERED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    let registered = REGISTERED.get_or_init(|| plotters::style::register_font(FAMILY, FontStyle::Normal, FONT).is_ok());
    if *registered {
        Ok(())
    } else {
        Err(PlotError::Font)
    }
}

/// Builds a chart over `x` × `y` and places a legend of `size` in it where it covers
/// no obstacle, raising the top of `y` by `grow` until there is such a place.
pub(crate) fn chart_with_legend<'a, 'b>(
    build: impl Fn(Range<f64>, Range<f64>) -> Result<Chart<'a, 'b>, Box<dyn std::error::Error>>,
    x: Range<f64>,
    mut y: Range<f64>,
    grow: impl Fn(&Range<f64>) -> Range<f64>,
    size: (f64, f64),
    obstacles: impl Fn(&Frame) -> Obstacles,
) -> Result<(Chart<'a, 'b>, Frame, Rect, Obstacles), Box<dyn std::error::Error>> {
    for _ in 0..16 {
        let chart = build(x.clone(), y.clone())?;
        let frame = Frame::of(&chart);
        let around = obstacles(&frame);
        if let Some(place) = free_place(&frame.area, size, &around) {
            return Ok((chart, frame, place, around));
        }
        y = grow(&y);
    }
    Err("no place for the legend that leaves the data visible".into())
}

/// What is drawn, computed once.
struct Scene {
    ellipse: Vec<(f64, f64)>,
    points: Vec<(&'static str, f64, f64)>,
    top_load: f64,
    tangential_extent: f64,
    segments: Segments<Vec<(f64, f64)>>,
    dissipation: f64,
}

/// Draws the ellipse and the loop side by side into `path` (.svg, .png or .pdf).
pub fn plot_cycle(path: &Path, cycle: &LoadCycle<f64>, result: &SimulationResult) -> Result<(), PlotError> {
    Format::of(path)?;
    cycle_picture(cycle, result)?.write(path)
}

/// The picture of a simulated cycle: the load ellipse, then the hysteresis loop.
pub fn cycle_picture(cycle: &LoadCycle<f64>, result: &SimulationResult) -> Result<Picture, PlotError> {
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
    draw_svg((1200, 600), |root, overlay| draw_cycle(root, overlay, &scene))
}

const MARKER_RADIUS: f64 = 5.0;

fn draw_cycle(root: &Canvas<'_>, overlay: &mut Overlay, scene: &Scene) -> Drawn {
    let (left, right) = root.split_horizontally(root.dim_in_pixel().0 / 2);
    Ok(vec![
        draw_ellipse(&left, overlay, scene)?,
        draw_loop(&right, overlay, scene)?,
    ])
}

/// A chart over `x` × `y` on `area` (its title already drawn), with room for tick
/// labels and axis names in the type of [`TEXT`].
pub(crate) fn chart_on<'a, 'b>(
    area: &'a Canvas<'b>,
    x: Range<f64>,
    y: Range<f64>,
) -> Result<Chart<'a, 'b>, Box<dyn std::error::Error>> {
    Ok(ChartBuilder::on(area)
        .margin(10)
        .margin_right(24)
        .x_label_area_size(72)
        .y_label_area_size(112)
        .build_cartesian_2d(x, y)?)
}

/// A linear chart on `area` (its title already drawn).
fn linear_chart<'a, 'b>(
    area: &'a Canvas<'b>,
) -> impl Fn(Range<f64>, Range<f64>) -> Result<Chart<'a, 'b>, Box<dyn std::error::Error>> {
    move |x, y| chart_on(area, x, y)
}

/// Draws the mesh of a linear chart with its axis names (and units).
fn linear_mesh(chart: &mut Chart<'_, '_>, frame: &Frame, x: &str, y: &str) -> Result<(), Box<dyn std::error::Error>> {
    let (x_range, y_range) = (frame.x.clone(), frame.y.clone());
    chart
        .configure_mesh()
        .x_desc(x)
        .y_desc(y)
        .x_labels(6)
        .y_labels(8)
        .label_style((FAMILY, TEXT))
        .axis_desc_style((FAMILY, TEXT))
        .light_line_style(WHITE)
        .x_label_formatter(&|v| ticks::linear(*v, &x_range))
        .y_label_formatter(&|v| ticks::linear(*v, &y_range))
        .draw()?;
    Ok(())
}

/// The load ellipse with the friction wedge and the points B, C, H, E labelled beside them.
fn draw_ellipse(
    area: &Canvas<'_>,
    overlay: &mut Overlay,
    scene: &Scene,
) -> Result<ChartLayout, Box<dyn std::error::Error>> {
    let area = area.titled("load cycle in the (P, Q) plane", (FAMILY, TITLE))?;
    let (top, extent) = (scene.top_load * 1.05, scene.tangential_extent);
    let wedge = BLACK.mix(0.5);
    let entries = [LegendEntry {
        label: "|Q| = fP".to_string(),
        swatch: Swatch::Dashed(wedge, 1.5),
    }];
    let wedge_lines = [[(0.0, 0.0), (top, extent)], [(0.0, 0.0), (top, -extent)]];
    let obstacles = |frame: &Frame| {
        let mut around = Obstacles::default();
        for line in wedge_lines {
            around.line(frame, line);
        }
        around.line(frame, scene.ellipse.iter().copied());
        for (_, p, q) in &scene.points {
            around.disc(frame, (*p, *q), MARKER_RADIUS);
        }
        around
    };
    let (mut chart, frame, legend, mut around) = chart_with_legend(
        linear_chart(&area),
        0.0..top,
        -extent..extent,
        |y| y.start..(y.end + 0.15 * (y.end - y.start)),
        legend_size(&entries),
        obstacles,
    )?;
    linear_mesh(
        &mut chart,
        &frame,
        "normal load P (load units)",
        "tangential load Q (load units)",
    )?;
    let pixels = |points: &[(f64, f64)]| points.iter().map(|p| frame.pixel(*p)).collect::<Vec<_>>();
    overlay.clip(&frame.area);
    for line in wedge_lines {
        overlay.polyline(&pixels(&line), Stroke::dashed(wedge, 1.5));
    }
    overlay.polyline(&pixels(&scene.ellipse), Stroke::solid(BLACK.to_rgba(), LINE_WIDTH));
    overlay.end_clip();
    for (_, p, q) in &scene.points {
        overlay.circle(
            frame.pixel((*p, *q)),
            MARKER_RADIUS,
            None,
            Some(style::PALETTE[1].to_rgba()),
        );
    }
    let mut labels = Vec::new();
    for (name, p, q) in &scene.points {
        let rect = beside(
            frame.pixel((*p, *q)),
            MARKER_RADIUS,
            text_size(name, TEXT),
            &frame.area,
            &around,
        );
        around.taken(rect);
        overlay.text(name, (rect.left, 0.5 * (rect.top + rect.bottom)), TEXT);
        labels.push(Label {
            text: name.to_string(),
            at: (*p, *q),
            radius: MARKER_RADIUS,
            rect,
        });
    }
    draw_legend(overlay, &legend, &entries);
    Ok(ChartLayout { frame, legend, labels })
}

/// Consecutive pieces (point pairs) joined into lines where one ends where the next starts.
fn joined(pairs: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
    for pair in pairs.chunks(2) {
        match runs.last_mut() {
            Some(run) if run.last() == pair.first() => run.extend_from_slice(&pair[1..]),
            _ => runs.push(pair.to_vec()),
        }
    }
    runs
}

/// The hysteresis loop, its four segments in four colours and dash patterns.
fn draw_loop(
    area: &Canvas<'_>,
    overlay: &mut Overlay,
    scene: &Scene,
) -> Result<ChartLayout, Box<dyn std::error::Error>> {
    let area = area.titled(
        &format!("hysteresis loop, W = {:.6e}", scene.dissipation),
        (FAMILY, TITLE),
    )?;
    let all = scene.segments.iter().flat_map(|(_, points)| points);
    let (u_min, u_max, q_min, q_max) = all.fold(
        (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY),
        |(a, b, c, d), (u, q)| (a.min(*u), b.max(*u), c.min(*q), d.max(*q)),
    );
    let pad = |a: f64, b: f64| 0.05 * (b - a).abs().max(1e-300);
    let entries: Vec<LegendEntry> = Segment::ALL
        .into_iter()
        .enumerate()
        .map(|(index, segment)| LegendEntry {
            label: segment.name().to_string(),
            swatch: Swatch::Series(series(index), false),
        })
        .collect();
    let obstacles = |frame: &Frame| {
        let mut around = Obstacles::default();
        for (_, points) in scene.segments.iter() {
            for pair in points.chunks(2) {
                around.line(frame, pair.iter().copied());
            }
        }
        around
    };
    let (mut chart, frame, legend, _) = chart_with_legend(
        linear_chart(&area),
        (u_min - pad(u_min, u_max))..(u_max + pad(u_min, u_max)),
        (q_min - pad(q_min, q_max))..(q_max + pad(q_min, q_max)),
        |y| y.start..(y.end + 0.15 * (y.end - y.start)),
        legend_size(&entries),
        obstacles,
    )?;
    linear_mesh(
        &mut chart,
        &frame,
        "tangential displacement u (approach units)",
        "tangential load Q (load units)",
    )?;
    overlay.clip(&frame.area);
    for (index, segment) in Segment::ALL.into_iter().enumerate() {
        let style = series(index);
        for run in joined(scene.segments.get(segment)) {
            let pixels: Vec<(f64, f64)> = run.iter().map(|p| frame.pixel(*p)).collect();
            overlay.polyline(&pixels, Stroke::of(&style, LINE_WIDTH));
        }
    }
    overlay.end_clip();
    draw_legend(overlay, &legend, &entries);
    Ok(ChartLayout {
        frame,
        legend,
        labels: Vec::new(),
    })
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
