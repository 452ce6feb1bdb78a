//! `bvhkit collide`: one tree-against-tree query, measured and (optionally)
//! checked against brute force.
//!
//! The default scene is the rock of the tour and a moved copy of the *same*
//! tree: B is not rebuilt, it is queried in A's frame through a rigid motion
//! (each moved node volume counts as an update, `Nu`).
//!
//! With [`CollideOptions::distance`], the run also asks
//! [`bvhkit::query::Distance`] for the closest pair of triangles, with B in
//! the same place (on the built-in scene, through the same motion: no
//! rebuild).

use crate::builders::Builder;
use crate::tour::reference_pairs;
use crate::{median_time, scene};
use bvhkit::glam::{DVec3, Quat, Vec3};
use bvhkit::query::Distance;
use bvhkit::{
    Aabb, BoundingVolume, Counts, Descent, Dop14, Dop18, Dop26, Frame, Intersects, Obb,
    PairTraversal, Pairs, Place, Primitive, Rigid, Same, Sphere, Triangle,
};
use serde::Serialize;
use std::time::Instant;

/// Bounding volume names accepted by `--bv`: `obb` fits by PCA, `obb-dito`
/// by DiTO ([`bvhkit::ObbDito`]).
pub const VOLUMES: [&str; 7] = [
    "aabb", "sphere", "obb", "obb-dito", "14-dop", "18-dop", "26-dop",
];

/// Traversal kinds accepted by `--traversal`.
pub const TRAVERSALS: [&str; 4] = ["stack", "recursive", "simultaneous", "leaf-directed"];

/// What the query returns.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Mode {
    /// Every contact, handed to a callback (here: stored).
    All,
    /// Stop at the first contact.
    First,
    /// Only count.
    Count,
}

/// Options of one `collide` run.
#[derive(Clone, Debug)]
pub struct CollideOptions {
    /// One of [`VOLUMES`].
    pub volume: String,
    /// A builder name (see [`crate::builders::names`]).
    pub builder: String,
    /// One of [`TRAVERSALS`].
    pub traversal: String,
    /// Descent rule for the stack and recursive traversals.
    pub descent: Descent,
    /// Result mode.
    pub mode: Mode,
    /// Timed runs (median reported).
    pub runs: usize,
    /// Compare with brute force.
    pub verify: bool,
    /// Also measure the distance between the objects (the closest pair of
    /// triangles); with `verify`, against [`bvhkit::brute_force::closest_pair`].
    pub distance: bool,
}

/// The most triangle pairs (`|A| * |B|`) that `verify` with `distance`
/// measures by brute force (every pair: about 0.2 s per million in a
/// release build on the 2-core test machine, 5 s for the rock at 4
/// subdivisions, 5 120 triangles each): larger scenes are refused with a
/// message rather than left running for minutes (the default rock pair
/// would take about 20 minutes). The contacts' --verify needs no limit:
/// it only tests box pairs.
pub const VERIFY_DISTANCE_MAX_PAIRS: usize = 30_000_000;

/// Refuses a brute-force distance check over more than
/// [`VERIFY_DISTANCE_MAX_PAIRS`] triangle pairs.
pub fn check_verify_distance(triangles_a: usize, triangles_b: usize) -> Result<(), String> {
    let pairs = triangles_a.saturating_mul(triangles_b);
    if pairs > VERIFY_DISTANCE_MAX_PAIRS {
        return Err(format!(
            "--verify with --distance measures every triangle pair by brute force: \
             {triangles_a} x {triangles_b} = {pairs} pairs is over the limit of \
             {VERIFY_DISTANCE_MAX_PAIRS} (use smaller meshes, --subdivisions 4 or less, \
             or leave out --verify)"
        ));
    }
    Ok(())
}

impl Default for CollideOptions {
    fn default() -> Self {
        CollideOptions {
            volume: "aabb".into(),
            builder: "sah".into(),
            traversal: "stack".into(),
            descent: Descent::Simultaneous,
            mode: Mode::All,
            runs: 5,
            verify: false,
            distance: false,
        }
    }
}

/// The objects to collide.
#[derive(Clone, Debug)]
pub enum Input {
    /// The built-in rock against a moved copy of itself.
    Default {
        /// Icosphere subdivisions (6 = 81 920 triangles).
        subdivisions: u32,
        /// Applied to B after [`default_motion`] (the identity leaves the
        /// default scene): B's tree is moved, not rebuilt.
        placement: Rigid,
    },
    /// Two meshes, in the same frame.
    Meshes {
        /// Name for the report.
        name: String,
        /// Triangles of A.
        a: Vec<Triangle>,
        /// Triangles of B.
        b: Vec<Triangle>,
    },
}

impl Input {
    /// The built-in scene as it is, with `subdivisions`.
    pub fn default_scene(subdivisions: u32) -> Input {
        Input::Default {
            subdivisions,
            placement: Rigid::IDENTITY,
        }
    }
}

/// The motion that places the default scene's copy: a turn and a shift that
/// make the two rocks overlap partly.
pub fn default_motion() -> Rigid {
    let turn = Quat::from_rotation_y(0.7) * Quat::from_rotation_x(0.35);
    match Rigid::new(turn, Vec3::new(1.35, 0.2, 0.1)) {
        Ok(m) => m,
        Err(e) => unreachable!("constant motion is valid: {e}"),
    }
}

/// What `collide` measured.
#[derive(Clone, Debug, Serialize)]
pub struct CollideReport {
    /// Scene description.
    pub scene: String,
    /// Triangles in A.
    pub triangles_a: usize,
    /// Triangles in B.
    pub triangles_b: usize,
    /// Bounding volume.
    pub volume: String,
    /// Builder preset.
    pub builder: String,
    /// Traversal kind.
    pub traversal: String,
    /// Descent rule (for stack / recursive).
    pub descent: String,
    /// Result mode.
    pub mode: Mode,
    /// Median build time of the tree(s).
    pub build_ms: f64,
    /// `Nv`: bounding-volume pair tests.
    pub bv_tests: u64,
    /// `Np`: primitive pair tests.
    pub prim_tests: u64,
    /// `Nu`: volumes moved into A's frame.
    pub updates: u64,
    /// Primitive pairs whose bounds overlap (in the first mode: seen before stopping).
    pub candidate_pairs: usize,
    /// Triangle pairs that really touch (exact test; 0 or 1 in the first mode).
    pub intersecting_pairs: usize,
    /// The first contact found (first mode).
    pub first_pair: Option<(u32, u32)>,
    /// Median query time in the chosen mode.
    pub time_ms: f64,
    /// Brute-force contact count, when verified.
    pub reference_pairs: Option<usize>,
    /// Whether the answer equals brute force, when verified.
    pub verified: Option<bool>,
    /// The closest pair, when asked for (`--distance`); its fields join the
    /// report's (absent otherwise).
    #[serde(flatten)]
    pub closest: Option<DistanceReport>,
}

/// What the distance query measured (`collide --distance`).
#[derive(Clone, Debug, Serialize)]
pub struct DistanceReport {
    /// Distance between the objects: `0` when they touch; `None` when one
    /// has no triangles.
    pub distance: Option<f64>,
    /// The point of A nearest to B (`[x, y, z]`, A's frame).
    pub closest_a: Option<[f64; 3]>,
    /// The point of B nearest to A (`[x, y, z]`, A's frame).
    pub closest_b: Option<[f64; 3]>,
    /// The closest triangles: index in A, index in B.
    pub closest_pair: Option<[u32; 2]>,
    /// `Nv` of the distance query: box pairs bounded.
    pub distance_bv_tests: u64,
    /// `Np` of the distance query: triangle pairs measured.
    pub distance_prim_tests: u64,
    /// Median time of the distance query.
    pub distance_time_ms: f64,
    /// The distance by brute force (every triangle pair), when verified.
    pub reference_distance: Option<f64>,
    /// Whether the distance equals brute force's, when verified.
    pub distance_verified: Option<bool>,
}

/// The traversal named `name` with rule `descent`.
pub fn traversal(name: &str, descent: Descent) -> Result<PairTraversal, String> {
    Ok(match name {
        "stack" => PairTraversal::Stack(descent),
        "recursive" => PairTraversal::Recursive(descent),
        "simultaneous" => PairTraversal::SIMULTANEOUS,
        "leaf-directed" => PairTraversal::LEAF_DIRECTED,
        other => {
            return Err(format!(
                "unknown traversal '{other}' (one of {TRAVERSALS:?})"
            ))
        }
    })
}

/// Runs one collide query as configured.
pub fn run(input: &Input, opts: &CollideOptions) -> Result<CollideReport, String> {
    match opts.volume.as_str() {
        "aabb" => run_with::<Aabb>(input, opts),
        "sphere" => run_with::<Sphere>(input, opts),
        "obb" => run_with::<Obb>(input, opts),
        "obb-dito" => run_with::<bvhkit::ObbDito>(input, opts),
        "14-dop" => run_with::<Dop14>(input, opts),
        "18-dop" => run_with::<Dop18>(input, opts),
        "26-dop" => run_with::<Dop26>(input, opts),
        other => Err(format!("unknown volume '{other}' (one of {VOLUMES:?})")),
    }
}

fn run_with<B: BoundingVolume>(
    input: &Input,
    opts: &CollideOptions,
) -> Result<CollideReport, String> {
    let builder = Builder::by_name(&opts.builder).ok_or_else(|| {
        format!(
            "unknown builder '{}' (one of {:?})",
            opts.builder,
            crate::builders::names()
        )
    })?;
    let trav = traversal(&opts.traversal, opts.descent)?;
    let err = |e: bvhkit::Error| e.to_string();
    match input {
        Input::Default {
            subdivisions,
            placement,
        } => {
            let mesh = scene::rock(*subdivisions, 1);
            if opts.distance && opts.verify {
                check_verify_distance(mesh.len(), mesh.len())?;
            }
            let (build, tree) = median_time(opts.runs, || builder.build::<B>(&mesh));
            let tree = tree.map_err(err)?;
            let t = tree.view();
            let motion = placement.after(&default_motion());
            let placed = if placement.is_identity() {
                ""
            } else {
                ", placed further by --rotate-b / --translate-b"
            };
            let name = format!(
                "rock ({subdivisions} subdivisions) and a moved copy of the same tree{placed}"
            );
            let mut report = measure(
                &name,
                &t,
                &mesh,
                &t,
                &mesh,
                motion,
                trav,
                opts,
                build_ms(build),
            )?;
            if opts.distance {
                report.closest = Some(measure_distance(&t, &mesh, &t, &mesh, motion, opts)?);
            }
            Ok(report)
        }
        Input::Meshes { name, a, b } => {
            if opts.distance && opts.verify {
                check_verify_distance(a.len(), b.len())?;
            }
            let start = Instant::now();
            let ta = builder.build::<B>(a).map_err(err)?;
            let tb = builder.build::<B>(b).map_err(err)?;
            let build = start.elapsed().as_secs_f64() * 1e3;
            let (ta, tb) = (ta.view(), tb.view());
            let mut report = measure(name, &ta, a, &tb, b, Same, trav, opts, build)?;
            if opts.distance {
                report.closest = Some(measure_distance(&ta, a, &tb, b, Same, opts)?);
            }
            Ok(report)
        }
    }
}

fn build_ms(d: std::time::Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

#[allow(clippy::too_many_arguments)]
fn measure<B, F>(
    name: &str,
    ta: &bvhkit::Bvh<B>,
    a: &[Triangle],
    tb: &bvhkit::Bvh<B>,
    b: &[Triangle],
    frame: F,
    trav: PairTraversal,
    opts: &CollideOptions,
    build_ms: f64,
) -> Result<CollideReport, String>
where
    B: BoundingVolume,
    F: Frame + Place<Triangle> + Copy,
{
    let err = |e: bvhkit::Error| e.to_string();
    let q = || Pairs::new(ta, a, tb, b).traversal(trav).in_frame_of(frame);
    // One counted run: the cost-function terms, candidates and contacts.
    let mut counts = Counts::default();
    let mut candidates = 0usize;
    let mut contacts = Vec::new();
    let mut first_pair = None;
    let answer = |p: &Triangle, q: &Triangle| {
        if p.bounds().overlaps(&q.bounds()) {
            candidates += 1;
            p.intersects(q)
        } else {
            false
        }
    };
    match opts.mode {
        Mode::First => {
            first_pair = q()
                .answer(answer)
                .counted(&mut counts)
                .first()
                .map_err(err)?
        }
        Mode::All | Mode::Count => {
            q().answer(answer)
                .counted(&mut counts)
                .for_each(|i, j| contacts.push((i, j)))
                .map_err(err)?;
        }
    }
    let intersecting = match opts.mode {
        Mode::First => first_pair.is_some() as usize,
        _ => contacts.len(),
    };
    // Timed runs: no counters, the plain exact answer, the chosen mode.
    let mut out = Vec::with_capacity(contacts.len());
    let (t, r) = median_time(opts.runs, || match opts.mode {
        Mode::All => {
            out.clear();
            q().exact().for_each(|i, j| out.push((i, j)))
        }
        Mode::First => q().exact().first().map(|f| f.is_some() as usize),
        Mode::Count => q().exact().count(),
    });
    r.map_err(err)?;
    let (reference_pairs, verified) = if opts.verify {
        let placed: Vec<Triangle> = b.iter().map(|t| frame.place(t)).collect();
        let reference: Vec<(u32, u32)> = reference_pairs(a, &placed)
            .into_iter()
            .filter(|&(i, j)| a[i as usize].intersects(&placed[j as usize]))
            .collect();
        let ok = match opts.mode {
            Mode::First => {
                first_pair.is_some() != reference.is_empty()
                    && first_pair.is_none_or(|p| reference.binary_search(&p).is_ok())
            }
            _ => {
                contacts.sort_unstable();
                contacts == reference
            }
        };
        (Some(reference.len()), Some(ok))
    } else {
        (None, None)
    };
    Ok(CollideReport {
        scene: name.to_string(),
        triangles_a: a.len(),
        triangles_b: b.len(),
        volume: B::NAME.to_string(),
        builder: opts.builder.clone(),
        traversal: trav.name().to_string(),
        descent: match trav {
            PairTraversal::Stack(d) | PairTraversal::Recursive(d) => d.name().to_string(),
            _ => String::new(),
        },
        mode: opts.mode,
        build_ms,
        bv_tests: counts.bv_tests,
        prim_tests: counts.prim_tests,
        updates: counts.updates,
        candidate_pairs: candidates,
        intersecting_pairs: intersecting,
        first_pair,
        time_ms: t.as_secs_f64() * 1e3,
        reference_pairs,
        verified,
        closest: None,
    })
}

/// The closest pair of triangles of `a` (tree `ta`) and `b` (tree `tb`,
/// placed in A's frame by `frame`): one counted run, the median of
/// `opts.runs` timed runs and, with `opts.verify`, brute force over every
/// pair (B's triangles placed by the same frame).
fn measure_distance<B: BoundingVolume, F: Frame + Place<Triangle> + Copy>(
    ta: &bvhkit::Bvh<B>,
    a: &[Triangle],
    tb: &bvhkit::Bvh<B>,
    b: &[Triangle],
    frame: F,
    opts: &CollideOptions,
) -> Result<DistanceReport, String> {
    let err = |e: bvhkit::Error| e.to_string();
    let mut counts = Counts::default();
    let query = || Distance::new(ta, a, tb, b).in_frame_of(frame);
    let closest = query().counted(&mut counts).closest().map_err(err)?;
    let (time, r) = median_time(opts.runs, || query().closest());
    r.map_err(err)?;
    let (reference_distance, distance_verified) = if opts.verify {
        check_verify_distance(a.len(), b.len())?;
        let placed: Vec<Triangle> = b.iter().map(|t| frame.place(t)).collect();
        let reference = bvhkit::brute_force::closest_pair(a, &placed);
        // The same f64 arithmetic on the same pairs: the least squared
        // distance is equal to the bit, whichever pair attains it.
        let ok = match (closest, reference) {
            (None, None) => true,
            (Some(c), Some(r)) => c.points.distance_squared == r.points.distance_squared,
            _ => false,
        };
        (reference.map(|r| r.distance()), Some(ok))
    } else {
        (None, None)
    };
    let xyz = |p: DVec3| [p.x, p.y, p.z];
    Ok(DistanceReport {
        distance: closest.map(|c| c.distance()),
        closest_a: closest.map(|c| xyz(c.points.on_a)),
        closest_b: closest.map(|c| xyz(c.points.on_b)),
        closest_pair: closest.map(|c| [c.a, c.b]),
        distance_bv_tests: counts.bv_tests,
        distance_prim_tests: counts.prim_tests,
        distance_time_ms: time.as_secs_f64() * 1e3,
        reference_distance,
        distance_verified,
    })
}

/// What `collide --self` measured: one mesh against itself, each pair of
/// triangles `i < j` once.
#[derive(Clone, Debug, Serialize)]
pub struct SelfReport {
    /// Scene description.
    pub scene: String,
    /// Triangles in the mesh.
    pub triangles: usize,
    /// Bounding volume.
    pub volume: String,
    /// Builder preset.
    pub builder: String,
    /// Traversal kind (how sibling subtrees are walked against each other).
    pub traversal: String,
    /// Descent rule (for stack / recursive).
    pub descent: String,
    /// Median build time of the tree.
    pub build_ms: f64,
    /// `Nv`: bounding-volume pair tests.
    pub bv_tests: u64,
    /// `Np`: primitive pair tests.
    pub prim_tests: u64,
    /// Pairs `i < j` whose boxes overlap and which share no vertex.
    pub candidate_pairs: usize,
    /// Pairs `i < j` whose boxes overlap but which share a vertex
    /// (neighbours: skipped, never tested exactly).
    pub adjacent_pairs: usize,
    /// Candidate pairs that really touch (exact test): the self-intersections.
    pub intersecting_pairs: usize,
    /// Median time of the exact self query.
    pub time_ms: f64,
    /// Candidate pairs by an independent sort-and-sweep, when verified.
    pub reference_pairs: Option<usize>,
    /// Whether candidates and intersections equal the sweep's, when verified.
    pub verified: Option<bool>,
}

/// `collide --self`: the mesh's tree against itself. Two triangles are
/// neighbours, skipped, when they share a vertex *index*: `corners[i]` holds
/// triangle `i`'s three (from [`mesh::load_indexed`](crate::mesh::load_indexed),
/// or [`mesh::weld`](crate::mesh::weld) for a mesh without a vertex list).
/// Two corners at one position with different indices (a seam of split
/// vertices) are not neighbours: such a pair touches and is reported.
pub fn run_self(
    name: &str,
    mesh: &[Triangle],
    corners: &[[u32; 3]],
    opts: &CollideOptions,
) -> Result<SelfReport, String> {
    if corners.len() != mesh.len() {
        return Err(format!(
            "{} triangles but {} corner triples",
            mesh.len(),
            corners.len()
        ));
    }
    if opts.distance {
        return Err(
            "--distance measures between two objects and cannot be used with --self".into(),
        );
    }
    match opts.volume.as_str() {
        "aabb" => self_with::<Aabb>(name, mesh, corners, opts),
        "sphere" => self_with::<Sphere>(name, mesh, corners, opts),
        "obb" => self_with::<Obb>(name, mesh, corners, opts),
        "obb-dito" => self_with::<bvhkit::ObbDito>(name, mesh, corners, opts),
        "14-dop" => self_with::<Dop14>(name, mesh, corners, opts),
        "18-dop" => self_with::<Dop18>(name, mesh, corners, opts),
        "26-dop" => self_with::<Dop26>(name, mesh, corners, opts),
        other => Err(format!("unknown volume '{other}' (one of {VOLUMES:?})")),
    }
}

fn self_with<B: BoundingVolume>(
    name: &str,
    mesh: &[Triangle],
    corners: &[[u32; 3]],
    opts: &CollideOptions,
) -> Result<SelfReport, String> {
    use bvhkit::query::SelfPairs;
    let share = |i: u32, j: u32| {
        let (a, b) = (corners[i as usize], corners[j as usize]);
        a.iter().any(|x| b.contains(x))
    };
    let builder = Builder::by_name(&opts.builder).ok_or_else(|| {
        format!(
            "unknown builder '{}' (one of {:?})",
            opts.builder,
            crate::builders::names()
        )
    })?;
    let trav = traversal(&opts.traversal, opts.descent)?;
    let err = |e: bvhkit::Error| e.to_string();
    let (build, tree) = median_time(opts.runs, || builder.build::<B>(mesh));
    let tree = tree.map_err(err)?;
    let t = tree.view();
    let q = || SelfPairs::new(&t, mesh).traversal(trav).skip(share);
    // One counted run: every overlapping pair, sorted into neighbours,
    // candidates and intersections.
    let mut counts = Counts::default();
    let (mut candidates, mut adjacent) = (0usize, 0usize);
    let mut contacts = Vec::new();
    q().keep_adjacent()
        .counted(&mut counts)
        .for_each(|i, j| {
            let (p, r) = (&mesh[i as usize], &mesh[j as usize]);
            if share(i, j) {
                adjacent += 1;
            } else {
                candidates += 1;
                if p.intersects(r) {
                    contacts.push((i, j));
                }
            }
        })
        .map_err(err)?;
    let mut out = Vec::with_capacity(contacts.len());
    let (time, r) = median_time(opts.runs, || {
        out.clear();
        q().exact().for_each(|i, j| out.push((i, j)))
    });
    r.map_err(err)?;
    let (reference_pairs, verified) = if opts.verify {
        let sweep: Vec<(u32, u32)> = sweep_self_pairs(mesh)
            .into_iter()
            .filter(|&(i, j)| !share(i, j))
            .collect();
        let touching: Vec<(u32, u32)> = sweep
            .iter()
            .copied()
            .filter(|&(i, j)| mesh[i as usize].intersects(&mesh[j as usize]))
            .collect();
        contacts.sort_unstable();
        out.sort_unstable();
        let ok = sweep.len() == candidates && touching == contacts && touching == out;
        (Some(sweep.len()), Some(ok))
    } else {
        (None, None)
    };
    Ok(SelfReport {
        scene: name.to_string(),
        triangles: mesh.len(),
        volume: B::NAME.to_string(),
        builder: opts.builder.clone(),
        traversal: trav.name().to_string(),
        descent: match trav {
            PairTraversal::Stack(d) | PairTraversal::Recursive(d) => d.name().to_string(),
            _ => String::new(),
        },
        build_ms: build_ms(build),
        bv_tests: counts.bv_tests,
        prim_tests: counts.prim_tests,
        candidate_pairs: candidates,
        adjacent_pairs: adjacent,
        intersecting_pairs: contacts.len(),
        time_ms: time.as_secs_f64() * 1e3,
        reference_pairs,
        verified,
    })
}

/// Every pair `i < j` whose boxes overlap, sorted, by sort-and-sweep on x:
/// no tree involved, so it checks the self query independently, and fast
/// enough for real meshes (brute force is quadratic).
pub fn sweep_self_pairs(mesh: &[Triangle]) -> Vec<(u32, u32)> {
    let mut boxes: Vec<(Aabb, u32)> = mesh
        .iter()
        .enumerate()
        .map(|(i, t)| (t.bounds(), i as u32))
        .collect();
    boxes.sort_unstable_by(|x, y| x.0.min.x.total_cmp(&y.0.min.x));
    let mut pairs = Vec::new();
    for (k, (b, i)) in boxes.iter().enumerate() {
        for (c, j) in &boxes[k + 1..] {
            if c.min.x > b.max.x {
                break;
            }
            if b.overlaps(c) {
                pairs.push((*i.min(j), *i.max(j)));
            }
        }
    }
    pairs.sort_unstable();
    pairs
}

/// The self report as text.
pub fn render_self(r: &SelfReport) -> String {
    let mut s = format!(
        "scene: {}: {} triangles, against itself\n\
         tree: {} volumes, builder {}, built in {:.2} ms\n\
         query: {} traversal{}, each pair i < j once\n\n\
         bv tests (Nv)        {:>12}\n\
         prim tests (Np)      {:>12}\n\
         adjacent pairs       {:>12} (share a vertex: skipped)\n\
         candidate pairs      {:>12}\n\
         intersecting pairs   {:>12}\n\
         time                 {:>12.3} ms (median)\n",
        r.scene,
        r.triangles,
        r.volume,
        r.builder,
        r.build_ms,
        r.traversal,
        if r.descent.is_empty() {
            String::new()
        } else {
            format!(", descend {}", r.descent)
        },
        r.bv_tests,
        r.prim_tests,
        r.adjacent_pairs,
        r.candidate_pairs,
        r.intersecting_pairs,
        r.time_ms,
    );
    if let (Some(n), Some(ok)) = (r.reference_pairs, r.verified) {
        s += &format!(
            "sort and sweep       {:>12} candidates: {}\n",
            n,
            if ok { "match" } else { "MISMATCH" }
        );
    }
    s
}

/// The report as text.
pub fn render(r: &CollideReport) -> String {
    let mut s = format!(
        "scene: {}: {} + {} triangles\n\
         tree: {} volumes, builder {}, built in {:.2} ms\n\
         query: {} traversal{}, mode {:?}\n\n\
         bv tests (Nv)        {:>12}\n\
         prim tests (Np)      {:>12}\n\
         updates (Nu)         {:>12}\n\
         candidate pairs      {:>12}\n\
         intersecting pairs   {:>12}\n\
         time                 {:>12.3} ms (median)\n",
        r.scene,
        r.triangles_a,
        r.triangles_b,
        r.volume,
        r.builder,
        r.build_ms,
        r.traversal,
        if r.descent.is_empty() {
            String::new()
        } else {
            format!(", descend {}", r.descent)
        },
        r.mode,
        r.bv_tests,
        r.prim_tests,
        r.updates,
        r.candidate_pairs,
        r.intersecting_pairs,
        r.time_ms,
    );
    if let Some(p) = r.first_pair {
        s += &format!(
            "first pair           {:>12}\n",
            format!("{} x {}", p.0, p.1)
        );
    }
    if let (Some(n), Some(ok)) = (r.reference_pairs, r.verified) {
        s += &format!(
            "brute force          {:>12} contacts: {}\n",
            n,
            if ok { "match" } else { "MISMATCH" }
        );
    }
    if let Some(d) = &r.closest {
        s += &render_distance(d);
    }
    s
}

/// The distance lines of the text report.
fn render_distance(d: &DistanceReport) -> String {
    let mut s = String::from("\n");
    match (d.distance, d.closest_pair, d.closest_a, d.closest_b) {
        (Some(dist), Some([i, j]), Some(pa), Some(pb)) => {
            let touch = if dist == 0.0 { ", touching" } else { "" };
            s += &format!(
                "distance             {:>12} (triangles {i} x {j}{touch})\n\
                 closest on A         {:>12}\n\
                 closest on B         {:>12}\n",
                significant(dist),
                point(pa),
                point(pb),
            );
        }
        _ => s += "distance                     none (an object has no triangles)\n",
    }
    s += &format!(
        "distance Nv          {:>12}\n\
         distance Np          {:>12}\n",
        d.distance_bv_tests, d.distance_prim_tests
    );
    s += &format!(
        "distance time        {:>12.3} ms (median)\n",
        d.distance_time_ms
    );
    if let Some(ok) = d.distance_verified {
        s += &format!(
            "brute force          {:>12} distance: {}\n",
            d.reference_distance.map_or("none".into(), significant),
            if ok { "match" } else { "MISMATCH" }
        );
    }
    s
}

/// `x` to six significant digits (plain notation), `0` as `0`.
fn significant(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let digits = (5 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.digits$}")
}

/// `(x, y, z)`, six significant digits each.
fn point(p: [f64; 3]) -> String {
    format!(
        "({}, {}, {})",
        significant(p[0]),
        significant(p[1]),
        significant(p[2])
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_mode_and_traversal_verifies_on_a_small_scene() {
        for traversal in TRAVERSALS {
            for mode in [Mode::All, Mode::First, Mode::Count] {
                let opts = CollideOptions {
                    traversal: traversal.into(),
                    mode,
                    runs: 1,
                    verify: true,
                    ..CollideOptions::default()
                };
                let r = run(&Input::default_scene(3), &opts).unwrap();
                assert_eq!(r.verified, Some(true), "{traversal} {mode:?}");
                assert!(r.reference_pairs.unwrap() > 0);
                assert!(
                    r.updates > 0 && r.bv_tests > 0 && r.prim_tests >= r.candidate_pairs as u64
                );
                if mode != Mode::First {
                    assert_eq!(r.intersecting_pairs, r.reference_pairs.unwrap());
                    assert!(r.candidate_pairs >= r.intersecting_pairs);
                }
            }
        }
    }

    #[test]
    fn self_collision_verifies_in_every_traversal() {
        // A strip of neighbours (shared corners) and one triangle folded
        // through it: neighbours are skipped, the fold is found.
        let mut mesh: Vec<Triangle> = (0..40)
            .map(|i| {
                let x = i as f32 * 0.5;
                Triangle::new(
                    Vec3::new(x, 0.0, 0.0),
                    Vec3::new(x + 0.5, 0.0, 0.0),
                    Vec3::new(x, 1.0, 0.0),
                )
            })
            .collect();
        mesh.push(Triangle::new(
            Vec3::new(3.1, 0.2, -1.0),
            Vec3::new(3.1, 0.2, 1.0),
            Vec3::new(7.3, 0.3, 0.0),
        ));
        for traversal in TRAVERSALS {
            let opts = CollideOptions {
                traversal: traversal.into(),
                runs: 1,
                verify: true,
                ..CollideOptions::default()
            };
            let r = run_self("strip", &mesh, &crate::mesh::weld(&mesh), &opts).unwrap();
            assert_eq!(r.verified, Some(true), "{traversal}");
            assert!(r.adjacent_pairs >= 39, "{r:?}");
            assert!(r.intersecting_pairs > 0 && r.candidate_pairs >= r.intersecting_pairs);
            assert_eq!(r.reference_pairs, Some(r.candidate_pairs));
        }
        // The closed rock does not cut itself.
        let rock = scene::rock(3, 1);
        let r = run_self(
            "rock",
            &rock,
            &crate::mesh::weld(&rock),
            &CollideOptions {
                runs: 1,
                verify: true,
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!((r.verified, r.intersecting_pairs), (Some(true), 0));
        assert!(r.adjacent_pairs > rock.len());
    }

    #[test]
    fn neighbours_are_triangles_sharing_a_vertex_index_not_a_position() {
        // Two triangles meeting at one corner position. Welded (one index)
        // they are neighbours; with the corner split into two indices (a
        // seam) they are a candidate pair, and they touch.
        let mesh = [
            Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y),
            Triangle::new(Vec3::ZERO, -Vec3::X, -Vec3::Y),
        ];
        let opts = CollideOptions {
            runs: 1,
            verify: true,
            ..CollideOptions::default()
        };
        let welded = run_self("welded", &mesh, &crate::mesh::weld(&mesh), &opts).unwrap();
        assert_eq!((welded.adjacent_pairs, welded.candidate_pairs), (1, 0));
        let split = run_self("split", &mesh, &[[0, 1, 2], [3, 4, 5]], &opts).unwrap();
        assert_eq!(
            (
                split.adjacent_pairs,
                split.candidate_pairs,
                split.intersecting_pairs
            ),
            (0, 1, 1)
        );
        assert_eq!(split.verified, Some(true));
        assert!(run_self("short", &mesh, &[[0, 1, 2]], &opts).is_err());
    }

    /// A flat square of `n` x `n` cells (two triangles each), side 2, at
    /// height `z`, its corner at (`x`, 0).
    fn sheet(n: usize, x: f32, z: f32) -> Vec<Triangle> {
        let s = 2.0 / n as f32;
        let at = |i: usize, j: usize| Vec3::new(x + i as f32 * s, j as f32 * s, z);
        (0..n * n)
            .flat_map(|k| {
                let (i, j) = (k % n, k / n);
                [
                    Triangle::new(at(i, j), at(i + 1, j), at(i + 1, j + 1)),
                    Triangle::new(at(i, j), at(i + 1, j + 1), at(i, j + 1)),
                ]
            })
            .collect()
    }

    fn with_distance() -> CollideOptions {
        CollideOptions {
            runs: 1,
            verify: true,
            distance: true,
            ..CollideOptions::default()
        }
    }

    #[test]
    fn distance_of_the_built_in_rocks_touching_and_apart() {
        // 320 triangles a rock: the distance's reference is a double loop.
        let r = run(&Input::default_scene(2), &with_distance()).unwrap();
        let d = r.closest.as_ref().unwrap();
        assert_eq!((r.verified, d.distance_verified), (Some(true), Some(true)));
        // The rocks overlap: distance 0, the same answer as the contacts.
        assert!(r.intersecting_pairs > 0);
        assert_eq!(d.distance, Some(0.0));
        let [pa, pb] = [d.closest_a.unwrap(), d.closest_b.unwrap()].map(DVec3::from);
        assert!((pa - pb).length() < 1e-9, "{pa} {pb}");
        assert!(d.distance_bv_tests > 0 && d.distance_prim_tests > 0);
        assert!(render(&r).contains("touching"), "{}", render(&r));

        // Moved 5 further along x: apart (the rock's radius is about 1).
        let placement = Rigid::new(Quat::IDENTITY, Vec3::new(5.0, 0.0, 0.0)).unwrap();
        let input = Input::Default {
            subdivisions: 2,
            placement,
        };
        let r = run(&input, &with_distance()).unwrap();
        let d = r.closest.as_ref().unwrap();
        assert_eq!((r.verified, d.distance_verified), (Some(true), Some(true)));
        assert_eq!(r.intersecting_pairs, 0);
        let dist = d.distance.unwrap();
        assert!(dist > 2.0 && dist < 6.0, "{dist}");
        assert_eq!(d.reference_distance, Some(dist));
        // The points are on the reported triangles, `dist` apart.
        let [pa, pb] = [d.closest_a.unwrap(), d.closest_b.unwrap()].map(DVec3::from);
        assert!(((pa - pb).length() - dist).abs() < 1e-12);
    }

    #[test]
    fn distance_of_two_parallel_sheets_is_their_gap() {
        // B above A by 0.25, shifted by half a cell: every point of A's
        // middle is 0.25 below B.
        let (a, b) = (sheet(6, 0.0, 0.0), sheet(6, 1.0, 0.25));
        let input = Input::Meshes {
            name: "sheets".into(),
            a,
            b,
        };
        let r = run(&input, &with_distance()).unwrap();
        let d = r.closest.as_ref().unwrap();
        assert_eq!(d.distance, Some(0.25));
        assert_eq!(d.distance_verified, Some(true));
        assert_eq!(d.closest_a.unwrap()[2], 0.0);
        assert_eq!(d.closest_b.unwrap()[2], 0.25);
        let text = render(&r);
        assert!(
            text.contains("0.250000") && text.contains("match"),
            "{text}"
        );
    }

    #[test]
    fn distance_with_an_empty_object_is_none() {
        for (a, b) in [
            (Vec::new(), sheet(2, 0.0, 0.0)),
            (sheet(2, 0.0, 0.0), Vec::new()),
        ] {
            let input = Input::Meshes {
                name: "empty".into(),
                a,
                b,
            };
            let r = run(&input, &with_distance()).unwrap();
            let d = r.closest.as_ref().unwrap();
            assert_eq!((d.distance, d.closest_pair), (None, None));
            assert_eq!(d.distance_verified, Some(true));
            assert!(render(&r).contains("none (an object has no triangles)"));
        }
    }

    #[test]
    fn distance_is_refused_with_self_and_verify_on_large_scenes() {
        let rock = scene::rock(1, 1);
        let err = run_self("rock", &rock, &crate::mesh::weld(&rock), &with_distance()).unwrap_err();
        assert!(err.contains("--self"), "{err}");
        assert!(check_verify_distance(5_120, 5_120).is_ok());
        let err = check_verify_distance(81_920, 81_920).unwrap_err();
        assert!(err.contains("limit") && err.contains("--verify"), "{err}");
        // Refused before anything is built; fine without --verify.
        assert!(run(&Input::default_scene(6), &with_distance()).is_err());
    }

    #[test]
    fn bad_names_are_errors() {
        let input = Input::default_scene(1);
        for opts in [
            CollideOptions {
                volume: "cube".into(),
                ..Default::default()
            },
            CollideOptions {
                builder: "magic".into(),
                ..Default::default()
            },
            CollideOptions {
                traversal: "sideways".into(),
                ..Default::default()
            },
        ] {
            assert!(run(&input, &opts).is_err());
        }
    }
}
