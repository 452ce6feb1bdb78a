//! The book's BVH explorer: bvhkit compiled to `wasm32-unknown-unknown` for
//! the canvas page `book/src/explorer.md`.
//!
//! The page talks to this crate through plain `extern "C"` functions (no
//! wasm-bindgen): numbers go in as arguments, and results stay in buffers
//! owned here, which the page reads through typed-array views of the wasm
//! memory at the pointers these functions return (`*_ptr`, with a length).
//! A view is valid until the next call, which may grow the memory: the page
//! makes a new one after every call.
//!
//! The scene is a set of boxes in the plane, each a slab of thickness 1 in z
//! (z from 0 to 1), so that volumes compare like areas and every rule that
//! weighs volume ([`Descent::Larger`], the min-volume partition) has something
//! to weigh. Every node's volume is drawn as its section at mid-height (z =
//! 1/2): the box itself, a circle, the OBB's rectangle, the 18-DOP's octagon.
//!
//! Natively (an `rlib`), the same functions run the unit tests and the
//! `selftest` binary whose output the browser test compares with the page's.

use bvhkit::builders::{BottomUp, BottomUpScratch, Cluster, Collapse, DynNode, Insertion, PRESETS};
use bvhkit::glam::{Vec2, Vec3};
use bvhkit::{
    brute_force, max_nodes, Aabb, AxisChoice, BoundingVolume, Bvh, Counts, Descent, Dop18, Node,
    Obb, Order, PairTraversal, Pairs, Partition, Sphere,
};
use std::cell::RefCell;

/// Height of every box (z from 0 to this).
pub const THICKNESS: f32 = 1.0;
/// The plane the outlines are drawn in.
const SECTION_Z: f32 = THICKNESS / 2.0;

/// The builders beyond the top-down presets, after them in the list.
const PLOC: usize = PRESETS.len();
const INSERTION: usize = PRESETS.len() + 1;

/// Most boxes a generated scene has (more would not show on the canvas).
pub const MAX_SCENE: u32 = 5000;

/// Volume types, in the order `build` numbers them.
pub const VOLUMES: [&str; 4] = ["aabb", "sphere", "obb", "18-dop"];

/// Partition criteria a top-down preset can be switched to.
pub const PARTITIONS: [(&str, Partition); 6] = [
    ("surface-area", Partition::SurfaceArea),
    ("balance", Partition::Balance),
    ("volume", Partition::Volume),
    ("larger-child", Partition::LargerChild),
    ("overlap", Partition::Overlap),
    ("separation", Partition::Separation),
];

/// Axis choices a top-down preset can be switched to (z is flat here).
pub const AXES: [(&str, AxisChoice); 7] = [
    ("best-of-xyz", AxisChoice::BestOfXyz),
    ("longest", AxisChoice::Longest),
    ("x", AxisChoice::X),
    ("y", AxisChoice::Y),
    ("variance", AxisChoice::Variance),
    ("distant-points", AxisChoice::DistantPoints),
    ("parent-volume", AxisChoice::ParentVolume),
];

/// Ints per node in the info buffer: depth, leaf (0/1), primitives beneath,
/// first (left child, or first entry of the index buffer for a leaf),
/// first outline point, outline points.
pub const INFO: usize = 6;

/// A tree kept between calls: its storage, copied out of the builder's.
#[derive(Debug)]
struct Owned<B> {
    nodes: Vec<Node<B>>,
    indices: Vec<u32>,
    depth: usize,
}

impl<B: BoundingVolume> Owned<B> {
    fn keep(t: &Bvh<'_, B>) -> Self {
        Owned {
            nodes: t.nodes().to_vec(),
            indices: t.indices().to_vec(),
            depth: t.depth(),
        }
    }

    fn view(&self) -> Bvh<'_, B> {
        Bvh::from_raw_parts(&self.nodes, &self.indices, self.depth)
    }
}

#[derive(Debug)]
enum Tree {
    Aabb(Owned<Aabb>),
    Sphere(Owned<Sphere>),
    Obb(Owned<Obb>),
    Dop(Owned<Dop18>),
}

/// Runs `$body` with `$t` bound to the tree of whichever volume type.
macro_rules! with_tree {
    ($tree:expr, $t:ident => $body:expr) => {
        match $tree {
            Tree::Aabb($t) => $body,
            Tree::Sphere($t) => $body,
            Tree::Obb($t) => $body,
            Tree::Dop($t) => $body,
        }
    };
}

/// What a build was asked for: a query rebuilds B the same way.
#[derive(Clone, Copy, Debug)]
struct Config {
    builder: usize,
    partition: Option<Partition>,
    axis: Option<AxisChoice>,
    max_leaf: u32,
}

#[derive(Debug, Default)]
struct State {
    input: Vec<f32>,
    labels: String,
    err: String,
    boxes: Vec<Aabb>,
    built: Option<(Tree, Config)>,
    info: Vec<i32>,
    outline: Vec<f32>,
    counts: Counts,
    pairs: Vec<u32>,
    pairs_ok: Option<bool>,
    steps: Vec<i32>,
    region_ok: Option<bool>,
}

thread_local! {
    static STATE: RefCell<State> = RefCell::new(State::default());
}

fn with<R>(f: impl FnOnce(&mut State) -> R) -> R {
    STATE.with(|s| f(&mut s.borrow_mut()))
}

/// The names of every choice, one section a line:
/// `builders:sah,...`, `volumes:...`, `partitions:...`, `axes:...`,
/// `descents:...`; the page numbers each list from 0.
pub fn label_text() -> String {
    let mut builders: Vec<&str> = PRESETS.iter().map(|p| p.name).collect();
    builders.extend(["ploc", "insertion"]);
    format!(
        "builders:{}\nvolumes:{}\npartitions:{}\naxes:{}\ndescents:{}\n",
        builders.join(","),
        VOLUMES.join(","),
        PARTITIONS.map(|(n, _)| n).join(","),
        AXES.map(|(n, _)| n).join(","),
        Descent::ALL.map(|d| d.name()).join(","),
    )
}

fn labels(s: &mut State) -> &str {
    if s.labels.is_empty() {
        s.labels = label_text();
    }
    &s.labels
}

/// [`label_text`], for the page.
#[no_mangle]
pub extern "C" fn labels_ptr() -> *const u8 {
    with(|s| labels(s).as_ptr())
}

#[no_mangle]
pub extern "C" fn labels_len() -> usize {
    with(|s| labels(s).len())
}

/// The last error's text (after a call returned -1).
#[no_mangle]
pub extern "C" fn err_ptr() -> *const u8 {
    with(|s| s.err.as_ptr())
}

#[no_mangle]
pub extern "C" fn err_len() -> usize {
    with(|s| s.err.len())
}

/// Room for `n` boxes (minx, miny, maxx, maxy each), read by the next `build`.
#[no_mangle]
pub extern "C" fn input(n: usize) -> *mut f32 {
    with(|s| {
        s.input.resize(4 * n, 0.0);
        s.input.as_mut_ptr()
    })
}

/// A generated scene of `n` boxes written to the input buffer (read it
/// back at `input(count)`): kind 0 random, 1 a row, 2 clusters. Returns
/// the count (at most [`MAX_SCENE`]). The world is 100 by 70 units.
#[no_mangle]
pub extern "C" fn scene(kind: u32, n: u32, seed: u32) -> u32 {
    let boxes = generate(kind, n.min(MAX_SCENE) as usize, seed);
    with(|s| {
        s.input = boxes.iter().flatten().copied().collect();
        boxes.len() as u32
    })
}

/// A small xorshift generator: the same scene natively and in the browser.
fn generate(kind: u32, n: usize, seed: u32) -> Vec<[f32; 4]> {
    let mut x = 0x9e37_79b9_7f4a_7c15u64 ^ u64::from(seed).wrapping_mul(0x2545_f491_4f6c_dd1d);
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 40) as f32 / (1u64 << 24) as f32
    };
    let (w, h) = (100.0f32, 70.0f32);
    let mut out = Vec::with_capacity(n);
    match kind {
        1 => {
            // A row of slightly overlapping boxes, wobbling up and down.
            let step = (w - 8.0) / n.max(1) as f32;
            for i in 0..n {
                let x0 = 4.0 + i as f32 * step;
                let y0 = h / 2.0 - 3.0 + next() * 6.0;
                out.push([x0, y0, x0 + step * 1.3, y0 + 2.0 + next() * 3.0]);
            }
        }
        2 => {
            let k = 3 + (n / 25).min(4);
            let centres: Vec<(f32, f32)> = (0..k)
                .map(|_| (10.0 + next() * (w - 20.0), 10.0 + next() * (h - 20.0)))
                .collect();
            for i in 0..n {
                let (cx, cy) = centres[i % k];
                let (x0, y0) = (cx + (next() - 0.5) * 18.0, cy + (next() - 0.5) * 18.0);
                out.push([x0, y0, x0 + 1.0 + next() * 3.0, y0 + 1.0 + next() * 3.0]);
            }
        }
        _ => {
            for _ in 0..n {
                let (bw, bh) = (1.5 + next() * 6.0, 1.5 + next() * 6.0);
                let (x0, y0) = (next() * (w - bw), next() * (h - bh));
                out.push([x0, y0, x0 + bw, y0 + bh]);
            }
        }
    }
    out
}

/// Builds a tree over the input boxes: `builder` indexes the builders' list
/// (top-down presets, then PLOC and insertion), `partition` and `axis` switch
/// a top-down preset's criterion or axis choice (-1: the preset's own),
/// `max_leaf` is the largest leaf (top-down: the stopping rule; PLOC and
/// insertion: the SAH collapse's limit), `volume` indexes [`VOLUMES`].
/// Returns the node count, or -1 with the reason at `err_ptr`.
#[no_mangle]
pub extern "C" fn build(
    builder: i32,
    partition: i32,
    axis: i32,
    max_leaf: i32,
    volume: i32,
) -> i32 {
    with(
        |s| match build_in(s, builder, partition, axis, max_leaf, volume) {
            Ok(n) => n as i32,
            Err(e) => {
                s.err = e;
                -1
            }
        },
    )
}

fn pick<T: Copy>(list: &[(&str, T)], i: i32, what: &str) -> Result<Option<T>, String> {
    match i {
        -1 => Ok(None),
        _ => list
            .get(i as usize)
            .map(|x| Some(x.1))
            .ok_or(format!("no {what} {i}")),
    }
}

fn build_in(
    s: &mut State,
    builder: i32,
    partition: i32,
    axis: i32,
    max_leaf: i32,
    volume: i32,
) -> Result<usize, String> {
    s.built = None;
    s.info.clear();
    s.outline.clear();
    s.pairs.clear();
    s.steps.clear();
    s.pairs_ok = None;
    s.region_ok = None;
    s.counts = Counts::default();
    if !(0..=INSERTION as i32).contains(&builder) {
        return Err(format!("no builder {builder}"));
    }
    if !(1..=64).contains(&max_leaf) {
        return Err("the largest leaf must be 1 to 64 boxes".into());
    }
    let config = Config {
        builder: builder as usize,
        partition: pick(&PARTITIONS, partition, "partition")?,
        axis: pick(&AXES, axis, "axis")?,
        max_leaf: max_leaf as u32,
    };
    if let Some(k) = s.input.iter().position(|x| !x.is_finite()) {
        return Err(format!(
            "box {} has a coordinate that is not a finite number",
            k / 4
        ));
    }
    s.boxes = s
        .input
        .chunks_exact(4)
        .map(|b| {
            Aabb::new(
                Vec3::new(b[0].min(b[2]), b[1].min(b[3]), 0.0),
                Vec3::new(b[0].max(b[2]), b[1].max(b[3]), THICKNESS),
            )
        })
        .collect();
    let boxes = &s.boxes;
    let tree = match volume {
        0 => Tree::Aabb(build_tree(&config, boxes)?),
        1 => Tree::Sphere(build_tree(&config, boxes)?),
        2 => Tree::Obb(build_tree(&config, boxes)?),
        3 => Tree::Dop(build_tree(&config, boxes)?),
        _ => return Err(format!("no volume {volume}")),
    };
    let (info, outline) = with_tree!(&tree, t => describe(&t.view()));
    s.info = info;
    s.outline = outline;
    s.built = Some((tree, config));
    Ok(s.info.len() / INFO)
}

fn collapse(max_leaf: u32) -> Collapse {
    if max_leaf <= 1 {
        Collapse::None
    } else {
        // The default collapse's weight of a node visit, with this limit.
        let traversal_cost = match Collapse::DEFAULT {
            Collapse::Sah { traversal_cost, .. } => traversal_cost,
            Collapse::None => 3.0,
        };
        Collapse::Sah {
            max_leaf_size: max_leaf,
            traversal_cost,
        }
    }
}

fn build_tree<B: BoundingVolume>(c: &Config, boxes: &[Aabb]) -> Result<Owned<B>, String> {
    let n = boxes.len();
    let mut nodes = vec![Node::<B>::EMPTY; max_nodes(n)];
    let err = |e: bvhkit::Error| e.to_string();
    if c.builder < PLOC {
        let mut b = PRESETS[c.builder].builder.with_max_leaf_size(c.max_leaf);
        if let Some(p) = c.partition {
            b.partition = p;
        }
        if let Some(a) = c.axis {
            b.axis = a;
        }
        let mut idx = vec![0u32; b.index_capacity(n)];
        Ok(Owned::keep(
            &b.build(boxes, &mut nodes, &mut idx).map_err(err)?,
        ))
    } else if c.builder == PLOC {
        let b = BottomUp {
            collapse: collapse(c.max_leaf),
            ..BottomUp::default()
        };
        let (nc, nw, nk) = BottomUp::scratch_len(n);
        let mut clusters = vec![Cluster::<B>::EMPTY; nc];
        let (mut work, mut keys) = (vec![0u32; nw], vec![0u64; nk]);
        let mut scratch = BottomUpScratch {
            clusters: &mut clusters,
            work: &mut work,
            keys: &mut keys,
        };
        let mut idx = vec![0u32; n];
        Ok(Owned::keep(
            &b.build(boxes, &mut nodes, &mut idx, &mut scratch)
                .map_err(err)?,
        ))
    } else {
        let b = Insertion {
            collapse: collapse(c.max_leaf),
            ..Insertion::default()
        };
        let (ns, no) = Insertion::scratch_len(n);
        let mut storage = vec![DynNode::<B>::EMPTY; ns];
        let (mut order, mut idx) = (vec![0u32; no], vec![0u32; n]);
        Ok(Owned::keep(
            &b.build(boxes, &mut storage, &mut order, &mut nodes, &mut idx)
                .map_err(err)?,
        ))
    }
}

/// A volume's section at z = [`SECTION_Z`], as a convex polygon.
pub trait Section: BoundingVolume {
    /// The polygon's corners, counter-clockwise in a y-up plane.
    fn section(&self) -> Vec<Vec2>;
}

/// The volume's box, cut to the plane: where every section starts.
fn box_section(b: &Aabb) -> Vec<Vec2> {
    vec![
        Vec2::new(b.min.x, b.min.y),
        Vec2::new(b.max.x, b.min.y),
        Vec2::new(b.max.x, b.max.y),
        Vec2::new(b.min.x, b.max.y),
    ]
}

/// The polygon `poly` cut to the half-plane `n . p <= d` (as in bvhkit-std's
/// figures, which draw the book's sections the same way).
fn clip(poly: &[Vec2], n: Vec2, d: f32) -> Vec<Vec2> {
    let mut out = Vec::new();
    for (i, &p) in poly.iter().enumerate() {
        let q = poly[(i + 1) % poly.len()];
        let (dp, dq) = (n.dot(p) - d, n.dot(q) - d);
        if dp <= 0.0 {
            out.push(p);
        }
        if (dp < 0.0) != (dq < 0.0) && dp != dq {
            out.push(p + (q - p) * (dp / (dp - dq)));
        }
    }
    out
}

/// `poly` cut to the slab `lo <= a . (x, y, z) <= hi` at z = [`SECTION_Z`].
fn slab(poly: Vec<Vec2>, a: Vec3, lo: f32, hi: f32) -> Vec<Vec2> {
    let n = a.truncate();
    if n.length_squared() < 1e-12 {
        return poly; // parallel to the plane: the box already holds it
    }
    let off = a.z * SECTION_Z;
    let poly = clip(&poly, n, hi - off);
    clip(&poly, -n, off - lo)
}

impl Section for Aabb {
    fn section(&self) -> Vec<Vec2> {
        box_section(self)
    }
}

impl Section for Sphere {
    fn section(&self) -> Vec<Vec2> {
        let dz = SECTION_Z - self.center.z;
        let r = (self.radius * self.radius - dz * dz).max(0.0).sqrt();
        // A 32-gon around the circle (its corners a hair outside it).
        let r = r / (std::f32::consts::PI / 32.0).cos();
        (0..32)
            .map(|i| {
                let t = i as f32 * std::f32::consts::TAU / 32.0;
                self.center.truncate() + r * Vec2::new(t.cos(), t.sin())
            })
            .collect()
    }
}

impl Section for Obb {
    fn section(&self) -> Vec<Vec2> {
        let mut poly = box_section(&self.aabb());
        for (a, h) in self.axes.iter().zip(self.half_extents.to_array()) {
            let c = a.dot(self.center);
            poly = slab(poly, *a, c - h, c + h);
        }
        poly
    }
}

impl Section for Dop18 {
    fn section(&self) -> Vec<Vec2> {
        let mut poly = box_section(&self.aabb());
        for i in 0..9 {
            let [a, b, c] = Dop18::direction(i);
            let dir = Vec3::new(a as f32, b as f32, c as f32);
            poly = slab(poly, dir, self.min[i], self.max[i]);
        }
        poly
    }
}

/// The info and outline buffers of a tree (see [`INFO`]).
fn describe<B: Section>(t: &Bvh<'_, B>) -> (Vec<i32>, Vec<f32>) {
    let nodes = t.nodes();
    let mut info = vec![0i32; nodes.len() * INFO];
    let mut outline = Vec::new();
    // Depth first from the root: (node, depth); returns primitives beneath.
    fn visit<B: Section>(
        t: &Bvh<'_, B>,
        n: u32,
        depth: i32,
        info: &mut [i32],
        outline: &mut Vec<f32>,
    ) -> i32 {
        let node = &t.nodes()[n as usize];
        let poly = node.bv.section();
        let start = (outline.len() / 2) as i32;
        outline.extend(poly.iter().flat_map(|p| [p.x, p.y]));
        let count = match node.children() {
            Some((l, r)) => {
                visit(t, l, depth + 1, info, outline) + visit(t, r, depth + 1, info, outline)
            }
            None => node.count as i32,
        };
        let at = n as usize * INFO;
        info[at..at + INFO].copy_from_slice(&[
            depth,
            node.is_leaf() as i32,
            count,
            node.first as i32,
            start,
            poly.len() as i32,
        ]);
        count
    }
    if !nodes.is_empty() {
        visit(t, 0, 0, &mut info, &mut outline);
    }
    (info, outline)
}

/// Per node, [`INFO`] ints (see there); as many nodes as `build` returned.
#[no_mangle]
pub extern "C" fn info_ptr() -> *const i32 {
    with(|s| s.info.as_ptr())
}

/// The outlines' points (x, y pairs) the info buffer points into.
#[no_mangle]
pub extern "C" fn outline_ptr() -> *const f32 {
    with(|s| s.outline.as_ptr())
}

#[no_mangle]
pub extern "C" fn outline_len() -> usize {
    with(|s| s.outline.len())
}

/// The tree's index buffer: a leaf's boxes are entries `first .. first + count`.
#[no_mangle]
pub extern "C" fn indices_ptr() -> *const u32 {
    with(|s| match &s.built {
        Some((tree, _)) => with_tree!(tree, t => t.indices.as_ptr()),
        None => std::ptr::null(),
    })
}

/// Depth of the deepest leaf (-1 before a build).
#[no_mangle]
pub extern "C" fn depth() -> i32 {
    with(|s| match &s.built {
        Some((tree, _)) => with_tree!(tree, t => t.depth as i32),
        None => -1,
    })
}

/// The pair query: tree A (the last build) against tree B, the same boxes
/// moved by (dx, dy) and built the same way, on the explicit-stack traversal
/// with descent rule `descent` (an index into `Descent::ALL`), counted.
/// Returns the pair count (pairs at `pairs_ptr`, a then b), or -1.
#[no_mangle]
pub extern "C" fn query(dx: f32, dy: f32, descent: i32) -> i32 {
    with(|s| match query_in(s, dx, dy, descent) {
        Ok(n) => n as i32,
        Err(e) => {
            s.err = e;
            -1
        }
    })
}

fn query_in(s: &mut State, dx: f32, dy: f32, descent: i32) -> Result<usize, String> {
    s.pairs.clear();
    s.pairs_ok = None;
    s.counts = Counts::default();
    let (tree, config) = s.built.as_ref().ok_or("build a tree first")?;
    let rule = *Descent::ALL
        .get(descent as usize)
        .ok_or(format!("no descent rule {descent}"))?;
    let d = Vec3::new(dx, dy, 0.0);
    let moved: Vec<Aabb> = s
        .boxes
        .iter()
        .map(|b| Aabb::new(b.min + d, b.max + d))
        .collect();
    let (boxes, pairs, counts) = (&s.boxes, &mut s.pairs, &mut s.counts);
    let found = with_tree!(tree, t => {
        let b = build_tree(config, &moved)?;
        let (ta, tb) = (t.view(), b.view());
        Pairs::new(&ta, boxes, &tb, &moved)
            .traversal(PairTraversal::Stack(rule))
            .counted(&mut *counts)
            .for_each(|i, j| pairs.extend([i, j]))
            .map_err(|e| e.to_string())?
    });
    // The library's answer without a tree, to hold the tree's to.
    let mut expected = Vec::new();
    brute_force::pairs(boxes, &moved, |i, j| expected.push([i, j]));
    let mut got: Vec<[u32; 2]> = pairs.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
    got.sort_unstable();
    expected.sort_unstable();
    s.pairs_ok = Some(got == expected && found == got.len());
    Ok(found)
}

/// The last query's counters: 0 `Nv` (volume tests), 1 `Np` (primitive
/// tests), 2 `Nu` (volumes moved: 0 here, B is built in place).
#[no_mangle]
pub extern "C" fn counter(k: i32) -> f64 {
    with(|s| match k {
        0 => s.counts.bv_tests as f64,
        1 => s.counts.prim_tests as f64,
        2 => s.counts.updates as f64,
        _ => -1.0,
    })
}

#[no_mangle]
pub extern "C" fn pairs_ptr() -> *const u32 {
    with(|s| s.pairs.as_ptr())
}

/// A region query with the box (x0, y0)-(x1, y1), walked depth first over
/// the built tree and recorded step by step for the page to replay: three
/// ints a step, kind (0 a node's volume tested, 1 a box tested), node or box
/// index, and whether it overlapped. The walk is checked against the
/// library's own region query (see `check`). Returns the step count, or -1.
#[no_mangle]
pub extern "C" fn region(x0: f32, y0: f32, x1: f32, y1: f32) -> i32 {
    with(|s| match region_in(s, x0, y0, x1, y1) {
        Ok(n) => n as i32,
        Err(e) => {
            s.err = e;
            -1
        }
    })
}

fn region_in(s: &mut State, x0: f32, y0: f32, x1: f32, y1: f32) -> Result<usize, String> {
    s.steps.clear();
    s.region_ok = None;
    let (tree, _) = s.built.as_ref().ok_or("build a tree first")?;
    let region = Aabb::new(
        Vec3::new(x0.min(x1), y0.min(y1), 0.0),
        Vec3::new(x0.max(x1), y0.max(y1), THICKNESS),
    );
    let (boxes, steps) = (&s.boxes, &mut s.steps);
    let ok = with_tree!(tree, t => {
        let t = t.view();
        if !t.is_empty() {
            walk(&t, boxes, &region, 0, steps);
        }
        let mut hits: Vec<u32> = steps
            .chunks_exact(3)
            .filter(|st| st[0] == 1 && st[2] == 1)
            .map(|st| st[1] as u32)
            .collect();
        let tested = |kind| steps.chunks_exact(3).filter(|st| st[0] == kind).count() as u64;
        // The library's walk in the same order, counted, and its plain query.
        let mut counts = Counts::default();
        let mut lib = Vec::new();
        t.search(boxes, &region, Order::Recursive, &mut counts, |i| lib.push(i))
            .map_err(|e| e.to_string())?;
        let mut plain = Vec::new();
        t.overlapping(boxes, &region, |i| plain.push(i))
            .map_err(|e| e.to_string())?;
        let mut brute = Vec::new();
        brute_force::overlapping(boxes, &region, |i| brute.push(i));
        for v in [&mut hits, &mut lib, &mut plain, &mut brute] {
            v.sort_unstable();
        }
        hits == lib
            && hits == plain
            && hits == brute
            && tested(0) == counts.bv_tests
            && tested(1) == counts.prim_tests
    });
    s.region_ok = Some(ok);
    Ok(s.steps.len() / 3)
}

/// The depth-first walk of a region query over the public tree: test a
/// node's volume; on a leaf test its boxes; else the left, then the right.
fn walk<B: BoundingVolume>(
    t: &Bvh<'_, B>,
    boxes: &[Aabb],
    region: &Aabb,
    n: u32,
    steps: &mut Vec<i32>,
) {
    let node = &t.nodes()[n as usize];
    let hit = node.bv.overlaps_aabb(region);
    steps.extend([0, n as i32, hit as i32]);
    if !hit {
        return;
    }
    match node.children() {
        Some((l, r)) => {
            walk(t, boxes, region, l, steps);
            walk(t, boxes, region, r, steps);
        }
        None => {
            for &p in t.leaf_primitives(node) {
                let hit = region.overlaps_aabb(&boxes[p as usize]);
                steps.extend([1, p as i32, hit as i32]);
            }
        }
    }
}

#[no_mangle]
pub extern "C" fn steps_ptr() -> *const i32 {
    with(|s| s.steps.as_ptr())
}

/// Whether the last pair query found the brute-force answer and the last
/// region walk matched the library's query (hits, `Nv`, `Np`): 1 yes,
/// 0 no, -1 neither has run since the build.
#[no_mangle]
pub extern "C" fn check() -> i32 {
    with(|s| match (s.pairs_ok, s.region_ok) {
        (None, None) => -1,
        (p, r) => (p != Some(false) && r != Some(false)) as i32,
    })
}

/// The fixed scenario of the page's `?selftest`, run natively: the same
/// calls, the same `key=value` lines (the browser test compares the two).
/// `ui`, `canvas` and `errors` are the page's own checks (its controls
/// work, its canvas is drawn on, nothing went to the console as an error):
/// natively there is nothing to check, so they print what the page must.
pub fn selftest() -> String {
    let labels = label_text();
    let list = |key: &str| -> Vec<String> {
        labels
            .lines()
            .find_map(|l| l.strip_prefix(&format!("{key}:")))
            .map(|l| l.split(',').map(String::from).collect())
            .unwrap_or_default()
    };
    let index = |key: &str, name: &str| list(key).iter().position(|x| x == name).unwrap() as i32;
    let sc = SELFTEST;
    let n = scene(sc.scene, sc.boxes, sc.seed);
    let nodes = build(
        index("builders", sc.builder),
        -1,
        -1,
        sc.max_leaf,
        index("volumes", sc.volume),
    );
    let pairs = query(sc.offset.0, sc.offset.1, index("descents", sc.descent));
    let (nv, np) = (counter(0), counter(1));
    let r = sc.region;
    let steps = region(r[0], r[1], r[2], r[3]);
    let (hits, region_nv) = with(|s| {
        let st: Vec<&[i32]> = s.steps.chunks_exact(3).collect();
        (
            st.iter().filter(|x| x[0] == 1 && x[2] == 1).count(),
            st.iter().filter(|x| x[0] == 0).count(),
        )
    });
    format!(
        "boxes={n}\nnodes={nodes}\ndepth={}\npairs={pairs}\nnv={nv}\nnp={np}\nregion_steps={steps}\nregion_hits={hits}\nregion_nv={region_nv}\nrust_check={}\nui=ok\ncanvas=drawn\nerrors=0\n",
        depth(),
        if check() == 1 { "ok" } else { "FAILED" },
    )
}

/// The selftest's scenario; explorer.js repeats it (the browser test fails
/// when the two disagree).
#[derive(Clone, Copy, Debug)]
pub struct Scenario {
    pub scene: u32,
    pub boxes: u32,
    pub seed: u32,
    pub builder: &'static str,
    pub volume: &'static str,
    pub max_leaf: i32,
    pub offset: (f32, f32),
    pub descent: &'static str,
    pub region: [f32; 4],
}

pub const SELFTEST: Scenario = Scenario {
    scene: 2,
    boxes: 60,
    seed: 7,
    builder: "sah",
    volume: "18-dop",
    max_leaf: 2,
    offset: (1.5, 1.0),
    descent: "larger",
    region: [20.0, 15.0, 55.0, 40.0],
};

#[cfg(test)]
mod tests {
    use super::*;

    fn builders() -> usize {
        INSERTION + 1
    }

    fn set_boxes(boxes: &[[f32; 4]]) {
        with(|s| s.input = boxes.iter().flatten().copied().collect());
    }

    /// Whether `p` lies in the convex counter-clockwise polygon `poly`,
    /// allowing a rounding hair.
    fn inside(poly: &[Vec2], p: Vec2) -> bool {
        (0..poly.len()).all(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            (b - a).perp_dot(p - a) >= -1e-3 * (b - a).length().max(1.0)
        })
    }

    /// Every node's outline holds the corners of every box beneath it.
    fn outlines_hold_their_boxes() {
        with(|s| {
            let Some((tree, _)) = &s.built else {
                panic!("no tree")
            };
            let indices = with_tree!(tree, t => t.indices.clone());
            let nodes = s.info.len() / INFO;
            // The boxes beneath each node, from the leaves up (children
            // follow their parent in the node array).
            let mut beneath: Vec<Vec<u32>> = vec![Vec::new(); nodes];
            for n in (0..nodes).rev() {
                let i = &s.info[n * INFO..(n + 1) * INFO];
                beneath[n] = if i[1] == 1 {
                    indices[i[3] as usize..(i[3] + i[2]) as usize].to_vec()
                } else {
                    let (l, r) = (i[3] as usize, i[3] as usize + 1);
                    [beneath[l].clone(), beneath[r].clone()].concat()
                };
                assert_eq!(beneath[n].len(), i[2] as usize, "node {n} count");
                let poly: Vec<Vec2> = (i[4]..i[4] + i[5])
                    .map(|k| Vec2::new(s.outline[2 * k as usize], s.outline[2 * k as usize + 1]))
                    .collect();
                assert!(
                    poly.len() >= 3,
                    "node {n}: outline of {} points",
                    poly.len()
                );
                for &p in &beneath[n] {
                    let b = s.boxes[p as usize];
                    for c in [
                        Vec2::new(b.min.x, b.min.y),
                        Vec2::new(b.max.x, b.min.y),
                        Vec2::new(b.max.x, b.max.y),
                        Vec2::new(b.min.x, b.max.y),
                    ] {
                        assert!(
                            inside(&poly, c),
                            "node {n}: corner {c} of box {p} outside {poly:?}"
                        );
                    }
                }
            }
            assert_eq!(s.info[2], s.boxes.len() as i32, "the root holds every box");
        });
    }

    #[test]
    fn labels_list_every_builder_volume_and_rule() {
        let text = label_text();
        let line = |k: &str| text.lines().find(|l| l.starts_with(k)).unwrap().to_string();
        assert_eq!(line("builders:").split(',').count(), builders());
        for p in PRESETS {
            assert!(line("builders:").contains(p.name));
        }
        assert!(line("builders:").ends_with(",ploc,insertion"));
        assert_eq!(line("volumes:"), "volumes:aabb,sphere,obb,18-dop");
        assert_eq!(line("descents:").split(',').count(), Descent::ALL.len());
        // What the page reads through the pointer is the same text.
        labels_ptr();
        assert_eq!(with(|s| s.labels.clone()), text);
        assert_eq!(labels_len(), text.len());
    }

    #[test]
    fn every_builder_and_volume_builds_and_its_outlines_hold_its_boxes() {
        for kind in 0..3 {
            scene(kind, 40, 3);
            for builder in 0..builders() as i32 {
                for volume in 0..4 {
                    for leaf in [1, 3] {
                        let n = build(builder, -1, -1, leaf, volume);
                        let err = with(|s| s.err.clone());
                        assert!(
                            n > 0,
                            "scene {kind} builder {builder} volume {volume}: {err}"
                        );
                        assert!(depth() >= 1);
                        outlines_hold_their_boxes();
                    }
                }
            }
        }
    }

    #[test]
    fn every_partition_and_axis_builds_or_says_why() {
        scene(0, 30, 11);
        for p in 0..PARTITIONS.len() as i32 {
            for a in 0..AXES.len() as i32 {
                for volume in 0..4 {
                    if build(0, p, a, 2, volume) > 0 {
                        outlines_hold_their_boxes();
                    } else {
                        assert!(err_len() > 0, "partition {p} axis {a}: -1 without a reason");
                    }
                }
            }
        }
    }

    #[test]
    fn pair_counters_are_the_librarys() {
        scene(2, 50, 5);
        let boxes: Vec<Aabb> = with(|s| s.input.clone())
            .chunks_exact(4)
            .map(|b| Aabb::new(Vec3::new(b[0], b[1], 0.0), Vec3::new(b[2], b[3], THICKNESS)))
            .collect();
        let d = Vec3::new(2.0, -1.0, 0.0);
        let moved: Vec<Aabb> = boxes
            .iter()
            .map(|b| Aabb::new(b.min + d, b.max + d))
            .collect();
        let sah = bvhkit::TopDown::sah().with_max_leaf_size(2);
        let n = boxes.len();
        let (mut na, mut nb) = (
            vec![Node::<Sphere>::EMPTY; 2 * n],
            vec![Node::<Sphere>::EMPTY; 2 * n],
        );
        let (mut ia, mut ib) = (vec![0u32; n], vec![0u32; n]);
        let ta = sah.build(&boxes, &mut na, &mut ia).unwrap();
        let tb = sah.build(&moved, &mut nb, &mut ib).unwrap();
        assert!(build(0, -1, -1, 2, 1) > 0);
        for (k, rule) in Descent::ALL.into_iter().enumerate() {
            let mut counts = Counts::default();
            let found = Pairs::new(&ta, &boxes, &tb, &moved)
                .descent(rule)
                .counted(&mut counts)
                .count()
                .unwrap();
            assert_eq!(query(2.0, -1.0, k as i32), found as i32, "{}", rule.name());
            assert!(found > 0);
            assert_eq!(counter(0), counts.bv_tests as f64, "{} Nv", rule.name());
            assert_eq!(counter(1), counts.prim_tests as f64, "{} Np", rule.name());
            assert_eq!(counter(2), 0.0);
            assert_eq!(check(), 1);
            // The pairs listed are the pairs found, each overlapping.
            let pairs = with(|s| s.pairs.clone());
            assert_eq!(pairs.len(), 2 * found);
            for p in pairs.chunks_exact(2) {
                assert!(boxes[p[0] as usize].overlaps(&moved[p[1] as usize]));
            }
        }
    }

    #[test]
    fn region_walk_finds_the_librarys_hits_with_its_counts() {
        scene(0, 60, 9);
        for builder in [0, 4, PLOC as i32, INSERTION as i32] {
            for volume in 0..4 {
                assert!(build(builder, -1, -1, 3, volume) > 0);
                for r in [
                    [10.0, 10.0, 40.0, 30.0],
                    [0.0, 0.0, 100.0, 70.0],
                    [50.0, 5.0, 51.0, 6.0],
                ] {
                    let steps = region(r[0], r[1], r[2], r[3]);
                    assert!(steps > 0);
                    assert_eq!(check(), 1, "builder {builder} volume {volume} region {r:?}");
                    let (steps, boxes) = with(|s| (s.steps.clone(), s.boxes.clone()));
                    let region = Aabb::new(Vec3::new(r[0], r[1], 0.0), Vec3::new(r[2], r[3], 1.0));
                    let mut hits: Vec<u32> = steps
                        .chunks_exact(3)
                        .filter(|s| s[0] == 1 && s[2] == 1)
                        .map(|s| s[1] as u32)
                        .collect();
                    hits.sort_unstable();
                    let brute: Vec<u32> = (0..boxes.len() as u32)
                        .filter(|&i| boxes[i as usize].overlaps(&region))
                        .collect();
                    assert_eq!(hits, brute);
                }
            }
        }
    }

    #[test]
    fn typed_in_boxes_build_in_any_corner_order_and_empty_scenes_answer_nothing() {
        set_boxes(&[
            [5.0, 5.0, 1.0, 1.0],
            [2.0, 2.0, 8.0, 3.0],
            [20.0, 20.0, 22.0, 25.0],
        ]);
        assert_eq!(build(0, -1, -1, 1, 0), 5);
        outlines_hold_their_boxes();
        // Each box with itself, and the first two with each other both ways.
        assert_eq!(query(0.0, 0.0, 2), 5);
        input(0);
        assert_eq!(build(0, -1, -1, 4, 3), 0);
        assert_eq!(query(1.0, 1.0, 0), 0);
        assert_eq!(region(0.0, 0.0, 10.0, 10.0), 0);
        assert_eq!(check(), 1);
    }

    #[test]
    fn bad_arguments_are_errors_with_a_reason() {
        scene(0, 10, 1);
        for (b, p, a, leaf, v) in [
            (99, -1, -1, 2, 0),
            (0, 42, -1, 2, 0),
            (0, -1, 9, 2, 0),
            (0, -1, -1, 0, 0),
            (0, -1, -1, 2, 7),
        ] {
            assert_eq!(build(b, p, a, leaf, v), -1);
            assert!(err_len() > 0);
        }
        assert_eq!(query(0.0, 0.0, 0), -1, "no tree after a failed build");
        assert!(build(0, -1, -1, 2, 0) > 0);
        assert_eq!(query(0.0, 0.0, 99), -1);
        set_boxes(&[[0.0, 0.0, f32::NAN, 1.0]]);
        assert_eq!(build(0, -1, -1, 2, 0), -1);
    }

    #[test]
    fn selftest_checks_out() {
        let out = selftest();
        assert!(out.contains("rust_check=ok\n"), "{out}");
        assert!(
            out.contains(&format!("boxes={}\n", SELFTEST.boxes)),
            "{out}"
        );
    }
}
