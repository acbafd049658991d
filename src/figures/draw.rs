//! The pictures of Figures 4–8: SVG, or PNG when the file name ends in `.png`.
//! Log–log figures are drawn in log10 of both variables with the ticks labelled
//! as powers of ten; a curve's end at gross slip is marked with a cross, and the
//! notes (what is stated rather than drawn) go under the charts.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{Curve, Figure, Style};
use crate::plot::{write_picture, PlotError};

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
    write_picture!(path, (820 * figure.panels.len() as u32, 640), draw(figure))
}

/// The samples of a curve in plotting coordinates (log10 of both for log–log figures).
fn plotted(curve: &Curve, log_log: bool) -> Vec<(f64, f64)> {
    curve
        .samples
        .iter()
        .filter(|(x, w, _)| !log_log || (*x > 0.0 && *w > 0.0))
        .map(|(x, w, _)| if log_log { (x.log10(), w.log10()) } else { (*x, *w) })
        .collect()
}

/// A tick label: the value, or the power of ten it is the log10 of.
fn tick(value: f64, log: bool) -> String {
    if !log {
        return format!("{}", (value * 1e6).round() / 1e6);
    }
    if (value - value.round()).abs() < 1e-9 {
        format!("1e{}", value.round() as i64)
    } else {
        format!("{:.2}", 10f64.powf(value))
    }
}

fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, figure: &Figure) -> Result<(), Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let (charts, notes) = root.split_vertically(root.dim_in_pixel().1 - 34);
    for (index, line) in figure.notes.iter().enumerate() {
        notes.draw(&Text::new(
            line.clone(),
            (70, 4 + 15 * index as i32),
            ("sans-serif", 14),
        ))?;
    }
    let areas = charts.split_evenly((1, figure.panels.len()));
    let log = figure.log_log;
    for (area, panel) in areas.iter().zip(&figure.panels) {
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
        let mut chart = ChartBuilder::on(area)
            .caption(&panel.caption, ("sans-serif", 20))
            .margin(14)
            .x_label_area_size(44)
            .y_label_area_size(64)
            .build_cartesian_2d(x_range.clone(), y_range.clone())?;
        let x_ticks = if log {
            (x_range.end - x_range.start) as usize + 1
        } else {
            11
        };
        let y_ticks = if log {
            (y_range.end - y_range.start) as usize + 1
        } else {
            11
        };
        chart
            .configure_mesh()
            .x_labels(x_ticks)
            .y_labels(y_ticks)
            .x_label_formatter(&|v| tick(*v, log))
            .y_label_formatter(&|v| tick(*v, log))
            .x_desc(figure.x_label)
            .y_desc("Ŵ = W/(C λ f² P0^(β+2)),  β = −1")
            .axis_desc_style(("sans-serif", 16))
            .draw()?;
        for (index, curve) in panel.curves.iter().enumerate() {
            let colour = COLOURS[index % COLOURS.len()];
            let points = plotted(curve, log);
            match curve.style {
                Style::Line => {
                    chart
                        .draw_series(LineSeries::new(points.clone(), colour.stroke_width(2)))?
                        .label(curve.label.clone())
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2)));
                }
                Style::Points => {
                    chart
                        .draw_series(points.iter().map(|p| Circle::new(*p, 5, colour.stroke_width(2))))?
                        .label(curve.label.clone())
                        .legend(move |(x, y)| Circle::new((x + 10, y), 5, colour.stroke_width(2)));
                }
            }
            // A cross on each end sample next to a gross-slip limit.
            for limit in &curve.gross_slip_at {
                let end = if curve.samples.first().is_some_and(|(x, _, _)| x >= limit) {
                    points.first()
                } else {
                    points.last()
                };
                if let Some(end) = end {
                    chart.draw_series(std::iter::once(Cross::new(*end, 7, BLACK.stroke_width(2))))?;
                }
            }
        }
        if panel.curves.iter().any(|c| !c.gross_slip_at.is_empty()) {
            chart
                .draw_series(std::iter::empty::<Cross<(f64, f64), i32>>())?
                .label("gross slip: the curve ends")
                .legend(|(x, y)| Cross::new((x + 10, y), 6, BLACK.stroke_width(2)));
        }
        if log {
            draw_slope_guide(&mut chart, panel, figure.number)?;
        }
        chart
            .configure_series_labels()
            .label_font(("sans-serif", 15))
            .border_style(BLACK)
            .background_style(WHITE.mix(0.9))
            .position(SeriesLabelPosition::UpperLeft)
            .draw()?;
    }
    root.present()?;
    Ok(())
}

/// A dashed reference line of the small-amplitude slope (3 for fixed ratios, 2 for
/// fixed P̂1), a decade below the lowest curve's first sample.
fn draw_slope_guide<DB: DrawingBackend>(
    chart: &mut ChartContext<
        '_,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    panel: &super::Panel,
    number: u32,
) -> Result<(), Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    let slope = if number == 8 { 2.0 } else { 3.0 };
    let Some((x0, y0)) = panel
        .curves
        .iter()
        .filter_map(|c| c.samples.first())
        .filter(|(x, w, _)| *x > 0.0 && *w > 0.0)
        .map(|(x, w, _)| (x.log10(), w.log10()))
        .min_by(|a, b| a.1.total_cmp(&b.1))
    else {
        return Ok(());
    };
    let (x1, y0) = (x0 + 1.5, y0 - 1.0);
    let grey = RGBColor(90, 90, 90);
    chart
        .draw_series(DashedLineSeries::new(
            [(x0, y0), (x1, y0 + slope * (x1 - x0))],
            6,
            4,
            grey.stroke_width(2),
        ))?
        .label(format!("slope {slope}"))
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], grey.stroke_width(1)));
    Ok(())
}
