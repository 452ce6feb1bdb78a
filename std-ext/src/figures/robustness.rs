//! Figures of the book's `robustness.md` chapter: outward rounding made
//! visible. Near 2^20 the `f32` values are 0.125 apart, so the grid of
//! representable coordinates can be drawn; the bounds the library stores
//! (a sphere's box, a sliver's 18-DOP) sit on grid lines outside the exact
//! bounds, where rounding to nearest could have cut into the shape.

use super::performance::{text_width, Pic, View};
use super::svg::{colour, Style};
use super::{kdop_section, lift, Figure, FigureError};
use bvhkit::glam::{Vec2, Vec3};
use bvhkit::{BoundingVolume, Dop18, Sphere};
use std::path::Path;

pub(super) fn figures(book_src: &Path) -> Result<Vec<Figure>, FigureError> {
    let _ = book_src;
    Ok(vec![outward_rounding()?])
}

/// Where the scene sits: 2^20 = 1 048 576 on x and y. Every coordinate is
/// drawn as its offset from here, computed in `f64` (exact).
const BASE: f64 = 1_048_576.0;

fn local(v: f32) -> f32 {
    (v as f64 - BASE) as f32
}

fn local2(p: Vec3) -> Vec2 {
    Vec2::new(local(p.x), local(p.y))
}

/// The scene's points as `f32` coordinates near `BASE` (offsets on the
/// 0.125 grid there, so each is exactly an `f32`).
fn at_base(offsets: &[(f32, f32)]) -> Vec<Vec2> {
    offsets
        .iter()
        .map(|&(x, y)| Vec2::new((BASE + x as f64) as f32, (BASE + y as f64) as f32))
        .collect()
}

/// Grid lines at every `f32` value of the window (offsets from `BASE`,
/// `step` apart), every other value written beside it.
fn grid(pic: &mut Pic, v: &View, step: f32) {
    let faint = Style::line("#d4d4d4").width(0.7);
    let first = (v.lo.x / step).ceil() as i32;
    let last = (v.hi.x / step).floor() as i32;
    let [x0, y0, x1, y1] = v.area();
    for k in first..=last {
        let t = k as f32 * step;
        let (px, py) = v.map(Vec2::splat(t));
        pic.line((px, y0), (px, y1), faint);
        pic.line((x0, py), (x1, py), faint);
        if k % 2 == 0 {
            pic.text(px, y1 + 10.0, 9.5, "middle", &format!("{t}"));
            pic.text(x0 - 4.0, py, 9.5, "end", &format!("{t}"));
        }
    }
    pic.rect(x0, y0, x1 - x0, y1 - y0, Style::line("#888888").width(0.8));
}

fn outward_rounding() -> Result<Figure, FigureError> {
    // One f32 step at BASE, from the float itself.
    let step = ((BASE as f32).next_up() as f64 - BASE) as f32;
    let (lo, hi) = (Vec2::splat(-0.125), Vec2::splat(1.125));
    let (w, h) = (880.0, 445.0);
    let mut pic = Pic::new(w, h);
    let side = 290.0;
    let views = [
        View::new(lo, hi, [95.0, 56.0, side, side]),
        View::new(lo, hi, [535.0, 56.0, side, side]),
    ];
    pic.text(
        w * 0.5,
        14.0,
        13.0,
        "middle",
        &format!(
            "Coordinates near 2^20 = {BASE:.0}, drawn as offsets from it: the grid is every f32 value, {step} apart",
        ),
    );

    // Panel 1: Welzl's sphere around five points, and its box.
    let pts = at_base(&[
        (0.625, 0.75),
        (0.375, 0.25),
        (0.75, 0.375),
        (0.25, 0.625),
        (0.375, 0.5),
    ]);
    let sphere = Sphere::welzl(lift(&pts).as_slice());
    let stored = sphere.aabb();
    let (c, r) = (sphere.center, sphere.radius);
    // Exact c +/- r (f64), and what f32 arithmetic stores (each sum
    // rounded to the nearest f32).
    let exact_lo = Vec2::new(
        (c.x as f64 - r as f64 - BASE) as f32,
        (c.y as f64 - r as f64 - BASE) as f32,
    );
    let exact_hi = Vec2::new(
        (c.x as f64 + r as f64 - BASE) as f32,
        (c.y as f64 + r as f64 - BASE) as f32,
    );
    let near_lo = Vec2::new(local(c.x - r), local(c.y - r));
    let near_hi = Vec2::new(local(c.x + r), local(c.y + r));
    let v = &views[0];
    pic.text(
        v.at[0] + side * 0.5,
        38.0,
        12.0,
        "middle",
        "Welzl's sphere around 5 points, and its box c ± r",
    );
    grid(&mut pic, v, step);
    let (cx, cy) = v.map(local2(c));
    pic.ring(cx, cy, r * v.scale(), Style::filled(colour(2), 0.15));
    v.rect(
        &mut pic,
        exact_lo,
        exact_hi,
        Style::line("#000000").width(1.0).dashed(),
    );
    v.rect(
        &mut pic,
        near_lo,
        near_hi,
        Style::line(colour(5)).width(1.8).dashed(),
    );
    v.rect(
        &mut pic,
        local2(stored.min),
        local2(stored.max),
        Style::line(colour(0)).width(2.0),
    );
    for &p in &pts {
        let (x, y) = v.map(Vec2::new(local(p.x), local(p.y)));
        pic.dot(x, y, 3.0, "#000000");
    }
    let y_text = v.at[1] + side + 30.0;
    let x_text = v.at[0] - 60.0;
    pic.text(
        x_text,
        y_text,
        10.5,
        "start",
        &format!("r = {r} (rounded up); each side of the box:"),
    );
    let sides = [
        ("c.x + r", exact_hi.x, near_hi.x, local(stored.max.x), 1.0),
        ("c.x − r", exact_lo.x, near_lo.x, local(stored.min.x), -1.0),
    ];
    for (k, (name, exact, near, kept, out)) in sides.into_iter().enumerate() {
        let how = if (near - exact) * out < 0.0 {
            "cuts into the sphere"
        } else {
            "outside"
        };
        pic.text(
            x_text,
            y_text + 15.0 * (k + 1) as f32,
            10.5,
            "start",
            &format!("{name} = {exact:.3} exact: nearest {near} {how}, stored {kept}"),
        );
    }

    // Panel 2: a sliver triangle's 18-DOP.
    let tri = at_base(&[(0.125, 0.125), (1.0, 0.875), (0.25, 0.375)]);
    let dop = Dop18::fit(lift(&tri).as_slice());
    // The exact slabs (f64 dot products of the corners) and the stored
    // ones, both as offsets from the base along each direction.
    let (mut exact, mut shown) = (dop, dop);
    for i in 0..9 {
        let [a, b, _] = Dop18::direction(i);
        let offset = (a as f64 + b as f64) * BASE;
        let dots = tri
            .iter()
            .map(|p| a as f64 * p.x as f64 + b as f64 * p.y as f64);
        let (mn, mx) = dots.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), d| {
            (l.min(d), h.max(d))
        });
        exact.min[i] = (mn - offset) as f32;
        exact.max[i] = (mx - offset) as f32;
        shown.min[i] = (dop.min[i] as f64 - offset) as f32;
        shown.max[i] = (dop.max[i] as f64 - offset) as f32;
    }
    let v = &views[1];
    pic.text(
        v.at[0] + side * 0.5,
        38.0,
        12.0,
        "middle",
        "A sliver triangle's 18-DOP (section at z = 0)",
    );
    grid(&mut pic, v, step);
    v.polygon(
        &mut pic,
        &kdop_section(&shown),
        Style::filled(colour(0), 0.10).width(2.0),
    );
    v.polygon(
        &mut pic,
        &kdop_section(&exact),
        Style::line("#000000").width(1.0).dashed(),
    );
    let corners: Vec<Vec2> = tri
        .iter()
        .map(|p| Vec2::new(local(p.x), local(p.y)))
        .collect();
    v.polygon(&mut pic, &corners, Style::filled(colour(1), 0.7).width(1.0));
    // The slabs of x + y (values near 2^21) and x - y (near 0).
    let slab = |d: [i8; 3]| {
        (0..9)
            .find(|&i| Dop18::direction(i) == d)
            .ok_or_else(|| FigureError(format!("the 18-DOP has no direction {d:?}")))
    };
    let (plus, minus) = (slab([1, 1, 0])?, slab([1, -1, 0])?);
    let x_steps = (shown.max[0] - exact.max[0]) / step;
    let plus_step = ((2.0 * BASE) as f32).next_up() as f64 - 2.0 * BASE;
    let lines = [
        format!(
            "x ≤ {} exact, stored {} ({x_steps} step out)",
            exact.max[0], shown.max[0]
        ),
        format!(
            "x + y ≤ {} exact, stored {} (f32 step {plus_step} near 2^21)",
            exact.max[plus], shown.max[plus]
        ),
        format!(
            "x − y ≥ {} exact, stored {:.1e} lower (fine steps near 0)",
            exact.min[minus],
            exact.min[minus] as f64 - shown.min[minus] as f64
        ),
    ];
    for (k, s) in lines.iter().enumerate() {
        pic.text(v.at[0] - 60.0, y_text + 15.0 * k as f32, 10.5, "start", s);
    }
    legend(&mut pic, (w * 0.5 - 330.0, h - 16.0));
    Ok(Figure {
        name: "robustness-outward-rounding",
        chapter: "robustness.md",
        svg: pic.finish(),
    })
}

/// The line styles, explained in one row from `at`.
fn legend(pic: &mut Pic, at: (f32, f32)) {
    let rows: [(&str, Style); 3] = [
        (
            "exact bound (f64)",
            Style::line("#000000").width(1.0).dashed(),
        ),
        (
            "rounded to the nearest f32",
            Style::line(colour(5)).width(1.8).dashed(),
        ),
        (
            "stored by bvhkit (round::down / up)",
            Style::line(colour(0)).width(2.0),
        ),
    ];
    let mut x = at.0;
    for (name, style) in rows {
        pic.line((x, at.1), (x + 24.0, at.1), style);
        pic.text(x + 30.0, at.1, 10.5, "start", name);
        x += 30.0 + text_width(name, 10.5) + 24.0;
    }
}
