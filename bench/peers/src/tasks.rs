//! The engine tasks (issue #26): each job written the way each crate's
//! one-call API invites, timed end to end (building the mesh's tree
//! included), its lines counted from this file, its answers checked.
//!
//! - `rays`: the closest hit of every ray (the scene's random rays);
//!   bvhkit's `Mesh::cast_ray`, parry3d's `TriMesh` with
//!   `cast_local_ray_and_get_normal`.
//! - `closest-points`: the closest point of the mesh to every point of a
//!   seeded set in the mesh's box; bvhkit's `Mesh::closest_point`, parry3d's
//!   `TriMesh` with `project_local_point` (not solid: the surface).
//! - `mesh-pairs`: every intersecting pair of triangles of the mesh and its
//!   moved copy (the scene's `b`, given to both crates as triangles);
//!   bvhkit's `Mesh::pairs`, parry3d's `Bvh::leaf_pairs` of two `TriMesh`es
//!   with `query::intersection_test` on each pair of triangles.
//!
//! Each crate gets the mesh as it takes it, converted untimed: bvhkit a
//! `Vec<Triangle>`, parry3d vertices and index triples. Every sampled
//! answer is compared with brute force over every triangle: bvhkit's must
//! be equal, parry3d's within a relative 1e-4 (its arithmetic is its own).
//! The pairs are compared whole with the exact answer (`truth::exact_pairs`);
//! a peer's wrong pairs are counted and reported, not fatal.
//! - `moving-boxes`: 10,000 boxes drifting for 100 frames (the
//!   `--broad-phase` scene, every box moving each frame), every overlapping
//!   pair each frame, the first frame's tree built in the task; bvhkit's
//!   `collision::PairTracker`, parry3d's `Bvh` kept up as its docs do it
//!   (`insert_or_update_partially`, `refit`, `optimize_incremental`, a self
//!   traversal). Each frame's pair count is compared between the crates,
//!   and the first and last frames' with brute force. `--broad-phase` has
//!   the per-step figures for more sizes.

use crate::common::{boxes_overlap, random_rays, time_pair, union, Runs, Scene, Timing};
use bvhkit::builders::DynamicConfig;
use bvhkit::collision::PairTracker;
use bvhkit::glam::Vec3;
use bvhkit::{Aabb, Mesh, Rigid, Triangle};
use bvhkit_std::scene::Drift;
use bvhkit_std::TrackerBuffers;
use parry3d::bounding_volume::Aabb as ParryAabb;
use parry3d::math::Pose;
use parry3d::math::Vector;
use parry3d::partitioning::{Bvh, BvhBuildStrategy, BvhWorkspace};
use parry3d::query::{intersection_test, PointQuery, Ray as ParryRay, RayCast};
use parry3d::shape::TriMesh;

/// One task run by one crate.
#[derive(Clone, Debug, serde::Serialize)]
pub struct TaskRow {
    /// The scene.
    pub mesh: String,
    /// `rays` or `closest-points`.
    pub task: &'static str,
    /// `bvhkit` or `parry3d`.
    #[serde(rename = "crate")]
    pub krate: &'static str,
    /// Build plus queries.
    pub ms: Timing,
    /// Non-blank lines of the task's code, counted from this file.
    pub lines: usize,
    /// Every sampled answer agreed with brute force.
    pub correct: bool,
    /// Answers that did not (for pairs: pairs reported wrongly or missed).
    pub wrong: usize,
    /// How many answers were sampled.
    pub checked: usize,
}

/// The source this module was built from, for counting each task's lines.
const SOURCE: &str = include_str!("tasks.rs");

/// Non-blank lines between `// task: NAME` and `// end of task`. (The
/// `// ANCHOR:` lines around each task are mdbook's: the book's engine
/// chapter shows each task's code from them.)
fn lines_of(name: &str) -> usize {
    let start = format!("// task: {name}");
    SOURCE
        .lines()
        .skip_while(|l| l.trim() != start)
        .skip(1)
        .take_while(|l| l.trim() != "// end of task")
        .filter(|l| !l.trim().is_empty())
        .count()
}

fn vector(v: Vec3) -> Vector {
    Vector::from_array(v.to_array())
}

/// The tasks on `scene`'s mesh `a`, `sample` answers of each checked.
pub fn run(scene: &Scene, runs: Runs, points: usize, sample: usize) -> Vec<TaskRow> {
    let tris: &[Triangle] = &scene.a;
    // parry3d's input: three vertices per triangle, converted untimed.
    let vertices: Vec<Vector> = tris.iter().flat_map(|t| t.v.map(vector)).collect();
    let indices: Vec<[u32; 3]> = (0..tris.len() as u32)
        .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
        .collect();
    let rays = &scene.rays;
    let parry_rays: Vec<ParryRay> = rays
        .iter()
        .map(|r| ParryRay::new(vector(r.origin()), vector(r.dir())))
        .collect();
    let bounds = union(&scene.boxes_a);
    let queries: Vec<Vec3> = random_rays(&bounds, points, 0x5eed_0002)
        .iter()
        .map(|r| r.origin())
        .collect();
    let parry_points: Vec<Vector> = queries.iter().map(|&p| vector(p)).collect();
    let moved: &[Triangle] = &scene.b;
    let moved_vertices: Vec<Vector> = moved.iter().flat_map(|t| t.v.map(vector)).collect();

    let ((ours_rays, hits), (parry_rays_ms, parry_hits)) = time_pair(
        runs.rays,
        || {
            // ANCHOR: bvhkit-rays
            // task: bvhkit rays
            let mesh = Mesh::new(tris.to_vec()).expect("a valid mesh");
            let hits: Vec<Option<f32>> = rays
                .iter()
                .map(|ray| mesh.cast_ray(ray).map(|hit| hit.t))
                .collect();
            // end of task
            // ANCHOR_END: bvhkit-rays
            hits
        },
        || {
            // ANCHOR: parry3d-rays
            // task: parry3d rays
            let mesh = TriMesh::new(vertices.clone(), indices.clone()).expect("a valid mesh");
            let hits: Vec<Option<f32>> = parry_rays
                .iter()
                .map(|ray| {
                    mesh.cast_local_ray_and_get_normal(ray, f32::MAX, true)
                        .map(|hit| hit.time_of_impact)
                })
                .collect();
            // end of task
            // ANCHOR_END: parry3d-rays
            hits
        },
    );
    let ((ours_points, near), (parry_points_ms, parry_near)) = time_pair(
        runs.rays,
        || {
            // ANCHOR: bvhkit-closest-points
            // task: bvhkit closest-points
            let mesh = Mesh::new(tris.to_vec()).expect("a valid mesh");
            let near: Vec<f64> = queries
                .iter()
                .map(|&p| mesh.closest_point(p).expect("a point").distance)
                .collect();
            // end of task
            // ANCHOR_END: bvhkit-closest-points
            near
        },
        || {
            // ANCHOR: parry3d-closest-points
            // task: parry3d closest-points
            let mesh = TriMesh::new(vertices.clone(), indices.clone()).expect("a valid mesh");
            let near: Vec<f32> = parry_points
                .iter()
                .map(|&p| (mesh.project_local_point(p, false).point - p).length())
                .collect();
            // end of task
            // ANCHOR_END: parry3d-closest-points
            near
        },
    );

    let ((ours_pairs, pairs), (parry_pairs_ms, parry_pairs)) = time_pair(
        runs.pairs,
        || {
            // ANCHOR: bvhkit-mesh-pairs
            // task: bvhkit mesh-pairs
            let a = Mesh::new(tris.to_vec()).expect("a valid mesh");
            let b = Mesh::new(moved.to_vec()).expect("a valid mesh");
            let pairs = a.pairs(&b, &Rigid::IDENTITY);
            // end of task
            // ANCHOR_END: bvhkit-mesh-pairs
            pairs
        },
        || {
            // ANCHOR: parry3d-mesh-pairs
            // task: parry3d mesh-pairs
            let a = TriMesh::new(vertices.clone(), indices.clone()).expect("a valid mesh");
            let b = TriMesh::new(moved_vertices.clone(), indices.clone()).expect("a valid mesh");
            let (pose, bvh_b) = (Pose::IDENTITY, b.bvh());
            let mut pairs: Vec<(u32, u32)> = a
                .bvh()
                .leaf_pairs(bvh_b, |x, y| x.intersects(y))
                .filter(|&(i, j)| {
                    intersection_test(&pose, &a.triangle(i), &pose, &b.triangle(j))
                        .is_ok_and(|hit| hit.intersecting)
                })
                .collect();
            pairs.sort_unstable();
            // end of task
            // ANCHOR_END: parry3d-mesh-pairs
            pairs
        },
    );
    let exact = crate::truth::exact_pairs(scene);
    let differ = |got: &[(u32, u32)]| {
        let extra = got
            .iter()
            .filter(|p| exact.binary_search(p).is_err())
            .count();
        let missed = exact
            .iter()
            .filter(|p| got.binary_search(p).is_err())
            .count();
        extra + missed
    };
    let (ours_wrong, parry_wrong) = (differ(&pairs), differ(&parry_pairs));

    // Brute force on a sample of each.
    let step = |n: usize| (n / sample.max(1)).max(1);
    let ray_sample: Vec<usize> = (0..rays.len()).step_by(step(rays.len())).collect();
    let truth_rays: Vec<Option<f32>> = ray_sample
        .iter()
        .map(|&k| crate::truth::ray(scene, k).map(|h| h.1))
        .collect();
    let point_sample: Vec<usize> = (0..queries.len()).step_by(step(queries.len())).collect();
    let truth_points: Vec<f64> = point_sample
        .iter()
        .map(|&k| {
            tris.iter()
                .map(|t| t.closest_point(queries[k]).distance_squared)
                .fold(f64::INFINITY, f64::min)
                .sqrt()
        })
        .collect();
    let close = |x: f64, y: f64| (x - y).abs() <= 1e-4 * y.abs().max(1.0);
    let rays_wrong = ray_sample
        .iter()
        .zip(&truth_rays)
        .filter(|&(&k, t)| hits[k] != *t)
        .count();
    let parry_rays_wrong = ray_sample
        .iter()
        .zip(&truth_rays)
        .filter(|&(&k, t)| match (parry_hits[k], t) {
            (Some(a), Some(b)) => !close(f64::from(a), f64::from(*b)),
            (None, None) => false,
            _ => true,
        })
        .count();
    let points_wrong = point_sample
        .iter()
        .zip(&truth_points)
        .filter(|&(&k, &d)| near[k] != d)
        .count();
    let parry_points_wrong = point_sample
        .iter()
        .zip(&truth_points)
        .filter(|&(&k, &d)| !close(f64::from(parry_near[k]), d))
        .count();

    let row = |task, krate, ms, wrong, checked| TaskRow {
        mesh: scene.name.clone(),
        task,
        krate,
        ms,
        lines: lines_of(&format!("{krate} {task}")),
        correct: wrong == 0,
        wrong,
        checked,
    };
    let (nr, np) = (ray_sample.len(), point_sample.len());
    vec![
        row("rays", "bvhkit", ours_rays, rays_wrong, nr),
        row("rays", "parry3d", parry_rays_ms, parry_rays_wrong, nr),
        row("closest-points", "bvhkit", ours_points, points_wrong, np),
        row(
            "closest-points",
            "parry3d",
            parry_points_ms,
            parry_points_wrong,
            np,
        ),
        row("mesh-pairs", "bvhkit", ours_pairs, ours_wrong, exact.len()),
        row(
            "mesh-pairs",
            "parry3d",
            parry_pairs_ms,
            parry_wrong,
            exact.len(),
        ),
    ]
}

/// The moving-boxes task: `n` drifting boxes, `frames` frames, every box
/// moving each frame; both crates' rows.
pub fn moving_boxes(runs: Runs, n: usize, frames: usize) -> Vec<TaskRow> {
    // Every frame's boxes, made untimed: both crates see the same motion.
    let mut drift = Drift::new(n);
    let frames: Vec<Vec<Aabb>> = (1..=frames)
        .map(|k| {
            drift.advance(1, k, |_, _| {});
            drift.boxes()
        })
        .collect();
    let parry_box = |b: &Aabb| {
        ParryAabb::new(
            Vector::from_array(b.min.to_array()),
            Vector::from_array(b.max.to_array()),
        )
    };
    let ((ours, counts), (peer, peer_counts)) = time_pair(
        runs.pairs,
        || {
            // ANCHOR: bvhkit-moving-boxes
            // task: bvhkit moving-boxes
            let mut buffers = TrackerBuffers::new(n, 16 * n);
            let config = DynamicConfig {
                margin: 0.1,
                ..Default::default()
            };
            let mut world = PairTracker::new(buffers.storage(), config).expect("storage");
            for (i, b) in frames[0].iter().enumerate() {
                world.insert(i as u32, b).expect("a valid box");
            }
            let mut counts = Vec::new();
            for frame in &frames {
                for (i, b) in frame.iter().enumerate() {
                    world.set_bounds(i as u32, b).expect("a valid box");
                }
                counts.push(world.step(|_| {}).expect("room for the pairs").pairs);
            }
            // end of task
            // ANCHOR_END: bvhkit-moving-boxes
            counts
        },
        || {
            // ANCHOR: parry3d-moving-boxes
            // task: parry3d moving-boxes
            let fat = |b: &Aabb| parry_box(&Aabb::new(b.min - 0.1, b.max + 0.1));
            let leaves: Vec<ParryAabb> = frames[0].iter().map(fat).collect();
            let mut bvh = Bvh::from_leaves(BvhBuildStrategy::Binned, &leaves);
            let mut workspace = BvhWorkspace::default();
            let mut counts = Vec::new();
            for frame in &frames {
                for (i, b) in frame.iter().enumerate() {
                    bvh.insert_or_update_partially(parry_box(b), i as u32, 0.1);
                }
                bvh.refit(&mut workspace);
                bvh.optimize_incremental(&mut workspace);
                let mut count = 0;
                bvh.traverse_bvtt_single_tree::<false>(&mut workspace, &mut |i, j| {
                    count += usize::from(boxes_overlap(&frame[i as usize], &frame[j as usize]));
                });
                counts.push(count);
            }
            // end of task
            // ANCHOR_END: parry3d-moving-boxes
            counts
        },
    );
    // Brute force on the first and the last frame; the crates' counts
    // compared on every frame.
    let brute = |boxes: &[Aabb]| {
        let mut count = 0;
        for (i, p) in boxes.iter().enumerate() {
            count += boxes[i + 1..]
                .iter()
                .filter(|q| boxes_overlap(p, q))
                .count();
        }
        count
    };
    let ends = [0, frames.len() - 1];
    let truth: Vec<usize> = ends.iter().map(|&k| brute(&frames[k])).collect();
    let wrong = |got: &[usize], other: &[usize]| {
        let frames_off = got.iter().zip(other).filter(|(a, b)| a != b).count();
        let ends_off = ends
            .iter()
            .zip(&truth)
            .filter(|&(&k, &t)| got[k] != t)
            .count();
        frames_off + ends_off
    };
    let (ours_wrong, peer_wrong) = (wrong(&counts, &peer_counts), wrong(&peer_counts, &counts));
    let row = |krate, ms, wrong| TaskRow {
        mesh: format!("drift {n} boxes"),
        task: "moving-boxes",
        krate,
        ms,
        lines: lines_of(&format!("{krate} moving-boxes")),
        correct: wrong == 0,
        wrong,
        checked: frames.len() + ends.len(),
    };
    vec![
        row("bvhkit", ours, ours_wrong),
        row("parry3d", peer, peer_wrong),
    ]
}

/// The tasks' table: per mesh and task, each crate's time and lines, and
/// bvhkit's time over parry3d's.
pub fn markdown(
    rows: &[TaskRow],
    stamp: &crate::report::Stamp,
    rays: usize,
    points: usize,
) -> String {
    let mut md = format!(
        "# bvhkit against parry3d: engine tasks\n\n{} · {} · {} · {} run: medians of {} \
         (rays, closest points) and {} (mesh pairs, moving boxes) alternating runs of the \
         two crates (build and queries together) · {:.0} s\n\n\
         Each task as a user writes it with each crate's one-call API, timed from the \
         triangles to the last answer (the tree's build included). Lines: the task's \
         non-blank lines in `bench/peers/src/tasks.rs`. Ratio: bvhkit's time over \
         parry3d's (below 1 means bvhkit is faster). Checked: sampled answers against \
         brute force over every triangle (bvhkit's equal, parry3d's within 1e-4).\n\n\
         | mesh | task | bvhkit ms | lines | parry3d ms | lines | ratio | checked |\n\
         |---|---|---:|---:|---:|---:|---:|---|\n",
        stamp.date,
        stamp.machine,
        stamp.peers,
        stamp.mode,
        stamp.runs[2],
        stamp.runs[1],
        stamp.seconds
    );
    for pair in rows.chunks(2) {
        let [ours, peer] = pair else { continue };
        let verdict = |r: &TaskRow| {
            if r.correct {
                format!("{} ok", r.checked)
            } else {
                format!("{} of {} wrong", r.wrong, r.checked)
            }
        };
        md.push_str(&format!(
            "| {} | {} | {:.1} | {} | {:.1} | {} | {:.2}x | bvhkit {}, parry3d {} |\n",
            ours.mesh,
            ours.task,
            ours.ms.median_ms,
            ours.lines,
            peer.ms.median_ms,
            peer.lines,
            ours.ms.median_ms / peer.ms.median_ms,
            verdict(ours),
            verdict(peer),
        ));
    }
    md.push_str(&format!(
        "\n- rays: {rays} random rays per mesh aimed into its box, closest hit.\n\
         - closest-points: {points} seeded points in the mesh's box, the closest point of \
         the surface.\n\
         - mesh-pairs: the mesh against its moved copy, every intersecting pair of \
         triangles, checked whole against the exact answer (the pairs of overlapping boxes, \
         each decided with exact predicates); wrong: pairs reported that do not intersect \
         plus pairs missed.\n\
         - moving-boxes: 10,000 boxes of side 1 drifting for 100 frames, every one moving \
         each frame, every overlapping pair each frame, the first frame's tree built in the \
         task; checked: each frame's pair count against the other crate's, and the first and \
         last frames' against brute force. `--broad-phase` (`broad-phase.md`) has the \
         per-step figures for more sizes and for one box in ten moving.\n"
    ));
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each task's code is found and counted.
    #[test]
    fn every_task_has_its_lines() {
        for name in [
            "bvhkit rays",
            "parry3d rays",
            "bvhkit closest-points",
            "parry3d closest-points",
            "bvhkit mesh-pairs",
            "parry3d mesh-pairs",
            "bvhkit moving-boxes",
            "parry3d moving-boxes",
        ] {
            let n = lines_of(name);
            assert!((3..25).contains(&n), "{name}: {n} lines");
        }
    }

    /// On a small scene every answer of both crates checks out.
    #[test]
    fn both_crates_answer_the_tasks_correctly() {
        let scene = crate::common::reference::small_scene();
        let runs = Runs {
            build: 1,
            pairs: 1,
            rays: 1,
        };
        let rows = run(&scene, runs, 200, 50);
        assert_eq!(rows.len(), 6);
        for r in &rows {
            assert!(r.checked > 10, "{r:?}");
            // bvhkit is exact; the peer's rays and points are within 1e-4.
            assert!(r.correct || r.task == "mesh-pairs", "{r:?}");
        }
    }

    /// Both crates find every frame's pairs of a small drift.
    #[test]
    fn both_crates_keep_up_with_moving_boxes() {
        let runs = Runs {
            build: 1,
            pairs: 1,
            rays: 1,
        };
        let rows = moving_boxes(runs, 500, 12);
        assert_eq!(rows.len(), 2);
        for r in &rows {
            assert_eq!(r.checked, 14, "{r:?}");
            assert!(r.correct, "{r:?}");
        }
    }
}
