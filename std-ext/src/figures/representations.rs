//! Figures of the book's `representations.md` chapter: one small tree
//! (seven triangles in the plane, binned SAH, one per leaf) as the library
//! lays it out: the pointerless array with its holes, the preorder records
//! with their right links, a 4-wide record's boxes side by side, and a
//! quantized record's 8-bit grid. Every position, link and box is read
//! back from the converted layout.

use super::performance::{text_width, Pic, View};
use super::svg::{colour, Style};
use super::{Figure, FigureError};
use bvhkit::glam::{Vec2, Vec3};
use bvhkit::layout::{Implicit, PreNode, Preorder, QuantNode, Slot, Wide, WideNode, ESCAPE};
use bvhkit::{Aabb, Bvh, Content, Hierarchy, Node, TopDown, Triangle};
use std::path::Path;

pub(super) fn figures(book_src: &Path) -> Result<Vec<Figure>, FigureError> {
    let _ = book_src;
    let tris = scene();
    let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(tris.len())];
    let mut idx = vec![0u32; tris.len()];
    let tree = TopDown::sah()
        .with_max_leaf_size(1)
        .build(&tris, &mut nodes, &mut idx)?;
    let mut slots = vec![Slot::EMPTY; Implicit::slots_needed(&tree)?];
    let implicit = Implicit::from_bvh(&tree, &mut slots)?;
    let mut records = vec![PreNode::<Aabb, u16>::EMPTY; tree.node_count()];
    let pre = Preorder::from_bvh(&tree, &mut records)?;
    let drawn = walk(&tree, &implicit, &pre)?;
    let mut wide_records = vec![WideNode::EMPTY; Wide::records_needed(&tree)?];
    let wide = Wide::from_bvh(&tree, &mut wide_records)?;
    Ok(vec![
        implicit_figure(&tree, &implicit, &drawn),
        preorder_figure(&pre, &drawn),
        wide_figure(&tris, &tree, &wide)?,
        quantized_figure(&wide)?,
    ])
}

/// Seven small triangles in the plane, in three uneven groups: the SAH
/// tree over them is deeper on one side.
fn scene() -> Vec<Triangle> {
    let centres = [
        (0.4, 1.1, 0.3),
        (0.9, 2.9, 0.3),
        (1.6, 1.3, 0.3),
        (3.2, 4.8, 0.4),
        (3.8, 2.2, 0.3),
        (7.0, 1.8, 0.5),
        (9.5, 6.2, 0.6),
    ];
    centres
        .iter()
        .map(|&(x, y, s)| {
            let c = Vec3::new(x, y, 0.0);
            Triangle::new(
                c + Vec3::new(-s, -0.6 * s, 0.0),
                c + Vec3::new(s, -0.4 * s, 0.0),
                c + Vec3::new(0.2 * s, s, 0.0),
            )
        })
        .collect()
}

/// One node of the tree as the figures draw it.
struct Drawn {
    /// Its letter: A, B, ... level by level, left to right.
    letter: char,
    /// Its entry in the pointerless array (also its place in a complete
    /// tree's drawing).
    slot: usize,
    /// Its preorder record.
    record: usize,
    /// The triangle of a leaf.
    prim: Option<u32>,
}

/// The tree level by level, with each node's place in the two arrays,
/// found by walking the three views side by side (each must agree on the
/// node's box).
fn walk(
    tree: &Bvh<'_, Aabb>,
    implicit: &Implicit<'_, Aabb>,
    pre: &Preorder<'_, Aabb, u16>,
) -> Result<Vec<Drawn>, FigureError> {
    let mut out = Vec::new();
    let mut queue = std::collections::VecDeque::from([(
        Hierarchy::root(tree),
        Hierarchy::root(implicit) as usize,
        Hierarchy::root(pre) as usize,
    )]);
    while let Some((n, s, r)) = queue.pop_front() {
        let bv = Hierarchy::bv(tree, n);
        if implicit.bv(s as u32) != bv || pre.bv(r as u32) != bv {
            return Err(FigureError(format!(
                "node {n}: the layouts disagree on its box"
            )));
        }
        let letter = char::from(b'A' + (out.len() % 26) as u8);
        let prim = match (
            tree.content(n),
            implicit.content(s as u32),
            pre.content(r as u32),
        ) {
            (Content::Leaf(ids), Content::Leaf(_), Content::Leaf(_)) => ids.first().copied(),
            (Content::Inner(a), Content::Inner(b), Content::Inner(c)) => {
                for k in 0..2 {
                    queue.push_back((
                        a.as_slice()[k],
                        b.as_slice()[k] as usize,
                        c.as_slice()[k] as usize,
                    ));
                }
                None
            }
            _ => {
                return Err(FigureError(format!(
                    "node {n}: the layouts disagree on its children"
                )))
            }
        };
        out.push(Drawn {
            letter,
            slot: s,
            record: r,
            prim,
        });
    }
    Ok(out)
}

const INNER_FILL: &str = "#cfe3f3";
const LEAF_FILL: &str = "#f7dfae";
const HOLE_FILL: &str = "#e6e6e6";

/// Where entry `slot` of a complete tree is drawn, in `[left, right]`
/// from `top`, `dy` per level.
fn tree_pos(slot: usize, left: f32, right: f32, top: f32, dy: f32) -> (f32, f32) {
    let level = (usize::BITS - 1 - (slot + 1).leading_zeros()) as usize;
    let p = slot + 1 - (1 << level);
    let w = (right - left) / (1 << level) as f32;
    (left + (p as f32 + 0.5) * w, top + level as f32 * dy)
}

/// A node of a tree drawing: a circle (inner) or a square (leaf) with its
/// letter, and a small note under it.
fn node_mark(pic: &mut Pic, (x, y): (f32, f32), d: &Drawn, note: &str) {
    let r = 10.0;
    if d.prim.is_some() {
        pic.rect(
            x - r,
            y - r,
            2.0 * r,
            2.0 * r,
            Style::filled(LEAF_FILL, 1.0).width(1.0),
        );
        pic.rect(
            x - r,
            y - r,
            2.0 * r,
            2.0 * r,
            Style::line("#8a6d2b").width(1.0),
        );
    } else {
        pic.ring(x, y, r, Style::filled(INNER_FILL, 1.0).width(1.0));
        pic.ring(x, y, r, Style::line("#3d6f99").width(1.0));
    }
    pic.text(x, y + 0.5, 11.0, "middle", &d.letter.to_string());
    if !note.is_empty() {
        pic.text(x + r + 2.0, y + r, 8.5, "start", note);
    }
}

/// A curve from `x0` to `x1` bulging `height` above (`height > 0`) or
/// below the line `y`, with an arrow head at `x1`.
fn arc(pic: &mut Pic, x0: f32, x1: f32, y: f32, height: f32, c: &'static str) {
    let n = 24;
    let pts: Vec<(f32, f32)> = (0..=n)
        .map(|i| {
            let t = i as f32 / n as f32;
            (
                x0 + (x1 - x0) * t,
                y - height * (std::f32::consts::PI * t).sin(),
            )
        })
        .collect();
    for seg in pts.windows(2).take(n - 2) {
        pic.line(seg[0], seg[1], Style::line(c).width(1.2));
    }
    pic.arrow(pts[n - 2], pts[n], c);
}

fn cell(pic: &mut Pic, x: f32, y: f32, w: f32, h: f32, fill: &'static str, text: &str) {
    pic.rect(x, y, w, h, Style::filled(fill, 1.0).width(0.0));
    pic.rect(x, y, w, h, Style::line("#555555").width(0.8));
    pic.text(x + w * 0.5, y + h * 0.5 + 0.5, 11.0, "middle", text);
}

fn implicit_figure(tree: &Bvh<'_, Aabb>, implicit: &Implicit<'_, Aabb>, drawn: &[Drawn]) -> Figure {
    let slots = implicit.slots();
    let (w, h) = (880.0, 48.0 + 40.0 * tree.depth() as f32 + 162.0);
    let mut pic = Pic::new(w, h);
    pic.text(
        w * 0.5,
        14.0,
        13.0,
        "middle",
        &format!(
            "Pointerless array: {} nodes of depth {} take 2^({}+1) − 1 = {} entries, {} of them holes",
            tree.node_count(),
            tree.depth(),
            tree.depth(),
            slots.len(),
            implicit.unused()
        ),
    );
    let (left, right, top, dy) = (20.0, w - 20.0, 48.0, 40.0);
    let at = |s: usize| tree_pos(s, left, right, top, dy);
    let hole = Style::line("#aaaaaa").width(0.8).dashed();
    // Edges first, then nodes over them; holes dashed.
    for (s, slot) in slots.iter().enumerate().skip(1) {
        let style = if slot.is_unused() {
            hole
        } else {
            Style::line("#555555").width(1.0)
        };
        pic.line(at((s - 1) / 2), at(s), style);
    }
    for (s, slot) in slots.iter().enumerate() {
        if slot.is_unused() {
            let (x, y) = at(s);
            pic.ring(x, y, 6.0, Style::filled("#ffffff", 1.0).width(0.0));
            pic.ring(x, y, 6.0, hole);
        }
    }
    for d in drawn {
        node_mark(&mut pic, at(d.slot), d, &d.slot.to_string());
    }
    // The array, level by level.
    let n = slots.len();
    let cw = ((w - 40.0) / n as f32).min(44.0);
    let x0 = (w - cw * n as f32) * 0.5;
    let y0 = top + dy * (tree.depth() as f32) + 70.0;
    for level in 0..=tree.depth() {
        let (a, b) = ((1usize << level) - 1, (2usize << level) - 2);
        let (xa, xb) = (x0 + cw * a as f32 + 2.0, x0 + cw * (b + 1) as f32 - 2.0);
        pic.line(
            (xa, y0 - 6.0),
            (xb, y0 - 6.0),
            Style::line("#777777").width(1.0),
        );
        let name = format!("level {level}");
        let name = if text_width(&name, 9.5) < xb - xa {
            name
        } else {
            format!("{level}")
        };
        pic.text((xa + xb) * 0.5, y0 - 15.0, 9.5, "middle", &name);
    }
    for (s, slot) in slots.iter().enumerate() {
        let x = x0 + cw * s as f32;
        let (fill, text) = match drawn.iter().find(|d| d.slot == s) {
            Some(d) if d.prim.is_some() => (LEAF_FILL, d.letter.to_string()),
            Some(d) => (INNER_FILL, d.letter.to_string()),
            None => (HOLE_FILL, String::new()),
        };
        debug_assert_eq!(slot.is_unused(), text.is_empty());
        cell(&mut pic, x, y0, cw, 24.0, fill, &text);
        pic.text(x + cw * 0.5, y0 + 33.0, 8.5, "middle", &s.to_string());
    }
    // The children of the first inner entry below the root, by arithmetic.
    if let Some(d) = drawn
        .iter()
        .find(|d| d.slot > 0 && d.prim.is_none())
        .or_else(|| drawn.first())
    {
        let i = d.slot;
        let mid = |s: usize| x0 + cw * (s as f32 + 0.5);
        let yb = y0 + 40.0;
        for c in [2 * i + 1, 2 * i + 2] {
            arc(
                &mut pic,
                mid(i),
                mid(c),
                yb,
                -(14.0 + 3.0 * (c - i) as f32),
                colour(0),
            );
        }
        pic.text(
            mid(2 * i + 2) + 14.0,
            yb + 16.0,
            10.5,
            "start",
            &format!(
                "the children of entry {i} ({}) are entries 2·{i} + 1 = {} and 2·{i} + 2 = {}: no links stored",
                d.letter,
                2 * i + 1,
                2 * i + 2
            ),
        );
    }
    Figure {
        name: "representations-implicit",
        chapter: "representations.md",
        svg: pic.finish(),
    }
}

fn preorder_figure(pre: &Preorder<'_, Aabb, u16>, drawn: &[Drawn]) -> Figure {
    let records = pre.records();
    let depth = drawn
        .iter()
        .map(|d| tree_pos(d.slot, 0.0, 1.0, 0.0, 1.0).1 as usize)
        .max()
        .unwrap_or(0);
    let (top, dy) = (44.0, 34.0);
    let longest = (0..records.len())
        .filter_map(|r| Some(pre.right(r)? - r))
        .max()
        .unwrap_or(0);
    let arc_height = |d: usize| 12.0 + 9.0 * d as f32;
    let y0 = top + dy * depth as f32 + 30.0 + arc_height(longest);
    let (w, h) = (880.0, y0 + 86.0);
    let mut pic = Pic::new(w, h);
    pic.text(
        w * 0.5,
        14.0,
        13.0,
        "middle",
        &format!(
            "Preorder: {} records of {} B (16-bit links); the left child is the next record",
            records.len(),
            core::mem::size_of::<PreNode<Aabb, u16>>()
        ),
    );
    // The tree, drawn as in the pointerless figure, numbered by record.
    let (left, right) = (150.0, w - 150.0);
    let at = |s: usize| tree_pos(s, left, right, top, dy);
    for d in drawn.iter().filter(|d| d.slot > 0) {
        pic.line(
            at((d.slot - 1) / 2),
            at(d.slot),
            Style::line("#555555").width(1.0),
        );
    }
    for d in drawn {
        node_mark(&mut pic, at(d.slot), d, &d.record.to_string());
    }
    // The records, with each right link as an arc over them.
    let n = records.len();
    let cw = ((w - 40.0) / n as f32).min(52.0);
    let x0 = (w - cw * n as f32) * 0.5;
    let mid = |r: usize| x0 + cw * (r as f32 + 0.5);
    for (r, rec) in records.iter().enumerate() {
        let Some(right) = pre.right(r) else { continue };
        let hgt = arc_height(right - r);
        arc(&mut pic, mid(r), mid(right), y0 - 2.0, hgt, colour(5));
        let apex = (mid(r) + mid(right)) * 0.5;
        pic.rect(
            apex - 11.0,
            y0 - 2.0 - hgt - 7.0,
            22.0,
            13.0,
            Style::filled("#ffffff", 1.0).width(0.0),
        );
        pic.text(
            apex,
            y0 - 2.0 - hgt,
            10.0,
            "middle",
            &format!("+{}", rec.link()),
        );
    }
    for (r, rec) in records.iter().enumerate() {
        let d = drawn.iter().find(|d| d.record == r);
        let letter = d.map(|d| d.letter.to_string()).unwrap_or_default();
        let fill = if rec.has_left_child() {
            INNER_FILL
        } else {
            LEAF_FILL
        };
        cell(&mut pic, x0 + cw * r as f32, y0, cw, 24.0, fill, &letter);
        pic.text(mid(r), y0 + 33.0, 8.5, "middle", &r.to_string());
        if let Some(p) = d.and_then(|d| d.prim) {
            pic.text(mid(r), y0 + 46.0, 8.5, "middle", &format!("tri {p}"));
        }
    }
    pic.text(
        w * 0.5,
        y0 + 68.0,
        10.5,
        "middle",
        &format!(
            "arcs: the right child, stored as an offset from the record; far table: {} entries (a link escapes only past {} records)",
            pre.far_links().len(),
            ESCAPE - 1
        ),
    );
    Figure {
        name: "representations-preorder",
        chapter: "representations.md",
        svg: pic.finish(),
    }
}

/// The children of a wide node, with their boxes.
fn kids_of(wide: &Wide<'_>, node: u32) -> Vec<u32> {
    match wide.content(node) {
        Content::Inner(k) => k.as_slice().to_vec(),
        Content::Leaf(_) => Vec::new(),
    }
}

fn v2(p: Vec3) -> Vec2 {
    Vec2::new(p.x, p.y)
}

fn wide_figure(
    tris: &[Triangle],
    tree: &Bvh<'_, Aabb>,
    wide: &Wide<'_>,
) -> Result<Figure, FigureError> {
    let top_kids = kids_of(wide, wide.root());
    let Some(&first) = top_kids.first() else {
        return Err(FigureError("the wide tree has no inner root".into()));
    };
    let record_index = (first / 4) as usize;
    let record = &wide.records()[record_index];
    let (w, h) = (880.0, 340.0);
    let mut pic = Pic::new(w, h);
    pic.text(
        w * 0.5,
        14.0,
        13.0,
        "middle",
        &format!(
            "4-wide records: {} records for {} binary nodes; depth {} becomes {}",
            wide.records().len(),
            tree.node_count(),
            tree.depth(),
            wide.depth()
        ),
    );
    // Left: the scene and the root record's child boxes, their own
    // children dashed.
    let root_box = tree.root().map(|n| n.bv).unwrap_or(Aabb::EMPTY);
    let pad = Vec2::splat(0.3);
    let view = View::new(
        v2(root_box.min) - pad,
        v2(root_box.max) + pad,
        [20.0, 50.0, 410.0, 270.0],
    );
    pic.text(
        220.0,
        38.0,
        12.0,
        "middle",
        &format!("the root's record: {} child boxes", record.used()),
    );
    for (k, &kid) in top_kids.iter().enumerate() {
        let b = wide.bv(kid);
        view.rect(
            &mut pic,
            v2(b.min),
            v2(b.max),
            Style::filled(colour(k), 0.08).width(2.0),
        );
        for &g in &kids_of(wide, kid) {
            let gb = wide.bv(g);
            view.rect(
                &mut pic,
                v2(gb.min),
                v2(gb.max),
                Style::line(colour(k)).width(1.0).dashed(),
            );
        }
        let (x, y) = view.map(Vec2::new(b.min.x, b.max.y));
        pic.text(x + 2.0, y - 7.0, 10.0, "start", &format!("slot {k}"));
    }
    for t in tris {
        let pts: Vec<Vec2> = t.v.iter().map(|&p| v2(p)).collect();
        view.polygon(&mut pic, &pts, Style::filled("#555555", 0.55).width(0.8));
    }
    // Right: the record's bytes, a structure of arrays.
    let (tx, ty, cw, ch) = (530.0, 62.0, 80.0, 30.0);
    pic.text(
        tx + 2.0 * cw,
        38.0,
        12.0,
        "middle",
        &format!(
            "its record in memory: {} bytes, slots side by side",
            core::mem::size_of::<WideNode>()
        ),
    );
    for k in 0..4 {
        pic.text(
            tx + cw * (k as f32 + 0.5),
            ty - 8.0,
            10.0,
            "middle",
            &format!("slot {k}"),
        );
    }
    let rows = [
        "min.x", "min.y", "min.z", "max.x", "max.y", "max.z", "link", "count",
    ];
    for (row, name) in rows.iter().enumerate() {
        let y = ty + ch * row as f32;
        pic.text(tx - 8.0, y + ch * 0.5, 10.5, "end", name);
        pic.text(
            tx - 62.0,
            y + ch * 0.5,
            9.0,
            "end",
            &format!("{}", 16 * row),
        );
        for k in 0..4 {
            let x = tx + cw * k as f32;
            let Some(&kid) = top_kids.get(k) else {
                cell(&mut pic, x, y, cw, ch, HOLE_FILL, "unused");
                continue;
            };
            let b = record.slot_box(k);
            let text = match row {
                0..=2 => format!("{:.2}", b.min[row]),
                3..=5 => format!("{:.2}", b.max[row - 3]),
                6 => match wide.content(kid) {
                    Content::Inner(kids) => format!("record {}", kids.as_slice()[0] / 4),
                    Content::Leaf(ids) => format!("tri {}", ids.first().copied().unwrap_or(0)),
                },
                _ => match wide.content(kid) {
                    Content::Inner(kids) => format!("{} children", kids.as_slice().len()),
                    Content::Leaf(ids) => format!("leaf of {}", ids.len()),
                },
            };
            cell(&mut pic, x, y, cw, ch, "#ffffff", "");
            pic.rect(
                x + 1.0,
                y + 1.0,
                cw - 2.0,
                ch - 2.0,
                Style::filled(colour(k), 0.16).width(0.0),
            );
            pic.text(x + cw * 0.5, y + ch * 0.5 + 0.5, 10.5, "middle", &text);
        }
    }
    pic.text(tx - 62.0, ty - 8.0, 9.0, "end", "byte");
    pic.text(
        tx + 2.0 * cw,
        ty + ch * 8.0 + 18.0,
        10.0,
        "middle",
        "one fetch brings all four boxes: a query tests them in one pass",
    );
    Ok(Figure {
        name: "representations-wide",
        chapter: "representations.md",
        svg: pic.finish(),
    })
}

/// The part of the box `lo..hi` inside the view's window: its fill, and
/// those of its sides that lie in the window.
fn clipped_rect(pic: &mut Pic, view: &View, (lo, hi): (Vec2, Vec2), style: Style) {
    let (a, b) = (lo.clamp(view.lo, view.hi), hi.clamp(view.lo, view.hi));
    if style.fill != "none" {
        view.rect(
            pic,
            a,
            b,
            Style {
                width: 0.0,
                ..style
            },
        );
    }
    let inside = |v: f32, axis: usize| v >= view.lo[axis] && v <= view.hi[axis];
    for x in [lo.x, hi.x] {
        if inside(x, 0) {
            view.line(pic, Vec2::new(x, a.y), Vec2::new(x, b.y), style);
        }
    }
    for y in [lo.y, hi.y] {
        if inside(y, 1) {
            view.line(pic, Vec2::new(a.x, y), Vec2::new(b.x, y), style);
        }
    }
}

/// The grid step of a quantized axis, as `QuantNode` documents it: the
/// smallest power of two whose 255 steps reach from the frame's low side
/// past its high side. Checked against the record: every decoded
/// coordinate must lie on that grid.
fn grid_step(lo: f32, hi: f32) -> f32 {
    let mut e = ((hi as f64 - lo as f64) / 255.0).log2().ceil() as i32;
    while lo + 255.0 * 2f32.powi(e) < hi {
        e += 1;
    }
    2f32.powi(e)
}

fn quantized_figure(wide: &Wide<'_>) -> Result<Figure, FigureError> {
    // The root record's child boxes, encoded as one quantized record.
    let kids = kids_of(wide, wide.root());
    let exact: Vec<Aabb> = kids.iter().map(|&k| wide.bv(k)).collect();
    let record = QuantNode::encode(&exact);
    let coarse: Vec<Aabb> = (0..exact.len()).map(|k| record.slot_box(k)).collect();
    let frame = exact.iter().fold(exact[0], |a, b| a.union(b));
    let (origin, step) = (
        v2(frame.min),
        Vec2::new(
            grid_step(frame.min.x, frame.max.x),
            grid_step(frame.min.y, frame.max.y),
        ),
    );
    let q = |v: f32, axis: usize| -> f32 { (v - origin[axis]) / step[axis] };
    for (k, b) in coarse.iter().enumerate() {
        for axis in 0..2 {
            for v in [b.min[axis], b.max[axis]] {
                // Decoding rounds `origin + q * step` to an f32: on the
                // grid up to that rounding.
                let g = q(v, axis);
                if (g - g.round()).abs() > 1e-3 || !(0.0..=255.0).contains(&g.round()) {
                    return Err(FigureError(format!(
                        "slot {k}: decoded {v} is off the documented grid"
                    )));
                }
            }
            if b.min[axis] > exact[k].min[axis] || b.max[axis] < exact[k].max[axis] {
                return Err(FigureError(format!("slot {k}: decoded box is smaller")));
            }
        }
    }
    // The corner (low or high) that moved most, in grid steps, among
    // those inside the frame (on its sides the grid starts or ends).
    let mut best: Option<(usize, bool, f32)> = None;
    for (k, (e, c)) in exact.iter().zip(&coarse).enumerate() {
        for high in [false, true] {
            let (ev, cv) = if high { (e.max, c.max) } else { (e.min, c.min) };
            let inside = (0..2).all(|a| ev[a] > frame.min[a] && ev[a] < frame.max[a]);
            let moved: f32 = (0..2).map(|a| (cv[a] - ev[a]).abs() / step[a]).sum();
            if inside && best.is_none_or(|b| moved > b.2) {
                best = Some((k, high, moved));
            }
        }
    }
    let Some((k, high, _)) = best else {
        return Err(FigureError("no box corner inside the frame".into()));
    };
    let (e, c) = (exact[k], coarse[k]);
    let pick = |b: &Aabb| if high { v2(b.max) } else { v2(b.min) };
    let (corner, rounded) = (pick(&e), pick(&c));
    let (w, h) = (880.0, 420.0);
    let mut pic = Pic::new(w, h);
    pic.text(
        w * 0.5,
        14.0,
        13.0,
        "middle",
        &format!(
            "Quantized record: {} child boxes as 8-bit coordinates on a grid over their union ({} B per record)",
            exact.len(),
            core::mem::size_of::<QuantNode>()
        ),
    );
    // Left: the frame with every 16th grid line.
    let view = View::new(v2(frame.min), v2(frame.max), [30.0, 56.0, 400.0, 290.0]);
    pic.text(
        230.0,
        40.0,
        12.0,
        "middle",
        &format!(
            "the union, every 16th grid line (steps {} × {})",
            step.x, step.y
        ),
    );
    let faint = Style::line("#d0d0d0").width(0.7);
    for axis in 0..2 {
        let mut g = 0.0;
        while origin[axis] + g * step[axis] <= frame.max[axis] {
            let v = origin[axis] + g * step[axis];
            let (a, b) = if axis == 0 {
                (Vec2::new(v, frame.min.y), Vec2::new(v, frame.max.y))
            } else {
                (Vec2::new(frame.min.x, v), Vec2::new(frame.max.x, v))
            };
            view.line(&mut pic, a, b, faint);
            g += 16.0;
        }
    }
    view.rect(
        &mut pic,
        v2(frame.min),
        v2(frame.max),
        Style::line("#444444").width(1.2),
    );
    for (i, (e, c)) in exact.iter().zip(&coarse).enumerate() {
        view.rect(
            &mut pic,
            v2(e.min),
            v2(e.max),
            Style::filled(colour(i), 0.08).width(1.0).dashed(),
        );
        view.rect(
            &mut pic,
            v2(c.min),
            v2(c.max),
            Style::line(colour(i)).width(1.4),
        );
    }
    // The zoom, in grid steps: 5 either side of the rounded corner.
    let g_corner = Vec2::new(q(rounded.x, 0).round(), q(rounded.y, 1).round());
    let (zlo, zhi) = (g_corner - Vec2::splat(5.0), g_corner + Vec2::splat(5.0));
    let to_world = |g: Vec2| origin + g * step;
    view.rect(
        &mut pic,
        to_world(zlo),
        to_world(zhi),
        Style::line("#000000").width(1.2),
    );
    let zoom = View::new(zlo, zhi, [540.0, 56.0, 290.0, 290.0]);
    pic.text(
        685.0,
        40.0,
        12.0,
        "middle",
        &format!("zoom on a corner of slot {k}: every grid line"),
    );
    let [l, t, r, b] = zoom.area();
    for g in (zlo.x as i32)..=(zhi.x as i32) {
        let x = zoom.map(Vec2::new(g as f32, zlo.y)).0;
        pic.line((x, t), (x, b), Style::line("#cfcfcf").width(0.8));
        if g % 2 == 0 {
            pic.text(x, b + 10.0, 9.0, "middle", &g.to_string());
        }
    }
    for g in (zlo.y as i32)..=(zhi.y as i32) {
        let y = zoom.map(Vec2::new(zlo.x, g as f32)).1;
        pic.line((l, y), (r, y), Style::line("#cfcfcf").width(0.8));
        if g % 2 == 0 {
            pic.text(l - 4.0, y, 9.0, "end", &g.to_string());
        }
    }
    // Both boxes in grid units, clipped to the zoom.
    let in_grid = |p: Vec2| Vec2::new(q(p.x, 0), q(p.y, 1));
    clipped_rect(
        &mut pic,
        &zoom,
        (in_grid(v2(e.min)), in_grid(v2(e.max))),
        Style::filled(colour(k), 0.12).width(1.4).dashed(),
    );
    clipped_rect(
        &mut pic,
        &zoom,
        (in_grid(v2(c.min)), in_grid(v2(c.max))),
        Style::line(colour(k)).width(2.2),
    );
    pic.rect(l, t, r - l, b - t, Style::line("#000000").width(1.2));
    let lines = [
        format!(
            "exact corner (dashed): ({:.4}, {:.4}), grid ({:.2}, {:.2})",
            corner.x,
            corner.y,
            q(corner.x, 0),
            q(corner.y, 1)
        ),
        format!(
            "stored (rounded {}): grid ({}, {}) = ({:.4}, {:.4})",
            if high { "up" } else { "down" },
            g_corner.x,
            g_corner.y,
            rounded.x,
            rounded.y
        ),
    ];
    for (i, line) in lines.iter().enumerate() {
        pic.text(
            (l + r) * 0.5,
            b + 30.0 + 15.0 * i as f32,
            10.5,
            "middle",
            line,
        );
    }
    pic.text(
        230.0,
        b + 30.0,
        10.5,
        "middle",
        "dashed: the exact boxes; solid: as decoded, never smaller",
    );
    Ok(Figure {
        name: "representations-quantized",
        chapter: "representations.md",
        svg: pic.finish(),
    })
}
