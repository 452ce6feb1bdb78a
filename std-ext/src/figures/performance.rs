//! Figures of the book's `performance.md` chapter: the builders' time
//! against error, read from the recorded `bvhkit bench` run
//! (`measured/bench/report.json`), never timed at draw time.
//!
//! Also home of the small drawing helpers the figures of `embedded.md`,
//! `representations.md` and `robustness.md` share: [`Pic`], a picture drawn
//! in picture units (y down) for plots and memory diagrams; [`View`], a
//! world window inside it; [`Axes`], a plot's frame and scales; and
//! [`Labeller`], which places labels where they overlap nothing.

use super::svg::{colour, Style, Svg};
use super::{Figure, FigureError};
use bvhkit::glam::Vec2;
use std::path::Path;

pub(super) fn figures(book_src: &Path) -> Result<Vec<Figure>, FigureError> {
    Ok(vec![builders_pareto(book_src)?])
}

/// A picture drawn in picture units, y down, origin at the top-left corner:
/// an [`Svg`] whose world box is the picture itself. `Svg::new` maps its
/// world box into the picture less a margin of 12 units on each side; a
/// world box of exactly that size, starting at 12, makes the map the
/// identity in x and `y -> height - y` (checked by a test below).
pub(super) struct Pic {
    svg: Svg,
    h: f32,
}

impl Pic {
    pub fn new(w: f32, h: f32) -> Pic {
        Pic {
            svg: Svg::new(w, h, Vec2::splat(12.0), Vec2::new(w - 12.0, h - 12.0)),
            h,
        }
    }
    fn world(&self, x: f32, y: f32) -> Vec2 {
        Vec2::new(x, self.h - y)
    }
    /// A rectangle with top-left corner `(x, y)`.
    pub fn rect(&mut self, x: f32, y: f32, w: f32, h: f32, style: Style) {
        let (lo, hi) = (self.world(x, y + h), self.world(x + w, y));
        self.svg.rect(lo, hi, style);
    }
    pub fn line(&mut self, a: (f32, f32), b: (f32, f32), style: Style) {
        let (p, q) = (self.world(a.0, a.1), self.world(b.0, b.1));
        self.svg.line(p, q, style);
    }
    pub fn polygon(&mut self, pts: &[(f32, f32)], style: Style) {
        let pts: Vec<Vec2> = pts.iter().map(|&(x, y)| self.world(x, y)).collect();
        self.svg.polygon(&pts, style);
    }
    pub fn dot(&mut self, x: f32, y: f32, r: f32, c: &'static str) {
        let p = self.world(x, y);
        self.svg.dot(p, r, c);
    }
    /// A circle of picture radius `r` drawn with `style`.
    pub fn ring(&mut self, x: f32, y: f32, r: f32, style: Style) {
        let p = self.world(x, y);
        self.svg.circle(p, r, style);
    }
    /// Text anchored `start`, `middle` or `end` at `(x, y)` (vertically centred).
    pub fn text(&mut self, x: f32, y: f32, size: f32, anchor: &str, s: &str) {
        self.svg.label_at(Vec2::new(x, y), s, size, anchor);
    }
    /// An arrow from `a` to `b` with a filled head at `b`.
    pub fn arrow(&mut self, a: (f32, f32), b: (f32, f32), c: &'static str) {
        let d = Vec2::new(b.0 - a.0, b.1 - a.1).normalize_or_zero();
        let n = d.perp();
        let tip = Vec2::new(b.0, b.1);
        let base = tip - d * 7.0;
        self.line(a, (base.x, base.y), Style::line(c).width(1.2));
        let (l, r) = (base + n * 3.0, base - n * 3.0);
        self.polygon(
            &[(tip.x, tip.y), (l.x, l.y), (r.x, r.y)],
            Style::filled(c, 1.0).width(0.5),
        );
    }
    pub fn finish(self) -> String {
        self.svg.finish()
    }
}

/// A world window `lo..hi` (y up) drawn into the picture rectangle `at`
/// (left, top, width, height) at one scale on both axes, centred.
pub(super) struct View {
    pub lo: Vec2,
    pub hi: Vec2,
    pub at: [f32; 4],
}

impl View {
    pub fn new(lo: Vec2, hi: Vec2, at: [f32; 4]) -> View {
        View { lo, hi, at }
    }
    /// Picture units per world unit.
    pub fn scale(&self) -> f32 {
        let size = (self.hi - self.lo).max(Vec2::splat(1e-12));
        (self.at[2] / size.x).min(self.at[3] / size.y)
    }
    /// The picture rectangle the window takes: left, top, right, bottom.
    pub fn area(&self) -> [f32; 4] {
        let (a, b) = (
            self.map(Vec2::new(self.lo.x, self.hi.y)),
            self.map(Vec2::new(self.hi.x, self.lo.y)),
        );
        [a.0, a.1, b.0, b.1]
    }
    pub fn map(&self, p: Vec2) -> (f32, f32) {
        let s = self.scale();
        let used = (self.hi - self.lo) * s;
        let left = self.at[0] + (self.at[2] - used.x) * 0.5;
        let top = self.at[1] + (self.at[3] - used.y) * 0.5;
        (left + (p.x - self.lo.x) * s, top + (self.hi.y - p.y) * s)
    }
    pub fn rect(&self, pic: &mut Pic, lo: Vec2, hi: Vec2, style: Style) {
        let (a, b) = (
            self.map(Vec2::new(lo.x, hi.y)),
            self.map(Vec2::new(hi.x, lo.y)),
        );
        pic.rect(a.0, a.1, b.0 - a.0, b.1 - a.1, style);
    }
    pub fn polygon(&self, pic: &mut Pic, pts: &[Vec2], style: Style) {
        let pts: Vec<(f32, f32)> = pts.iter().map(|&p| self.map(p)).collect();
        pic.polygon(&pts, style);
    }
    pub fn line(&self, pic: &mut Pic, a: Vec2, b: Vec2, style: Style) {
        pic.line(self.map(a), self.map(b), style);
    }
}

/// Approximate width of a label in picture units (sans-serif).
pub(super) fn text_width(s: &str, size: f32) -> f32 {
    s.chars().count() as f32 * size * 0.56
}

/// Places labels next to their points without overlapping each other, the
/// points, or anything registered as taken.
#[derive(Default)]
pub(super) struct Labeller {
    /// Taken rectangles: left, top, right, bottom.
    taken: Vec<[f32; 4]>,
    /// Where labels may go: left, top, right, bottom.
    pub bounds: [f32; 4],
}

impl Labeller {
    pub fn new(bounds: [f32; 4]) -> Labeller {
        Labeller {
            taken: Vec::new(),
            bounds,
        }
    }
    pub fn take(&mut self, r: [f32; 4]) {
        self.taken.push(r);
    }
    fn free(&self, r: [f32; 4]) -> bool {
        let b = self.bounds;
        r[0] >= b[0]
            && r[2] <= b[2]
            && r[1] >= b[1]
            && r[3] <= b[3]
            && self
                .taken
                .iter()
                .all(|t| r[2] <= t[0] || t[2] <= r[0] || r[3] <= t[1] || t[3] <= r[1])
    }
    /// Puts `s` near the point `(x, y)` (a marker of radius `r`): to its
    /// right, left, above or below, further out if all are taken (then
    /// with a leader line). Draws it on `pic`.
    pub fn place(&mut self, pic: &mut Pic, x: f32, y: f32, r: f32, s: &str, size: f32) {
        let (w, h) = (text_width(s, size), size);
        for step in 0..8 {
            let d = r + 3.0 + step as f32 * 9.0;
            // (centre of the label box) for each direction.
            let candidates = [
                (x + d + w * 0.5, y),
                (x - d - w * 0.5, y),
                (x, y - d - h * 0.5),
                (x, y + d + h * 0.5),
                (x + d * 0.7 + w * 0.5, y - d * 0.7 - h * 0.5),
                (x + d * 0.7 + w * 0.5, y + d * 0.7 + h * 0.5),
                (x - d * 0.7 - w * 0.5, y - d * 0.7 - h * 0.5),
                (x - d * 0.7 - w * 0.5, y + d * 0.7 + h * 0.5),
            ];
            for (k, (cx, cy)) in candidates.into_iter().enumerate() {
                let rect = [cx - w * 0.5, cy - h * 0.5, cx + w * 0.5, cy + h * 0.5];
                if self.free(rect) {
                    if step > 0 || k >= 4 {
                        // A leader from the marker to the nearest point of the box.
                        let nx = x.clamp(rect[0], rect[2]);
                        let ny = y.clamp(rect[1], rect[3]);
                        pic.line((x, y), (nx, ny), Style::line("#777777").width(0.7));
                    }
                    // A white ground, so that grid and lines pass behind.
                    pic.rect(
                        rect[0] - 1.0,
                        rect[1],
                        w + 2.0,
                        h,
                        Style::filled("#ffffff", 0.85).width(0.0),
                    );
                    pic.text(cx, cy, size, "middle", s);
                    self.taken.push(rect);
                    return;
                }
            }
        }
        // Nowhere free: right of the point, overlapping.
        pic.text(x + r + 3.0, y, size, "start", s);
    }
}

/// A plot area: `[left, top, right, bottom]` in picture units, a data range
/// on each axis, x on a log scale or not.
pub(super) struct Axes {
    pub area: [f32; 4],
    pub x: (f64, f64),
    pub y: (f64, f64),
    pub log_x: bool,
}

impl Axes {
    pub fn px(&self, x: f64) -> f32 {
        let t = if self.log_x {
            (x.log10() - self.x.0.log10()) / (self.x.1.log10() - self.x.0.log10())
        } else {
            (x - self.x.0) / (self.x.1 - self.x.0)
        };
        self.area[0] + (self.area[2] - self.area[0]) * t as f32
    }
    pub fn py(&self, y: f64) -> f32 {
        let t = (y - self.y.0) / (self.y.1 - self.y.0);
        self.area[3] - (self.area[3] - self.area[1]) * t as f32
    }
    /// Frame, grid lines and tick labels; axis titles under and beside.
    pub fn draw(&self, pic: &mut Pic, x_ticks: &[f64], y_ticks: &[f64], titles: (&str, &str)) {
        let [l, t, r, b] = self.area;
        let grid = Style::line("#dddddd").width(0.8);
        for &x in x_ticks {
            let px = self.px(x);
            pic.line((px, t), (px, b), grid);
            pic.text(px, b + 11.0, 11.0, "middle", &tick(x));
        }
        for &y in y_ticks {
            let py = self.py(y);
            pic.line((l, py), (r, py), grid);
            pic.text(l - 5.0, py, 11.0, "end", &tick(y));
        }
        pic.rect(l, t, r - l, b - t, Style::line("#444444").width(1.0));
        pic.text((l + r) * 0.5, b + 28.0, 12.0, "middle", titles.0);
        if !titles.1.is_empty() {
            pic.text(l, t - 10.0, 12.0, "start", titles.1);
        }
    }
}

/// A tick label: no trailing zeros.
fn tick(v: f64) -> String {
    if v == v.round() {
        format!("{v:.0}")
    } else {
        let s = format!("{v:.2}");
        s.trim_end_matches('0').to_string()
    }
}

/// 1, 2, 5 times powers of ten within `[lo, hi]`.
pub(super) fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut p = 10f64.powf(lo.log10().floor());
    while p <= hi {
        for m in [1.0, 2.0, 5.0] {
            let v = p * m;
            if v >= lo && v <= hi {
                out.push(v);
            }
        }
        p *= 10.0;
    }
    out
}

/// Multiples of `step` within `[lo, hi]`.
pub(super) fn linear_ticks(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let mut v = (lo / step).ceil() * step;
    let mut out = Vec::new();
    while v <= hi + 1e-9 {
        out.push(v);
        v += step;
    }
    out
}

/// A builder's row of the recorded run.
struct Row {
    builder: String,
    build_ms: f64,
    sah: f64,
    /// Bold in the chapter's table: on the front of build time, SAH and
    /// query time.
    bold: bool,
}

fn recorded_rows(book_src: &Path, scene: &str) -> Result<(Vec<Row>, String, String), FigureError> {
    let path = book_src.join("measured/bench/report.json");
    let text = std::fs::read_to_string(&path)
        .map_err(|e| FigureError(format!("{}: {e}", path.display())))?;
    let json: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| FigureError(format!("{}: {e}", path.display())))?;
    let bad = |what: &str| FigureError(format!("{}: no {what}", path.display()));
    let mut rows = Vec::new();
    for b in json["builders"].as_array().ok_or_else(|| bad("builders"))? {
        if b["scene"] != scene {
            continue;
        }
        rows.push(Row {
            builder: b["builder"].as_str().ok_or_else(|| bad("builder"))?.into(),
            build_ms: b["build_ms"].as_f64().ok_or_else(|| bad("build_ms"))?,
            sah: b["sah_cost"].as_f64().ok_or_else(|| bad("sah_cost"))?,
            bold: b["pareto"].as_bool().ok_or_else(|| bad("pareto"))?,
        });
    }
    if rows.is_empty() {
        return Err(bad(&format!("builder rows of scene {scene}")));
    }
    let about = json["scene"].as_str().unwrap_or_default().to_string();
    let recorded = json["recorded"].as_str().unwrap_or_default().to_string();
    Ok((rows, about, recorded))
}

/// The builders of the recorded run on the rocks: build time (log) against
/// SAH cost, the front of the two drawn as a staircase.
fn builders_pareto(book_src: &Path) -> Result<Figure, FigureError> {
    let (rows, about, recorded) = recorded_rows(book_src, "rocks")?;
    let keys: Vec<[f64; 2]> = rows.iter().map(|r| [r.build_ms, r.sah]).collect();
    let front = crate::report::pareto(&keys);
    let (w, h) = (880.0, 470.0);
    let mut pic = Pic::new(w, h);
    pic.text(
        w * 0.5,
        16.0,
        14.0,
        "middle",
        &format!("Builders on {about}: build time against SAH cost"),
    );
    pic.text(
        w * 0.5,
        33.0,
        11.0,
        "middle",
        &format!("recorded run ({recorded})"),
    );
    let (xmin, xmax) = rows.iter().fold((f64::INFINITY, 0f64), |(a, b), r| {
        (a.min(r.build_ms), b.max(r.build_ms))
    });
    let (ymin, ymax) = rows.iter().fold((f64::INFINITY, 0f64), |(a, b), r| {
        (a.min(r.sah), b.max(r.sah))
    });
    let axes = Axes {
        area: [60.0, 60.0, w - 20.0, h - 50.0],
        x: (xmin / 1.25, xmax * 1.6),
        y: ((ymin - 3.0).floor(), (ymax + 3.0).ceil()),
        log_x: true,
    };
    axes.draw(
        &mut pic,
        &log_ticks(axes.x.0, axes.x.1),
        &linear_ticks(axes.y.0, axes.y.1, 5.0),
        ("build time, ms (log scale)", "SAH cost"),
    );
    // The front as a staircase: what it dominates lies above and right.
    let mut on: Vec<&Row> = rows
        .iter()
        .zip(&front)
        .filter(|(_, &f)| f)
        .map(|(r, _)| r)
        .collect();
    on.sort_by(|a, b| a.build_ms.total_cmp(&b.build_ms));
    let red = colour(5);
    for pair in on.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        let corner = (axes.px(b.build_ms), axes.py(a.sah));
        pic.line(
            (axes.px(a.build_ms), axes.py(a.sah)),
            corner,
            Style::line(red).dashed(),
        );
        pic.line(
            corner,
            (axes.px(b.build_ms), axes.py(b.sah)),
            Style::line(red).dashed(),
        );
    }
    let mut labels = Labeller::new([
        axes.area[0] + 2.0,
        axes.area[1] + 2.0,
        axes.area[2] - 2.0,
        axes.area[3] - 2.0,
    ]);
    // Legend, top right.
    let (lx, ly) = (
        axes.area[2] - 330.0,
        (axes.area[1] + axes.area[3]) * 0.5 - 30.0,
    );
    pic.rect(
        lx - 10.0,
        ly - 12.0,
        322.0,
        44.0,
        Style {
            stroke: "#bbbbbb",
            ..Style::filled("#ffffff", 1.0).width(0.8)
        },
    );
    pic.dot(lx, ly, 5.0, red);
    pic.text(
        lx + 10.0,
        ly,
        11.0,
        "start",
        "on the front of build time and SAH cost",
    );
    pic.dot(lx, ly + 20.0, 3.5, colour(0));
    pic.ring(lx, ly + 20.0, 7.0, Style::line(colour(2)).width(1.6));
    pic.text(
        lx + 10.0,
        ly + 20.0,
        11.0,
        "start",
        "bold in the table (front with query time too)",
    );
    labels.take([lx - 10.0, ly - 12.0, lx + 322.0, ly + 32.0]);
    for r in &rows {
        let (x, y) = (axes.px(r.build_ms), axes.py(r.sah));
        let r = if r.bold { 8.5 } else { 5.0 };
        labels.take([x - r, y - r, x + r, y + r]);
    }
    for (r, &f) in rows.iter().zip(&front) {
        let (x, y) = (axes.px(r.build_ms), axes.py(r.sah));
        if r.bold {
            pic.ring(x, y, 7.0, Style::line(colour(2)).width(1.6));
        }
        if f {
            pic.dot(x, y, 5.0, red);
        } else {
            pic.dot(x, y, 3.5, colour(0));
        }
    }
    // Front labels first, with their numbers.
    let mut order: Vec<usize> = (0..rows.len()).collect();
    order.sort_by_key(|&i| !front[i]);
    for i in order {
        let r = &rows[i];
        let (x, y) = (axes.px(r.build_ms), axes.py(r.sah));
        let s = if front[i] {
            format!("{}: {:.1} ms, SAH {:.2}", r.builder, r.build_ms, r.sah)
        } else {
            r.builder.clone()
        };
        labels.place(&mut pic, x, y, 5.0, &s, 10.5);
    }
    Ok(Figure {
        name: "performance-builders-pareto",
        chapter: "performance.md",
        svg: pic.finish(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pic_draws_in_picture_units() {
        let mut pic = Pic::new(200.0, 100.0);
        pic.rect(10.0, 20.0, 30.0, 40.0, Style::line("#000000"));
        let out = pic.finish();
        assert!(
            out.contains(r#"<rect x="10.00" y="20.00" width="30.00" height="40.00""#),
            "{out}"
        );
    }

    #[test]
    fn ticks_are_one_two_five() {
        assert_eq!(log_ticks(3.0, 60.0), [5.0, 10.0, 20.0, 50.0]);
        assert_eq!(linear_ticks(33.0, 47.0, 5.0), [35.0, 40.0, 45.0]);
    }
}
