//! The advisor: from a scene's statistics and its workload, pick a builder,
//! a bounding volume, a tree representation and a traversal rule, and say
//! why.
//!
//! The advice is a handful of rules over cheap statistics ([`SceneStats`]),
//! not a search: it costs one pass over the primitives. [`evaluate`] keeps
//! the rules honest. It measures every combination of the grid on a scene
//! (each answer checked against brute force), finds the fastest for the
//! workload, and reports how much slower the advised combination is.
//!
//! ```
//! use bvhkit_std::advisor::{advise, Motion, QueryKind, SceneStats, Workload};
//! let a = bvhkit_std::scene::rock(2, 1);
//! let b = bvhkit_std::scene::rock(2, 2);
//! let stats = SceneStats::of(&a, Some(&b));
//! let advice = advise(&stats, &Workload::new(QueryKind::Pairs, Motion::Deforming));
//! assert!(!advice.reasons.is_empty());
//! println!("{}: {}", advice.choice, advice.reasons.join("; "));
//! ```

use crate::{median_time, scene, tour::Builder};
use bvhkit::builders::{BottomUp, Method};
use bvhkit::glam::{Quat, Vec3};
use bvhkit::layout::{
    Implicit, PreNode, Preorder, QuantNode, QuantizedWide, Slot, TriNode, TriNodes, Wide, WideNode,
};
use bvhkit::{
    Aabb, BoundingVolume, Bvh, Descent, Dop14, Error, Frame, Hierarchy, Obb, PairTraversal, Pairs,
    Place, Primitive, Query, Ray, RayOrder, Rigid, Same, Sphere, TopDown, Triangle,
};
use serde::Serialize;
use std::collections::HashSet;
use std::fmt;
use std::time::Instant;

/// What the scene is queried for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum QueryKind {
    /// Every intersecting triangle pair between two objects (exact test).
    Pairs,
    /// A batch of rays cast at one object (closest hit).
    Rays,
}

/// How the scene changes between frames.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Motion {
    /// Nothing moves: build once, query every frame.
    Static,
    /// Object B moves as a rigid body: build once in B's own frame, query
    /// with B's pose every frame.
    Rigid,
    /// The shapes change: rebuild every frame, then query.
    Deforming,
}

/// A workload: what is asked, how the scene moves, and for how many frames.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Workload {
    /// The query.
    pub query: QueryKind,
    /// The motion.
    pub motion: Motion,
    /// Frames (queries) per build for a static or rigid scene, and frames
    /// (each with its own build) for a deforming one.
    pub frames: usize,
}

impl Workload {
    /// One second at 60 frames per second.
    pub const fn new(query: QueryKind, motion: Motion) -> Self {
        Workload {
            query,
            motion,
            frames: 60,
        }
    }

    /// The workloads [`evaluate`] measures (rays do not distinguish rigid
    /// motion: the ray is moved instead of the tree).
    pub const ALL: [Workload; 5] = [
        Workload::new(QueryKind::Pairs, Motion::Static),
        Workload::new(QueryKind::Pairs, Motion::Rigid),
        Workload::new(QueryKind::Pairs, Motion::Deforming),
        Workload::new(QueryKind::Rays, Motion::Static),
        Workload::new(QueryKind::Rays, Motion::Deforming),
    ];
}

impl fmt::Display for Workload {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let q = match self.query {
            QueryKind::Pairs => "pairs",
            QueryKind::Rays => "rays",
        };
        let m = match self.motion {
            Motion::Static => "static",
            Motion::Rigid => "rigid",
            Motion::Deforming => "deforming",
        };
        write!(f, "{q}, {m}, {} frames", self.frames)
    }
}

/// Total time of a workload: a static or rigid scene builds once and queries
/// every frame; a deforming scene builds and queries every frame.
pub fn workload_ms(build_ms: f64, query_ms: f64, motion: Motion, frames: usize) -> f64 {
    let frames = frames as f64;
    match motion {
        Motion::Static | Motion::Rigid => build_ms + frames * query_ms,
        Motion::Deforming => frames * (build_ms + query_ms),
    }
}

/// The statistics the advice is drawn from: one pass over the primitives.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SceneStats {
    /// Primitives of object A (the one rays are cast at).
    pub primitives: usize,
    /// Primitives of object B (0 when there is none).
    pub other_primitives: usize,
    /// How evenly A fills its bounding box: the fraction of the cells of a
    /// cubic grid (about one cell per primitive) that hold a centroid. About
    /// 0.6 for a uniform soup, 0.2 down to a few percent for a surface of
    /// 5 000 primitives and more (a surface's share shrinks as the count
    /// grows; below a few thousand primitives everything looks filled),
    /// less for tight clusters.
    pub occupancy: f64,
    /// How much primitive sizes vary: the 90th percentile of the box
    /// diagonals over the 10th.
    pub size_spread: f64,
    /// Median sliver ratio of A's triangles: longest edge squared over twice
    /// the area (about 1.2 for an equilateral triangle, large for slivers).
    pub thinness: f64,
    /// B's bounding box diagonal over A's (1 when there is no B).
    pub size_ratio: f64,
}

impl SceneStats {
    /// Measures object `a` and, for a pair workload, object `b`.
    pub fn of(a: &[Triangle], b: Option<&[Triangle]>) -> SceneStats {
        let box_of = |tris: &[Triangle]| {
            tris.iter()
                .fold(Aabb::EMPTY, |acc, t| acc.union(&Primitive::bounds(t)))
        };
        let ba = box_of(a);
        let diag_a = (ba.max - ba.min).length() as f64;
        let size_ratio = match b {
            Some(b) if !b.is_empty() && diag_a > 0.0 => {
                let bb = box_of(b);
                (bb.max - bb.min).length() as f64 / diag_a
            }
            _ => 1.0,
        };
        let mut diagonals: Vec<f32> = a
            .iter()
            .map(|t| {
                let x = Primitive::bounds(t);
                (x.max - x.min).length()
            })
            .collect();
        diagonals.sort_unstable_by(f32::total_cmp);
        let pick = |q: f64| {
            diagonals
                .get(((diagonals.len() as f64 - 1.0) * q) as usize)
                .copied()
                .unwrap_or(0.0) as f64
        };
        let size_spread = pick(0.9) / pick(0.1).max(f64::MIN_POSITIVE);
        let mut thin: Vec<f64> = a
            .iter()
            .map(|t| {
                let [p, q, r] = t.v;
                let longest = (q - p)
                    .length_squared()
                    .max((r - q).length_squared())
                    .max((p - r).length_squared()) as f64;
                let twice_area = (q - p).cross(r - p).length() as f64;
                longest / twice_area.max(f64::MIN_POSITIVE)
            })
            .collect();
        thin.sort_unstable_by(f64::total_cmp);
        SceneStats {
            primitives: a.len(),
            other_primitives: b.map_or(0, <[Triangle]>::len),
            occupancy: occupancy(a, &ba),
            size_spread,
            thinness: thin.get(thin.len() / 2).copied().unwrap_or(0.0),
            size_ratio,
        }
    }
}

/// Fraction of the cells of a cubic grid over `bounds` (about one cell per
/// primitive) that hold at least one centroid.
fn occupancy(prims: &[Triangle], bounds: &Aabb) -> f64 {
    if prims.is_empty() {
        return 0.0;
    }
    let extent = (bounds.max - bounds.min).max(Vec3::splat(f32::MIN_POSITIVE));
    let volume = extent.x as f64 * extent.y as f64 * extent.z as f64;
    let cell = (volume / prims.len() as f64).cbrt() as f32;
    let dims = (extent / cell).ceil().max(Vec3::ONE);
    let total = dims.x as f64 * dims.y as f64 * dims.z as f64;
    let cells: HashSet<(u32, u32, u32)> = prims
        .iter()
        .map(|t| {
            let c = ((t.v[0] + t.v[1] + t.v[2]) / 3.0 - bounds.min) / cell;
            let c = c.min(dims - Vec3::ONE).max(Vec3::ZERO);
            (c.x as u32, c.y as u32, c.z as u32)
        })
        .collect();
    cells.len() as f64 / total
}

/// The builders of the grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum BuilderChoice {
    /// Top-down, binned SAH (16 bins): the best trees for their build time.
    Sah,
    /// Top-down, binned SAH with 8 bins: cheaper, slightly worse trees.
    Sah8,
    /// Top-down, object median on the widest axis: the cheapest top-down build.
    Median,
    /// Bottom-up PLOC (radius 4) over Morton-sorted clusters.
    Ploc,
}

impl BuilderChoice {
    /// Every builder of the grid.
    pub const ALL: [BuilderChoice; 4] = [
        BuilderChoice::Sah,
        BuilderChoice::Sah8,
        BuilderChoice::Median,
        BuilderChoice::Ploc,
    ];

    /// Short name.
    pub const fn name(self) -> &'static str {
        match self {
            BuilderChoice::Sah => "sah",
            BuilderChoice::Sah8 => "sah-8bins",
            BuilderChoice::Median => "median",
            BuilderChoice::Ploc => "ploc-r4",
        }
    }

    /// The builder itself.
    pub fn builder(self) -> Builder {
        match self {
            BuilderChoice::Sah => Builder::TopDown(TopDown::sah()),
            BuilderChoice::Sah8 => Builder::TopDown(
                bvhkit::builders::PRESETS
                    .iter()
                    .find(|p| p.name == "sah-8bins")
                    .map_or(TopDown::sah(), |p| p.builder),
            ),
            BuilderChoice::Median => Builder::TopDown(TopDown::median()),
            BuilderChoice::Ploc => Builder::BottomUp(BottomUp {
                method: Method::Ploc { radius: 4 },
                ..BottomUp::default()
            }),
        }
    }
}

/// The bounding volumes of the grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum VolumeChoice {
    /// Axis-aligned box.
    Aabb,
    /// Sphere.
    Sphere,
    /// Oriented box.
    Obb,
    /// 14-DOP.
    Dop14,
}

impl VolumeChoice {
    /// Every volume of the grid.
    pub const ALL: [VolumeChoice; 4] = [
        VolumeChoice::Aabb,
        VolumeChoice::Sphere,
        VolumeChoice::Obb,
        VolumeChoice::Dop14,
    ];

    /// Short name.
    pub const fn name(self) -> &'static str {
        match self {
            VolumeChoice::Aabb => "aabb",
            VolumeChoice::Sphere => "sphere",
            VolumeChoice::Obb => "obb",
            VolumeChoice::Dop14 => "14-dop",
        }
    }
}

/// The tree representations of the grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum LayoutChoice {
    /// The builder's own node array (children by index).
    Canonical,
    /// Preorder with one right link per node (32-bit).
    Preorder,
    /// Implicit complete-tree array (no links).
    Implicit,
    /// Tri-nodes (a node and its two children in one record).
    TriNode,
    /// 4-wide nodes with the children's boxes side by side (boxes only).
    Wide,
    /// 4-wide nodes with 8-bit boxes (boxes only).
    Quantized,
}

impl LayoutChoice {
    /// Every representation of the grid.
    pub const ALL: [LayoutChoice; 6] = [
        LayoutChoice::Canonical,
        LayoutChoice::Preorder,
        LayoutChoice::Implicit,
        LayoutChoice::TriNode,
        LayoutChoice::Wide,
        LayoutChoice::Quantized,
    ];

    /// Short name.
    pub const fn name(self) -> &'static str {
        match self {
            LayoutChoice::Canonical => "canonical",
            LayoutChoice::Preorder => "preorder",
            LayoutChoice::Implicit => "implicit",
            LayoutChoice::TriNode => "tri-node",
            LayoutChoice::Wide => "wide-4",
            LayoutChoice::Quantized => "quantized-4",
        }
    }
}

/// How the tree is walked: a two-tree traversal for pairs, an order for rays.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Walk {
    /// Two-tree pair traversal.
    Pairs(#[serde(with = "traversal_name")] PairTraversal),
    /// Ray traversal order.
    Rays(#[serde(with = "order_name")] RayOrder),
}

mod traversal_name {
    pub fn serialize<S: serde::Serializer>(
        t: &bvhkit::PairTraversal,
        s: S,
    ) -> Result<S::Ok, S::Error> {
        s.serialize_str(&super::Walk::Pairs(*t).to_string())
    }
}

mod order_name {
    pub fn serialize<S: serde::Serializer>(o: &bvhkit::RayOrder, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&super::Walk::Rays(*o).to_string())
    }
}

impl Walk {
    /// The pair traversals of the grid: the stack traversal with every
    /// descent rule, and the leaf-directed one.
    pub fn pair_walks() -> impl Iterator<Item = Walk> {
        Descent::ALL
            .into_iter()
            .map(|d| Walk::Pairs(PairTraversal::Stack(d)))
            .chain([Walk::Pairs(PairTraversal::LeafDirected)])
    }

    /// The ray orders of the grid.
    pub fn ray_walks() -> impl Iterator<Item = Walk> {
        [RayOrder::DepthFirst, RayOrder::BestFirst]
            .into_iter()
            .map(Walk::Rays)
    }
}

impl fmt::Display for Walk {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Walk::Pairs(PairTraversal::Stack(d)) => write!(f, "{}", d.name()),
            Walk::Pairs(t) => write!(f, "{}", t.name()),
            Walk::Rays(RayOrder::DepthFirst) => write!(f, "depth-first"),
            Walk::Rays(RayOrder::BestFirst) => write!(f, "best-first"),
        }
    }
}

/// One combination: builder, volume, representation, walk.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct Choice {
    /// Builder.
    pub builder: BuilderChoice,
    /// Bounding volume.
    pub volume: VolumeChoice,
    /// Representation.
    pub layout: LayoutChoice,
    /// Traversal rule.
    pub walk: Walk,
}

impl fmt::Display for Choice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} / {} / {} / {}",
            self.builder.name(),
            self.volume.name(),
            self.layout.name(),
            self.walk
        )
    }
}

/// The advisor's pick and its reasons, one per decision.
#[derive(Clone, Debug, Serialize)]
pub struct Advice {
    /// The combination.
    pub choice: Choice,
    /// Why, one sentence per part of the choice.
    pub reasons: Vec<String>,
}

/// Above this [`occupancy`](SceneStats::occupancy) a scene fills its box
/// (a soup, a field of grass) rather than lining a surface.
pub const VOLUME_FILLING: f64 = 0.3;

/// Picks a combination for `stats` under `workload`, with reasons.
///
/// The rules, and what they rest on (the book's Performance chapter has
/// the measurements):
/// - **builder:** a deforming scene rebuilds every frame, so the build is
///   paid per frame: binned SAH with 8 bins, which builds as fast as the
///   object median or PLOC (from 1,280 to 75,000 triangles measured) and
///   gives trees that query faster than either. Built once (static or
///   rigid): binned SAH with 16 bins, whose trees measured fastest for pairs
///   and rays.
/// - **volume:** boxes, always. Tighter volumes prune more, but each test
///   costs more and boxes enable the 4-wide layout; no scene measured
///   preferred another volume, not even slivers, where spheres are 35 times
///   looser.
/// - **layout:** 4-wide, unless the tree is rebuilt every frame (then the
///   conversion is paid per frame and the canonical nodes win).
/// - **walk:** rays depth-first, nearer child first. Pairs: simultaneous
///   descent when the objects are of similar size (the lectures' rule for
///   alike trees), larger-first when they differ by more than 2x; with B
///   moving through a volume-filling scene, B first.
pub fn advise(stats: &SceneStats, workload: &Workload) -> Advice {
    let mut reasons = Vec::new();
    let n = stats.primitives;
    let builder = match (workload.motion, workload.query) {
        (Motion::Deforming, _) => {
            reasons.push(format!(
                "builder sah-8bins: the scene deforms, so the tree is rebuilt every frame and the \
                 build is part of each frame's cost; binned SAH with 8 bins builds {n} primitives \
                 about as fast as the object median or PLOC, and its trees query faster than \
                 either (measured on every scene of the recorded bench run)"
            ));
            BuilderChoice::Sah8
        }
        (Motion::Static, QueryKind::Pairs) => {
            reasons.push(format!(
                "builder sah: built once and queried {} times, so query speed decides; binned \
                 SAH trees gave the fastest pair queries on the measured scenes (PLOC's build \
                 is no faster and its trees query slower)",
                workload.frames
            ));
            BuilderChoice::Sah
        }
        (Motion::Rigid, _) | (Motion::Static, QueryKind::Rays) => {
            reasons.push(format!(
                "builder sah: built once and queried {} times, so tree quality pays back the \
                 build; SAH minimises the expected ray cost, and its trees measured fastest for \
                 rays and for pairs with B moving",
                workload.frames
            ));
            BuilderChoice::Sah
        }
    };
    reasons.push(
        "volume aabb: the cheapest overlap and ray tests, and the 4-wide layouts store boxes; \
         tighter volumes prune a few more tests but each costs more (no measured scene preferred \
         another volume)"
            .into(),
    );
    let layout = if workload.motion == Motion::Deforming {
        reasons.push(
            "layout canonical: the tree is rebuilt every frame, and a conversion to the 4-wide \
             layout would be paid every frame for less than it saves in one query"
                .into(),
        );
        LayoutChoice::Canonical
    } else {
        reasons.push(
            "layout wide-4: one record holds four child boxes side by side, tested together, \
             which halves the node visits; converting costs a few percent of a build"
                .into(),
        );
        LayoutChoice::Wide
    };
    let walk = match workload.query {
        QueryKind::Rays => {
            reasons.push(
                "walk depth-first: nearer child first finds the closest hit early and prunes \
                 the rest; best-first pays a priority queue per node"
                    .into(),
            );
            Walk::Rays(RayOrder::DepthFirst)
        }
        QueryKind::Pairs => {
            let ratio = stats.size_ratio;
            let alike = (0.5..=2.0).contains(&ratio);
            let descent =
                if workload.motion == Motion::Rigid && stats.occupancy > VOLUME_FILLING && alike {
                    reasons.push(format!(
                        "walk b-first: B moves, and the scene fills its box (occupancy {:.2} > \
                     {VOLUME_FILLING}), so nearly every node pair overlaps; descending B first \
                     measured fastest there",
                        stats.occupancy
                    ));
                    Descent::BFirst
                } else if alike {
                    reasons.push(format!(
                        "walk simultaneous: the objects are of similar size (B/A {ratio:.2}), so \
                     opening both nodes keeps them matched with the fewest steps"
                    ));
                    Descent::Simultaneous
                } else {
                    reasons.push(format!(
                        "walk larger-first: the objects differ in size (B/A {ratio:.2}), so open \
                     the larger volume and keep the two comparable"
                    ));
                    Descent::Larger
                };
            Walk::Pairs(PairTraversal::Stack(descent))
        }
    };
    Advice {
        choice: Choice {
            builder,
            volume: VolumeChoice::Aabb,
            layout,
            walk,
        },
        reasons,
    }
}

/// The combination a user gets without advice: SAH, boxes, canonical nodes,
/// the default walk.
pub fn default_choice(query: QueryKind) -> Choice {
    Choice {
        builder: BuilderChoice::Sah,
        volume: VolumeChoice::Aabb,
        layout: LayoutChoice::Canonical,
        walk: match query {
            QueryKind::Pairs => Walk::Pairs(PairTraversal::default()),
            QueryKind::Rays => Walk::Rays(RayOrder::DepthFirst),
        },
    }
}

/// A scene to evaluate on: object A, object B in its own frame, and B's pose.
#[derive(Clone, Debug)]
pub struct Case {
    /// Scene name.
    pub name: String,
    /// Object A (rays are cast at it).
    pub a: Vec<Triangle>,
    /// Object B in its own frame.
    pub b_local: Vec<Triangle>,
    /// B's pose in A's frame.
    pub motion: Rigid,
}

impl Case {
    /// A case from one mesh: B is a copy turned by about 20 degrees and
    /// shifted by a twentieth of the mesh's size, so the two overlap widely.
    pub fn from_mesh(name: &str, mesh: &[Triangle]) -> Result<Case, Error> {
        let b = mesh
            .iter()
            .fold(Aabb::EMPTY, |acc, t| acc.union(&Primitive::bounds(t)));
        // An empty mesh has no box (an inverted one): place B at the origin.
        let (centre, size) = if mesh.is_empty() {
            (Vec3::ZERO, 0.0)
        } else {
            (b.center(), (b.max - b.min).length())
        };
        let local: Vec<Triangle> = mesh.iter().map(|t| t.translated(-centre)).collect();
        let turn = Quat::from_rotation_y(0.35) * Quat::from_rotation_x(0.1);
        Ok(Case {
            name: name.to_string(),
            a: mesh.to_vec(),
            b_local: local,
            motion: Rigid::new(turn, centre + Vec3::X * size / 20.0)?,
        })
    }

    /// The generated scenes at about `n` triangles per object: two rocks, a
    /// soup, clusters and slivers (each against a turned, shifted copy of a
    /// second draw).
    pub fn generated(subdivisions: u32) -> Result<Vec<Case>, Error> {
        let a = scene::rock(subdivisions, 1);
        let n = a.len();
        let rocks = Case {
            name: "rocks".into(),
            a,
            b_local: scene::rock(subdivisions, 2),
            motion: crate::collide::default_motion(),
        };
        let draw = |name: &str, f: fn(usize, u64) -> Vec<Triangle>| -> Result<Case, Error> {
            Ok(Case {
                name: name.into(),
                a: f(n, 7),
                b_local: f(n, 8),
                motion: Rigid::new(Quat::from_rotation_y(0.6), Vec3::new(0.3, 0.05, 0.1))?,
            })
        };
        Ok(vec![
            rocks,
            draw("soup", scene::soup)?,
            draw("clustered", scene::clustered)?,
            draw("slivers", scene::slivers)?,
        ])
    }

    /// B placed in A's frame.
    pub fn b_world(&self) -> Vec<Triangle> {
        self.b_local.iter().map(|t| self.motion.place(t)).collect()
    }
}

/// One combination measured on one case.
#[derive(Clone, Debug, Serialize)]
pub struct Measurement {
    /// The combination.
    pub choice: Choice,
    /// For pairs: whether B was queried through its pose (built in its own
    /// frame) rather than placed in A's frame.
    pub moved: bool,
    /// Median build (plus conversion) time: A and B for pairs, A for rays.
    pub build_ms: f64,
    /// Median time of one query: all pairs, or the whole ray batch.
    pub query_ms: f64,
    /// Whether the answer equalled brute force.
    pub verified: bool,
}

impl Measurement {
    /// Whether this measurement prices `workload`.
    pub fn serves(&self, workload: &Workload) -> bool {
        match (workload.query, self.choice.walk) {
            (QueryKind::Pairs, Walk::Pairs(_)) => self.moved == (workload.motion == Motion::Rigid),
            (QueryKind::Rays, Walk::Rays(_)) => true,
            _ => false,
        }
    }

    /// The workload's total time with this combination.
    pub fn total_ms(&self, workload: &Workload) -> f64 {
        workload_ms(
            self.build_ms,
            self.query_ms,
            workload.motion,
            workload.frames,
        )
    }
}

/// What the grid is checked against, computed once per case.
struct Reference<'c> {
    case: &'c Case,
    b_world: Vec<Triangle>,
    pairs: Vec<(u32, u32)>,
    rays: Vec<Ray>,
    hits: Vec<Option<u32>>,
    runs: usize,
    /// Fastest single query so far per class (pairs in A's frame, pairs
    /// moved, rays): a combination whose checking run is already more than
    /// twice as slow keeps that run's time instead of `runs` more. It stays
    /// in the grid; only its time is less precise.
    fastest: std::cell::Cell<[f64; 3]>,
}

impl Reference<'_> {
    /// Times `query` (whose first, checking run took `first_ms`): the median
    /// of `runs` runs, or `first_ms` alone when it is far behind the fastest
    /// of its class.
    fn time<R>(&self, class: usize, first_ms: f64, query: impl FnMut() -> R) -> f64 {
        let mut fastest = self.fastest.get();
        let ms = if first_ms > 2.0 * fastest[class] {
            first_ms
        } else {
            ms(median_time(self.runs, query).0)
        };
        fastest[class] = fastest[class].min(ms);
        self.fastest.set(fastest);
        ms
    }
}

impl<'c> Reference<'c> {
    fn new(case: &'c Case, rays: usize, runs: usize) -> Reference<'c> {
        let b_world = case.b_world();
        // Exact pairs by brute force, filtered by boxes first (an exact hit
        // implies the boxes overlap).
        let mut pairs: Vec<(u32, u32)> = crate::tour::reference_pairs(&case.a, &b_world)
            .into_iter()
            .filter(|&(i, j)| {
                bvhkit::narrow::triangles_intersect(&case.a[i as usize], &b_world[j as usize])
            })
            .collect();
        pairs.sort_unstable();
        let rays = crate::layouts::rays(&case.a, rays);
        let hits = rays
            .iter()
            .map(|r| bvhkit::brute_force::ray_closest(&case.a, r).map(|h| h.prim))
            .collect();
        Reference {
            case,
            b_world,
            pairs,
            rays,
            hits,
            runs,
            fastest: std::cell::Cell::new([f64::INFINITY; 3]),
        }
    }
}

fn ms(d: std::time::Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

/// Times every pair walk between `ta` and `tb` (B in `frame`) and every ray
/// order on `ta`.
#[allow(clippy::too_many_arguments)]
fn time_walks<A, H, F>(
    r: &Reference<'_>,
    ta: &A,
    tb: &H,
    pb: &[Triangle],
    frame: F,
    with_rays: bool,
    (builder, volume, layout): (BuilderChoice, VolumeChoice, LayoutChoice),
    (build_a, build_b): (f64, f64),
    out: &mut Vec<Measurement>,
) -> Result<(), Error>
where
    A: Hierarchy,
    H: Hierarchy<Bv = A::Bv>,
    F: Frame + Place<Triangle> + Copy,
{
    let a = &r.case.a[..];
    let measured = |walk, moved, build_ms, query_ms, verified| Measurement {
        choice: Choice {
            builder,
            volume,
            layout,
            walk,
        },
        moved,
        build_ms,
        query_ms,
        verified,
    };
    for walk in Walk::pair_walks() {
        let Walk::Pairs(traversal) = walk else {
            continue;
        };
        let query = || {
            Pairs::new(ta, a, tb, pb)
                .traversal(traversal)
                .in_frame_of(frame)
                .exact()
        };
        let mut found = Vec::with_capacity(r.pairs.len());
        let t = Instant::now();
        query().for_each(|i, j| found.push((i, j)))?;
        let first = ms(t.elapsed());
        found.sort_unstable();
        let t = r.time(usize::from(F::MOVES), first, || query().count());
        out.push(measured(
            walk,
            F::MOVES,
            build_a + build_b,
            t,
            found == r.pairs,
        ));
    }
    if !with_rays {
        return Ok(());
    }
    for walk in Walk::ray_walks() {
        let Walk::Rays(order) = walk else {
            continue;
        };
        let cast = || -> Result<Vec<Option<u32>>, Error> {
            r.rays
                .iter()
                .map(|ray| Ok(ta.cast_ray(a, ray, order, ())?.map(|h| h.prim)))
                .collect()
        };
        let t = Instant::now();
        let hits = cast()?;
        let first = ms(t.elapsed());
        let t = r.time(2, first, cast);
        out.push(measured(walk, false, build_a, t, hits == r.hits));
    }
    Ok(())
}

/// Converts a canonical tree into a layout, timing the conversion (best of
/// `runs`): `$needed` sizes the storage, `$convert` fills it.
macro_rules! convert {
    ($runs:expr, $tree:expr, $store:ident, $empty:expr, $needed:expr, $convert:expr) => {{
        let n = $needed($tree)?;
        $store = vec![$empty; n];
        let mut best = f64::INFINITY;
        for _ in 0..$runs {
            let mut scratch = vec![$empty; n];
            let t = Instant::now();
            $convert($tree, &mut scratch)?;
            best = best.min(ms(t.elapsed()));
        }
        ($convert($tree, &mut $store)?, best)
    }};
}

/// The three trees of one builder and volume: A, B placed, B in its frame.
struct Trees<'t, B> {
    a: Bvh<'t, B>,
    b_world: Bvh<'t, B>,
    b_local: Bvh<'t, B>,
}

/// Measures every representation and walk of one (builder, volume).
fn measure_trees<B: BoundingVolume>(
    r: &Reference<'_>,
    trees: &Trees<'_, B>,
    (builder, volume): (BuilderChoice, VolumeChoice),
    (build_a, build_b): (f64, f64),
    out: &mut Vec<Measurement>,
) -> Result<(), Error> {
    let (a, bw, bl) = (&trees.a, &trees.b_world, &trees.b_local);
    let motion = r.case.motion;
    let local = &r.case.b_local[..];
    let runs = r.runs;
    let key = |layout| (builder, volume, layout);
    let times = |extra: f64| (build_a + extra, build_b + extra);
    // Canonical.
    time_walks(
        r,
        a,
        bw,
        &r.b_world,
        Same,
        true,
        key(LayoutChoice::Canonical),
        times(0.0),
        out,
    )?;
    time_walks(
        r,
        a,
        bl,
        local,
        motion,
        false,
        key(LayoutChoice::Canonical),
        times(0.0),
        out,
    )?;

    // The binary layouts, generic over the volume. A refused conversion
    // (an implicit array too sparse) drops the layout from the grid.
    macro_rules! binary {
        ($layout:expr, $rec:ty, $empty:expr, $needed:expr, $convert:expr) => {{
            let mut go = || -> Result<(), Error> {
                let (mut sa, mut sw, mut sl): (Vec<$rec>, Vec<$rec>, Vec<$rec>);
                let (la, ca) = convert!(runs, a, sa, $empty, $needed, $convert);
                let (lw, cw) = convert!(1, bw, sw, $empty, $needed, $convert);
                let (ll, _) = convert!(1, bl, sl, $empty, $needed, $convert);
                let key = key($layout);
                let t = (build_a + ca, build_b + cw);
                time_walks(r, &la, &lw, &r.b_world, Same, true, key, t, out)?;
                time_walks(r, &la, &ll, local, motion, false, key, t, out)
            };
            match go() {
                Ok(()) | Err(Error::SparseTree { .. }) => {}
                Err(e) => return Err(e),
            }
        }};
    }
    // Representations only on boxes: the other volumes lose to boxes on
    // every scene measured, by more than any representation changes, and
    // their queries are the slow part of the grid.
    if volume != VolumeChoice::Aabb {
        return Ok(());
    }
    let nodes = |t: &Bvh<B>| Ok::<usize, Error>(t.node_count());
    binary!(
        LayoutChoice::Preorder,
        PreNode<B, u32>,
        PreNode::<B, u32>::EMPTY,
        nodes,
        Preorder::from_bvh
    );
    binary!(
        LayoutChoice::Implicit,
        Slot<B>,
        Slot::EMPTY,
        Implicit::slots_needed,
        Implicit::from_bvh
    );
    binary!(
        LayoutChoice::TriNode,
        TriNode<B>,
        TriNode::EMPTY,
        TriNodes::records_needed,
        TriNodes::from_bvh
    );
    binary!(
        LayoutChoice::Wide,
        WideNode,
        WideNode::EMPTY,
        Wide::records_needed,
        Wide::from_bvh
    );
    binary!(
        LayoutChoice::Quantized,
        QuantNode,
        QuantNode::EMPTY,
        QuantizedWide::records_needed,
        QuantizedWide::from_bvh
    );
    Ok(())
}

fn measure_volume<B: BoundingVolume>(
    r: &Reference<'_>,
    builder: BuilderChoice,
    volume: VolumeChoice,
    out: &mut Vec<Measurement>,
) -> Result<(), Error> {
    let b = builder.builder();
    let (ta, a) = median_time(r.runs, || b.build::<B>(&r.case.a));
    let (tb, bw) = median_time(r.runs, || b.build::<B>(&r.b_world));
    let (a, bw) = (a?, bw?);
    let bl = b.build::<B>(&r.case.b_local)?;
    let trees = Trees {
        a: a.view(),
        b_world: bw.view(),
        b_local: bl.view(),
    };
    measure_trees(r, &trees, (builder, volume), (ms(ta), ms(tb)), out)
}

/// Measures the grid on `case`: every builder × walk with boxes in every
/// representation, and with the other volumes in the canonical one; for
/// pairs in A's frame, pairs with B moved, and a batch of `rays` rays;
/// `runs` timed runs each (the median is kept).
///
/// ```
/// use bvhkit_std::advisor::{judge, measure_grid, Case, Workload};
/// let case = Case::generated(1)?.swap_remove(0); // two rocks of 80 triangles
/// let grid = measure_grid(&case, 10, 1, |_| {})?;
/// assert!(grid.iter().all(|m| m.verified));
/// let rows = judge(&case, &grid, &Workload::ALL);
/// assert_eq!(rows.len(), Workload::ALL.len());
/// assert!(rows.iter().all(|r| r.ratio >= 1.0 && r.rank <= r.candidates));
/// # Ok::<(), bvhkit::Error>(())
/// ```
pub fn measure_grid(
    case: &Case,
    rays: usize,
    runs: usize,
    mut progress: impl FnMut(&str),
) -> Result<Vec<Measurement>, Error> {
    let r = Reference::new(case, rays, runs);
    let mut out = Vec::new();
    for builder in BuilderChoice::ALL {
        for volume in VolumeChoice::ALL {
            progress(&format!(
                "{}: {} / {}",
                case.name,
                builder.name(),
                volume.name()
            ));
            match volume {
                VolumeChoice::Aabb => measure_volume::<Aabb>(&r, builder, volume, &mut out)?,
                VolumeChoice::Sphere => measure_volume::<Sphere>(&r, builder, volume, &mut out)?,
                VolumeChoice::Obb => measure_volume::<Obb>(&r, builder, volume, &mut out)?,
                VolumeChoice::Dop14 => measure_volume::<Dop14>(&r, builder, volume, &mut out)?,
            }
        }
    }
    Ok(out)
}

/// The advisor against the best combination on one case and workload.
#[derive(Clone, Debug, Serialize)]
pub struct AdvisorRow {
    /// Scene.
    pub scene: String,
    /// Workload.
    pub workload: String,
    /// The advised combination.
    pub advised: String,
    /// Its total time.
    pub advised_ms: f64,
    /// The fastest combination measured.
    pub best: String,
    /// Its total time.
    pub best_ms: f64,
    /// `advised_ms / best_ms` (1 is the best possible).
    pub ratio: f64,
    /// The default combination's (SAH, AABB, canonical, default walk)
    /// total time over the best.
    pub default_ratio: f64,
    /// The advised combination's place among all measured (1 = fastest).
    pub rank: usize,
    /// Combinations measured for this workload.
    pub candidates: usize,
    /// Whether every combination's answers equalled brute force.
    pub all_verified: bool,
}

/// Compares the advice with the measured grid for each workload (see
/// [`measure_grid`] for an example). A workload whose advised or default
/// combination is missing from the grid gets no row.
pub fn judge(case: &Case, grid: &[Measurement], workloads: &[Workload]) -> Vec<AdvisorRow> {
    let stats = SceneStats::of(&case.a, Some(&case.b_local));
    workloads
        .iter()
        .filter_map(|w| {
            let mut rows: Vec<(f64, &Measurement)> = grid
                .iter()
                .filter(|m| m.serves(w))
                .map(|m| (m.total_ms(w), m))
                .collect();
            rows.sort_by(|x, y| x.0.total_cmp(&y.0));
            let (best_ms, best) = *rows.first()?;
            let advice = advise(&stats, w);
            let find = |c: Choice| rows.iter().position(|(_, m)| m.choice == c);
            let at = find(advice.choice)?;
            let default_at = find(default_choice(w.query))?;
            let best_ms = best_ms.max(f64::MIN_POSITIVE);
            Some(AdvisorRow {
                scene: case.name.clone(),
                workload: w.to_string(),
                advised: advice.choice.to_string(),
                advised_ms: rows[at].0,
                best: best.choice.to_string(),
                best_ms,
                ratio: rows[at].0 / best_ms,
                default_ratio: rows[default_at].0 / best_ms,
                rank: at + 1,
                candidates: rows.len(),
                all_verified: rows.iter().all(|(_, m)| m.verified),
            })
        })
        .collect()
}

/// Measures the grid on each case and judges the advice on every workload.
pub fn evaluate(
    cases: &[Case],
    rays: usize,
    runs: usize,
    mut progress: impl FnMut(&str),
) -> Result<Vec<AdvisorRow>, Error> {
    let mut rows = Vec::new();
    for case in cases {
        let grid = measure_grid(case, rays, runs, &mut progress)?;
        rows.extend(judge(case, &grid, &Workload::ALL));
    }
    Ok(rows)
}

/// Geometric mean and largest value of the ratios (`(1, 1)` when empty).
pub fn summary(ratios: impl IntoIterator<Item = f64>) -> (f64, f64) {
    let (mut log_sum, mut n, mut worst) = (0.0, 0usize, 1.0f64);
    for r in ratios {
        log_sum += r.ln();
        n += 1;
        worst = worst.max(r);
    }
    if n == 0 {
        return (1.0, 1.0);
    }
    ((log_sum / n as f64).exp(), worst)
}

/// The rows as a markdown table with a summary line.
pub fn render(rows: &[AdvisorRow]) -> String {
    let mut out = String::from(
        "| scene | workload | advised | best measured | advised / best | default / best | rank | verified |\n\
         |---|---|---|---|---:|---:|---:|---|\n",
    );
    for r in rows {
        out += &format!(
            "| {} | {} | {} | {} | {:.2} | {:.2} | {}/{} | {} |\n",
            r.scene,
            r.workload,
            r.advised,
            r.best,
            r.ratio,
            r.default_ratio,
            r.rank,
            r.candidates,
            if r.all_verified { "yes" } else { "NO" }
        );
    }
    let (mean, worst) = summary(rows.iter().map(|r| r.ratio));
    let (dmean, dworst) = summary(rows.iter().map(|r| r.default_ratio));
    out += &format!(
        "\nAdvised over best: geometric mean {mean:.2}, worst {worst:.2}. \
         The default combination: geometric mean {dmean:.2}, worst {dworst:.2}.\n"
    );
    out
}

/// What `bvhkit advise` prints: the statistics, the advice and, when
/// measured, how it compares with the fastest combinations.
#[derive(Clone, Debug, Serialize)]
pub struct CaseReport {
    /// Scene.
    pub scene: String,
    /// Workload.
    pub workload: Workload,
    /// The statistics the advice came from.
    pub stats: SceneStats,
    /// The advice.
    pub advice: Advice,
    /// The comparison with the grid (empty unless measured).
    pub measured: Vec<AdvisorRow>,
    /// The five fastest combinations and their total times (unless empty).
    pub fastest: Vec<(String, f64)>,
}

/// Advises on one case and, if `measure`, measures the grid on it.
pub fn advise_case(
    case: &Case,
    workload: &Workload,
    measure: bool,
    rays: usize,
    runs: usize,
    progress: impl FnMut(&str),
) -> Result<CaseReport, Error> {
    let stats = SceneStats::of(&case.a, Some(&case.b_local));
    let advice = advise(&stats, workload);
    let (mut measured, mut fastest) = (Vec::new(), Vec::new());
    if measure {
        let grid = measure_grid(case, rays, runs, progress)?;
        measured = judge(case, &grid, std::slice::from_ref(workload));
        let mut totals: Vec<(String, f64)> = grid
            .iter()
            .filter(|m| m.serves(workload))
            .map(|m| (m.choice.to_string(), m.total_ms(workload)))
            .collect();
        totals.sort_by(|x, y| x.1.total_cmp(&y.1));
        totals.truncate(5);
        fastest = totals;
    }
    Ok(CaseReport {
        scene: case.name.clone(),
        workload: *workload,
        stats,
        advice,
        measured,
        fastest,
    })
}

/// The report as text.
pub fn render_case(r: &CaseReport) -> String {
    let s = &r.stats;
    let mut out = format!(
        "scene: {} ({} + {} triangles)\nworkload: {}\n\nstatistics: occupancy {:.3}, size spread {:.1}, \
         thinness {:.1}, B/A size {:.2}\n\nadvice: {}\n",
        r.scene,
        s.primitives,
        s.other_primitives,
        r.workload,
        s.occupancy,
        s.size_spread,
        s.thinness,
        s.size_ratio,
        r.advice.choice
    );
    for why in &r.advice.reasons {
        out += &format!("  - {why}\n");
    }
    for m in &r.measured {
        out +=
            &format!(
            "\nmeasured {} combinations (answers {} brute force):\n  advised: {:.2} ms, rank {} \
             ({:.2}x the fastest)\n  default (sah/aabb/canonical): {:.2}x the fastest\n",
            m.candidates,
            if m.all_verified { "all equal" } else { "NOT all equal to" },
            m.advised_ms,
            m.rank,
            m.ratio,
            m.default_ratio
        );
    }
    if !r.fastest.is_empty() {
        out += "\nfastest:\n";
        for (c, ms) in &r.fastest {
            out += &format!("  {ms:10.2} ms  {c}\n");
        }
    }
    out
}
