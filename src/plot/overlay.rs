//! The data layer of a picture: curves, markers, legends and labels written as SVG
//! elements with fractional pixel coordinates, over the axes plotters draws. Plotters
//! rounds every coordinate to a whole pixel, which turns a smooth curve into a
//! staircase; here nothing is rounded, so the renderer can anti-alias the true curve.

use std::fmt::Write;

use plotters::style::{Color, RGBAColor};

use super::rect::Rect;
use super::style::{Marker, SeriesStyle, FAMILY};

/// SVG elements to be drawn over the axes, in order.
#[derive(Debug, Default)]
pub struct Overlay {
    svg: String,
    clips: usize,
}

/// `fill` or `stroke` of colour `c`, with its opacity.
fn paint(what: &str, c: &RGBAColor) -> String {
    let (r, g, b) = c.rgb();
    format!("{what}=\"#{r:02X}{g:02X}{b:02X}\" {what}-opacity=\"{}\"", c.alpha())
}

fn fill(c: Option<RGBAColor>) -> String {
    c.map_or("fill=\"none\"".to_string(), |c| paint("fill", &c))
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}

/// How a line is stroked: its colour, width and dash pattern (dash, gap, …; empty: solid).
#[derive(Clone, Copy, Debug)]
pub struct Stroke {
    pub colour: RGBAColor,
    pub width: f64,
    pub dash: &'static [f64],
}

impl Stroke {
    /// A solid line.
    pub fn solid(colour: RGBAColor, width: f64) -> Self {
        Stroke {
            colour,
            width,
            dash: &[],
        }
    }

    /// The line of a series: its colour and dash pattern.
    pub fn of(style: &SeriesStyle, width: f64) -> Self {
        Stroke {
            colour: style.colour.to_rgba(),
            width,
            dash: style.dash,
        }
    }

    /// A dashed line: dashes of 6 units, gaps of 4, in charts and legends alike.
    pub fn dashed(colour: RGBAColor, width: f64) -> Self {
        Stroke {
            colour,
            width,
            dash: &[6.0, 4.0],
        }
    }

    fn attributes(&self) -> String {
        let mut text = format!(
            "{} stroke-width=\"{}\" stroke-linejoin=\"round\" stroke-linecap=\"butt\"",
            paint("stroke", &self.colour),
            self.width
        );
        if !self.dash.is_empty() {
            let pattern: Vec<String> = self.dash.iter().map(f64::to_string).collect();
            let _ = write!(text, " stroke-dasharray=\"{}\"", pattern.join(" "));
        }
        text
    }
}

impl Overlay {
    /// Starts clipping what follows to `area` (until [`Overlay::end_clip`]).
    pub fn clip(&mut self, area: &Rect) {
        let (w, h) = area.size();
        let id = self.clips;
        self.clips += 1;
        let _ = writeln!(
            self.svg,
            "<clipPath id=\"plot{id}\"><rect x=\"{}\" y=\"{}\" width=\"{w}\" height=\"{h}\"/></clipPath><g clip-path=\"url(#plot{id})\">",
            area.left, area.top
        );
    }

    /// Ends the clipping started last.
    pub fn end_clip(&mut self) {
        self.svg.push_str("</g>\n");
    }

    /// A line through `points` (pixels).
    pub fn polyline(&mut self, points: &[(f64, f64)], stroke: Stroke) {
        if points.len() < 2 {
            return;
        }
        let mut list = String::new();
        for (x, y) in points {
            let _ = write!(list, "{x:.2},{y:.2} ");
        }
        let _ = writeln!(
            self.svg,
            "<polyline fill=\"none\" {} points=\"{}\"/>",
            stroke.attributes(),
            list.trim_end()
        );
    }

    /// A marker of half-size `size` at `centre`, outlined in `stroke` and filled white
    /// (so that it reads over the lines beneath it).
    pub fn marker(&mut self, marker: Marker, (x, y): (f64, f64), size: f64, stroke: Stroke) {
        let white = Some(RGBAColor(255, 255, 255, 1.0));
        let polygon = |overlay: &mut Self, corners: &[(f64, f64)]| {
            let mut list = String::new();
            for (dx, dy) in corners {
                let _ = write!(list, "{:.2},{:.2} ", x + dx * size, y + dy * size);
            }
            let _ = writeln!(
                overlay.svg,
                "<polygon {} {} points=\"{}\"/>",
                fill(white),
                stroke.attributes(),
                list.trim_end()
            );
        };
        match marker {
            Marker::Circle => self.circle((x, y), size, Some(stroke), white),
            Marker::Square => polygon(self, &[(-0.85, -0.85), (0.85, -0.85), (0.85, 0.85), (-0.85, 0.85)]),
            Marker::TriangleUp => polygon(self, &[(0.0, -1.15), (1.0, 0.6), (-1.0, 0.6)]),
            Marker::TriangleDown => polygon(self, &[(0.0, 1.15), (1.0, -0.6), (-1.0, -0.6)]),
            Marker::Diamond => polygon(self, &[(0.0, -1.2), (1.0, 0.0), (0.0, 1.2), (-1.0, 0.0)]),
            Marker::Star | Marker::Pentagon => {
                // Five points out (a star's alternate with inner ones).
                let star = marker == Marker::Star;
                let corners: Vec<(f64, f64)> = (0..if star { 10 } else { 5 })
                    .map(|k| {
                        let turns = if star { f64::from(k) / 10.0 } else { f64::from(k) / 5.0 };
                        let angle = 2.0 * std::f64::consts::PI * turns - 0.5 * std::f64::consts::PI;
                        let r = if star && k % 2 == 1 { 0.5 } else { 1.2 };
                        (r * angle.cos(), r * angle.sin())
                    })
                    .collect();
                polygon(self, &corners);
            }
            Marker::Plus => {
                let d = 1.15 * size;
                self.polyline(&[(x - d, y), (x + d, y)], stroke);
                self.polyline(&[(x, y - d), (x, y + d)], stroke);
            }
        }
    }

    /// A filled triangle pointing down onto `(x, y)`: a value below the axis' floor,
    /// drawn there.
    pub fn floor_marker(&mut self, (x, y): (f64, f64), size: f64, colour: RGBAColor) {
        let _ = writeln!(
            self.svg,
            "<polygon {} points=\"{:.2},{:.2} {:.2},{:.2} {:.2},{:.2}\"/>",
            fill(Some(colour)),
            x,
            y,
            x + size,
            y - 1.7 * size,
            x - size,
            y - 1.7 * size
        );
    }

    /// A circle, open (stroked) or filled.
    pub fn circle(&mut self, (x, y): (f64, f64), radius: f64, stroke: Option<Stroke>, inside: Option<RGBAColor>) {
        let fill = fill(inside);
        let stroke = stroke.map_or(String::new(), |s| s.attributes());
        let _ = writeln!(
            self.svg,
            "<circle cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"{radius}\" {fill} {stroke}/>"
        );
    }

    /// A cross (×) of half-width `size`.
    pub fn cross(&mut self, (x, y): (f64, f64), size: f64, stroke: Stroke) {
        let d = size / std::f64::consts::SQRT_2;
        self.polyline(&[(x - d, y - d), (x + d, y + d)], stroke);
        self.polyline(&[(x - d, y + d), (x + d, y - d)], stroke);
    }

    /// A rectangle, filled and/or stroked.
    pub fn rect(&mut self, rect: &Rect, inside: Option<RGBAColor>, stroke: Option<Stroke>) {
        let (w, h) = rect.size();
        let fill = fill(inside);
        let stroke = stroke.map_or(String::new(), |s| s.attributes());
        let _ = writeln!(
            self.svg,
            "<rect x=\"{}\" y=\"{}\" width=\"{w}\" height=\"{h}\" {fill} {stroke}/>",
            rect.left, rect.top
        );
    }

    /// Text in the built-in font of `size` pixels (as plotters sizes it), starting at
    /// `x`, its box's vertical middle at `y`.
    pub fn text(&mut self, text: &str, (x, y): (f64, f64), size: u32) {
        let _ = writeln!(
            self.svg,
            "<text x=\"{x:.2}\" y=\"{y:.2}\" dy=\"0.35em\" font-family=\"{FAMILY}\" font-size=\"{}\" fill=\"#000000\">{}</text>",
            f64::from(size) / 1.24,
            escape(text)
        );
    }

    /// The elements, in order.
    pub fn into_svg(self) -> String {
        self.svg
    }
}
