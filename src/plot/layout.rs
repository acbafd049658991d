//! Where legends and labels go: each is placed, from the data, where it covers no
//! plotted point, line or marker, and the geometry is returned with the picture so
//! that it can be checked.

use std::ops::Range;

use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use super::overlay::{Overlay, Stroke};
pub use super::rect::Rect;
use super::style::{SeriesStyle, FAMILY, LINE_WIDTH, MARKER_SIZE, TEXT};

/// A chart's plotting area in pixels and the ranges of the drawn coordinates it spans
/// (log10 of the values on logarithmic axes), mapped linearly.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// The plotting area, from the first to the last pixel column and row.
    pub area: Rect,
    /// The abscissa's range, left to right.
    pub x: Range<f64>,
    /// The ordinate's range, bottom to top.
    pub y: Range<f64>,
}

impl Frame {
    /// The frame of a chart drawn by plotters.
    pub(crate) fn of<DB: DrawingBackend>(
        chart: &ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    ) -> Self {
        let (xs, ys) = chart.plotting_area().get_pixel_range();
        let (x, y) = (chart.x_range(), chart.y_range());
        Frame {
            area: Rect {
                left: f64::from(xs.start),
                top: f64::from(ys.start),
                right: f64::from(xs.end - 1),
                bottom: f64::from(ys.end - 1),
            },
            x,
            y,
        }
    }

    /// The pixel of a point in drawn coordinates.
    pub fn pixel(&self, (x, y): (f64, f64)) -> (f64, f64) {
        let a = &self.area;
        (
            a.left + (x - self.x.start) / (self.x.end - self.x.start) * (a.right - a.left),
            a.bottom - (y - self.y.start) / (self.y.end - self.y.start) * (a.bottom - a.top),
        )
    }
}

/// What a legend or label must not cover, in pixels: lines through points, and discs
/// (markers with their radius).
#[derive(Clone, Debug, Default)]
pub struct Obstacles {
    lines: Vec<Vec<(f64, f64)>>,
    discs: Vec<((f64, f64), f64)>,
    boxes: Vec<Rect>,
}

impl Obstacles {
    /// A polyline through `points` (drawn coordinates).
    pub fn line(&mut self, frame: &Frame, points: impl IntoIterator<Item = (f64, f64)>) {
        self.lines.push(points.into_iter().map(|p| frame.pixel(p)).collect());
    }

    /// A marker of `radius` pixels at `point` (drawn coordinates).
    pub fn disc(&mut self, frame: &Frame, point: (f64, f64), radius: f64) {
        self.discs.push((frame.pixel(point), radius));
    }

    /// A box already taken (a placed label).
    pub fn taken(&mut self, rect: Rect) {
        self.boxes.push(rect);
    }

    /// How many obstacles `rect` touches.
    pub fn hits(&self, rect: &Rect) -> usize {
        let lines = self
            .lines
            .iter()
            .filter(|line| match line.as_slice() {
                [single] => rect.contains(*single),
                points => points.windows(2).any(|w| rect.meets_segment(w[0], w[1])),
            })
            .count();
        let discs = self
            .discs
            .iter()
            .filter(|(centre, radius)| rect.inflate(*radius).contains(*centre))
            .count();
        lines + discs + self.boxes.iter().filter(|b| b.intersects(rect)).count()
    }
}

/// How a legend entry shows its series: as drawn in the chart.
#[derive(Clone, Copy, Debug)]
pub enum Swatch {
    /// A dashed line of the given width (dashes of 6 pixels, gaps of 4, as in the chart).
    Dashed(RGBAColor, f64),
    /// A series' line in its colour and dash pattern, with its marker if `true`.
    Series(SeriesStyle, bool),
    /// A series' marker alone.
    Marker(SeriesStyle),
    /// The filled marker of a value below an axis' floor.
    Floor(RGBAColor),
    /// An open circle of the given radius.
    Circle(RGBAColor, f64),
    /// A filled circle of the given radius.
    Dot(RGBAColor, f64),
    /// A cross of half-width [`CROSS`].
    Cross(RGBAColor),
}

/// The half-width of the crosses that mark where a curve ends, in pixels.
pub const CROSS: f64 = 7.0;

/// One line of a legend.
#[derive(Clone, Debug)]
pub struct LegendEntry {
    pub label: String,
    pub swatch: Swatch,
}

const SWATCH: f64 = 52.0;
const PADDING: f64 = 8.0;
const ROW: f64 = 30.0;
/// The space between a swatch and its text, and between columns.
const GAP: f64 = 8.0;
/// The clearance kept between a legend or label and the data, in pixels.
pub const CLEARANCE: f64 = 3.0;

/// The size of `text` in pixels, in the built-in font of `size` pixels.
pub fn text_size(text: &str, size: u32) -> (f64, f64) {
    let (w, h) = (FAMILY, size).into_font().box_size(text).unwrap_or((0, 0));
    (f64::from(w), f64::from(h))
}

/// The size of the legend of `entries` in pixels, in one column.
pub fn legend_size(entries: &[LegendEntry]) -> (f64, f64) {
    legend_size_in(entries, 1)
}

/// The width of one column of a legend of `entries`.
fn column_width(entries: &[LegendEntry]) -> f64 {
    let widest = entries.iter().map(|e| text_size(&e.label, TEXT).0).fold(0.0, f64::max);
    SWATCH + GAP + widest
}

/// The size of the legend of `entries` in pixels, set in `columns` columns (filled row by row).
pub fn legend_size_in(entries: &[LegendEntry], columns: usize) -> (f64, f64) {
    let columns = columns.clamp(1, entries.len().max(1));
    let rows = entries.len().div_ceil(columns);
    (
        2.0 * PADDING + columns as f64 * column_width(entries) + (columns - 1) as f64 * 2.0 * GAP,
        2.0 * PADDING + ROW * rows as f64 - 4.0,
    )
}

/// The most columns (at most one per entry) in which the legend of `entries` fits `width`.
pub fn legend_columns(entries: &[LegendEntry], width: f64) -> usize {
    (1..=entries.len().max(1))
        .rev()
        .find(|&columns| legend_size_in(entries, columns).0 <= width)
        .unwrap_or(1)
}

/// The first of the plotting area's corners and edge middles (upper right first) where
/// a box of `size` covers no obstacle, keeping [`CLEARANCE`]; None if every one does.
pub fn free_place(area: &Rect, size: (f64, f64), obstacles: &Obstacles) -> Option<Rect> {
    let inset = 8.0;
    let (w, h) = size;
    let (left, right) = (area.left + inset, area.right - inset - w);
    let (top, bottom) = (area.top + inset, area.bottom - inset - h);
    let (centre_x, centre_y) = (0.5 * (area.left + area.right - w), 0.5 * (area.top + area.bottom - h));
    [
        (right, top),
        (left, top),
        (centre_x, top),
        (right, bottom),
        (left, bottom),
        (centre_x, bottom),
        (right, centre_y),
        (left, centre_y),
    ]
    .into_iter()
    .map(|(x, y)| Rect::at(x, y, size))
    .find(|rect| area.encloses(rect) && obstacles.hits(&rect.inflate(CLEARANCE)) == 0)
}

/// Draws a legend box at `rect` (pixels) into `overlay`, in one column.
pub fn draw_legend(overlay: &mut Overlay, rect: &Rect, entries: &[LegendEntry]) {
    draw_legend_in(overlay, rect, entries, 1);
}

/// Draws a legend box at `rect` (pixels) into `overlay`, in `columns` columns filled row by row.
pub fn draw_legend_in(overlay: &mut Overlay, rect: &Rect, entries: &[LegendEntry], columns: usize) {
    let columns = columns.clamp(1, entries.len().max(1));
    let step = column_width(entries) + 2.0 * GAP;
    overlay.rect(rect, Some(WHITE.mix(0.9)), Some(Stroke::solid(BLACK.to_rgba(), 1.0)));
    for (index, entry) in entries.iter().enumerate() {
        let (row, column) = (index / columns, index % columns);
        let x = rect.left + PADDING + step * column as f64;
        let middle = rect.top + PADDING + ROW * row as f64 + 0.5 * (ROW - 4.0);
        draw_swatch(overlay, entry.swatch, x, middle);
        overlay.text(&entry.label, (x + SWATCH + GAP, middle), TEXT);
    }
}

fn draw_swatch(overlay: &mut Overlay, swatch: Swatch, x: f64, y: f64) {
    let centre = (x + 0.5 * SWATCH, y);
    let line = [(x, y), (x + SWATCH, y)];
    match swatch {
        Swatch::Dashed(colour, width) => overlay.polyline(&line, Stroke::dashed(colour, width)),
        Swatch::Series(style, marked) => {
            overlay.polyline(&line, Stroke::of(&style, LINE_WIDTH));
            if marked {
                let outline = Stroke::solid(style.colour.to_rgba(), 1.5);
                overlay.marker(style.marker, centre, MARKER_SIZE, outline);
            }
        }
        Swatch::Marker(style) => overlay.marker(
            style.marker,
            centre,
            MARKER_SIZE,
            Stroke::solid(style.colour.to_rgba(), 1.5),
        ),
        Swatch::Floor(colour) => overlay.floor_marker(centre, MARKER_SIZE, colour),
        Swatch::Circle(colour, radius) => overlay.circle(centre, radius, Some(Stroke::solid(colour, 2.0)), None),
        Swatch::Dot(colour, radius) => overlay.circle(centre, radius, None, Some(colour)),
        Swatch::Cross(colour) => overlay.cross(centre, CROSS, Stroke::solid(colour, 2.0)),
    }
}

/// A text label beside its marker.
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    /// The text.
    pub text: String,
    /// The marker's position in drawn coordinates.
    pub at: (f64, f64),
    /// The marker's radius in pixels.
    pub radius: f64,
    /// The text's box in pixels.
    pub rect: Rect,
}

/// Places a label of `size` beside a marker of `radius` at pixel `centre`: of the eight
/// positions around it (right first), the one inside `bounds` that touches the fewest
/// obstacles.
pub fn beside(centre: (f64, f64), radius: f64, size: (f64, f64), bounds: &Rect, obstacles: &Obstacles) -> Rect {
    let (w, h) = size;
    let gap = radius + CLEARANCE + 1.0;
    let (x, y) = centre;
    let candidates = [
        (x + gap, y - 0.5 * h),
        (x - gap - w, y - 0.5 * h),
        (x - 0.5 * w, y - gap - h),
        (x - 0.5 * w, y + gap),
        (x + 0.7 * gap, y - 0.7 * gap - h),
        (x - 0.7 * gap - w, y - 0.7 * gap - h),
        (x + 0.7 * gap, y + 0.7 * gap),
        (x - 0.7 * gap - w, y + 0.7 * gap),
    ];
    candidates
        .into_iter()
        .map(|(left, top)| Rect::at(left, top, size))
        .enumerate()
        .min_by_key(|(order, rect)| {
            let outside = usize::from(!bounds.encloses(rect));
            (outside, obstacles.hits(&rect.inflate(1.0)), *order)
        })
        .map(|(_, rect)| rect)
        .unwrap_or_else(|| Rect::at(x + gap, y - 0.5 * h, size))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_meet_a_rectangle_only_where_they_cross_it() {
        let r = Rect::at(10.0, 10.0, (10.0, 10.0));
        assert!(r.meets_segment((0.0, 15.0), (30.0, 15.0)));
        assert!(r.meets_segment((12.0, 12.0), (13.0, 13.0)));
        assert!(!r.meets_segment((0.0, 0.0), (30.0, 5.0)));
        assert!(!r.meets_segment((0.0, 25.0), (25.0, 40.0)));
        // The diagonal just past a corner misses it.
        assert!(!r.meets_segment((0.0, 19.0), (12.0, 31.0)));
        assert!(r.meets_segment((0.0, 21.0), (12.0, 9.0)));
    }

    #[test]
    fn a_legend_goes_to_the_first_free_corner() {
        let frame = Frame {
            area: Rect::at(0.0, 0.0, (400.0, 300.0)),
            x: 0.0..1.0,
            y: 0.0..1.0,
        };
        let mut obstacles = Obstacles::default();
        // A rising line through the upper right corner: the upper left is free.
        obstacles.line(&frame, [(0.5, 0.5), (1.0, 1.0)]);
        let place = free_place(&frame.area, (100.0, 60.0), &obstacles).unwrap();
        assert_eq!((place.left, place.top), (8.0, 8.0));
        obstacles.line(&frame, [(0.0, 1.0), (0.3, 0.0)]);
        obstacles.line(&frame, [(0.5, 1.0), (0.5, 0.0)]);
        obstacles.line(&frame, [(0.0, 0.1), (1.0, 0.1)]);
        assert_eq!(
            free_place(&frame.area, (100.0, 60.0), &obstacles).map(|r| (r.left, r.top)),
            Some((292.0, 120.0)),
            "the middle of the right edge"
        );
        obstacles.line(&frame, [(0.0, 0.5), (1.0, 0.5)]);
        assert_eq!(free_place(&frame.area, (100.0, 60.0), &obstacles), None);
    }
}
