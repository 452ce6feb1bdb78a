//! Figures of the book's `traversal.md` chapter: the order in which the
//! library's walks open the nodes of one small tree, for the region query
//! (depth-first and breadth-first) and for the ray cast (depth-first nearer
//! child first, and best-first).
//!
//! The queries do not report which node they open, only how many tests they
//! make (a [`Tally`]) and which primitives they find or test. So each walk is
//! retraced here over [`Bvh::nodes`] with the library's own node and
//! primitive tests ([`Region::may_overlap`], [`RayTarget::ray_hit`]), and the
//! retrace must make the very sequence of tests the library reports (node
//! tests, leaf tests, primitives found or tested, in order) or the figure
//! fails.

use super::svg::{colour, Style, Svg};
use super::walk_log::{Event, Log};
use super::{Figure, FigureError};
use crate::OwnedBvh;
use bvhkit::glam::{Vec2, Vec3};
use bvhkit::{
    Aabb, BoundingVolume, Bvh, Content, Counts, Hierarchy, Order, Primitive, Ray, RayOrder,
    RayTarget, Region, Sphere, TopDown,
};
use std::cell::RefCell;
use std::collections::VecDeque;
use std::path::Path;

pub(super) fn figures(book_src: &Path) -> Result<Vec<Figure>, FigureError> {
    let _ = book_src;
    let discs = discs();
    let owned = OwnedBvh::<Aabb>::build(&TopDown::default().with_max_leaf_size(1), &discs)?;
    let bvh = owned.view();
    Ok(vec![
        region_orders(&bvh, &discs)?,
        ray_orders(&bvh, &discs)?,
    ])
}

/// Thirteen discs in the plane (spheres at z = 0), from a seeded generator.
fn discs() -> Vec<Sphere> {
    let mut s = 0x035e_2aa2_e7e4_7acau64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / (1u64 << 24) as f32
    };
    (0..13)
        .map(|_| {
            let c = Vec3::new(next() * 12.0, next() * 6.0, 0.0);
            Sphere::new(c, 0.3 + next() * 0.35)
        })
        .collect()
}

/// A disc that notes every ray test made on it.
struct Noted<'a> {
    disc: Sphere,
    id: u32,
    events: &'a RefCell<Vec<Event>>,
}

impl RayTarget for Noted<'_> {
    fn ray_hit(&self, ray: &Ray) -> Option<f32> {
        self.events.borrow_mut().push(Event::Prim(self.id));
        self.disc.ray_hit(ray)
    }
}

/// One walk as the figure shows it.
struct Walk {
    /// Nodes in the order they were opened (passed their test and were
    /// worked on: a leaf's primitives tested, or an inner node's children).
    opened: Vec<u32>,
    /// Nodes tested and not opened (missed, or pruned by the best hit).
    rejected: Vec<u32>,
    /// The primitives the walk reports.
    found: Vec<u32>,
    /// The library's own counts.
    counts: Counts,
}

fn node_of<'a>(bvh: &'a Bvh<'_, Aabb>, n: u32) -> (Aabb, Content<'a>) {
    (Hierarchy::bv(bvh, n), Hierarchy::content(bvh, n))
}

/// The region query in `order` (`breadth` or depth-first), retraced, and
/// checked against [`Bvh::search`].
fn region_walk(
    bvh: &Bvh<'_, Aabb>,
    discs: &[Sphere],
    region: &Aabb,
    breadth: bool,
) -> Result<Walk, FigureError> {
    // The library's walk.
    let events = RefCell::new(Vec::new());
    let mut log = Log {
        counts: Counts::default(),
        events: &events,
    };
    let mut queue = vec![0u32; bvh.breadth_first_queue()];
    let order = if breadth {
        Order::BreadthFirst(&mut queue)
    } else {
        Order::DepthFirst
    };
    bvh.search(discs, region, order, &mut log, |p| {
        events.borrow_mut().push(Event::Prim(p))
    })?;
    // The retrace: same tests, same order.
    let mut mine = Vec::new();
    let (mut opened, mut rejected, mut found) = (Vec::new(), Vec::new(), Vec::new());
    let mut waiting = VecDeque::from([Hierarchy::root(bvh)]);
    while let Some(n) = if breadth {
        waiting.pop_front()
    } else {
        waiting.pop_back()
    } {
        mine.push(Event::Node);
        let (bv, content) = node_of(bvh, n);
        if !region.may_overlap(&bv) {
            rejected.push(n);
            continue;
        }
        opened.push(n);
        match content {
            Content::Leaf(ids) => {
                for &p in ids {
                    if region.overlaps_aabb(&discs[p as usize].bounds()) {
                        mine.push(Event::Prim(p));
                        found.push(p);
                    }
                }
                mine.push(Event::Prims(ids.len() as u32));
            }
            Content::Inner(kids) if breadth => waiting.extend(kids.as_slice()),
            Content::Inner(kids) => waiting.extend(kids.as_slice().iter().rev()),
        }
    }
    if mine != *events.borrow() {
        return Err(FigureError(format!(
            "the traversal figure's region walk (breadth-first: {breadth}) is not the library's"
        )));
    }
    Ok(Walk {
        opened,
        rejected,
        found,
        counts: log.counts,
    })
}

/// Whether hit `(t, p)` beats `best` (smaller `t`, then smaller index), as
/// the library decides.
fn beats(t: f32, p: u32, best: Option<(f32, u32)>) -> bool {
    best.is_none_or(|(bt, bp)| t < bt || (t == bt && p < bp))
}

/// The library's best-first queue: a binary min-heap on `(entry, node)`,
/// retraced so that ties pop in the same order.
#[derive(Default)]
struct Heap(Vec<(f64, u32)>);

impl Heap {
    fn push(&mut self, key: f64, node: u32) {
        let items = &mut self.0;
        items.push((key, node));
        let mut i = items.len() - 1;
        while i > 0 {
            let parent = (i - 1) / 2;
            if items[parent].0 <= items[i].0 {
                break;
            }
            items.swap(parent, i);
            i = parent;
        }
    }
    fn pop(&mut self) -> Option<(f64, u32)> {
        let items = &mut self.0;
        if items.is_empty() {
            return None;
        }
        let top = items.swap_remove(0);
        let mut i = 0;
        loop {
            let (l, r, mut m) = (2 * i + 1, 2 * i + 2, i);
            if l < items.len() && items[l].0 < items[m].0 {
                m = l;
            }
            if r < items.len() && items[r].0 < items[m].0 {
                m = r;
            }
            if m == i {
                break;
            }
            items.swap(i, m);
            i = m;
        }
        Some(top)
    }
}

/// The ray cast in `order`, retraced, and checked against
/// [`Bvh::cast_ray`]. Entry distances are the box's own ray test
/// ([`RayTarget`] for [`Aabb`]); the library's node test pads the box by a
/// few ulps, which the check would catch if it ever changed an order.
fn ray_walk(
    bvh: &Bvh<'_, Aabb>,
    discs: &[Sphere],
    ray: &Ray,
    order: RayOrder,
) -> Result<Walk, FigureError> {
    let events = RefCell::new(Vec::new());
    let noted: Vec<Noted<'_>> = discs
        .iter()
        .enumerate()
        .map(|(i, &disc)| Noted {
            disc,
            id: i as u32,
            events: &events,
        })
        .collect();
    let mut log = Log {
        counts: Counts::default(),
        events: &events,
    };
    let hit = bvh.cast_ray(&noted, ray, order, &mut log)?;

    let mut mine = vec![Event::Node];
    let (mut opened, mut rejected) = (Vec::new(), Vec::new());
    let mut best: Option<(f32, u32)> = None;
    let enter = |n: u32| Hierarchy::bv(bvh, n).ray_hit(ray);
    let root = Hierarchy::root(bvh);
    // Opens node `n`: tests a leaf's primitives, or returns the children
    // with their entries (the misses noted as rejected).
    let mut open = |n: u32,
                    mine: &mut Vec<Event>,
                    best: &mut Option<(f32, u32)>,
                    rejected: &mut Vec<u32>|
     -> Vec<(u32, f32)> {
        opened.push(n);
        match node_of(bvh, n).1 {
            Content::Leaf(ids) => {
                mine.push(Event::Prims(ids.len() as u32));
                for &p in ids {
                    mine.push(Event::Prim(p));
                    if let Some(t) = discs[p as usize].ray_hit(ray) {
                        if beats(t, p, *best) {
                            *best = Some((t, p));
                        }
                    }
                }
                Vec::new()
            }
            Content::Inner(kids) => {
                let mut entered = Vec::new();
                for &c in kids.as_slice() {
                    mine.push(Event::Node);
                    match enter(c) {
                        Some(t) => entered.push((c, t)),
                        None => rejected.push(c),
                    }
                }
                entered
            }
        }
    };
    match enter(root) {
        None => rejected.push(root),
        Some(t_root) => match order {
            RayOrder::DepthFirst => {
                // Nearer child first; the farther one waits on the stack.
                let mut stack = vec![(root, t_root)];
                while let Some((n, t)) = stack.pop() {
                    if best.is_some_and(|(bt, _)| t > bt) {
                        rejected.push(n);
                        continue;
                    }
                    let mut kids = open(n, &mut mine, &mut best, &mut rejected);
                    if let [(_, ta), (_, tb)] = kids[..] {
                        if tb < ta {
                            kids.swap(0, 1);
                        }
                    }
                    stack.extend(kids.into_iter().rev());
                }
            }
            RayOrder::BestFirst => {
                let mut heap = Heap::default();
                heap.push(t_root as f64, root);
                while let Some((t, n)) = heap.pop() {
                    if best.is_some_and(|(bt, _)| t as f32 > bt) {
                        // Everything still queued is at least as far.
                        rejected.push(n);
                        rejected.extend(heap.0.iter().map(|e| e.1));
                        break;
                    }
                    for (c, tc) in open(n, &mut mine, &mut best, &mut rejected) {
                        heap.push(tc as f64, c);
                    }
                }
            }
        },
    }
    if mine != *events.borrow() || hit.map(|h| (h.t, h.prim)) != best {
        return Err(FigureError(format!(
            "the traversal figure's ray walk ({order:?}) is not the library's"
        )));
    }
    Ok(Walk {
        opened,
        rejected,
        found: best.map(|b| b.1).into_iter().collect(),
        counts: log.counts,
    })
}

/// Vertical distance between two levels of the drawn tree, in leaf widths.
const LEVEL: f32 = 1.5;
/// Radius of a node's circle, in leaf widths.
const RADIUS: f32 = 0.42;

/// Where each node of the tree is drawn: leaves one unit apart from left to
/// right, each inner node above the middle of its children.
fn layout(bvh: &Bvh<'_, Aabb>) -> Vec<Vec2> {
    fn place(bvh: &Bvh<'_, Aabb>, n: u32, depth: f32, leaf: &mut f32, at: &mut [Vec2]) -> f32 {
        let x = match Hierarchy::content(bvh, n) {
            Content::Leaf(_) => {
                *leaf += 1.0;
                *leaf - 1.0
            }
            Content::Inner(kids) => {
                let xs: Vec<f32> = kids
                    .as_slice()
                    .iter()
                    .map(|&c| place(bvh, c, depth + 1.0, leaf, at))
                    .collect();
                (xs[0] + xs[xs.len() - 1]) * 0.5
            }
        };
        at[n as usize] = Vec2::new(x, -depth * LEVEL);
        x
    }
    let mut at = vec![Vec2::ZERO; bvh.node_count()];
    place(bvh, Hierarchy::root(bvh), 0.0, &mut 0.0, &mut at);
    at
}

/// The world box of the tree drawing.
fn tree_frame(at: &[Vec2]) -> (Vec2, Vec2) {
    let lo = at.iter().fold(Vec2::splat(f32::MAX), |m, &p| m.min(p));
    let hi = at.iter().fold(Vec2::splat(f32::MIN), |m, &p| m.max(p));
    (lo - Vec2::splat(0.6), hi + Vec2::splat(0.6))
}

/// Draws the tree as nodes and links, numbering the opened nodes in the
/// order of `walk`.
fn draw_tree(svg: &mut Svg, bvh: &Bvh<'_, Aabb>, at: &[Vec2], walk: &Walk) {
    let link = Style::line("#999999").width(1.0);
    for (n, node) in bvh.nodes().iter().enumerate() {
        if node.count == 0 {
            for c in [node.first, node.first + 1] {
                let (p, q) = (at[n], at[c as usize]);
                let d = (q - p).normalize() * RADIUS;
                svg.line(p + d, q - d, link);
            }
        }
    }
    let found_leaf = |n: u32| match Hierarchy::content(bvh, n) {
        Content::Leaf(ids) => ids.iter().any(|p| walk.found.contains(p)),
        Content::Inner(_) => false,
    };
    for n in 0..bvh.node_count() as u32 {
        let p = at[n as usize];
        if let Some(k) = walk.opened.iter().position(|&m| m == n) {
            let fill = if found_leaf(n) { colour(2) } else { colour(0) };
            svg.circle(p, RADIUS, Style::filled(fill, 0.3).width(1.2));
            svg.label(p, &(k + 1).to_string(), 10.0);
        } else if walk.rejected.contains(&n) {
            let style = Style {
                stroke: "#777777",
                fill: "#ffffff",
                fill_opacity: 1.0,
                width: 1.2,
                dashed: true,
            };
            svg.circle(p, RADIUS, style);
        } else {
            svg.dot(p, 2.5, "#aaaaaa");
        }
    }
}

/// The scene panel: the discs, the tree's inner boxes faintly, the found
/// discs filled.
fn draw_scene(svg: &mut Svg, bvh: &Bvh<'_, Aabb>, discs: &[Sphere], found: &[u32]) {
    for node in bvh.nodes().iter().filter(|n| n.count == 0) {
        svg.rect(
            node.bv.min.truncate(),
            node.bv.max.truncate(),
            Style::line("#bbbbbb").width(0.8),
        );
    }
    for (i, d) in discs.iter().enumerate() {
        let style = if found.contains(&(i as u32)) {
            Style::filled(colour(2), 0.5).width(1.0)
        } else {
            Style::filled("#555555", 0.12).width(1.0)
        };
        svg.circle(d.center.truncate(), d.radius, style);
    }
}

fn scene_frame(bvh: &Bvh<'_, Aabb>, extra: &[Vec2]) -> (Vec2, Vec2) {
    let root = Hierarchy::bv(bvh, Hierarchy::root(bvh));
    let (mut lo, mut hi) = (root.min.truncate(), root.max.truncate());
    for &p in extra {
        (lo, hi) = (lo.min(p), hi.max(p));
    }
    (lo - Vec2::splat(0.3), hi + Vec2::splat(0.3))
}

/// Size of every picture of this chapter.
const WIDTH: f32 = 900.0;
const HEIGHT: f32 = 300.0;

fn region_orders(bvh: &Bvh<'_, Aabb>, discs: &[Sphere]) -> Result<Figure, FigureError> {
    let region = Aabb::new(Vec3::new(3.0, 1.6, -1.0), Vec3::new(6.0, 3.6, 1.0));
    let depth = region_walk(bvh, discs, &region, false)?;
    let breadth = region_walk(bvh, discs, &region, true)?;
    let at = layout(bvh);
    let (lo, hi) = tree_frame(&at);
    let (slo, shi) = scene_frame(bvh, &[]);
    let mut svg = Svg::new(WIDTH, HEIGHT, slo, shi);
    svg.panel(
        0,
        3,
        slo,
        shi,
        &format!(
            "region: {} of {} discs found",
            depth.found.len(),
            discs.len()
        ),
    );
    draw_scene(&mut svg, bvh, discs, &depth.found);
    svg.rect(
        region.min.truncate(),
        region.max.truncate(),
        Style::line(colour(5)).width(2.0).dashed(),
    );
    for (i, (name, walk)) in [("depth-first", &depth), ("breadth-first", &breadth)]
        .into_iter()
        .enumerate()
    {
        svg.panel(
            i + 1,
            3,
            lo,
            hi,
            &format!(
                "{name}: Nv = {}, {} opened",
                walk.counts.bv_tests,
                walk.opened.len()
            ),
        );
        draw_tree(&mut svg, bvh, &at, walk);
    }
    Ok(Figure {
        name: "traversal-region-orders",
        chapter: "traversal.md",
        svg: svg.finish(),
    })
}

fn ray_orders(bvh: &Bvh<'_, Aabb>, discs: &[Sphere]) -> Result<Figure, FigureError> {
    let origin = Vec3::new(12.5, 5.0, 0.0);
    let a = 187.5f32.to_radians();
    let ray = Ray::new(origin, Vec3::new(a.cos(), a.sin(), 0.0), f32::INFINITY)?;
    let depth = ray_walk(bvh, discs, &ray, RayOrder::DepthFirst)?;
    let best = ray_walk(bvh, discs, &ray, RayOrder::BestFirst)?;
    let at = layout(bvh);
    let (lo, hi) = tree_frame(&at);
    let (slo, shi) = scene_frame(bvh, &[origin.truncate()]);
    // Where the ray leaves the drawn frame.
    let frame = Aabb::new(slo.extend(-1.0), shi.extend(1.0));
    let inside = Ray::new(origin + ray.dir() * 100.0, -ray.dir(), 100.0)?;
    let back = frame.ray_hit(&inside).unwrap_or(100.0);
    let end = origin + ray.dir() * (100.0 - back);
    let mut svg = Svg::new(WIDTH, HEIGHT, slo, shi);
    let hit = bvh.cast_ray(discs, &ray, RayOrder::BestFirst, ())?;
    svg.panel(
        0,
        3,
        slo,
        shi,
        &match hit {
            Some(h) => format!("ray: first hit at t = {:.2}", h.t),
            None => "ray: no hit".to_string(),
        },
    );
    draw_scene(&mut svg, bvh, discs, &best.found);
    let (o, e) = (origin.truncate(), end.truncate());
    svg.line(o, e, Style::line(colour(5)).width(2.0));
    svg.dot(o, 3.5, colour(5));
    if let Some(h) = hit {
        svg.dot((origin + ray.dir() * h.t).truncate(), 3.5, "#000000");
    }
    for (i, (name, walk)) in [("depth-first, nearer first", &depth), ("best-first", &best)]
        .into_iter()
        .enumerate()
    {
        svg.panel(
            i + 1,
            3,
            lo,
            hi,
            &format!(
                "{name}: Nv = {}, {} opened",
                walk.counts.bv_tests,
                walk.opened.len()
            ),
        );
        draw_tree(&mut svg, bvh, &at, walk);
    }
    Ok(Figure {
        name: "traversal-ray-orders",
        chapter: "traversal.md",
        svg: svg.finish(),
    })
}
