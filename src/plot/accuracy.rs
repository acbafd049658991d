//! The accuracy-against-cost chart: one panel per case, stacked, relative error
//! against seconds on logarithmic axes labelled in powers of ten. A rule has one
//! colour and dash pattern, a working precision one marker, so thirteen series are
//! read off two short keys. The error axis ends at the reference's precision
//! (10⁻¹⁰⁰): an error below it is not measured, and is drawn as a filled marker on
//! that floor, off the lines. The Pareto front is circled.

use std::path::Path;

use plotters::prelude::*;

use super::layout::{draw_legend_in, legend_columns, legend_size_in, Frame, LegendEntry, Rect, Swatch};
use super::overlay::{Overlay, Stroke};
use super::style::{series, Marker, SeriesStyle, FAMILY, LINE_WIDTH, MARKERS, MARKER_SIZE, TEXT, TITLE};
use super::{chart_on, draw_svg, register_font, ticks, Canvas, ChartLayout, Format, Picture, PlotError};
use crate::accuracy::{pareto_front, Measurement};

/// Draws the chart of `measurements` into `path` (.svg, .png or .pdf).
pub fn plot_accuracy(path: &Path, measurements: &[Measurement]) -> Result<(), PlotError> {
    Format::of(path)?;
    accuracy_picture(measurements)?.write(path)
}

/// log10 of the smallest relative error the 100-digit references resolve: the floor of
/// the error axis.
pub const FLOOR_EXPONENT: f64 = -100.0;

/// The precisions the markers stand for, in bits (53: f64).
const PRECISIONS: [u32; 5] = [53, 128, 256, 512, 1024];

const WIDTH: u32 = 600;
const PANEL_HEIGHT: u32 = 440;
const MARGIN: f64 = 12.0;

/// A measurement in drawn coordinates: log10 seconds, log10 relative error, the
/// error raised to the floor where it lies below.
pub fn point(m: &Measurement) -> (f64, f64) {
    (m.seconds.max(1e-9).log10(), m.rel_error.log10().max(FLOOR_EXPONENT))
}

/// Whether a measurement's error lies below what the reference resolves.
pub fn below_floor(m: &Measurement) -> bool {
    m.rel_error.log10() < FLOOR_EXPONENT
}

/// The rules, in order of first appearance.
fn rules(measurements: &[Measurement]) -> Vec<&'static str> {
    let mut rules: Vec<&'static str> = Vec::new();
    for m in measurements {
        if !rules.contains(&m.rule) {
            rules.push(m.rule);
        }
    }
    rules
}

/// The cases, in order of first appearance.
fn cases(measurements: &[Measurement]) -> Vec<&str> {
    let mut cases: Vec<&str> = Vec::new();
    for m in measurements {
        if !cases.contains(&m.case.as_str()) {
            cases.push(&m.case);
        }
    }
    cases
}

/// The marker of a precision.
fn precision_marker(bits: u32) -> Marker {
    let index = PRECISIONS.iter().position(|&b| b == bits).unwrap_or(PRECISIONS.len());
    MARKERS[index % MARKERS.len()]
}

fn precision_name(bits: u32) -> String {
    if bits == 53 {
        "f64".to_string()
    } else {
        format!("{bits} bits")
    }
}

/// The legend: the rules (line and dash), the precisions (markers), the floor and the front.
fn legend_entries(measurements: &[Measurement]) -> Vec<LegendEntry> {
    let mut entries: Vec<LegendEntry> = rules(measurements)
        .into_iter()
        .enumerate()
        .map(|(index, rule)| LegendEntry {
            label: rule.to_string(),
            swatch: Swatch::Series(series(index), false),
        })
        .collect();
    let mut precisions: Vec<u32> = measurements.iter().map(|m| m.precision_bits).collect();
    precisions.sort_unstable();
    precisions.dedup();
    for bits in precisions {
        let style = SeriesStyle {
            colour: RGBColor(0, 0, 0),
            dash: &[],
            marker: precision_marker(bits),
        };
        entries.push(LegendEntry {
            label: precision_name(bits),
            swatch: Swatch::Marker(style),
        });
    }
    entries.push(LegendEntry {
        label: "error below 10⁻¹⁰⁰ (the reference's digits)".to_string(),
        swatch: Swatch::Floor(RGBColor(0, 0, 0).to_rgba()),
    });
    entries.push(LegendEntry {
        label: "Pareto front".to_string(),
        swatch: Swatch::Circle(BLACK.to_rgba(), 7.0),
    });
    entries
}

/// The chart of `measurements` as a picture: a panel per case, the legend under them.
pub fn accuracy_picture(measurements: &[Measurement]) -> Result<Picture, PlotError> {
    register_font()?;
    let entries = legend_entries(measurements);
    let columns = legend_columns(&entries, f64::from(WIDTH) - 2.0 * MARGIN);
    let legend = legend_size_in(&entries, columns);
    let panels = cases(measurements).len().max(1) as u32;
    let height = PANEL_HEIGHT * panels + (legend.1 + 2.0 * MARGIN).ceil() as u32;
    draw_svg((WIDTH, height), |root, overlay| {
        let (charts, _) = root.split_vertically(PANEL_HEIGHT * panels);
        let rect = Rect::at(
            0.5 * (f64::from(WIDTH) - legend.0),
            f64::from(PANEL_HEIGHT * panels) + MARGIN,
            legend,
        );
        let mut layouts = Vec::new();
        for (area, case) in charts
            .split_evenly((panels as usize, 1))
            .iter()
            .zip(cases(measurements))
        {
            let frame = draw_case(area, overlay, measurements, case)?;
            layouts.push(ChartLayout {
                frame,
                legend: rect,
                labels: Vec::new(),
            });
        }
        draw_legend_in(overlay, &rect, &entries, columns);
        Ok(layouts)
    })
}

/// One case's panel: a line per rule and precision through the measured errors, a
/// marker on each, the ones below the floor on it.
fn draw_case(
    area: &Canvas<'_>,
    overlay: &mut Overlay,
    measurements: &[Measurement],
    case: &str,
) -> Result<Frame, Box<dyn std::error::Error>> {
    let area = area.titled(&format!("case {case}"), (FAMILY, TITLE))?;
    // One time axis for every panel, so that the cases compare.
    let (x_min, x_max) = measurements
        .iter()
        .map(point)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (x, _)| {
            (a.min(x), b.max(x))
        });
    let (x_range, y_range) = ((x_min - 0.1).floor()..(x_max + 0.1).ceil(), FLOOR_EXPONENT..0.0);
    let mut chart = chart_on(&area, x_range.clone(), y_range.clone())?;
    chart
        .configure_mesh()
        .x_labels(ticks::decade_ticks(&x_range, 8))
        .y_labels(6)
        .x_label_formatter(&|v| ticks::power_of_ten(*v))
        .y_label_formatter(&|v| ticks::power_of_ten(*v))
        .x_desc("seconds per W")
        .y_desc("relative error of W")
        .label_style((FAMILY, TEXT))
        .axis_desc_style((FAMILY, TEXT))
        .light_line_style(WHITE)
        .draw()?;
    let frame = Frame::of(&chart);
    let ours: Vec<&Measurement> = measurements.iter().filter(|m| m.case == case).collect();
    overlay.clip(&frame.area.inflate(MARKER_SIZE + 2.0));
    for (index, rule) in rules(measurements).into_iter().enumerate() {
        let style = series(index);
        let mut precisions: Vec<u32> = ours
            .iter()
            .filter(|m| m.rule == rule)
            .map(|m| m.precision_bits)
            .collect();
        precisions.dedup();
        for bits in precisions {
            let mut list: Vec<&&Measurement> = ours
                .iter()
                .filter(|m| m.rule == rule && m.precision_bits == bits)
                .collect();
            list.sort_by(|a, b| a.parameter.total_cmp(&b.parameter));
            // The line joins measured errors only: it breaks where an error is below the floor.
            for run in list.split(|m| below_floor(m)) {
                let pixels: Vec<(f64, f64)> = run.iter().map(|m| frame.pixel(point(m))).collect();
                overlay.polyline(&pixels, Stroke::of(&style, LINE_WIDTH));
            }
            let outline = Stroke::solid(style.colour.to_rgba(), 1.5);
            for m in &list {
                let at = frame.pixel(point(m));
                if below_floor(m) {
                    overlay.floor_marker(at, MARKER_SIZE, style.colour.to_rgba());
                } else {
                    overlay.marker(precision_marker(bits), at, MARKER_SIZE, outline);
                }
            }
        }
    }
    let case_measurements: Vec<Measurement> = ours.iter().map(|m| (*m).clone()).collect();
    for m in pareto_front(&case_measurements) {
        overlay.circle(
            frame.pixel(point(m)),
            MARKER_SIZE + 3.0,
            Some(Stroke::solid(BLACK.to_rgba(), 1.5)),
            None,
        );
    }
    overlay.end_clip();
    Ok(frame)
}
