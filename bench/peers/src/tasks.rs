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
//!
//! Each crate gets the mesh as it takes it, converted untimed: bvhkit a
//! `Vec<Triangle>`, parry3d vertices and index triples. Every sampled
//! answer is compared with brute force over every triangle: bvhkit's must
//! be equal, parry3d's within a relative 1e-4 (its arithmetic is its own).
//! The moving-boxes task is the `--broad-phase` section.

use crate::common::{random_rays, time, union, Runs, Scene, Timing};
use bvhkit::glam::Vec3;
use bvhkit::{Mesh, Triangle};
use parry3d::math::Vector;
use parry3d::query::{PointQuery, Ray as ParryRay, RayCast};
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
    /// How many answers were sampled.
    pub checked: usize,
}

/// The source this module was built from, for counting each task's lines.
const SOURCE: &str = include_str!("tasks.rs");

/// Non-blank lines between `// task: NAME` and `// end of task`.
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

    let (ours_rays, hits) = time(runs.rays, || {
        // task: bvhkit rays
        let mesh = Mesh::new(tris.to_vec()).expect("a valid mesh");
        let hits: Vec<Option<f32>> = rays
            .iter()
            .map(|ray| mesh.cast_ray(ray).map(|hit| hit.t))
            .collect();
        // end of task
        hits
    });
    let (parry_rays_ms, parry_hits) = time(runs.rays, || {
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
        hits
    });
    let (ours_points, near) = time(runs.rays, || {
        // task: bvhkit closest-points
        let mesh = Mesh::new(tris.to_vec()).expect("a valid mesh");
        let near: Vec<f64> = queries
            .iter()
            .map(|&p| mesh.closest_point(p).expect("a point").distance)
            .collect();
        // end of task
        near
    });
    let (parry_points_ms, parry_near) = time(runs.rays, || {
        // task: parry3d closest-points
        let mesh = TriMesh::new(vertices.clone(), indices.clone()).expect("a valid mesh");
        let near: Vec<f32> = parry_points
            .iter()
            .map(|&p| (mesh.project_local_point(p, false).point - p).length())
            .collect();
        // end of task
        near
    });

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
    let rays_equal = ray_sample
        .iter()
        .zip(&truth_rays)
        .all(|(&k, t)| hits[k] == *t);
    let rays_close = ray_sample
        .iter()
        .zip(&truth_rays)
        .all(|(&k, t)| match (parry_hits[k], t) {
            (Some(a), Some(b)) => close(f64::from(a), f64::from(*b)),
            (None, None) => true,
            _ => false,
        });
    let points_equal = point_sample
        .iter()
        .zip(&truth_points)
        .all(|(&k, &d)| near[k] == d);
    let points_close = point_sample
        .iter()
        .zip(&truth_points)
        .all(|(&k, &d)| close(f64::from(parry_near[k]), d));

    let row = |task, krate, ms, correct, checked| TaskRow {
        mesh: scene.name.clone(),
        task,
        krate,
        ms,
        lines: lines_of(&format!("{krate} {task}")),
        correct,
        checked,
    };
    vec![
        row("rays", "bvhkit", ours_rays, rays_equal, ray_sample.len()),
        row(
            "rays",
            "parry3d",
            parry_rays_ms,
            rays_close,
            ray_sample.len(),
        ),
        row(
            "closest-points",
            "bvhkit",
            ours_points,
            points_equal,
            point_sample.len(),
        ),
        row(
            "closest-points",
            "parry3d",
            parry_points_ms,
            points_close,
            point_sample.len(),
        ),
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
        "# bvhkit against parry3d: engine tasks\n\n{} · {} · {} · {} run: median of {} \
         (build and queries together) · {:.0} s\n\n\
         Each task as a user writes it with each crate's one-call API, timed from the \
         triangles to the last answer (the tree's build included). Lines: the task's \
         non-blank lines in `bench/peers/src/tasks.rs`. Ratio: bvhkit's time over \
         parry3d's (below 1 means bvhkit is faster). Checked: sampled answers against \
         brute force over every triangle (bvhkit's equal, parry3d's within 1e-4).\n\n\
         | mesh | task | bvhkit ms | lines | parry3d ms | lines | ratio | checked |\n\
         |---|---|---:|---:|---:|---:|---:|---|\n",
        stamp.date, stamp.machine, stamp.peers, stamp.mode, stamp.runs[2], stamp.seconds
    );
    for pair in rows.chunks(2) {
        let [ours, peer] = pair else { continue };
        let verdict = |r: &TaskRow| {
            if r.correct {
                format!("{} ok", r.checked)
            } else {
                "WRONG".to_string()
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
         - moving boxes: see `--broad-phase` (`broad-phase.md`).\n"
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
        ] {
            let n = lines_of(name);
            assert!((3..15).contains(&n), "{name}: {n} lines");
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
        assert_eq!(rows.len(), 4);
        for r in &rows {
            assert!(r.correct && r.checked > 10, "{r:?}");
        }
    }
}
