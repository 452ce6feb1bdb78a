//! Checked rows, the markdown tables and the JSON lines.

use crate::common::{Measured, PairSum, RayHit, Runs, Scene};
use crate::truth::same_hit;
use crate::SceneResult;
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;
use std::time::{Duration, SystemTime};

/// One tree's measurements and verdict.
#[derive(Debug)]
pub struct Row {
    /// What was measured.
    pub m: Measured,
    /// Pairs equal to the ground truth (count and checksum), where run.
    pub pairs_ok: Option<bool>,
    /// Rays that disagree with brute force (sample) or bvhkit's default tree
    /// (all), where run.
    pub rays_wrong: Option<usize>,
    /// Every answer checked and right.
    pub correct: bool,
}

impl Row {
    /// Checks `m`'s answers: pairs against `truth`, rays against the brute
    /// force `sample` (ray index, hit) and against `reference` on all rays.
    pub fn checked(
        m: Measured,
        scene: &Scene,
        truth: &PairSum,
        sample: &[(usize, RayHit)],
        reference: Option<&[RayHit]>,
    ) -> Row {
        let pairs_ok = m.pairs.as_ref().map(|(_, got)| got == truth);
        let rays_wrong = m.rays.as_ref().map(|(_, hits)| {
            let wrong_sample = sample
                .iter()
                .filter(|(k, want)| !same_hit(&hits[*k], want))
                .count();
            let wrong_all = reference.map_or(0, |r| {
                hits.iter().zip(r).filter(|(h, w)| !same_hit(h, w)).count()
            });
            wrong_sample + wrong_all + scene.rays.len().abs_diff(hits.len())
        });
        let correct = pairs_ok != Some(false) && rays_wrong.is_none_or(|w| w == 0);
        Row {
            m,
            pairs_ok,
            rays_wrong,
            correct,
        }
    }

    /// `mesh crate builder`, for messages.
    pub fn label(&self, scene: &str) -> String {
        format!("{scene} {} {}", self.m.krate, self.m.builder)
    }

    fn mrays(&self, rays: usize) -> Option<f64> {
        self.m
            .rays
            .as_ref()
            .map(|(t, _)| rays as f64 / (t.median_ms * 1e-3) / 1e6)
    }
}

/// When, where and how the run was made.
#[derive(Debug, Serialize)]
pub struct Stamp {
    /// UTC date and time.
    pub date: String,
    /// CPU model and the cores the process may use.
    pub machine: String,
    /// Peer crates and versions.
    pub peers: &'static str,
    /// `quick` or `full`.
    pub mode: &'static str,
    /// Rays per scene.
    pub rays: usize,
    /// Counted runs (build, pairs, rays).
    pub runs: [usize; 3],
    /// Seconds the whole run took (ground truth included).
    pub seconds: f64,
}

impl Stamp {
    /// The stamp of a run that took `elapsed`.
    pub fn now(
        peers: &'static str,
        quick: &bool,
        rays: usize,
        runs: Runs,
        elapsed: Duration,
    ) -> Stamp {
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|s| {
                s.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split(':').nth(1))
                    .map(|m| m.trim().to_string())
            })
            .unwrap_or_else(|| std::env::consts::ARCH.to_string());
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        Stamp {
            date: utc_now(),
            machine: format!("{cpu}, {cores} cores"),
            peers,
            mode: if *quick { "quick" } else { "full" },
            rays,
            runs: [runs.build, runs.pairs, runs.rays],
            seconds: elapsed.as_secs_f64(),
        }
    }
}

/// `YYYY-MM-DD HH:MM UTC` from the system clock (days to civil date, after
/// Howard Hinnant's algorithm).
fn utc_now() -> String {
    let secs = SystemTime::now()
        .duration_since(SystemTime::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs()) as i64;
    let (days, rest) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02} {:02}:{:02} UTC",
        rest / 3600,
        rest % 3600 / 60
    )
}

fn find<'r>(r: &'r SceneResult, krate: &str, builder: &str) -> Option<&'r Row> {
    r.rows
        .iter()
        .find(|x| x.m.krate == krate && x.m.builder == builder)
}

fn bytes_per_tri(row: &Row, tris: usize) -> f64 {
    row.m.bytes as f64 / tris.max(1) as f64
}

/// `x / y` as `0.42x`, or `-` when either is missing.
pub(crate) fn ratio(x: Option<f64>, y: Option<f64>) -> String {
    match (x, y) {
        (Some(x), Some(y)) if y > 0.0 => format!("{:.2}x", x / y),
        _ => "-".into(),
    }
}

/// The best value of `f` over one side's rows (`min` or `max`).
fn best(rows: &[&Row], f: impl Fn(&Row) -> Option<f64>, max: bool) -> Option<(f64, String)> {
    rows.iter()
        .filter_map(|r| f(r).map(|v| (v, format!("{} {}", r.m.krate, r.m.builder))))
        .reduce(|a, b| if (b.0 > a.0) == max { b } else { a })
}

/// The report: targets, best against best, every tree, and how it was run.
pub fn markdown(results: &[SceneResult], stamp: &Stamp) -> String {
    let mut s = String::new();
    let w = &mut s;
    let _ = writeln!(w, "# bvhkit against peer crates\n");
    let _ = writeln!(
        w,
        "{} · {} · {} · {} run: {} rays per mesh; median of at least {} builds, {} pair queries, {} ray passes (more until {:.0} ms are timed) · {:.0} s\n",
        stamp.date,
        stamp.machine,
        stamp.peers,
        stamp.mode,
        stamp.rays,
        stamp.runs[0],
        stamp.runs[1],
        stamp.runs[2],
        crate::common::MIN_TIMED_MS,
        stamp.seconds
    );
    let _ = writeln!(w, "## Targets\n");
    let _ = writeln!(
        w,
        "Each cell is bvhkit / peer from this run. Times: below 1 means bvhkit is faster; \
         rays (Mrays/s): above 1 means bvhkit is faster; SAH and bytes: below 1 means bvhkit's is smaller.\n"
    );
    let _ = writeln!(
        w,
        "| mesh | tris | build: sah / parry3d binned (target <= 0.33) | SAH: sah / parry3d binned (<= 1) \
         | build: fastest bvhkit / obvhs fastest (< 1) | SAH: same two (<= 1) \
         | pairs: default / parry3d leaf_pairs (<= 0.33) | rays: default / best CWBVH (>= 1) \
         | rays: best layout / best CWBVH (>= 1.5) | B/tri: quantized4 / best CWBVH (<= 1) \
         | SAH: sah / obvhs medium_build (<= 0.95) | build: same two |"
    );
    let _ = writeln!(
        w,
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for r in results {
        let build = |row: Option<&Row>| row.map(|x| x.m.build.median_ms);
        let sah = |row: Option<&Row>| row.and_then(|x| x.m.sah);
        let pair = |row: Option<&Row>| row.and_then(|x| x.m.pairs.as_ref().map(|p| p.0.median_ms));
        let ours = find(r, "bvhkit", "sah");
        let parry = find(r, "parry3d", "binned");
        // bvhkit's fastest binary builder on this mesh, against obvhs's fastest.
        let ploc = r
            .rows
            .iter()
            .filter(|x| x.m.krate == "bvhkit" && x.m.sah.is_some())
            .min_by(|x, y| x.m.build.median_ms.total_cmp(&y.m.build.median_ms));
        let fastest = find(r, "obvhs", "fastest_build");
        // The quality target: obvhs's medium preset (SAH-driven PLOC with
        // reinsertion), against the default tree.
        let medium = find(r, "obvhs", "medium_build");
        let cwbvh: Vec<&Row> = r
            .rows
            .iter()
            .filter(|x| x.m.krate == "obvhs" && x.m.builder.ends_with("/cwbvh"))
            .collect();
        let ours_all: Vec<&Row> = r.rows.iter().filter(|x| x.m.krate == "bvhkit").collect();
        let mrays = |x: &Row| x.mrays(r.rays);
        let best_cw = best(&cwbvh, mrays, true).map(|b| b.0);
        let best_ours = best(&ours_all, mrays, true).map(|b| b.0);
        let cw_bytes = best(&cwbvh, |x| Some(bytes_per_tri(x, r.tris)), false).map(|b| b.0);
        let q_bytes = find(r, "bvhkit", "sah/quantized4").map(|x| bytes_per_tri(x, r.tris));
        let _ = writeln!(
            w,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.scene,
            r.tris,
            ratio(build(ours), build(parry)),
            ratio(sah(ours), sah(parry)),
            ratio(build(ploc), build(fastest)),
            ratio(sah(ploc), sah(fastest)),
            ratio(pair(ours), pair(parry)),
            ratio(ours.and_then(mrays), best_cw),
            ratio(best_ours, best_cw),
            ratio(q_bytes, cw_bytes),
            ratio(sah(ours), sah(medium)),
            ratio(build(ours), build(medium)),
        );
    }

    let _ = writeln!(w, "\n## Best against best\n");
    let _ = writeln!(
        w,
        "The best bvhkit tree against the best peer tree on each measure (whichever rows they are).\n"
    );
    let _ = writeln!(w, "| mesh | measure | bvhkit | best peer | ratio |");
    let _ = writeln!(w, "|---|---|---|---|---:|");
    for r in results {
        let (ours, peers): (Vec<&Row>, Vec<&Row>) =
            r.rows.iter().partition(|x| x.m.krate == "bvhkit");
        type Measure<'f> = (&'f str, Box<dyn Fn(&Row) -> Option<f64> + 'f>, bool);
        let measures: [Measure; 5] = [
            (
                "build ms",
                Box::new(|x: &Row| Some(x.m.build.median_ms)),
                false,
            ),
            ("SAH", Box::new(|x: &Row| x.m.sah), false),
            (
                "pair ms",
                Box::new(|x: &Row| x.m.pairs.as_ref().map(|p| p.0.median_ms)),
                false,
            ),
            ("Mrays/s", Box::new(|x: &Row| x.mrays(r.rays)), true),
            (
                "B/tri",
                Box::new(|x: &Row| Some(bytes_per_tri(x, r.tris))),
                false,
            ),
        ];
        for (name, f, max) in &measures {
            let (o, p) = (best(&ours, f, *max), best(&peers, f, *max));
            let show = |b: &Option<(f64, String)>| {
                b.as_ref()
                    .map_or("-".into(), |(v, who)| format!("{} ({who})", fmt(*v)))
            };
            let _ = writeln!(
                w,
                "| {} | {name} | {} | {} | {} |",
                r.scene,
                show(&o),
                show(&p),
                ratio(o.map(|b| b.0), p.map(|b| b.0))
            );
        }
    }

    let _ = writeln!(w, "\n## Every tree\n");
    let _ = writeln!(
        w,
        "| mesh | crate | builder | build ms (median) | build ms (min) | leaves | SAH | B/tri | pair ms | pairs | Mrays/s | checked |"
    );
    let _ = writeln!(
        w,
        "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|"
    );
    for r in results {
        for x in &r.rows {
            let pair = x.m.pairs.as_ref();
            let verdict = match (x.pairs_ok, x.rays_wrong) {
                _ if x.correct => "exact".to_string(),
                (ok, wrong) => format!(
                    "WRONG{}{}",
                    if ok == Some(false) { " pairs" } else { "" },
                    wrong
                        .filter(|&n| n > 0)
                        .map_or(String::new(), |n| format!(" {n} rays"))
                ),
            };
            let _ = writeln!(
                w,
                "| {} | {} | {} | {} | {} | {} | {} | {:.1} | {} | {} | {} | {} |",
                r.scene,
                x.m.krate,
                x.m.builder,
                fmt(x.m.build.median_ms),
                fmt(x.m.build.min_ms),
                x.m.leaves,
                x.m.sah.map_or("-".into(), |v| format!("{v:.2}")),
                bytes_per_tri(x, r.tris),
                pair.map_or("-".into(), |p| fmt(p.0.median_ms)),
                pair.map_or("-".into(), |p| p.1.count.to_string()),
                x.mrays(r.rays).map_or("-".into(), |v| format!("{v:.2}")),
                verdict
            );
        }
    }

    let _ = writeln!(w, "\n## How each crate was run\n");
    let mut seen = Vec::new();
    for x in results.iter().flat_map(|r| &r.rows) {
        let key = (x.m.krate, x.m.note);
        if !seen.contains(&key) {
            seen.push(key);
            let _ = writeln!(w, "- {} `{}`: {}", x.m.krate, x.m.builder, x.m.note);
        }
    }
    let _ = writeln!(
        w,
        "\nSAH = (C_t * sum of A(n) over internal nodes + C_i * sum of A(l) * |l| over leaves) / A(root), \
         C_t = C_i = 1, A = surface area of the node's box, computed by one function over every crate's \
         binary nodes (`-` for wide trees). Pairs: every (i, j) whose triangle boxes overlap (closed), \
         checked against a grid-based ground truth by count and checksum. Rays: closest hit with bvhkit's \
         f64 triangle test behind every crate's leaf callback, checked against brute force on a sample and \
         against bvhkit's default tree on all rays. B/tri: node bytes plus primitive indices."
    );
    s
}

/// A time or rate with three significant-ish digits.
pub(crate) fn fmt(v: f64) -> String {
    if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 10.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.3}")
    }
}

/// One JSON line per crate x builder x mesh.
#[derive(Serialize)]
struct JsonRow<'a> {
    #[serde(rename = "crate")]
    krate: &'a str,
    builder: &'a str,
    mesh: &'a str,
    tris: usize,
    build_ms: f64,
    build_min_ms: f64,
    leaves: usize,
    sah: Option<f64>,
    bytes: usize,
    pair_ms: Option<f64>,
    pairs: Option<u64>,
    pair_checksum: Option<u64>,
    correct: bool,
    mrays: Option<f64>,
    rays: usize,
    date: &'a str,
    machine: &'a str,
    mode: &'a str,
}

/// Writes `latest.md`, `latest.jsonl`, and appends the rows to `history.jsonl`.
pub fn write(dir: &Path, md: &str, results: &[SceneResult], stamp: &Stamp) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    std::fs::write(dir.join("latest.md"), md)?;
    let mut lines = String::new();
    for r in results {
        for x in &r.rows {
            let row = JsonRow {
                krate: x.m.krate,
                builder: &x.m.builder,
                mesh: &r.scene,
                tris: r.tris,
                build_ms: x.m.build.median_ms,
                build_min_ms: x.m.build.min_ms,
                leaves: x.m.leaves,
                sah: x.m.sah,
                bytes: x.m.bytes,
                pair_ms: x.m.pairs.as_ref().map(|p| p.0.median_ms),
                pairs: x.m.pairs.as_ref().map(|p| p.1.count),
                pair_checksum: x.m.pairs.as_ref().map(|p| p.1.checksum),
                correct: x.correct,
                mrays: x.mrays(r.rays),
                rays: r.rays,
                date: &stamp.date,
                machine: &stamp.machine,
                mode: stamp.mode,
            };
            lines.push_str(&serde_json::to_string(&row).map_err(std::io::Error::other)?);
            lines.push('\n');
        }
    }
    std::fs::write(dir.join("latest.jsonl"), &lines)?;
    use std::io::Write as _;
    std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(dir.join("history.jsonl"))?
        .write_all(lines.as_bytes())
}
