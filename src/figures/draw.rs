//! The pictures of Figures 4–8 and of the cubic law's error: SVG, PNG or PDF by the
//! file name's extension. A panel is 600 units wide, printing at a column width of
//! 85 mm with 8-pt type; a figure of two panels stacks them. Log–log figures are drawn
//! in log10 of both variables with the ticks labelled as powers of ten; each curve has
//! its own colour, dash pattern and markers; a curve's end at gross slip is marked with
//! a cross; the legend sits under the charts, off the data, and the notes (what is
//! stated rather than drawn) under it.

use std::path::Path;

use plotters::prelude::*;

use super::{Curve, Figure, Panel, Style};
use crate::plot::layout::{
    draw_legend_in, legend_columns, legend_size_in, text_size, Frame, LegendEntry, Rect, Swatch, CROSS,
};
use crate::plot::overlay::{Overlay, Stroke};
use crate::plot::style::{series, SeriesStyle, FAMILY, LINE_WIDTH, MARKER_SIZE, TEXT, TITLE};
use crate::plot::{chart_on, draw_svg, register_font, ticks, Canvas, ChartLayout, Drawn, Format, Picture, PlotError};

/// Draws `figure` into `path` (.svg, .png or .pdf).
pub fn draw_figure(path: &Path, figure: &Figure) -> Result<(), PlotError> {
    Format::of(path)?;
    figure_picture(figure)?.write(path)
}

/// The width of a figure, in drawing units (85 mm in print).
pub const FIGURE_WIDTH: u32 = 600;
/// The height of one panel: its caption, chart and axes.
const PANEL_HEIGHT: u32 = 520;
/// The margin left and right of the legend and the notes, and the gaps around them.
const MARGIN: f64 = 12.0;
/// The height of a line of notes.
const NOTE_ROW: f64 = 28.0;

/// What goes under the charts: the legend, in columns, and the notes, wrapped.
struct Footer {
    entries: Vec<LegendEntry>,
    columns: usize,
    legend: (f64, f64),
    notes: Vec<String>,
}

impl Footer {
    fn of(figure: &Figure) -> Self {
        let width = f64::from(FIGURE_WIDTH) - 2.0 * MARGIN;
        let entries = figure
            .panels
            .first()
            .map_or_else(Vec::new, |panel| legend_entries(figure, panel));
        let columns = legend_columns(&entries, width);
        let legend = legend_size_in(&entries, columns);
        let notes = figure.notes.iter().flat_map(|note| wrapped(note, width)).collect();
        Footer {
            entries,
            columns,
            legend,
            notes,
        }
    }

    fn height(&self) -> f64 {
        self.legend.1 + 2.0 * MARGIN + NOTE_ROW * self.notes.len() as f64
    }
}

/// `text` broken at spaces into lines no wider than `width` in the type of [`TEXT`].
fn wrapped(text: &str, width: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split(' ') {
        match lines.last_mut() {
            Some(line) if text_size(&format!("{line} {word}"), TEXT).0 <= width => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// The picture of `figure`: one chart per panel, stacked, the legend and notes underneath.
pub fn figure_picture(figure: &Figure) -> Result<Picture, PlotError> {
    register_font()?;
    let footer = Footer::of(figure);
    let height = PANEL_HEIGHT * figure.panels.len() as u32 + footer.height().ceil() as u32;
    draw_svg((FIGURE_WIDTH, height), |root, overlay| {
        draw(root, overlay, figure, &footer)
    })
}

/// The samples of a curve in plotting coordinates (log10 of both for log–log figures).
pub fn plotted(curve: &Curve, log_log: bool) -> Vec<(f64, f64)> {
    curve
        .samples
        .iter()
        .filter(|(x, w, _)| !log_log || (*x > 0.0 && *w > 0.0))
        .map(|(x, w, _)| if log_log { (x.log10(), w.log10()) } else { (*x, *w) })
        .collect()
}

/// The end samples of a curve that stop at gross slip, in plotting coordinates.
pub fn gross_slip_ends(curve: &Curve, log_log: bool) -> Vec<(f64, f64)> {
    let points = plotted(curve, log_log);
    curve
        .gross_slip_at
        .iter()
        .filter_map(|limit| {
            if curve.samples.first().is_some_and(|(x, _, _)| x >= limit) {
                points.first().copied()
            } else {
                points.last().copied()
            }
        })
        .collect()
}

/// The dashed reference line of the small-amplitude slope on a log–log panel (3 for
/// fixed ratios, 2 for fixed P̂1, 1 for the cubic law's error): its ends a decade below
/// the lowest curve's first sample and 1.5 decades to the right, and the slope.
pub fn slope_guide(panel: &Panel, slope: f64) -> Option<([(f64, f64); 2], f64)> {
    let (x0, y0) = panel
        .curves
        .iter()
        .filter_map(|c| c.samples.first())
        .filter(|(x, w, _)| *x > 0.0 && *w > 0.0)
        .map(|(x, w, _)| (x.log10(), w.log10()))
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    let (x1, y0) = (x0 + 1.5, y0 - 1.0);
    Some(([(x0, y0), (x1, y0 + slope * (x1 - x0))], slope))
}

/// The slope guide of `panel`, where its figure is log–log and has one.
fn guide_of(figure: &Figure, panel: &Panel) -> Option<([(f64, f64); 2], f64)> {
    figure
        .guide_slope
        .filter(|_| figure.log_log)
        .and_then(|slope| slope_guide(panel, slope))
}

/// The radius of Fig. 4's integrated points.
const POINT_RADIUS: f64 = 5.0;
/// The arc length, in drawing units, between the markers along a line.
const MARKER_SPACING: f64 = 120.0;
const GUIDE: RGBColor = RGBColor(90, 90, 90);

fn draw(root: &Canvas<'_>, overlay: &mut Overlay, figure: &Figure, footer: &Footer) -> Drawn {
    let charts_height = PANEL_HEIGHT * figure.panels.len() as u32;
    let (charts, _) = root.split_vertically(charts_height);
    let areas = charts.split_evenly((figure.panels.len(), 1));
    let (width, height) = footer.legend;
    let legend = Rect::at(
        0.5 * (f64::from(FIGURE_WIDTH) - width),
        f64::from(charts_height) + MARGIN,
        (width, height),
    );
    let mut layouts = Vec::new();
    for (area, panel) in areas.iter().zip(&figure.panels) {
        layouts.push(ChartLayout {
            frame: draw_panel(area, overlay, figure, panel)?,
            legend,
            labels: Vec::new(),
        });
    }
    draw_legend_in(overlay, &legend, &footer.entries, footer.columns);
    for (index, line) in footer.notes.iter().enumerate() {
        let middle = legend.bottom + MARGIN + NOTE_ROW * (index as f64 + 0.5);
        overlay.text(line, (MARGIN, middle), TEXT);
    }
    Ok(layouts)
}

/// Whether a panel's lines carry markers: where there are several to tell apart.
fn marked(panel: &Panel) -> bool {
    panel.curves.iter().filter(|c| c.style == Style::Line).count() > 1
}

/// The style of each curve of a panel, by its position.
pub fn curve_style(index: usize) -> SeriesStyle {
    series(index)
}

/// The legend of a panel, each entry drawn as its series is.
fn legend_entries(figure: &Figure, panel: &Panel) -> Vec<LegendEntry> {
    let with_markers = marked(panel);
    let mut entries: Vec<LegendEntry> = panel
        .curves
        .iter()
        .enumerate()
        .map(|(index, curve)| {
            let style = curve_style(index);
            LegendEntry {
                label: curve.label.clone(),
                swatch: match curve.style {
                    Style::Line => Swatch::Series(style, with_markers),
                    Style::Points => Swatch::Circle(style.colour.to_rgba(), POINT_RADIUS),
                },
            }
        })
        .collect();
    if panel.curves.iter().any(|c| !c.gross_slip_at.is_empty()) {
        entries.push(LegendEntry {
            label: "gross slip (end)".to_string(),
            swatch: Swatch::Cross(BLACK.to_rgba()),
        });
    }
    if let Some((_, slope)) = guide_of(figure, panel) {
        entries.push(LegendEntry {
            label: format!("slope {slope}"),
            swatch: Swatch::Dashed(GUIDE.to_rgba(), 2.0),
        });
    }
    entries
}

/// Points spaced `MARKER_SPACING` apart in arc length along the line through `points`,
/// the first `offset` from its start.
pub fn along(points: &[(f64, f64)], offset: f64) -> Vec<(f64, f64)> {
    let mut placed = Vec::new();
    let mut next = offset;
    let mut travelled = 0.0;
    for pair in points.windows(2) {
        let ((x0, y0), (x1, y1)) = (pair[0], pair[1]);
        let length = (x1 - x0).hypot(y1 - y0);
        while length > 0.0 && next <= travelled + length {
            let t = (next - travelled) / length;
            placed.push((x0 + t * (x1 - x0), y0 + t * (y1 - y0)));
            next += MARKER_SPACING;
        }
        travelled += length;
    }
    placed
}

/// Draws one panel's chart, curves, markers and slope guide; returns its frame. One
/// function because each element is placed in the chart's coordinates, built first.
fn draw_panel(
    area: &Canvas<'_>,
    overlay: &mut Overlay,
    figure: &Figure,
    panel: &Panel,
) -> Result<Frame, Box<dyn std::error::Error>> {
    let log = figure.log_log;
    let area = area.titled(&panel.caption, (FAMILY, TITLE))?;
    let all: Vec<(f64, f64)> = panel.curves.iter().flat_map(|c| plotted(c, log)).collect();
    let (x_min, x_max, y_min, y_max) = all.iter().fold(
        (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY),
        |(a, b, c, d), (x, y)| (a.min(*x), b.max(*x), c.min(*y), d.max(*y)),
    );
    let (x_range, y_range) = if log {
        (
            x_min.floor()..x_max.ceil().max(0.0),
            (y_min.floor() - 1.0)..(y_max + 0.3).ceil(),
        )
    } else {
        (0.0..x_max * 1.04, 0.0..y_max * 1.06)
    };
    let mut chart = chart_on(&area, x_range.clone(), y_range.clone())?;
    let frame = Frame::of(&chart);
    let tick = |v: &f64, range: &std::ops::Range<f64>| {
        if log {
            ticks::power_of_ten(*v)
        } else {
            ticks::linear(*v, range)
        }
    };
    chart
        .configure_mesh()
        .x_labels(if log { ticks::decade_ticks(&x_range, 8) } else { 6 })
        .y_labels(if log { ticks::decade_ticks(&y_range, 9) } else { 7 })
        .x_label_formatter(&|v| tick(v, &x_range))
        .y_label_formatter(&|v| tick(v, &y_range))
        .x_desc(format!("{}  (dimensionless)", figure.x_label))
        .y_desc(format!("{}  (dimensionless)", figure.y_label))
        .label_style((FAMILY, TEXT))
        .axis_desc_style((FAMILY, TEXT))
        .light_line_style(WHITE)
        .draw()?;
    let pixels = |points: &[(f64, f64)]| points.iter().map(|p| frame.pixel(*p)).collect::<Vec<_>>();
    let with_markers = marked(panel);
    overlay.clip(&frame.area);
    if let Some((line, _)) = guide_of(figure, panel) {
        overlay.polyline(&pixels(&line), Stroke::dashed(GUIDE.to_rgba(), 2.0));
    }
    for (index, curve) in panel.curves.iter().enumerate() {
        let style = curve_style(index);
        let points = pixels(&plotted(curve, log));
        if curve.style == Style::Line {
            overlay.polyline(&points, Stroke::of(&style, LINE_WIDTH));
        }
    }
    // Markers over every line, staggered from curve to curve so that curves lying on
    // one another still show each its own.
    let count = panel.curves.len() as f64;
    for (index, curve) in panel.curves.iter().enumerate() {
        let style = curve_style(index);
        let outline = Stroke::solid(style.colour.to_rgba(), 1.5);
        let points = pixels(&plotted(curve, log));
        match curve.style {
            Style::Line if with_markers => {
                let offset = MARKER_SPACING * (0.25 + 0.75 * index as f64 / count);
                for at in along(&points, offset) {
                    overlay.marker(style.marker, at, MARKER_SIZE, outline);
                }
            }
            Style::Line => {}
            Style::Points => {
                for point in points {
                    overlay.circle(
                        point,
                        POINT_RADIUS,
                        Some(Stroke::solid(style.colour.to_rgba(), 2.0)),
                        None,
                    );
                }
            }
        }
    }
    overlay.end_clip();
    // Crosses whole, also at the edges, on each end sample next to a gross-slip limit.
    for curve in &panel.curves {
        for end in gross_slip_ends(curve, log) {
            overlay.cross(frame.pixel(end), CROSS, Stroke::solid(BLACK.to_rgba(), 2.5));
        }
    }
    Ok(frame)
}
