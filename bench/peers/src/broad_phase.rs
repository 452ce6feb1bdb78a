//! The broad phase over moving boxes: bvhkit's incremental `PairTracker`,
//! bvhkit's rebuild every step plus `SelfPairs`, and parry3d's incremental
//! `Bvh` (leaves updated in place, `refit`, `optimize_incremental`, then a
//! self traversal of the whole tree).
//!
//! The scene is `std-ext/benches/broad_phase.rs`'s, copied: `n` boxes of
//! side 1 drifting in a cube (density fixed: about 4 overlapping pairs per
//! box), every box moving each step or one in ten. Each method runs on its
//! own copy of the scene, advanced the same way, so the pair count of every
//! step must be the same for all three; it is checked.

use crate::common::boxes_overlap;
use bvhkit::builders::DynamicConfig;
use bvhkit::collision::PairTracker;
use bvhkit::query::SelfPairs;
use bvhkit::{Aabb, Node, TopDown};
use bvhkit_std::scene::Drift;
use parry3d::bounding_volume::Aabb as ParryAabb;
use parry3d::math::Vector;
use parry3d::partitioning::{Bvh, BvhBuildStrategy, BvhWorkspace};
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;

/// The fat-leaf margin of both incremental trees.
const MARGIN: f32 = 0.1;

/// Steps run before the counted ones.
const WARM_UP: usize = 3;

/// One case: `n` boxes, one in `every` moving; the median step of each method.
pub struct Case {
    /// Boxes.
    pub n: usize,
    /// One in `every` boxes moves each step.
    pub every: usize,
    /// Counted steps.
    pub steps: usize,
    /// Median pairs per step (bvhkit's tracker).
    pub pairs: usize,
    /// (method, median ms per step), bvhkit's first.
    pub methods: Vec<(&'static str, f64)>,
    /// Every method reported the same pair count on every step.
    pub agree: bool,
}

/// Runs `step(k)` for `WARM_UP + steps` steps; the median of the counted
/// steps' times (ms) and every counted step's pair count.
fn timed(steps: usize, mut step: impl FnMut(usize) -> usize) -> (f64, Vec<usize>) {
    let mut ms = Vec::with_capacity(steps);
    let mut counts = Vec::with_capacity(steps);
    for k in 1..=WARM_UP + steps {
        let t = Instant::now();
        let count = black_box(step(k));
        let elapsed = t.elapsed().as_secs_f64() * 1e3;
        if k > WARM_UP {
            ms.push(elapsed);
            counts.push(count);
        }
    }
    ms.sort_by(f64::total_cmp);
    (ms[ms.len() / 2], counts)
}

fn tracker(n: usize, every: usize, steps: usize) -> (f64, Vec<usize>) {
    let mut drift = Drift::new(n);
    let mut buffers = bvhkit_std::TrackerBuffers::new(n, 16 * n);
    let storage = buffers.storage();
    let config = DynamicConfig {
        margin: MARGIN,
        ..Default::default()
    };
    let mut world = PairTracker::new(storage, config).expect("tracker storage");
    for (i, b) in drift.boxes().iter().enumerate() {
        world.insert(i as u32, b).expect("insert");
    }
    world.step(|_| {}).expect("first step");
    timed(steps, |k| {
        drift.advance(every, k, |i, b| {
            world.set_bounds(i as u32, &b).expect("set_bounds")
        });
        world.step(|_| {}).expect("step").pairs
    })
}

fn rebuild(n: usize, every: usize, steps: usize) -> (f64, Vec<usize>) {
    let mut drift = Drift::new(n);
    let mut all: Vec<Aabb> = drift.boxes();
    let mut nodes = vec![Node::<Aabb>::EMPTY; bvhkit::max_nodes(n)];
    let mut idx = vec![0u32; n];
    timed(steps, |k| {
        drift.advance(every, k, |i, b| all[i] = b);
        let tree = TopDown::default()
            .build(&all, &mut nodes, &mut idx)
            .expect("build");
        SelfPairs::new(&tree, &all).count().expect("self pairs")
    })
}

/// Our box in parry's glam version.
fn parry_box(b: &Aabb) -> ParryAabb {
    ParryAabb::new(
        Vector::from_array(b.min.to_array()),
        Vector::from_array(b.max.to_array()),
    )
}

fn parry(n: usize, every: usize, steps: usize) -> (f64, Vec<usize>) {
    let mut drift = Drift::new(n);
    let mut all: Vec<Aabb> = drift.boxes();
    // Fat leaves from the start, as `insert_or_update_partially` makes them.
    let fat: Vec<ParryAabb> = all
        .iter()
        .map(|b| parry_box(&Aabb::new(b.min - MARGIN, b.max + MARGIN)))
        .collect();
    let mut bvh = Bvh::from_leaves(BvhBuildStrategy::Binned, &fat);
    let mut ws = BvhWorkspace::default();
    timed(steps, |k| {
        drift.advance(every, k, |i, b| {
            all[i] = b;
            // A leaf is only enlarged (by MARGIN) when the box leaves it.
            let _ = bvh.insert_or_update_partially(parry_box(&all[i]), i as u32, MARGIN);
        });
        bvh.refit(&mut ws);
        bvh.optimize_incremental(&mut ws);
        // Each unordered pair of (fat) leaves once, never (i, i); the exact
        // boxes decide.
        let mut count = 0;
        bvh.traverse_bvtt_single_tree::<false>(&mut ws, &mut |i, j| {
            count += usize::from(boxes_overlap(&all[i as usize], &all[j as usize]));
        });
        count
    })
}

/// Runs every case: 10k boxes (and 100k unless `quick`), all moving and one
/// in ten moving.
pub fn run(quick: bool) -> Vec<Case> {
    let sizes: &[usize] = if quick { &[10_000] } else { &[10_000, 100_000] };
    let steps = if quick { 10 } else { 20 };
    let mut cases = Vec::new();
    for &n in sizes {
        for every in [1usize, 10] {
            let t = Instant::now();
            let (ours, want) = tracker(n, every, steps);
            let (re, got_re) = rebuild(n, every, steps);
            let (pa, got_pa) = parry(n, every, steps);
            let agree = got_re == want && got_pa == want;
            let mut sorted = want.clone();
            sorted.sort_unstable();
            eprintln!(
                "broad phase: {n} boxes, 1 in {every} moving: {} pairs, counts {} ({:.1} s)",
                sorted[sorted.len() / 2],
                if agree { "agree" } else { "DISAGREE" },
                t.elapsed().as_secs_f64()
            );
            if !agree {
                eprintln!("  tracker {want:?}\n  rebuild {got_re:?}\n  parry3d {got_pa:?}");
            }
            cases.push(Case {
                n,
                every,
                steps,
                pairs: sorted[sorted.len() / 2],
                methods: vec![
                    ("bvhkit PairTracker", ours),
                    ("bvhkit rebuild + SelfPairs", re),
                    ("parry3d Bvh", pa),
                ],
                agree,
            });
        }
    }
    cases
}

/// The broad-phase section of the report.
pub fn markdown(cases: &[Case], stamp: &crate::report::Stamp) -> String {
    use crate::report::{fmt, ratio};
    let mut s = String::new();
    let w = &mut s;
    let _ = writeln!(w, "# bvhkit against parry3d: broad phase\n");
    let _ = writeln!(
        w,
        "{} · {} · {} · {} run: median step of {} after {WARM_UP} warm-up steps · {:.0} s\n",
        stamp.date,
        stamp.machine,
        stamp.peers,
        stamp.mode,
        cases.first().map_or(0, |c| c.steps),
        stamp.seconds
    );
    let _ = writeln!(
        w,
        "Steps per second (higher is faster); ratios are bvhkit's step time / parry3d's \
         (below 1 means bvhkit is faster).\n"
    );
    let _ = writeln!(
        w,
        "| boxes | moving | pairs | PairTracker steps/s | rebuild + SelfPairs steps/s \
         | parry3d Bvh steps/s | PairTracker / parry3d | rebuild / parry3d | checked |"
    );
    let _ = writeln!(w, "|---:|---|---:|---:|---:|---:|---:|---:|---|");
    for c in cases {
        let ms = |k: usize| c.methods.get(k).map(|m| m.1);
        let per_s = |k: usize| ms(k).map_or("-".into(), |v| fmt(1e3 / v));
        let _ = writeln!(
            w,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            c.n,
            if c.every == 1 {
                "all".to_string()
            } else {
                format!("1 in {}", c.every)
            },
            c.pairs,
            per_s(0),
            per_s(1),
            per_s(2),
            ratio(ms(0), ms(2)),
            ratio(ms(1), ms(2)),
            if c.agree {
                "counts agree"
            } else {
                "WRONG counts"
            }
        );
    }
    let _ = writeln!(
        w,
        "\n- bvhkit `PairTracker`: `set_bounds` for the movers, then `step` (fat leaves, margin {MARGIN}; \
         pairs decided on the exact boxes).\n\
         - bvhkit rebuild: `TopDown::default().build` over all boxes, then `SelfPairs::count`.\n\
         - parry3d `Bvh` (built once by `Bvh::from_leaves(Binned)` over boxes fattened by {MARGIN}): \
         `insert_or_update_partially(box, i, {MARGIN})` for the movers, `refit`, `optimize_incremental`, \
         then `traverse_bvtt_single_tree::<false>` (every pair of overlapping leaves, each unordered pair \
         once). Its leaves are fat, so its pairs are filtered by the exact (closed) box overlap before \
         counting.\n\
         - The same scene as `std-ext/benches/broad_phase.rs` (`bvhkit_std::scene::Drift`) (boxes of side 1, about 4 pairs a box); \
         every method's pair count is checked on every counted step. One thread."
    );
    s
}
