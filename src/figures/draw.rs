//! The pictures of Figures 4–8: SVG, or PNG when the file name ends in `.png`.
//! Log–log figures are drawn in log10 of both variables with the ticks labelled
//! as powers of ten; a curve's end at gross slip is marked with a cross, each legend
//! sits where it covers no curve (with headroom added above the data if needed), and
//! the notes (what is stated rather than drawn) go under the charts.

use std::path::Path;

use plotters::prelude::*;

use super::{Curve, Figure, Panel, Style};
use crate::plot::layout::{draw_legend, legend_size, Frame, LegendEntry, Obstacles, Swatch, CROSS};
use crate::plot::overlay::{Overlay, Stroke};
use crate::plot::{chart_with_legend, draw_svg, ticks, Canvas, ChartLayout, Drawn, Format, Picture, PlotError};

const COLOURS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

/// Draws `figure` into `path` (.svg or .png).
pub fn draw_figure(path: &Path, figure: &Figure) -> Result<(), PlotError> {
    Format::of(path)?;
    figure_picture(figure)?.write(path)
}

/// The picture of `figure`: one chart per panel, the notes underneath.
pub fn figure_picture(figure: &Figure) -> Result<Picture, PlotError> {
    draw_svg((820 * figure.panels.len() as u32, 640), |root, overlay| {
        draw(root, overlay, figure)
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
/// fixed ratios, 2 for fixed P̂1): its ends a decade below the lowest curve's first
/// sample and 1.5 decades to the right, and the slope.
pub fn slope_guide(panel: &Panel, number: u32) -> Option<([(f64, f64); 2], f64)> {
    let slope = if number == 8 { 2.0 } else { 3.0 };
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

const POINT_RADIUS: f64 = 5.0;
const GUIDE: RGBColor = RGBColor(90, 90, 90);

fn draw(root: &Canvas<'_>, overlay: &mut Overlay, figure: &Figure) -> Drawn {
    let (charts, notes) = root.split_vertically(root.dim_in_pixel().1 - 34);
    for (index, line) in figure.notes.iter().enumerate() {
        notes.draw(&Text::new(
            line.clone(),
            (70, 4 + 15 * index as i32),
            ("sans-serif", 14),
        ))?;
    }
    let areas = charts.split_evenly((1, figure.panels.len()));
    let mut layouts = Vec::new();
    for (area, panel) in areas.iter().zip(&figure.panels) {
        layouts.push(draw_panel(area, overlay, figure, panel)?);
    }
    Ok(layouts)
}

/// The legend of a panel, each entry drawn as its series is.
fn legend_entries(figure: &Figure, panel: &Panel) -> Vec<LegendEntry> {
    let mut entries: Vec<LegendEntry> = panel
        .curves
        .iter()
        .enumerate()
        .map(|(index, curve)| {
            let colour = COLOURS[index % COLOURS.len()].to_rgba();
            LegendEntry {
                label: curve.label.clone(),
                swatch: match curve.style {
                    Style::Line => Swatch::Line(colour, 2.0),
                    Style::Points => Swatch::Circle(colour, POINT_RADIUS),
                },
            }
        })
        .collect();
    if panel.curves.iter().any(|c| !c.gross_slip_at.is_empty()) {
        entries.push(LegendEntry {
            label: "gross slip: the curve ends".to_string(),
            swatch: Swatch::Cross(BLACK.to_rgba()),
        });
    }
    if let Some((_, slope)) = figure.log_log.then(|| slope_guide(panel, figure.number)).flatten() {
        entries.push(LegendEntry {
            label: format!("slope {slope}"),
            swatch: Swatch::Dashed(GUIDE.to_rgba(), 2.0),
        });
    }
    entries
}

fn draw_panel(
    area: &Canvas<'_>,
    overlay: &mut Overlay,
    figure: &Figure,
    panel: &Panel,
) -> Result<ChartLayout, Box<dyn std::error::Error>> {
    let log = figure.log_log;
    let area = area.titled(&panel.caption, ("sans-serif", 20))?;
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
    let guide = if log { slope_guide(panel, figure.number) } else { None };
    let entries = legend_entries(figure, panel);
    let build = |x: std::ops::Range<f64>, y: std::ops::Range<f64>| {
        Ok(ChartBuilder::on(&area)
            .margin(14)
            .x_label_area_size(44)
            .y_label_area_size(64)
            .build_cartesian_2d(x, y)?)
    };
    let obstacles = |frame: &Frame| {
        let mut around = Obstacles::default();
        for curve in &panel.curves {
            match curve.style {
                Style::Line => around.line(frame, plotted(curve, log)),
                Style::Points => {
                    for point in plotted(curve, log) {
                        around.disc(frame, point, POINT_RADIUS + 1.0);
                    }
                }
            }
            for end in gross_slip_ends(curve, log) {
                around.disc(frame, end, CROSS);
            }
        }
        if let Some((line, _)) = guide {
            around.line(frame, line);
        }
        around
    };
    // Headroom for the legend: a decade at a time on log axes (ticks stay on powers of ten).
    let grow = |y: &std::ops::Range<f64>| {
        if log {
            y.start..(y.end + 1.0)
        } else {
            y.start..(y.end + 0.12 * (y.end - y.start))
        }
    };
    let (mut chart, frame, legend, _) =
        chart_with_legend(build, x_range, y_range, grow, legend_size(&entries), obstacles)?;
    let (x_range, y_range) = (frame.x.clone(), frame.y.clone());
    let tick = |v: &f64, range: &std::ops::Range<f64>| {
        if log {
            ticks::power_of_ten(*v)
        } else {
            ticks::linear(*v, range)
        }
    };
    chart
        .configure_mesh()
        .x_labels(if log { ticks::decade_ticks(&x_range, 12) } else { 11 })
        .y_labels(if log { ticks::decade_ticks(&y_range, 12) } else { 11 })
        .x_label_formatter(&|v| tick(v, &x_range))
        .y_label_formatter(&|v| tick(v, &y_range))
        .x_desc(figure.x_label)
        .y_desc("Ŵ = W/(C λ f² P0^(β+2)),  β = −1")
        .axis_desc_style(("sans-serif", 16))
        .draw()?;
    let pixels = |points: &[(f64, f64)]| points.iter().map(|p| frame.pixel(*p)).collect::<Vec<_>>();
    overlay.clip(&frame.area);
    for (index, curve) in panel.curves.iter().enumerate() {
        let colour = COLOURS[index % COLOURS.len()].to_rgba();
        let points = pixels(&plotted(curve, log));
        if curve.style == Style::Line {
            overlay.polyline(&points, Stroke::solid(colour, 2.0));
        }
    }
    if let Some((line, _)) = guide {
        overlay.polyline(&pixels(&line), Stroke::dashed(GUIDE.to_rgba(), 2.0));
    }
    overlay.end_clip();
    // Markers whole, also at the edges: the points, and a cross on each end sample next
    // to a gross-slip limit.
    for (index, curve) in panel.curves.iter().enumerate() {
        let colour = COLOURS[index % COLOURS.len()].to_rgba();
        if curve.style == Style::Points {
            for point in pixels(&plotted(curve, log)) {
                overlay.circle(point, POINT_RADIUS, Some(Stroke::solid(colour, 2.0)), None);
            }
        }
        for end in gross_slip_ends(curve, log) {
            overlay.cross(frame.pixel(end), CROSS, Stroke::solid(BLACK.to_rgba(), 2.0));
        }
    }
    draw_legend(overlay, &legend, &entries);
    Ok(ChartLayout {
        frame,
        legend,
        labels: Vec::new(),
    })
}
