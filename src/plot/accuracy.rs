//! The accuracy-against-cost chart: one curve per (rule, precision), relative error
//! against seconds on logarithmic axes labelled in powers of ten, the Pareto front
//! circled, the legend beside the chart.

use std::path::Path;

use plotters::prelude::*;

use super::layout::{draw_legend, legend_size, Frame, LegendEntry, Rect, Swatch};
use super::overlay::{Overlay, Stroke};
use super::{draw_svg, ticks, Canvas, ChartLayout, Format, Picture, PlotError};
use crate::accuracy::{pareto_front, Measurement};

/// Draws the chart of `measurements` into `path` (.svg or .png).
pub fn plot_accuracy(path: &Path, measurements: &[Measurement]) -> Result<(), PlotError> {
    Format::of(path)?;
    accuracy_picture(measurements)?.write(path)
}

/// A legend key and its lines (one per case).
type Curve = (String, Vec<Vec<(f64, f64)>>);

/// The curves: one per rule and precision, a polyline per case, in log10 of seconds
/// and of the relative error.
fn curves(measurements: &[Measurement]) -> Vec<Curve> {
    let mut grouped: Vec<(String, Vec<&Measurement>)> = Vec::new();
    for m in measurements {
        let key = if m.precision_bits == 53 {
            format!("{} f64", m.rule)
        } else {
            format!("{} {} bits", m.rule, m.precision_bits)
        };
        match grouped.iter_mut().find(|(k, _)| *k == key) {
            Some((_, list)) => list.push(m),
            None => grouped.push((key, vec![m])),
        }
    }
    grouped
        .into_iter()
        .map(|(key, mut list)| {
            list.sort_by(|a, b| a.case.cmp(&b.case).then(a.parameter.total_cmp(&b.parameter)));
            let mut by_case: Vec<Vec<(f64, f64)>> = Vec::new();
            let mut last_case = None;
            for m in list {
                if last_case != Some(&m.case) {
                    by_case.push(Vec::new());
                    last_case = Some(&m.case);
                }
                if let Some(curve) = by_case.last_mut() {
                    curve.push(point(m));
                }
            }
            (key, by_case)
        })
        .collect()
}

/// A measurement in drawn coordinates: log10 seconds, log10 relative error.
pub fn point(m: &Measurement) -> (f64, f64) {
    (m.seconds.max(1e-9).log10(), m.rel_error.max(1e-300).log10())
}

/// The chart of `measurements` as a picture (one chart; its legend lies outside the
/// plotting area, on the right).
pub fn accuracy_picture(measurements: &[Measurement]) -> Result<Picture, PlotError> {
    let curves = curves(measurements);
    let mut entries: Vec<LegendEntry> = curves
        .iter()
        .enumerate()
        .map(|(index, (key, _))| LegendEntry {
            label: key.clone(),
            swatch: Swatch::Line(Palette99::pick(index).to_rgba(), 2.0),
        })
        .collect();
    entries.push(LegendEntry {
        label: "Pareto front".to_string(),
        swatch: Swatch::Circle(BLACK.to_rgba(), 5.0),
    });
    // The legend's width decides the picture's.
    super::register_font()?;
    let (legend_w, _) = legend_size(&entries);
    let width = 1000 + legend_w.ceil() as u32 + 30;
    draw_svg((width, 700), |root, overlay| {
        draw(root, overlay, measurements, &curves, &entries, legend_w).map(|chart| vec![chart])
    })
}

fn draw(
    root: &Canvas<'_>,
    overlay: &mut Overlay,
    measurements: &[Measurement],
    curves: &[Curve],
    entries: &[LegendEntry],
    legend_w: f64,
) -> Result<ChartLayout, Box<dyn std::error::Error>> {
    let area = root.titled("accuracy against cost (all cases)", ("sans-serif", 20))?;
    let (x_min, x_max, y_min) = measurements.iter().map(point).fold(
        (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY),
        |(a, b, c), (x, y)| (a.min(x), b.max(x), c.min(y)),
    );
    let (x_range, y_range) = ((x_min - 0.1).floor()..(x_max + 0.1).ceil(), (y_min.floor() - 1.0)..1.0);
    let width = area.dim_in_pixel().0;
    let (plot, _) = area.split_horizontally(width - (legend_w.ceil() as u32 + 30));
    let mut chart = ChartBuilder::on(&plot)
        .margin(14)
        .x_label_area_size(44)
        .y_label_area_size(70)
        .build_cartesian_2d(x_range.clone(), y_range.clone())?;
    chart
        .configure_mesh()
        .x_labels(ticks::decade_ticks(&x_range, 12))
        .y_labels(ticks::decade_ticks(&y_range, 16))
        .x_label_formatter(&|v| ticks::power_of_ten(*v))
        .y_label_formatter(&|v| ticks::power_of_ten(*v))
        .x_desc("seconds per W")
        .y_desc("relative error")
        .axis_desc_style(("sans-serif", 16))
        .draw()?;
    let frame = Frame::of(&chart);
    overlay.clip(&frame.area);
    for (entry, (_, by_case)) in entries.iter().zip(curves) {
        let Swatch::Line(colour, width) = entry.swatch else {
            continue;
        };
        for curve in by_case {
            let pixels: Vec<(f64, f64)> = curve.iter().map(|p| frame.pixel(*p)).collect();
            overlay.polyline(&pixels, Stroke::solid(colour, width));
        }
    }
    overlay.end_clip();
    for m in pareto_front(measurements) {
        overlay.circle(
            frame.pixel(point(m)),
            6.0,
            Some(Stroke::solid(BLACK.to_rgba(), 2.0)),
            None,
        );
    }
    let (w, h) = legend_size(entries);
    let legend = Rect::at(frame.area.right + 24.0, frame.area.top, (w, h));
    draw_legend(overlay, &legend, entries);
    Ok(ChartLayout {
        frame,
        legend,
        labels: Vec::new(),
    })
}
