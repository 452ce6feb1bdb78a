//! `bvhkit tour`: every top-down strategy and every bounding volume on the
//! default scene, each checked against brute force.

use crate::{median_time, scene};
use bvhkit::{
    overlapping_pairs, Aabb, BoundingVolume, Descent, Dop14, Dop18, Dop26, Intersects, Obb,
    Primitive, Sphere, TopDown, Transform, Triangle,
};
use serde::Serialize;
use std::time::Instant;

/// What the tour measured, printable as a table or as JSON.
#[derive(Clone, Debug, Serialize)]
pub struct TourReport {
    /// The scene.
    pub scene: SceneInfo,
    /// One row per builder: every top-down preset, then bottom-up (AABB trees).
    pub strategies: Vec<Row>,
    /// One row per bounding volume (binned SAH trees).
    pub volumes: Vec<Row>,
    /// The collision scene of the descent-rule table.
    pub collision_scene: String,
    /// Exact contacts of that scene by brute force.
    pub reference_contacts: usize,
    /// The cost model's unit costs, per volume type.
    pub calibration: Vec<crate::cost::Calibration>,
    /// Descent rules and traversal kinds: counters, measured and predicted time.
    pub descent_rules: Vec<crate::cost::CostRow>,
    /// Moving objects: a twisting rock, refitted versus rebuilt each frame.
    pub motion: Vec<crate::motion::MotionRow>,
    /// The main builders on other kinds of generated scenes.
    pub other_scenes: Vec<(String, Vec<Row>)>,
    /// Every tree representation of the SAH tree: bytes, times, answers.
    pub layouts: Vec<crate::layouts::LayoutRow>,
    /// Queries whose answer equalled the brute-force reference.
    pub verified: usize,
    /// Queries run.
    pub queries: usize,
}

/// The scene the tour ran on.
#[derive(Clone, Debug, Serialize)]
pub struct SceneInfo {
    /// Name.
    pub name: String,
    /// Triangles in object A.
    pub triangles_a: usize,
    /// Triangles in object B.
    pub triangles_b: usize,
    /// Overlapping primitive pairs according to brute force.
    pub reference_pairs: usize,
    /// Time the brute-force reference took.
    pub reference_ms: f64,
}

/// One measured configuration.
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// Strategy name.
    pub strategy: String,
    /// Bounding volume name.
    pub volume: String,
    /// Median build time of tree A.
    pub build_ms: f64,
    /// SAH cost of tree A (C_t = C_i = 1, the volume type's own areas).
    pub sah_cost: f64,
    /// Depth of tree A.
    pub depth: usize,
    /// Mean leaf depth of tree A.
    pub mean_leaf_depth: f64,
    /// Nodes of tree A.
    pub nodes: usize,
    /// Bytes of node + index storage of tree A.
    pub bytes: usize,
    /// Median time of the A-vs-B pair query (the default, simultaneous descent).
    pub query_ms: f64,
    /// Pairs the query found.
    pub pairs: usize,
    /// Whether the pairs equal the brute-force reference.
    pub matches: bool,
}

/// The brute-force answer: every pair of A and B whose bounds overlap, sorted.
///
/// No tree is involved, only comparisons, so it can judge the trees. Two boxes
/// that overlap overlap on x, and then exactly one of them starts (its `min.x`)
/// inside the other's x interval, the tie going to A's. So each box, sorted by
/// `min.x`, is tested against the other side's boxes that start inside its own
/// interval: every candidate pair once, found by binary search and a scan, far
/// fewer than the double loop's `|A|·|B|` tests (a box with a NaN `min.x`
/// overlaps nothing, and is left out).
pub fn reference_pairs(a: &[Triangle], b: &[Triangle]) -> Vec<(u32, u32)> {
    let sorted = |t: &[Triangle]| {
        let mut boxes: Vec<(u32, Aabb)> = (0u32..)
            .zip(t)
            .map(|(i, p)| (i, p.bounds()))
            .filter(|(_, x)| !x.min.x.is_nan())
            .collect();
        boxes.sort_unstable_by(|p, q| p.1.min.x.total_cmp(&q.1.min.x));
        boxes
    };
    let (sa, sb) = (sorted(a), sorted(b));
    let mut pairs = Vec::new();
    // B's boxes that start in [x.min.x, x.max.x], then A's that start in
    // (y.min.x, y.max.x]: the `<` and `<=` split the tie of equal starts.
    for &(i, x) in &sa {
        let from = sb.partition_point(|(_, y)| y.min.x < x.min.x);
        for &(j, y) in sb[from..].iter().take_while(|(_, y)| y.min.x <= x.max.x) {
            if x.overlaps(&y) {
                pairs.push((i, j));
            }
        }
    }
    for &(j, y) in &sb {
        let from = sa.partition_point(|(_, x)| x.min.x <= y.min.x);
        for &(i, x) in sa[from..].iter().take_while(|(_, x)| x.min.x <= y.max.x) {
            if x.overlaps(&y) {
                pairs.push((i, j));
            }
        }
    }
    pairs.sort_unstable();
    pairs
}

fn ms(d: std::time::Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

pub use crate::builders::Builder;

fn measure<B: BoundingVolume>(
    name: &str,
    builder: &TopDown,
    a: &[Triangle],
    b: &[Triangle],
    reference: &[(u32, u32)],
    runs: usize,
) -> Result<Row, bvhkit::Error> {
    measure_with::<B>(name, Builder::TopDown(*builder), a, b, reference, runs)
}

pub(crate) fn measure_with<B: BoundingVolume>(
    name: &str,
    builder: Builder,
    a: &[Triangle],
    b: &[Triangle],
    reference: &[(u32, u32)],
    runs: usize,
) -> Result<Row, bvhkit::Error> {
    let (build, tree_a) = median_time(runs, || builder.build::<B>(a));
    let tree_a = tree_a?;
    let tree_b = builder.build::<B>(b)?;
    let (ta, tb) = (tree_a.view(), tree_b.view());
    let mut pairs = Vec::with_capacity(reference.len());
    let (query, found) = median_time(runs, || {
        pairs.clear();
        overlapping_pairs(&ta, a, &tb, b, Descent::Simultaneous, |i, j| {
            pairs.push((i, j))
        })
    });
    let found = found?;
    pairs.sort_unstable();
    let s = ta.stats();
    Ok(Row {
        strategy: name.to_string(),
        volume: B::NAME.to_string(),
        build_ms: ms(build),
        sah_cost: s.sah_cost,
        depth: s.max_depth,
        mean_leaf_depth: s.mean_leaf_depth,
        nodes: s.nodes,
        bytes: s.bytes,
        query_ms: ms(query),
        pairs: found,
        matches: pairs == reference,
    })
}

/// One row per builder of the catalogue but the textbook exhaustive one
/// (O(n^3): hours on the tour's scene), each measured once.
fn builder_rows(
    a: &[Triangle],
    b: &[Triangle],
    reference: &[(u32, u32)],
    runs: usize,
    progress: &mut impl FnMut(&str),
) -> Result<Vec<Row>, bvhkit::Error> {
    let mut rows = Vec::new();
    for (name, _, builder) in crate::builders::catalogue() {
        if name == "bottom-up-exhaustive" {
            continue;
        }
        progress(name);
        rows.push(measure_with::<Aabb>(name, builder, a, b, reference, runs)?);
    }
    Ok(rows)
}

/// Options of the tour.
#[derive(Clone, Copy, Debug)]
pub struct TourOptions {
    /// Icosphere subdivisions of each rock (6 = 81 920 triangles).
    pub subdivisions: u32,
    /// Timed runs per measurement (the median is reported).
    pub runs: usize,
}

impl Default for TourOptions {
    fn default() -> Self {
        TourOptions {
            subdivisions: 6,
            runs: 3,
        }
    }
}

/// The builders compared on every generated scene kind.
fn scene_builders() -> [(&'static str, Builder); 6] {
    [
        "sah",
        "median",
        "ploc-r16",
        "insert-bnb",
        "insert-descent",
        "insert-bnb-sorted",
    ]
    .map(|name| match Builder::by_name(name) {
        Some(b) => (name, b),
        None => unreachable!("{name} is in the builder catalogue"),
    })
}

type CostReport =
    fn(
        &[Triangle],
        bvhkit::Rigid,
        usize,
    ) -> Result<(crate::cost::Calibration, Vec<crate::cost::CostRow>), bvhkit::Error>;

/// Runs the tour; `progress` is told what is being measured.
pub fn run(opts: TourOptions, mut progress: impl FnMut(&str)) -> Result<TourReport, bvhkit::Error> {
    let (a, b) = scene::rock_pair(opts.subdivisions);
    progress("brute-force reference");
    let t = Instant::now();
    let reference = reference_pairs(&a, &b);
    let reference_ms = ms(t.elapsed());
    let strategies = builder_rows(&a, &b, &reference, opts.runs, &mut progress)?;
    let sah = TopDown::sah();
    let mut volumes = Vec::new();
    progress("volumes");
    volumes.push(measure::<Aabb>("sah", &sah, &a, &b, &reference, opts.runs)?);
    volumes.push(measure::<Sphere>(
        "sah", &sah, &a, &b, &reference, opts.runs,
    )?);
    volumes.push(measure::<Obb>("sah", &sah, &a, &b, &reference, opts.runs)?);
    volumes.push(measure::<Dop14>(
        "sah", &sah, &a, &b, &reference, opts.runs,
    )?);
    volumes.push(measure::<Dop18>(
        "sah", &sah, &a, &b, &reference, opts.runs,
    )?);
    volumes.push(measure::<Dop26>(
        "sah", &sah, &a, &b, &reference, opts.runs,
    )?);
    // Descent rules on the collision scene: the rock against a moved copy of
    // its own tree, exact contacts, with the calibrated cost model.
    progress("descent rules");
    let mesh = &a;
    let motion = crate::collide::default_motion();
    let placed: Vec<Triangle> = mesh.iter().map(|t| t.transformed(&motion)).collect();
    let reference_contacts = reference_pairs(mesh, &placed)
        .into_iter()
        .filter(|&(i, j)| mesh[i as usize].intersects(&placed[j as usize]))
        .count();
    let mut calibration = Vec::new();
    let mut descent_rules = Vec::new();
    for (name, report) in [
        ("aabb", crate::cost::report_for::<Aabb> as CostReport),
        ("sphere", crate::cost::report_for::<Sphere>),
        ("obb", crate::cost::report_for::<Obb>),
        ("14-dop", crate::cost::report_for::<Dop14>),
    ] {
        progress(&format!("descent rules, {name}"));
        let (cal, rows) = report(mesh, motion, opts.runs)?;
        calibration.push(cal);
        descent_rules.extend(rows);
    }
    let mut other_scenes = Vec::new();
    let n_other = 20 * 4usize.pow(opts.subdivisions.min(5));
    for (name, make) in [
        ("soup", scene::soup as fn(usize, u64) -> Vec<Triangle>),
        ("clustered", scene::clustered),
        ("slivers", scene::slivers),
    ] {
        progress(name);
        let sa = make(n_other, 11);
        let sb: Vec<Triangle> = sa
            .iter()
            .map(|t| t.translated(bvhkit::glam::Vec3::new(0.004, 0.003, 0.002)))
            .collect();
        let reference = reference_pairs(&sa, &sb);
        let mut rows = Vec::new();
        for (label, builder) in scene_builders() {
            rows.push(measure_with::<Aabb>(
                label, builder, &sa, &sb, &reference, opts.runs,
            )?);
        }
        other_scenes.push((
            format!("{name}: {n_other} triangles and a copy shifted by 0.005"),
            rows,
        ));
    }
    progress("tree representations");
    let layouts = crate::layouts::measure(&a, &b, &TopDown::sah(), 2_000, opts.runs)?;
    progress("refit versus rebuild");
    let motion = crate::motion::refit_vs_rebuild(opts.subdivisions, 8, 0.15, opts.runs)?;
    let rows = strategies
        .iter()
        .chain(&volumes)
        .chain(other_scenes.iter().flat_map(|(_, r)| r));
    let laid_out = layouts.iter().filter(|l| l.refused.is_none());
    let queries =
        rows.clone().count() + descent_rules.len() + motion.len() + laid_out.clone().count();
    let layouts_ok = laid_out
        .filter(|l| l.same_answers && l.pairs == reference.len())
        .count();
    let verified = rows.filter(|r| r.matches).count()
        + descent_rules
            .iter()
            .filter(|r| r.intersecting_pairs == reference_contacts)
            .count()
        + motion.iter().filter(|m| m.same_pairs).count()
        + layouts_ok;
    Ok(TourReport {
        scene: SceneInfo {
            name: format!(
                "two overlapping rocks (icosphere, {} subdivisions)",
                opts.subdivisions
            ),
            triangles_a: a.len(),
            triangles_b: b.len(),
            reference_pairs: reference.len(),
            reference_ms,
        },
        strategies,
        volumes,
        collision_scene: format!(
            "object A against a moved copy of its own tree ({} triangles each), exact contacts",
            mesh.len()
        ),
        reference_contacts,
        calibration,
        descent_rules,
        motion,
        other_scenes,
        layouts,
        verified,
        queries,
    })
}

fn table(title: &str, rows: &[Row]) -> String {
    let mut s = format!(
        "\n{title}\n{:<17} {:<7} {:>9} {:>9} {:>6} {:>9} {:>11} {:>9} {:>9} {:>6}\n",
        "strategy",
        "volume",
        "build ms",
        "SAH cost",
        "depth",
        "nodes",
        "bytes",
        "query ms",
        "pairs",
        "ok"
    );
    for r in rows {
        s += &format!(
            "{:<17} {:<7} {:>9.2} {:>9.2} {:>6} {:>9} {:>11} {:>9.2} {:>9} {:>6}\n",
            r.strategy,
            r.volume,
            r.build_ms,
            r.sah_cost,
            r.depth,
            r.nodes,
            r.bytes,
            r.query_ms,
            r.pairs,
            if r.matches { "yes" } else { "NO" }
        );
    }
    s
}

/// The report as the human-readable text `bvhkit tour` prints.
pub fn render(r: &TourReport) -> String {
    let mut s = format!(
        "scene: {}: {} + {} triangles, {} overlapping pairs (brute force: {:.0} ms)\n",
        r.scene.name,
        r.scene.triangles_a,
        r.scene.triangles_b,
        r.scene.reference_pairs,
        r.scene.reference_ms
    );
    s += &table(
        "Builders (AABB trees; top-down presets; bottom-up PLOC with search radius r; insertion with\n\
         branch-and-bound (bnb) or descent (dsc) sibling search, shuffled, in mesh order or sorted;\n\
         A-vs-B query, simultaneous descent (the default)):",
        &r.strategies,
    );
    s += &table(
        "Bounding volumes (binned SAH; SAH cost uses each volume's own areas):",
        &r.volumes,
    );
    s += &format!(
        "\nDescent rules and traversals: {} ({} contacts by brute force).\n\
         Cost model T = Nv*Cv + Np*Cp + Nu*Cu + Co, unit costs timed on this machine:\n",
        r.collision_scene, r.reference_contacts
    );
    for c in &r.calibration {
        let rows: Vec<_> = r
            .descent_rules
            .iter()
            .filter(|d| d.volume == c.volume)
            .collect();
        s += &format!(
            "  {:<7} Cv = {:>6.1} ns   Cp = {:>6.1} ns   Cu = {:>6.1} ns   Co = {:>7.1} ns   \
             rank agreement (Spearman) {:>5.2}\n",
            c.volume,
            c.cv_ns,
            c.cp_ns,
            c.cu_ns,
            c.co_ns,
            crate::cost::rank_agreement(&rows)
        );
    }
    s += &format!(
        "{:<7} {:<14} {:<13} {:>9} {:>9} {:>9} {:>9} {:>9} {:>9} {:>7} {:>4}\n",
        "volume", "traversal", "descent", "Nv", "Np", "Nu", "contacts", "ms", "T ms", "error", "ok"
    );
    for d in &r.descent_rules {
        s += &format!(
            "{:<7} {:<14} {:<13} {:>9} {:>9} {:>9} {:>9} {:>9.2} {:>9.2} {:>6.0}% {:>4}\n",
            d.volume,
            d.traversal,
            d.descent,
            d.bv_tests,
            d.prim_tests,
            d.updates,
            d.intersecting_pairs,
            d.measured_ms,
            d.predicted_ms,
            d.error * 100.0,
            if d.intersecting_pairs == r.reference_contacts {
                "yes"
            } else {
                "NO"
            }
        );
    }
    for (name, rows) in &r.other_scenes {
        s += &table(&format!("Builders on another scene kind ({name}):"), rows);
    }
    s += "\nMoving objects: a rock twisting a little more each frame, its frame-0 tree refitted\n\
          versus a tree rebuilt each frame (SAH cost, times, and the pair query against a static rock;\n\
          ok = the refitted tree finds exactly the pairs of the rebuilt one, itself checked above):\n";
    s += &crate::motion::render(&r.motion);
    s += "\nTree representations of tree A (sah, aabb): memory, conversion, pair query against\n\
          B in the same layout, 2 000 rays (same answers = pairs and hits equal the canonical tree's,\n\
          and the pairs equal brute force):\n";
    s += &crate::layouts::render(&r.layouts);
    s += &format!(
        "\nverified: {}/{} queries match brute force\n",
        r.verified, r.queries
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sweep against the double loop it replaced, on triangles whose
    /// corners sit on a coarse grid: equal starts, touching faces, `-0.0`
    /// next to `0.0`, and a NaN that overlaps nothing.
    #[test]
    fn reference_pairs_equal_the_double_loop() {
        let mut seed = 7u32;
        let mut grid = || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            match seed >> 28 {
                0 => -0.0,
                k => (k as f32 - 8.0) * 0.5,
            }
        };
        let mut corner = || bvhkit::glam::Vec3::new(grid(), grid(), grid());
        let mut triangles = |n| -> Vec<Triangle> {
            (0..n)
                .map(|_| Triangle::new(corner(), corner(), corner()))
                .collect()
        };
        let (mut a, b) = (triangles(150), triangles(120));
        a[3].v[0].x = f32::NAN;
        let mut want = Vec::new();
        for (i, x) in (0u32..).zip(&a) {
            for (j, y) in (0u32..).zip(&b) {
                if x.bounds().overlaps(&y.bounds()) {
                    want.push((i, j));
                }
            }
        }
        assert!(want.len() > 1000, "{}", want.len());
        assert_eq!(reference_pairs(&a, &b), want);
        assert_eq!(reference_pairs(&a, &[]), []);
    }

    #[test]
    fn every_builder_gets_one_verified_row() {
        let (a, b) = scene::rock_pair(1);
        let reference = reference_pairs(&a, &b);
        let rows = builder_rows(&a, &b, &reference, 1, &mut |_| {}).unwrap();
        let names: Vec<&str> = rows.iter().map(|r| r.strategy.as_str()).collect();
        let want: Vec<&str> = crate::builders::names()
            .into_iter()
            .filter(|n| *n != "bottom-up-exhaustive")
            .collect();
        assert_eq!(names, want);
        assert!(rows.iter().all(|r| r.matches), "{names:?}");
    }
}
