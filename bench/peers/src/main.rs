//! The peer benchmark: bvhkit against parry3d, obvhs and bvh, on the same
//! meshes, in one process, one thread, the same release profile.
//!
//! For every mesh and every tree: build time (median and minimum), leaves,
//! SAH cost (one formula, `common::sah`), bytes per triangle, the pair query
//! (the mesh against a moved copy, every pair of overlapping triangle boxes)
//! and closest-hit rays. Every pair answer is checked against a grid-based
//! ground truth (count and checksum); every ray answer against brute force on
//! a sample and against bvhkit's default tree on all rays.
//!
//! Run it through `scripts/bench-peers` (it fetches the meshes first):
//! `bvhkit-bench-peers [--quick] [--rays N] [--mesh FILE]... [--no-instanced] [--out DIR]`
//!
//! `--tasks` runs only the engine tasks (`tasks.rs`: rays and closest
//! points through each crate's one-call mesh API, timed end to end) and
//! writes `tasks.md` and `tasks.jsonl` instead.
//!
//! `--broad-phase` runs only the broad-phase comparison (`broad_phase.rs`:
//! moving boxes, bvhkit's `PairTracker` and rebuild against parry3d's
//! incremental `Bvh`) and writes `broad-phase.md` instead.

mod broad_phase;
mod bvh_peer;
mod common;
mod obvhs_peer;
mod ours;
mod parry;
mod report;
mod tasks;
mod truth;

use common::{Measured, Runs, Scene};
use std::path::PathBuf;
use std::time::Instant;

/// The peers' versions, pinned with `=` in Cargo.toml.
const PEERS: &str = "parry3d 0.31.1, obvhs 0.4.0, bvh 0.13.0";
/// The broad-phase section runs parry3d alone.
const BROAD_PHASE_PEERS: &str = "parry3d 0.31.1";

/// The real meshes `scripts/fetch-meshes` gets, smallest first.
const MESHES: [&str; 4] = [
    "ChineseDragon-10kv.off",
    "armadillo.off",
    "bunny00.off",
    "elephant.off",
];

/// The instanced scene: this many copies of the armadillo on a grid.
const COPIES: (usize, usize) = (5, 4);

struct Options {
    quick: bool,
    broad_phase: bool,
    tasks: bool,
    rays: usize,
    meshes: Vec<PathBuf>,
    instanced: bool,
    out: PathBuf,
}

fn options() -> Result<Options, String> {
    let mut o = Options {
        quick: false,
        broad_phase: false,
        tasks: false,
        rays: 0,
        meshes: Vec::new(),
        instanced: true,
        out: PathBuf::from("target/bench-peers"),
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut value = || args.next().ok_or(format!("{a} needs a value"));
        match a.as_str() {
            "--quick" => o.quick = true,
            "--broad-phase" => o.broad_phase = true,
            "--tasks" => o.tasks = true,
            "--no-instanced" => o.instanced = false,
            "--rays" => o.rays = value()?.parse().map_err(|e| format!("--rays: {e}"))?,
            "--mesh" => o.meshes.push(value()?.into()),
            "--out" => o.out = value()?.into(),
            "-h" | "--help" => return Err(
                "usage: bvhkit-bench-peers [--quick] [--broad-phase | --tasks] [--rays N] [--mesh FILE]... \
                            [--no-instanced] [--out DIR]"
                    .into(),
            ),
            _ => return Err(format!("unknown argument {a} (try --help)")),
        }
    }
    if o.rays == 0 {
        o.rays = if o.quick { 100_000 } else { 1_000_000 };
    }
    if o.meshes.is_empty() {
        o.meshes = MESHES
            .iter()
            .map(|m| PathBuf::from("data/meshes").join(m))
            .collect();
    }
    Ok(o)
}

fn main() {
    let o = match options() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(2);
        }
    };
    let runs = if o.quick {
        Runs {
            build: 5,
            pairs: 3,
            rays: 1,
        }
    } else {
        Runs {
            build: 9,
            pairs: 7,
            rays: 3,
        }
    };
    let sample = if o.quick { 32 } else { 200 };
    let started = Instant::now();
    if o.broad_phase {
        broad_phase_only(&o, started);
        return;
    }
    if o.tasks {
        tasks_only(&o, runs, sample, started);
        return;
    }
    let mut results = Vec::new();
    for path in &o.meshes {
        let (name, tris) = load(path);
        if o.instanced && name == "armadillo" {
            let copies = instanced(&tris);
            results.push(bench(Scene::new(&name, tris, o.rays), runs, sample));
            let name = format!("armadillo-x{}", COPIES.0 * COPIES.1);
            results.push(bench(Scene::new(&name, copies, o.rays), runs, sample));
        } else {
            results.push(bench(Scene::new(&name, tris, o.rays), runs, sample));
        }
    }
    let stamp = report::Stamp::now(PEERS, &o.quick, o.rays, runs, started.elapsed());
    let md = report::markdown(&results, &stamp);
    println!("{md}");
    if let Err(e) = report::write(&o.out, &md, &results, &stamp) {
        eprintln!("could not write {}: {e}", o.out.display());
        std::process::exit(1);
    }
    eprintln!("wrote {}/latest.md and latest.jsonl", o.out.display());
    let wrong: Vec<String> = results
        .iter()
        .flat_map(|r| {
            r.rows
                .iter()
                .filter(|m| !m.correct)
                .map(move |m| m.label(&r.scene))
        })
        .collect();
    if !wrong.is_empty() {
        eprintln!("WRONG ANSWERS: {}", wrong.join(", "));
        std::process::exit(1);
    }
}

/// The broad-phase section alone: prints it, writes `broad-phase.md` and
/// exits non-zero if the pair counts disagree.
fn broad_phase_only(o: &Options, started: Instant) {
    let cases = broad_phase::run(o.quick);
    let runs = Runs {
        build: 0,
        pairs: 0,
        rays: 0,
    };
    let stamp = report::Stamp::now(BROAD_PHASE_PEERS, &o.quick, 0, runs, started.elapsed());
    let md = broad_phase::markdown(&cases, &stamp);
    println!("{md}");
    let path = o.out.join("broad-phase.md");
    if let Err(e) = std::fs::create_dir_all(&o.out).and_then(|()| std::fs::write(&path, &md)) {
        eprintln!("could not write {}: {e}", path.display());
        std::process::exit(1);
    }
    eprintln!("wrote {}", path.display());
    if cases.iter().any(|c| !c.agree) {
        eprintln!("WRONG ANSWERS: broad-phase pair counts disagree");
        std::process::exit(1);
    }
}

/// A mesh file and its short name (the file name up to its first `-`,
/// lower case); exits with the loader's error (file and line) if it fails.
fn load(path: &std::path::Path) -> (String, Vec<bvhkit::Triangle>) {
    let tris = match bvhkit_std::mesh::load(path) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    };
    let name = path
        .file_stem()
        .map_or("mesh".into(), |s| s.to_string_lossy());
    let name = name.split('-').next().unwrap_or("mesh").to_lowercase();
    (name, tris)
}

/// The engine tasks alone, on every mesh (not the instanced one): prints
/// them, writes `tasks.md` and `tasks.jsonl`, and exits non-zero if an
/// answer is wrong.
fn tasks_only(o: &Options, runs: Runs, sample: usize, started: Instant) {
    let points = if o.quick { 10_000 } else { 100_000 };
    // Five rounds of each crate's rays and points, alternating (three made
    // a 0.8x ratio read 1.1x in the next run).
    let runs = Runs {
        rays: if o.quick { runs.rays } else { 5 },
        ..runs
    };
    let mut rows = Vec::new();
    for path in &o.meshes {
        let (name, tris) = load(path);
        let scene = Scene::new(&name, tris, o.rays);
        eprintln!("{name}: {} triangles", scene.a.len());
        rows.extend(tasks::run(&scene, runs, points, sample));
    }
    eprintln!("moving boxes: 10000 boxes, 100 frames");
    rows.extend(tasks::moving_boxes(runs, 10_000, 100));
    let stamp = report::Stamp::now(BROAD_PHASE_PEERS, &o.quick, o.rays, runs, started.elapsed());
    let md = tasks::markdown(&rows, &stamp, o.rays, points);
    println!("{md}");
    let jsonl: String = rows
        .iter()
        .filter_map(|r| serde_json::to_string(r).ok())
        .map(|l| l + "\n")
        .collect();
    let written = std::fs::create_dir_all(&o.out)
        .and_then(|()| std::fs::write(o.out.join("tasks.md"), &md))
        .and_then(|()| std::fs::write(o.out.join("tasks.jsonl"), jsonl));
    if let Err(e) = written {
        eprintln!("could not write {}: {e}", o.out.display());
        std::process::exit(1);
    }
    eprintln!("wrote {}/tasks.md and tasks.jsonl", o.out.display());
    // bvhkit's answers must be exact; a peer's wrong ones are reported.
    if rows.iter().any(|r| !r.correct && r.krate == "bvhkit") {
        eprintln!("WRONG ANSWERS from bvhkit in the tasks");
        std::process::exit(1);
    }
}

/// `tris` copied on a grid of `COPIES`, each copy 0.8 of the mesh's size away
/// from the next, so that neighbours overlap.
fn instanced(tris: &[bvhkit::Triangle]) -> Vec<bvhkit::Triangle> {
    let b = common::union(&common::bounds_of(tris));
    let step = (b.max - b.min) * 0.8;
    let mut out = Vec::with_capacity(tris.len() * COPIES.0 * COPIES.1);
    for i in 0..COPIES.0 {
        for k in 0..COPIES.1 {
            let shift = bvhkit::glam::Vec3::new(i as f32 * step.x, 0.0, k as f32 * step.z);
            out.extend(tris.iter().map(|t| bvhkit::Triangle {
                v: t.v.map(|p| p + shift),
            }));
        }
    }
    out
}

/// One scene's rows, checked.
pub struct SceneResult {
    /// Scene name.
    pub scene: String,
    /// Triangles in the mesh.
    pub tris: usize,
    /// Rays cast.
    pub rays: usize,
    /// The ground-truth pair answer.
    pub truth: common::PairSum,
    /// Every tree's measurements, with its verdict.
    pub rows: Vec<report::Row>,
}

fn bench(scene: Scene, runs: Runs, sample: usize) -> SceneResult {
    let t = Instant::now();
    let truth = truth::pairs(&scene);
    let step = (scene.rays.len() / sample.max(1)).max(1);
    let brute: Vec<(usize, common::RayHit)> = (0..scene.rays.len())
        .step_by(step)
        .map(|k| (k, truth::ray(&scene, k)))
        .collect();
    eprintln!(
        "{}: {} triangles, {} pairs, {} rays ({} checked by brute force); truth in {:.1} s",
        scene.name,
        scene.a.len(),
        truth.count,
        scene.rays.len(),
        brute.len(),
        t.elapsed().as_secs_f64()
    );
    let mut measured: Vec<Measured> = Vec::new();
    for (krate, run) in [
        ("bvhkit", ours::run as fn(&Scene, Runs) -> Vec<Measured>),
        ("parry3d", parry::run),
        ("obvhs", obvhs_peer::run),
        ("bvh", bvh_peer::run),
    ] {
        let t = Instant::now();
        let rows = run(&scene, runs);
        eprintln!(
            "  {krate}: {} trees in {:.1} s",
            rows.len(),
            t.elapsed().as_secs_f64()
        );
        measured.extend(rows);
    }
    // Every tree's rays against bvhkit's default tree, which is itself
    // checked against brute force on the sample.
    let reference: Option<Vec<common::RayHit>> = measured
        .iter()
        .find(|m| m.krate == "bvhkit")
        .and_then(|m| m.rays.as_ref().map(|r| r.1.clone()));
    let rows = measured
        .into_iter()
        .map(|m| report::Row::checked(m, &scene, &truth, &brute, reference.as_deref()))
        .collect();
    SceneResult {
        scene: scene.name.clone(),
        tris: scene.a.len(),
        rays: scene.rays.len(),
        truth,
        rows,
    }
}
