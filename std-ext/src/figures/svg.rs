//! A small SVG writer for the book's diagrams: world coordinates in, a
//! fixed-size picture out, every number printed with two decimals so that
//! the same drawing gives the same bytes on every machine.

use bvhkit::glam::Vec2;
use std::fmt::Write;

/// Colours that stay apart for readers with the common colour-vision
/// deficiencies (Okabe and Ito's palette), in the order figures use them.
pub const PALETTE: [&str; 8] = [
    "#0072b2", "#e69f00", "#009e73", "#cc79a7", "#56b4e9", "#d55e00", "#f0e442", "#000000",
];

/// A colour of [`PALETTE`], cycling.
pub fn colour(i: usize) -> &'static str {
    PALETTE[i % PALETTE.len()]
}

/// How a shape is drawn.
#[derive(Clone, Copy, Debug)]
pub struct Style {
    /// Outline colour (`none` for no outline).
    pub stroke: &'static str,
    /// Fill colour (`none` for no fill).
    pub fill: &'static str,
    /// Fill opacity, 0 to 1.
    pub fill_opacity: f32,
    /// Outline width in picture units.
    pub width: f32,
    /// Dashed outline.
    pub dashed: bool,
}

impl Style {
    /// An outline of `colour`.
    pub fn line(colour: &'static str) -> Style {
        Style {
            stroke: colour,
            fill: "none",
            fill_opacity: 1.0,
            width: 1.5,
            dashed: false,
        }
    }
    /// A shape filled with `colour` at `opacity`, outlined in the same colour.
    pub fn filled(colour: &'static str, opacity: f32) -> Style {
        Style {
            fill: colour,
            fill_opacity: opacity,
            ..Style::line(colour)
        }
    }
    /// The same style, dashed.
    pub fn dashed(self) -> Style {
        Style {
            dashed: true,
            ..self
        }
    }
    /// The same style with outline width `width`.
    pub fn width(self, width: f32) -> Style {
        Style { width, ..self }
    }

    fn attributes(&self) -> String {
        let mut s = format!(
            r#"stroke="{}" stroke-width="{:.2}" fill="{}""#,
            self.stroke, self.width, self.fill
        );
        if self.fill != "none" && self.fill_opacity < 1.0 {
            let _ = write!(s, r#" fill-opacity="{:.2}""#, self.fill_opacity);
        }
        if self.dashed {
            s.push_str(r#" stroke-dasharray="4 3""#);
        }
        s
    }
}

/// A picture of `width` x `height` units showing the world rectangle
/// `[lo, hi]` (y up), with a margin, or split into panels side by side.
#[derive(Debug)]
pub struct Svg {
    width: f32,
    height: f32,
    body: String,
    /// The panel being drawn: world box and its place in the picture.
    frame: Frame,
}

#[derive(Clone, Copy, Debug)]
struct Frame {
    lo: Vec2,
    hi: Vec2,
    /// Picture rectangle of the panel: left, top, width, height.
    at: [f32; 4],
}

impl Frame {
    /// World to picture: uniform scale, centred, y flipped.
    fn map(&self, p: Vec2) -> Vec2 {
        let size = (self.hi - self.lo).max(Vec2::splat(1e-12));
        let s = (self.at[2] / size.x).min(self.at[3] / size.y);
        let used = size * s;
        let offset = Vec2::new(
            self.at[0] + (self.at[2] - used.x) * 0.5,
            self.at[1] + (self.at[3] - used.y) * 0.5,
        );
        Vec2::new(
            offset.x + (p.x - self.lo.x) * s,
            offset.y + used.y - (p.y - self.lo.y) * s,
        )
    }
    fn scale(&self) -> f32 {
        let size = (self.hi - self.lo).max(Vec2::splat(1e-12));
        (self.at[2] / size.x).min(self.at[3] / size.y)
    }
}

/// Room left around a panel's drawing, in picture units.
const MARGIN: f32 = 12.0;

impl Svg {
    /// A picture of `width` x `height` units drawing the world box `lo..hi`.
    pub fn new(width: f32, height: f32, lo: Vec2, hi: Vec2) -> Svg {
        Svg {
            width,
            height,
            body: String::new(),
            frame: Frame {
                lo,
                hi,
                at: [MARGIN, MARGIN, width - 2.0 * MARGIN, height - 2.0 * MARGIN],
            },
        }
    }

    /// Draws from now on into panel `i` of `n` side by side (each with a
    /// title line above it), showing the world box `lo..hi`.
    pub fn panel(&mut self, i: usize, n: usize, lo: Vec2, hi: Vec2, title: &str) {
        let w = self.width / n as f32;
        let left = w * i as f32;
        self.frame = Frame {
            lo,
            hi,
            at: [
                left + MARGIN,
                MARGIN + 16.0,
                w - 2.0 * MARGIN,
                self.height - 2.0 * MARGIN - 16.0,
            ],
        };
        self.label_at(
            Vec2::new(left + w * 0.5, MARGIN + 4.0),
            title,
            13.0,
            "middle",
        );
    }

    /// An axis-aligned rectangle with corners `lo`, `hi` (world).
    pub fn rect(&mut self, lo: Vec2, hi: Vec2, style: Style) {
        let (a, b) = (
            self.frame.map(Vec2::new(lo.x, hi.y)),
            self.frame.map(Vec2::new(hi.x, lo.y)),
        );
        let _ = writeln!(
            self.body,
            r#"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" {}/>"#,
            a.x,
            a.y,
            (b.x - a.x).max(0.0),
            (b.y - a.y).max(0.0),
            style.attributes()
        );
    }

    /// A circle of world radius `r` around `c`.
    pub fn circle(&mut self, c: Vec2, r: f32, style: Style) {
        let p = self.frame.map(c);
        let _ = writeln!(
            self.body,
            r#"<circle cx="{:.2}" cy="{:.2}" r="{:.2}" {}/>"#,
            p.x,
            p.y,
            r * self.frame.scale(),
            style.attributes()
        );
    }

    /// A dot of fixed picture radius `r` at `c` (points, markers).
    pub fn dot(&mut self, c: Vec2, r: f32, colour: &'static str) {
        let p = self.frame.map(c);
        let _ = writeln!(
            self.body,
            r#"<circle cx="{:.2}" cy="{:.2}" r="{:.2}" fill="{colour}"/>"#,
            p.x, p.y, r
        );
    }

    /// A closed polygon through `points` (world).
    pub fn polygon(&mut self, points: &[Vec2], style: Style) {
        let pts: Vec<String> = points
            .iter()
            .map(|&p| {
                let q = self.frame.map(p);
                format!("{:.2},{:.2}", q.x, q.y)
            })
            .collect();
        let _ = writeln!(
            self.body,
            r#"<polygon points="{}" {}/>"#,
            pts.join(" "),
            style.attributes()
        );
    }

    /// A segment from `a` to `b` (world).
    pub fn line(&mut self, a: Vec2, b: Vec2, style: Style) {
        let (p, q) = (self.frame.map(a), self.frame.map(b));
        let _ = writeln!(
            self.body,
            r#"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" {}/>"#,
            p.x,
            p.y,
            q.x,
            q.y,
            style.attributes()
        );
    }

    /// Text centred at world point `at`, `size` units high.
    pub fn label(&mut self, at: Vec2, text: &str, size: f32) {
        let p = self.frame.map(at);
        self.label_at(p, text, size, "middle");
    }

    /// Text at picture point `p` (not world), anchored `start`, `middle` or
    /// `end`.
    pub fn label_at(&mut self, p: Vec2, text: &str, size: f32, anchor: &str) {
        let _ = writeln!(
            self.body,
            r#"<text x="{:.2}" y="{:.2}" font-size="{:.2}" text-anchor="{anchor}" dominant-baseline="middle">{}</text>"#,
            p.x,
            p.y,
            size,
            escape(text)
        );
    }

    /// The finished document.
    pub fn finish(self) -> String {
        format!(
            concat!(
                r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.0} {h:.0}" "#,
                r#"font-family="sans-serif">"#,
                "\n",
                r#"<rect width="100%" height="100%" fill="white"/>"#,
                "\n{body}</svg>\n"
            ),
            w = self.width,
            h = self.height,
            body = self.body
        )
    }
}

/// Stacks finished SVG documents (each `width` wide) one under the other
/// into one picture: each is nested as an `<svg>` element at its offset,
/// so every row keeps its own panels and coordinates.
pub fn stack_rows(width: f32, rows: &[(f32, String)]) -> String {
    let height: f32 = rows.iter().map(|r| r.0).sum();
    let mut out = format!(
        concat!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.0} {h:.0}" "#,
            r#"font-family="sans-serif">"#,
            "\n",
            r#"<rect width="100%" height="100%" fill="white"/>"#,
            "\n"
        ),
        w = width,
        h = height
    );
    let mut y = 0.0;
    for (h, doc) in rows {
        let nested = doc.replacen("<svg ", &format!(r#"<svg x="0" y="{y:.0}" "#), 1);
        out.push_str(&nested);
        y += h;
    }
    out.push_str("</svg>\n");
    out
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn world_maps_into_the_picture_with_y_up() {
        let mut svg = Svg::new(224.0, 124.0, Vec2::ZERO, Vec2::new(2.0, 1.0));
        svg.rect(Vec2::ZERO, Vec2::new(1.0, 1.0), Style::line("#000000"));
        let out = svg.finish();
        // Scale 100 per unit (200 x 100 inside a margin of 12): the unit
        // square's top-left corner is at (12, 12).
        assert!(
            out.contains(r#"<rect x="12.00" y="12.00" width="100.00" height="100.00""#),
            "{out}"
        );
        assert!(out.starts_with("<svg") && out.ends_with("</svg>\n"));
    }

    #[test]
    fn text_is_escaped() {
        let mut svg = Svg::new(100.0, 100.0, Vec2::ZERO, Vec2::ONE);
        svg.label(Vec2::splat(0.5), "a < b & c", 10.0);
        assert!(svg.finish().contains("a &lt; b &amp; c"));
    }
}
