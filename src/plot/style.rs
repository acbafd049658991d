//! How every picture looks in print: one font and type size readable at the printed
//! width, and series told apart by colour, dash pattern and marker together, so that
//! a reader with a colour-vision deficiency, or a greyscale print, still separates them.

use plotters::style::RGBColor;

/// The font family of every text, the DejaVu Sans built into the program; SVGs name it.
pub const FAMILY: &str = "DejaVu Sans";

/// Drawing units per millimetre of print: a figure panel, 600 units wide, prints at a
/// journal's column width of 85 mm; wider pictures print proportionally wider.
pub const UNITS_PER_MM: f64 = 600.0 / 85.0;

/// The smallest type a printed picture may have, in points.
pub const MIN_TEXT_PT: f64 = 8.0;

/// Millimetres per typographic point.
const MM_PER_PT: f64 = 25.4 / 72.0;

/// The smallest font size, in drawing units, that prints at [`MIN_TEXT_PT`].
pub fn min_font_units() -> f64 {
    MIN_TEXT_PT * MM_PER_PT * UNITS_PER_MM
}

/// The printed size, in points, of a font of `units` drawing units.
pub fn printed_pt(units: f64) -> f64 {
    units / UNITS_PER_MM / MM_PER_PT
}

/// Plotters' text size for a font size: plotters writes `font-size` as its size / 1.24.
const PLOTTERS_RATIO: f64 = 1.24;

/// The text size (as plotters counts it) of tick labels, axis names, legends and notes:
/// 8.4 pt in print.
pub const TEXT: u32 = 26;

/// The text size of captions: 9.1 pt in print.
pub const TITLE: u32 = 28;

/// The font size, in drawing units, of text of plotters size `size`.
pub fn font_units(size: u32) -> f64 {
    f64::from(size) / PLOTTERS_RATIO
}

/// The Okabe–Ito palette without its yellow (too light on white): blue, vermillion,
/// bluish green, reddish purple, orange, sky blue, black.
pub const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
];

/// Dash patterns (dash, gap, …, in drawing units), one per series: solid first.
pub const DASHES: [&[f64]; 8] = [
    &[],
    &[12.0, 5.0],
    &[2.5, 4.0],
    &[12.0, 4.0, 2.5, 4.0],
    &[22.0, 6.0],
    &[6.0, 4.0],
    &[12.0, 4.0, 2.5, 4.0, 2.5, 4.0],
    &[22.0, 5.0, 6.0, 5.0],
];

/// The shape of the markers set along a series.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Marker {
    Circle,
    Square,
    TriangleUp,
    Diamond,
    TriangleDown,
    Plus,
    Pentagon,
    Star,
}

/// Markers, one per series.
pub const MARKERS: [Marker; 8] = [
    Marker::Circle,
    Marker::Square,
    Marker::TriangleUp,
    Marker::Diamond,
    Marker::TriangleDown,
    Marker::Plus,
    Marker::Pentagon,
    Marker::Star,
];

/// How series number `index` of a chart is drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SeriesStyle {
    pub colour: RGBColor,
    pub dash: &'static [f64],
    pub marker: Marker,
}

/// The style of series `index`: colour, dash pattern and marker each cycle, so the
/// first eight series differ in all three.
pub fn series(index: usize) -> SeriesStyle {
    SeriesStyle {
        colour: PALETTE[index % PALETTE.len()],
        dash: DASHES[index % DASHES.len()],
        marker: MARKERS[index % MARKERS.len()],
    }
}

/// Width of a series' line, in drawing units.
pub const LINE_WIDTH: f64 = 2.5;

/// Half-size of a series' markers, in drawing units.
pub const MARKER_SIZE: f64 = 5.5;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_type_prints_at_eight_points_or_more() {
        assert!((min_font_units() - 19.92).abs() < 0.01, "{}", min_font_units());
        assert!(font_units(TEXT) >= min_font_units());
        assert!((printed_pt(font_units(TEXT)) - 8.43).abs() < 0.01);
    }

    #[test]
    fn the_first_eight_series_differ_in_dash_and_marker() {
        for a in 0..8 {
            for b in 0..a {
                assert_ne!(series(a).dash, series(b).dash);
                assert_ne!(series(a).marker, series(b).marker);
            }
        }
    }
}
