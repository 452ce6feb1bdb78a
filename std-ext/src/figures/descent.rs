//! Figures of the book's `descent-rules.md` chapter: where each descent
//! rule spends its volume tests on one query of two small trees.
//!
//! The pair query reports how many tests it makes ([`Counts`]) and which
//! pairs it finds, not which nodes it opens. So the stack traversal is
//! retraced here over [`Bvh::nodes`], asking the library's own rule
//! ([`DescentRule::choose`]) at every step, and the retrace must make the
//! sequence of tests and pairs the library reports, in order, or the figure
//! fails.

use super::svg::{colour, stack_rows, Style, Svg};
use super::walk_log::{Event, Log};
use super::{Figure, FigureError};
use crate::OwnedBvh;
use bvhkit::glam::{Vec2, Vec3};
use bvhkit::{
    Aabb, Bvh, Content, Counts, Decision, Descent, DescentRule, Hierarchy, Open, Pairs, Primitive,
    TopDown, Triangle,
};
use std::cell::RefCell;
use std::path::Path;

pub(super) fn figures(book_src: &Path) -> Result<Vec<Figure>, FigureError> {
    let _ = book_src;
    Ok(vec![rules_tests()?])
}

/// A closed outline, like the section of a rock: `n` thin triangles around
/// a centre, each from two points of a jagged circle of radius about
/// `radius` at z = 0 to a point inside at z = `lean` (0 for triangles in
/// the plane). Seeded, so always the same.
pub(super) fn outline(n: usize, radius: f32, lean: f32, seed: u64) -> Vec<Triangle> {
    let mut s = seed;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / (1u64 << 24) as f32
    };
    let rim: Vec<Vec2> = (0..n)
        .map(|k| {
            let a = k as f32 / n as f32 * core::f32::consts::TAU;
            Vec2::new(a.cos(), a.sin()) * radius * (0.85 + 0.3 * next())
        })
        .collect();
    (0..n)
        .map(|k| {
            let (p, q) = (rim[k], rim[(k + 1) % n]);
            let inner = (p + q) * 0.5 * 0.7;
            Triangle::new(p.extend(0.0), q.extend(0.0), inner.extend(lean))
        })
        .collect()
}

/// A triangle's corners in the plane.
pub(super) fn corners(t: &Triangle) -> [Vec2; 3] {
    t.v.map(|p| p.truncate())
}

/// What one rule did: how many volume tests it made at each pair of
/// depths (`tests[depth in A][depth in B]`), and the library's counts.
struct Walk {
    tests: Vec<Vec<u64>>,
    counts: Counts,
}

/// The depth of every node of `t`.
fn depths(t: &Bvh<'_, Aabb>) -> Vec<usize> {
    let mut out = vec![0; t.node_count()];
    let mut todo = vec![Hierarchy::root(t)];
    while let Some(n) = todo.pop() {
        for c in kids(t, n) {
            out[c as usize] = out[n as usize] + 1;
            todo.push(c);
        }
    }
    out
}

/// The children of node `n`, or none for a leaf.
fn kids(t: &Bvh<'_, Aabb>, n: u32) -> Vec<u32> {
    match Hierarchy::content(t, n) {
        Content::Inner(k) => k.as_slice().to_vec(),
        Content::Leaf(_) => Vec::new(),
    }
}

/// `Pairs::new(a, pa, b, pb).descent(rule)` (the stack traversal, same
/// frame, the bounds answer), run by the library and retraced.
fn walk(
    a: &Bvh<'_, Aabb>,
    pa: &[Triangle],
    b: &Bvh<'_, Aabb>,
    pb: &[Triangle],
    rule: Descent,
) -> Result<Walk, FigureError> {
    let events = RefCell::new(Vec::new());
    let mut log = Log {
        counts: Counts::default(),
        events: &events,
    };
    let pairs = Pairs::new(a, pa, b, pb)
        .descent(rule)
        .counted(&mut log)
        .for_each(|p, q| events.borrow_mut().push(Event::Pair(p, q)))?;

    let mut mine = Vec::new();
    let (da, db) = (depths(a), depths(b));
    let mut tests = vec![vec![0u64; b.depth() + 1]; a.depth() + 1];
    let bv_a = |n: u32| Hierarchy::bv(a, n);
    let bv_b = |n: u32| Hierarchy::bv(b, n);
    let (ra, rb) = (Hierarchy::root(a), Hierarchy::root(b));
    let mut stack = Vec::new();
    mine.push(Event::Node);
    tests[0][0] += 1;
    if bv_a(ra).overlaps(&bv_b(rb)) {
        stack.push((ra, rb, 0u32));
    }
    while let Some((i, j, depth)) = stack.pop() {
        let (ka, kb) = (kids(a, i), kids(b, j));
        if ka.is_empty() && kb.is_empty() {
            let (Content::Leaf(la), Content::Leaf(lb)) =
                (Hierarchy::content(a, i), Hierarchy::content(b, j))
            else {
                unreachable!("two nodes without children are leaves")
            };
            mine.push(Event::Prims((la.len() * lb.len()) as u32));
            for run in la.chunks(4) {
                for &q in lb {
                    for &p in run {
                        if pa[p as usize].bounds().overlaps(&pb[q as usize].bounds()) {
                            mine.push(Event::Pair(p, q));
                        }
                    }
                }
            }
            continue;
        }
        let open = match (ka.is_empty(), kb.is_empty()) {
            (false, true) => Open::A,
            (true, false) => Open::B,
            _ => {
                let (xa, yb) = (bv_a(i), bv_b(j));
                let (ca, cb): (Vec<Aabb>, Vec<Aabb>) = (
                    ka.iter().map(|&c| bv_a(c)).collect(),
                    kb.iter().map(|&c| bv_b(c)).collect(),
                );
                let wants = rule.wants_children();
                rule.choose(&Decision {
                    a: &xa,
                    b: &yb,
                    a_children: wants.then_some(&ca[..]),
                    b_children: wants.then_some(&cb[..]),
                    depth,
                })
            }
        };
        let side_a = if open == Open::B { vec![i] } else { ka };
        let side_b = if open == Open::A { vec![j] } else { kb };
        // Child pairs are tested before they are pushed, the last first, so
        // that the first pops first.
        for &u in side_a.iter().rev() {
            for &v in side_b.iter().rev() {
                mine.push(Event::Node);
                tests[da[u as usize]][db[v as usize]] += 1;
                if bv_a(u).overlaps(&bv_b(v)) {
                    stack.push((u, v, depth + 1));
                }
            }
        }
    }
    if mine != *events.borrow() {
        return Err(FigureError(format!(
            "the descent figure's walk with rule {} is not the library's",
            rule.name()
        )));
    }
    if pairs == 0 {
        return Err(FigureError(
            "the descent figure's trees do not touch".into(),
        ));
    }
    Ok(Walk {
        tests,
        counts: log.counts,
    })
}

/// Each rule of [`Descent::ALL`] on two outlines, one moved across the
/// other: where its volume tests go, counted by the depths of the two
/// nodes tested; then `Nv` of every rule side by side.
fn rules_tests() -> Result<Figure, FigureError> {
    // Leaning out of the plane, so that every box has a volume: the larger
    // rule compares volumes, which are all zero for boxes of a plane.
    let a = outline(12, 2.0, 0.5, 0x51a7_e0b3_c2d4_9f61);
    let b: Vec<Triangle> = a
        .iter()
        .map(|t| t.translated(Vec3::new(2.6, 0.8, 0.0)))
        .collect();
    let builder = TopDown::default().with_max_leaf_size(1);
    let (ta, tb) = (
        OwnedBvh::<Aabb>::build(&builder, &a)?,
        OwnedBvh::<Aabb>::build(&builder, &b)?,
    );
    let (ta, tb) = (ta.view(), tb.view());
    let walks = Descent::ALL
        .iter()
        .map(|&rule| walk(&ta, &a, &tb, &b, rule))
        .collect::<Result<Vec<_>, _>>()?;
    let (width, row) = (900.0, 250.0);
    // Eight panels, four a row: the scene, the six rules, the totals.
    let mut rows = Vec::new();
    let mut svg = Svg::new(width, row, Vec2::ZERO, Vec2::ONE);
    for slot in 0..8 {
        let k = slot % 4;
        if slot == 4 {
            rows.push((
                row,
                std::mem::replace(&mut svg, Svg::new(width, row, Vec2::ZERO, Vec2::ONE)).finish(),
            ));
        }
        match slot {
            0 => draw_scene(&mut svg, k, (&ta, &a), (&tb, &b)),
            7 => draw_totals(&mut svg, k, &walks),
            _ => draw_tests(&mut svg, k, Descent::ALL[slot - 1], &walks[slot - 1]),
        }
    }
    rows.push((row, svg.finish()));
    Ok(Figure {
        name: "descent-rules-tests",
        chapter: "descent-rules.md",
        svg: stack_rows(width, &rows),
    })
}

/// The two objects and the boxes of their trees.
fn draw_scene(
    svg: &mut Svg,
    k: usize,
    (ta, a): (&Bvh<'_, Aabb>, &[Triangle]),
    (tb, b): (&Bvh<'_, Aabb>, &[Triangle]),
) {
    let all = Hierarchy::bv(ta, 0).union(&Hierarchy::bv(tb, 0));
    let (lo, hi) = (
        all.min.truncate() - Vec2::splat(0.15),
        all.max.truncate() + Vec2::splat(0.15),
    );
    svg.panel(k, 4, lo, hi, "A and B, and their trees");
    for (t, tris, c) in [(ta, a, colour(0)), (tb, b, colour(1))] {
        for node in t.nodes().iter().filter(|n| n.count == 0) {
            svg.rect(
                node.bv.min.truncate(),
                node.bv.max.truncate(),
                Style::line(c).width(0.7),
            );
        }
        for tri in tris {
            svg.polygon(&corners(tri), Style::filled(c, 0.3).width(0.8));
        }
    }
    svg.label(Vec2::new(all.min.x + 0.3, all.max.y - 0.3), "A", 12.0);
    svg.label(Vec2::new(all.max.x - 0.3, all.max.y - 0.3), "B", 12.0);
}

/// One rule: a grid of the depth in A (rows) by the depth in B (columns),
/// each cell the number of volume tests of such a pair.
fn draw_tests(svg: &mut Svg, k: usize, rule: Descent, w: &Walk) {
    let (na, nb) = (w.tests.len() as f32, w.tests[0].len() as f32);
    let (lo, hi) = (Vec2::new(-0.9, -na), Vec2::new(nb, 0.9));
    svg.panel(
        k,
        4,
        lo,
        hi,
        &format!(
            "{}: Nv {}, Np {}",
            rule.name(),
            w.counts.bv_tests,
            w.counts.prim_tests
        ),
    );
    let most = w.tests.iter().flatten().copied().max().unwrap_or(1).max(1);
    for (i, row) in w.tests.iter().enumerate() {
        svg.label(Vec2::new(-0.35, -(i as f32) - 0.5), &i.to_string(), 10.0);
        for (j, &n) in row.iter().enumerate() {
            let (x, y) = (j as f32, -(i as f32) - 1.0);
            let cell = (Vec2::new(x, y), Vec2::new(x + 1.0, y + 1.0));
            if n == 0 {
                svg.rect(cell.0, cell.1, Style::line("#dddddd").width(0.8));
                continue;
            }
            let shade = 0.1 + 0.6 * n as f32 / most as f32;
            svg.rect(cell.0, cell.1, Style::filled(colour(0), shade).width(0.8));
            svg.label(Vec2::new(x + 0.5, y + 0.5), &n.to_string(), 10.0);
        }
    }
    for j in 0..w.tests[0].len() {
        svg.label(Vec2::new(j as f32 + 0.5, 0.35), &j.to_string(), 10.0);
    }
    svg.label(Vec2::new(-0.45, 0.35), "A\\B", 9.0);
}

/// `Nv` of every rule as bars.
fn draw_totals(svg: &mut Svg, k: usize, walks: &[Walk]) {
    let most = walks.iter().map(|w| w.counts.bv_tests).max().unwrap_or(1) as f32;
    let n = walks.len() as f32;
    let (lo, hi) = (Vec2::new(-2.5, -n), Vec2::new(2.5, 0.0));
    svg.panel(k, 4, lo, hi, "Nv by rule");
    for (i, (w, rule)) in walks.iter().zip(Descent::ALL).enumerate() {
        let y = -(i as f32) - 1.0;
        let len = 2.0 * w.counts.bv_tests as f32 / most;
        svg.rect(
            Vec2::new(0.0, y + 0.2),
            Vec2::new(len, y + 0.8),
            Style::filled(colour(0), 0.5).width(0.8),
        );
        svg.label(Vec2::new(-1.25, y + 0.5), rule.name(), 10.0);
        svg.label(
            Vec2::new(len + 0.25, y + 0.5),
            &w.counts.bv_tests.to_string(),
            10.0,
        );
    }
}
