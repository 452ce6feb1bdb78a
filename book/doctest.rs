//! The book's chapters as doctests: `cargo test -p bvhkit-book` compiles and
//! runs every Rust block, and a failure names `book/src/<chapter>.md (line N)`.
//! Prose-only blocks are fenced as `text` or `console`.
//!
//! A snippet that prints shows its output in the chapter: its `println!`
//! calls are captured by two hidden lines into an [`Output`], which checks
//! them against `book/src/output/NAME.txt`, the file the chapter includes in
//! a `text` block right after the snippet. Regenerate every output file with
//! `BVHKIT_BLESS=1 cargo test -p bvhkit-book --doc`, then read `git diff`.

use std::fmt::Write as _;

macro_rules! chapters {
    ($($name:ident => $file:literal),* $(,)?) => {
        $(
            #[cfg(doctest)]
            #[doc = include_str!(concat!("src/", $file))]
            pub mod $name {}
        )*
        /// Every chapter file, so a test can check that none is left out.
        pub const CHAPTERS: &[&str] = &[$($file),*];
    };
}

/// The README's Rust blocks (its embedded snippet) run as doctests too, on
/// the edition a new project gets (the block says `rust edition2024`: no
/// `&mut` to a `static mut`, for one).
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub mod readme {}

chapters! {
    introduction => "introduction.md",
    bounding_volumes => "bounding-volumes.md",
    characteristics => "characteristics.md",
    tree_degree => "tree-degree.md",
    top_down => "top-down.md",
    bottom_up => "bottom-up.md",
    insertion => "insertion.md",
    traversal => "traversal.md",
    descent_rules => "descent-rules.md",
    collision_system => "collision-system.md",
    engines => "engines.md",
    representations => "representations.md",
    robustness => "robustness.md",
    performance => "performance.md",
    embedded => "embedded.md",
    exercises => "exercises.md",
    explorer => "explorer.md",
}

/// What a book snippet prints, checked against the output its chapter shows.
///
/// In a snippet (the `#` lines are hidden in the book, so a reader sees and
/// copies plain `println!`):
///
/// ```text
/// # let mut out = bvhkit_book::Output::new("chapter-1");
/// # macro_rules! println { () => { out.line(String::new()) }; ($($t:tt)*) => { out.line(format!($($t)*)) } }
/// println!("{} triangles", 20);
/// # out.check();
/// ```
#[derive(Debug)]
pub struct Output {
    name: &'static str,
    text: String,
}

impl Output {
    /// Captures the output shown in `book/src/output/{name}.txt`.
    pub fn new(name: &'static str) -> Output {
        Output {
            name,
            text: String::new(),
        }
    }

    /// One printed line.
    pub fn line(&mut self, line: String) {
        let _ = writeln!(self.text, "{line}");
    }

    /// Prints the output, then checks that it is the file the chapter shows,
    /// digit for digit (or, with `BVHKIT_BLESS` set, writes that file).
    pub fn check(self) {
        self.compare(|s| s.to_string(), "digit for digit");
    }

    /// [`check`](Self::check) for output with timings in it: the text must
    /// match the file with every number masked (the file keeps the numbers
    /// of the run that wrote it; the chapter says it is a recorded run).
    /// The figures that follow the words `SAH` and `depth` still count,
    /// digit for digit: tree quality and shape come out of the code, not
    /// the clock (masked too, they went stale unnoticed once).
    pub fn check_shape(self) {
        self.compare(
            |s| format!("{}\n{}", mask_numbers(s), exact_figures(s).join(" ")),
            "with timings masked",
        );
    }

    fn compare(self, view: impl Fn(&str) -> String, how: &str) {
        print!("{}", self.text);
        let path = output_path(self.name);
        if std::env::var_os("BVHKIT_BLESS").is_some() {
            std::fs::write(&path, &self.text).unwrap_or_else(|e| panic!("{path}: {e}"));
            return;
        }
        let shown = std::fs::read_to_string(&path).unwrap_or_else(|e| {
            panic!("{path}: {e} (write it with BVHKIT_BLESS=1 cargo test -p bvhkit-book --doc)")
        });
        if view(&shown) != view(&self.text) {
            panic!(
                "the book shows an output ({path}) that this snippet no longer prints \
                 ({how}).\n--- shown:\n{shown}--- printed now:\n{}\nIf the new output is \
                 right, regenerate it with BVHKIT_BLESS=1 cargo test -p bvhkit-book --doc and \
                 review the diff.",
                self.text
            );
        }
    }
}

/// Where the output named `name` is kept.
/// (`NAME.txt`, shown in a `text` block; a name with an extension, such as
/// `NAME.md` for a table, is the file name and is included as it is.)
fn output_path(name: &str) -> String {
    let ext = if name.contains('.') { "" } else { ".txt" };
    format!("{}/src/output/{name}{ext}", env!("CARGO_MANIFEST_DIR"))
}

/// The figures of a timed output that do not depend on the clock: every
/// word after `SAH` or `depth` (a trailing comma dropped).
pub fn exact_figures(text: &str) -> Vec<&str> {
    let words: Vec<&str> = text.split_whitespace().collect();
    words
        .windows(2)
        .filter(|w| w[0] == "SAH" || w[0] == "depth")
        .map(|w| w[1].trim_end_matches(','))
        .collect()
}

/// `text` with every number (digits, a decimal point, an exponent) replaced
/// by `#` and runs of spaces by one (numbers of other widths move the
/// columns): what stays when timings change from run to run.
pub fn mask_numbers(text: &str) -> String {
    let mut out = String::new();
    let mut in_number = false;
    let mut chars = text.chars().peekable();
    let mut after_e = false;
    while let Some(c) = chars.next() {
        let next_digit = chars.peek().is_some_and(|d| d.is_ascii_digit());
        let next_sign = chars.peek().is_some_and(|d| *d == '-' || *d == '+');
        let continues = in_number
            && ((matches!(c, '.' | ',') && next_digit)
                || (c == 'e' && (next_digit || next_sign))
                || (after_e && matches!(c, '-' | '+') && next_digit));
        after_e = in_number && c == 'e';
        if c.is_ascii_digit() || continues {
            if !in_number {
                out.push('#');
            }
            in_number = true;
        } else {
            in_number = false;
            if !(c == ' ' && out.ends_with(' ')) {
                out.push(c);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_timed_output_keeps_its_sah_and_depth_figures() {
        let shown = "ploc-r4   0.18 ms  SAH 23.63\n exhaustive: 72.78 ms, SAH 22.52, depth 11\n";
        assert_eq!(super::exact_figures(shown), ["23.63", "22.52", "11"]);
        let now = "ploc-r4   0.25 ms  SAH 24.26\n exhaustive: 70.01 ms, SAH 22.52, depth 11\n";
        assert_eq!(super::mask_numbers(shown), super::mask_numbers(now));
        assert_ne!(super::exact_figures(shown), super::exact_figures(now));
    }

    #[test]
    fn masking_keeps_the_words_and_drops_the_numbers() {
        assert_eq!(
            super::mask_numbers("  sah:   0.12 ms, SAH 23.25, 1e-3 x2\n"),
            " sah: # ms, SAH #, # x#\n"
        );
        assert_eq!(
            super::mask_numbers("a 121.02 ms"),
            super::mask_numbers("a   86.1 ms")
        );
    }

    /// Every snippet that prints captures its output, and the chapter shows
    /// that output in a `text` block right after it; every output file is
    /// shown once. (The snippets check the files' contents when they run.)
    #[test]
    fn every_printing_snippet_shows_its_output() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/src");
        let mut shown = Vec::new();
        for file in super::CHAPTERS {
            let text = std::fs::read_to_string(format!("{dir}/{file}")).unwrap();
            let blocks: Vec<&str> = text.split("```").collect();
            // Odd pieces are fenced blocks: "rust\n...", "text\n...".
            for (k, block) in blocks.iter().enumerate().skip(1).step_by(2) {
                if !block.starts_with("rust") || !block.contains("println!") {
                    continue;
                }
                let at = format!(
                    "{file}, the snippet starting `{}`",
                    block.lines().nth(1).unwrap_or("")
                );
                let name = block
                    .split("bvhkit_book::Output::new(\"")
                    .nth(1)
                    .and_then(|s| s.split('"').next())
                    .unwrap_or_else(|| panic!("{at} prints without capturing its output"));
                assert!(
                    block.contains("# out.check();") || block.contains("# out.check_shape();"),
                    "{at} never checks its output"
                );
                if name.ends_with(".md") {
                    // A table: included as markdown right after the snippet.
                    assert!(
                        blocks[k + 1].starts_with(&format!("\n\n{{{{#include output/{name}}}}}\n")),
                        "{at} is not followed by its table"
                    );
                    shown.push(name.to_string());
                    continue;
                }
                let next = blocks.get(k + 2).copied().unwrap_or("");
                assert_eq!(
                    next,
                    format!("text\n{{{{#include output/{name}.txt}}}}\n"),
                    "{at} is not followed by its output"
                );
                assert!(
                    blocks[k + 1].trim().is_empty(),
                    "{at}: text between it and its output"
                );
                shown.push(format!("{name}.txt"));
            }
        }
        let mut files: Vec<String> = std::fs::read_dir(format!("{dir}/output"))
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        files.sort();
        shown.sort();
        assert_eq!(files, shown, "output files and the snippets that show them");
    }

    /// The exercises chapter has a section per exercise, in number order,
    /// each heading with the points the grader gives it.
    #[test]
    fn exercise_headings_match_the_grader() {
        use bvhkit_exercises::grader::{EXERCISES, checks};
        let chapter = include_str!("src/exercises.md");
        for &(n, _) in EXERCISES.iter() {
            let points: u32 = checks()
                .iter()
                .filter(|c| c.exercise == n)
                .map(|c| c.points)
                .sum();
            let heading = chapter
                .lines()
                .find(|l| l.starts_with(&format!("## {n}. ")))
                .unwrap_or_else(|| panic!("no section for exercise {n}"));
            assert!(
                heading.ends_with(&format!("({points} points)")),
                "{heading}: the grader gives {points} points"
            );
        }
        let sections = chapter
            .lines()
            .filter(|l| l.starts_with("## ") && l.as_bytes()[3].is_ascii_digit())
            .count();
        assert_eq!(sections, EXERCISES.len());
    }

    /// The recorded `bvhkit bench` run the performance chapter includes
    /// (`scripts/book-measure`): its JSON, and the rows of one table.
    fn recorded_bench() -> serde_json::Value {
        serde_json::from_str(include_str!("src/measured/bench/report.json")).unwrap()
    }

    fn rows<'r>(
        run: &'r serde_json::Value,
        table: &str,
        scene: &str,
    ) -> Vec<&'r serde_json::Value> {
        run[table]
            .as_array()
            .unwrap()
            .iter()
            .filter(|r| r["scene"] == scene || r["mesh"] == scene)
            .collect()
    }

    fn row<'r>(rows: &[&'r serde_json::Value], key: &str, name: &str) -> &'r serde_json::Value {
        rows.iter()
            .find(|r| r[key] == name)
            .unwrap_or_else(|| panic!("no row {name}"))
    }

    /// The recorded run's deterministic columns are what the code builds
    /// now: each builder's SAH cost on the rocks. A change to a builder
    /// that alters its trees fails here until the run is recorded again.
    #[test]
    fn recorded_bench_run_matches_the_code() {
        let run = recorded_bench();
        assert!(run["recorded"].as_str().unwrap().contains(" UTC · "));
        let rocks = rows(&run, "builders", "rocks");
        let (a, _) = bvhkit_std::scene::rock_pair(5);
        for (name, builder) in bvhkit_std::report::builder_candidates() {
            let recorded = row(&rocks, "builder", &name)["sah_cost"].as_f64().unwrap();
            let now = builder
                .build::<bvhkit::Aabb>(&a)
                .unwrap()
                .view()
                .stats()
                .sah_cost;
            assert!(
                (recorded - now).abs() <= 1e-9 * now,
                "{name}: the recorded run has SAH {recorded}, the code builds {now}: run \
                 scripts/book-measure and read the performance chapter against it"
            );
        }
        // The fits' volumes are deterministic too: the rock's, fitted now.
        let (rock, _) = bvhkit_std::scene::rock_pair(5);
        let pts: Vec<bvhkit::glam::Vec3> = rock.iter().flat_map(|t| t.v).collect();
        let pts = pts.as_slice();
        use bvhkit::{Aabb, BoundingVolume, Dop14, Dop18, Dop26, Obb, Sphere};
        let now = [
            ("aabb", Aabb::fit(pts).volume()),
            ("sphere-ritter", Sphere::ritter(pts).volume()),
            ("sphere-refined", Sphere::ritter_refined(pts, 8).volume()),
            ("sphere-welzl", Sphere::welzl(pts).volume()),
            ("obb-pca", Obb::pca(pts).volume()),
            ("obb-dito", Obb::dito(pts).volume()),
            ("14-dop", Dop14::fit(pts).volume()),
            ("18-dop", Dop18::fit(pts).volume()),
            ("26-dop", Dop26::fit(pts).volume()),
        ]
        .map(|(m, v)| (m, v as f64));
        let fits = rows(&run, "fits", "rock");
        for (method, volume) in now {
            let recorded = fits
                .iter()
                .find(|r| r["method"] == method)
                .and_then(|r| r["volume"].as_f64());
            assert!(
                recorded.is_some_and(|v| (v - volume).abs() <= 1e-6 * volume),
                "fit {method}: the recorded run has volume {recorded:?}, the code fits {volume}: \
                 run scripts/book-measure and read the performance chapter against it"
            );
        }
        let all_verified = ["builders", "layouts", "advisor"].iter().all(|t| {
            run[*t].as_array().unwrap().iter().all(|r| {
                r["verified"] != false && r["same_answers"] != false && r["all_verified"] != false
            })
        });
        assert!(all_verified, "a recorded answer differs from brute force");
    }

    /// What the performance chapter's prose says about the recorded run
    /// holds in it (the prose cites the tables instead of copying numbers).
    #[test]
    fn the_performance_chapter_reads_the_recorded_run_right() {
        let run = recorded_bench();
        let num = |r: &serde_json::Value, k: &str| r[k].as_f64().unwrap();
        assert!(
            rows(&run, "fits", "rock")[0]["hull_ratio"].is_number(),
            "the recorded run has no hull ratios (it predates exact k-DOP volumes): run \
             scripts/book-measure and read the performance chapter against it"
        );
        // Fits: nothing convex is smaller than the hull; on every mesh the
        // 26-DOP is the tightest volume and every k-DOP is tighter than the
        // box; Welzl's is the tightest sphere; the box is the fastest fit on
        // the rock; on slivers every sphere is over ten times looser.
        for mesh in [
            "rock",
            "soup",
            "clustered",
            "slivers",
            "armadillo.off",
            "bunny00.off",
        ] {
            let fits = rows(&run, "fits", mesh);
            assert!(
                fits.iter().all(|r| num(r, "hull_ratio") >= 1.0 - 1e-5),
                "{mesh}"
            );
            assert_eq!(
                num(row(&fits, "method", "26-dop"), "volume_ratio"),
                1.0,
                "{mesh}"
            );
            let aabb = num(row(&fits, "method", "aabb"), "volume");
            for dop in ["14-dop", "18-dop", "26-dop"] {
                assert!(
                    num(row(&fits, "method", dop), "volume") < aabb,
                    "{mesh} {dop}"
                );
            }
            let welzl = num(row(&fits, "method", "sphere-welzl"), "volume");
            assert!(
                welzl <= num(row(&fits, "method", "sphere-ritter"), "volume"),
                "{mesh}"
            );
        }
        // The hull fits: face-flush the tightest and the slowest OBB fit on
        // every mesh; surface PCA against vertex PCA goes both ways.
        let (mut hull_wins, mut hull_loses) = (false, false);
        for mesh in [
            "rock",
            "soup",
            "clustered",
            "slivers",
            "armadillo.off",
            "ChineseDragon-10kv.off",
            "bunny00.off",
        ] {
            let fits = rows(&run, "fits", mesh);
            let get = |m: &str, k: &str| num(row(&fits, "method", m), k);
            for other in ["obb-pca", "obb-dito", "obb-pca-hull"] {
                assert!(
                    get("obb-face-flush", "volume") <= get(other, "volume"),
                    "{mesh} {other}"
                );
                assert!(
                    get("obb-face-flush", "ms") > get(other, "ms"),
                    "{mesh} {other}"
                );
            }
            // "on these meshes the table shows the 18-DOP ahead" (of the 14-DOP).
            assert!(get("18-dop", "volume") < get("14-dop", "volume"), "{mesh}");
            if mesh == "rock" {
                // "on the round rock it is tighter than the 14-DOP, though
                // not the 18- or 26-DOP".
                let welzl = get("sphere-welzl", "volume");
                assert!(get("18-dop", "volume") < welzl && welzl < get("14-dop", "volume"));
            }
            let (surface, vertices) = (get("obb-pca-hull", "volume"), get("obb-pca", "volume"));
            hull_wins |= surface < vertices;
            hull_loses |= surface > vertices;
        }
        assert!(hull_wins && hull_loses);
        let rock = rows(&run, "fits", "rock");
        let fastest = rock
            .iter()
            .min_by(|x, y| num(x, "ms").total_cmp(&num(y, "ms")))
            .unwrap();
        assert_eq!(fastest["method"], "aabb");
        let slivers = rows(&run, "fits", "slivers");
        assert!(
            slivers
                .iter()
                .filter(|r| r["method"].as_str().unwrap().starts_with("sphere"))
                .all(|r| num(r, "hull_ratio") > 10.0)
        );
        // Volumes, on every scene: every answer exact; top-down k-DOP trees
        // test fewer volumes and primitives than the box tree; spheres test
        // several times the box tree's primitives; OBB trees test about as
        // many; both query over twice as slow as boxes; DiTO node fits
        // change Np and query time by little for a longer build; on the
        // scans the box tree queries fastest; exact k-DOP measures move SAH and Nv by
        // about a percent for a build at least ten times longer. The exact
        // rows exist on the rocks and the meshes up to 25 000 triangles.
        let mut exact_rows = 0;
        for scene in [
            "rocks",
            "armadillo.off",
            "ChineseDragon-10kv.off",
            "bunny00.off",
        ] {
            let v = rows(&run, "volumes", scene);
            assert!(v.iter().all(|r| r["verified"] == true), "{scene}");
            let get = |volume: &str, builder: &str| {
                *v.iter()
                    .find(|r| r["volume"] == volume && r["builder"] == builder)
                    .unwrap_or_else(|| panic!("{scene}: no {volume} {builder}"))
            };
            let aabb = get("aabb", "sah");
            for dop in ["14-dop", "18-dop", "26-dop"] {
                for k in ["bv_tests", "prim_tests"] {
                    assert!(num(get(dop, "sah"), k) <= num(aabb, k), "{scene} {dop} {k}");
                }
                if scene != "rocks" {
                    // "the pruning saves at most about a fifth of the volume
                    // tests and a few percent of the primitive tests".
                    let saved = |k: &str| 1.0 - num(get(dop, "sah"), k) / num(aabb, k);
                    assert!(saved("bv_tests") < 0.22, "{scene} {dop}");
                    assert!(saved("prim_tests") < 0.08, "{scene} {dop}");
                }
            }
            let sphere = get("sphere", "sah");
            assert!(
                num(sphere, "prim_tests") > 2.0 * num(aabb, "prim_tests"),
                "{scene}"
            );
            let obb = get("obb", "sah");
            let np = num(obb, "prim_tests") / num(aabb, "prim_tests");
            assert!((0.9..1.1).contains(&np), "{scene}: {np}");
            for slow in [obb, sphere] {
                assert!(
                    num(slow, "query_ms") > 2.0 * num(aabb, "query_ms"),
                    "{scene}"
                );
            }
            let dito = get("obb-dito", "sah");
            let ratio = |k: &str| num(dito, k) / num(obb, k);
            assert!((0.99..1.01).contains(&ratio("prim_tests")), "{scene}");
            // "within a fifth either way in the recorded run".
            assert!((0.8..1.2).contains(&ratio("query_ms")), "{scene}");
            // "a build 1.6 to 1.8 times as long".
            assert!((1.6..1.8).contains(&ratio("build_ms")), "{scene}");
            if scene != "rocks" {
                let fastest = v
                    .iter()
                    .min_by(|x, y| num(x, "query_ms").total_cmp(&num(y, "query_ms")))
                    .unwrap();
                // "the fastest query is a box or k-DOP tree's".
                let volume = fastest["volume"].as_str().unwrap();
                assert!(
                    volume == "aabb" || volume.ends_with("-dop"),
                    "{scene}: {volume}"
                );
            } else {
                assert!(v.iter().all(|r| num(r, "query_ms") < 1.0));
            }
            for (boxed, exact) in [("14-dop", "14-dop-exact"), ("26-dop", "26-dop-exact")] {
                let Some(e) = v.iter().find(|r| r["volume"] == exact) else {
                    continue;
                };
                exact_rows += 1;
                let b = get(boxed, "ploc-r1");
                let near = |k: &str| (num(e, k) / num(b, k) - 1.0).abs();
                assert!(
                    near("sah_cost") < 0.02 && near("bv_tests") < 0.02,
                    "{scene} {exact}"
                );
                assert!(
                    num(e, "build_ms") > 10.0 * num(b, "build_ms"),
                    "{scene} {exact}"
                );
            }
        }
        assert_eq!(exact_rows, 4, "the rocks and the dragon have exact rows");
        // Builders, on every scene: binned SAH on the front; the sweep within
        // 2% of its SAH for over 5x its build time; min-overlap and
        // max-separation dominated; PLOC's trees worse, and PLOC dominated
        // on the three scans (slower to build, queries within a fifth of
        // binned SAH's), its build within
        // a third of binned SAH's on the rocks.
        for scene in [
            "rocks",
            "armadillo.off",
            "ChineseDragon-10kv.off",
            "bunny00.off",
        ] {
            let b = rows(&run, "builders", scene);
            let (sah, sweep) = (row(&b, "builder", "sah"), row(&b, "builder", "sah-sweep"));
            assert_eq!(sah["pareto"], true, "{scene}");
            assert!(
                num(sweep, "sah_cost") > 0.98 * num(sah, "sah_cost"),
                "{scene}"
            );
            assert!(
                num(sweep, "build_ms") > 5.0 * num(sah, "build_ms"),
                "{scene}"
            );
            // "`parent-axes` ... nearly the same tree (SAH within 0.2%)
            // ... several times slower ... query times within a seventh".
            let parent = row(&b, "builder", "parent-axes");
            let ratio = |k: &str| num(parent, k) / num(sah, k);
            assert!((ratio("sah_cost") - 1.0).abs() < 0.002, "{scene}");
            assert!(ratio("build_ms") > 2.5, "{scene}");
            assert!((ratio("query_ms") - 1.0).abs() < 0.15, "{scene}");
            for dominated in ["min-overlap", "max-separation"] {
                assert_eq!(
                    row(&b, "builder", dominated)["pareto"],
                    false,
                    "{scene} {dominated}"
                );
            }
            if scene != "rocks" {
                assert_eq!(row(&b, "builder", "ploc-r4")["pareto"], false, "{scene}");
            }
            let ploc = row(&b, "builder", "ploc-r4");
            if scene == "rocks" {
                // "within a third of binned SAH's either way".
                let b = num(ploc, "build_ms") / num(sah, "build_ms");
                assert!((0.67..1.5).contains(&b), "{b}");
            } else {
                // "query within a fifth of binned SAH's time either way".
                let q = num(ploc, "query_ms") / num(sah, "query_ms");
                assert!((0.8..1.25).contains(&q), "{scene}: {q}");
                assert!(num(ploc, "build_ms") > num(sah, "build_ms"), "{scene}");
            }
            assert!(num(ploc, "sah_cost") > num(sah, "sah_cost"), "{scene}");
            // performance.md: "a SAH cost up to 12% above binned SAH's".
            assert!(
                num(ploc, "sah_cost") < 1.12 * num(sah, "sah_cost"),
                "{scene}"
            );
        }
        // Narrow phase: the exact count of disagreements, and exactness
        // costing more on near contacts than on random pairs.
        let narrow = run["narrow"].as_array().unwrap();
        let get = |pairs: &str, signs: &str| {
            narrow
                .iter()
                .find(|r| r["pairs"] == pairs && r["signs"] == signs)
                .unwrap()
        };
        let wrong = |p: &str, s: &str| {
            let r = get(p, s);
            (num(r, "disagreement") * num(r, "tested")).round() as u64
        };
        assert_eq!(wrong("adversarial", "f64"), 1);
        assert_eq!(wrong("adversarial", "f32"), 341);
        assert_eq!(wrong("random", "f32"), 0);
        let slow =
            |p: &str| num(get(p, "exact"), "ns_per_test") / num(get(p, "f64"), "ns_per_test");
        assert!(slow("adversarial") > slow("random"));
        // Scans: the face-flush box is the tightest OBB on all three, and
        // tighter than the axis-aligned box; the 26-DOP (checked above) is
        // tighter still.
        for mesh in ["armadillo.off", "ChineseDragon-10kv.off", "bunny00.off"] {
            let fits = rows(&run, "fits", mesh);
            let v = |m: &str| num(row(&fits, "method", m), "volume");
            let flush = v("obb-face-flush");
            for other in ["aabb", "obb-pca", "obb-dito", "obb-pca-hull"] {
                assert!(flush <= v(other), "{mesh} {other}");
            }
            assert!(v("26-dop") < flush, "{mesh}");
        }
        // Layouts: 4-wide casts rays fastest; quantized has the fewest bytes
        // per triangle and is the slowest for both queries.
        let layouts: Vec<&serde_json::Value> = run["layouts"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|r| r["refused"].is_null())
            .collect();
        let best = |k: &str, min: bool| {
            let pick = layouts.iter().min_by(|x, y| {
                let o = num(x, k).total_cmp(&num(y, k));
                if min { o } else { o.reverse() }
            });
            pick.unwrap()["layout"].as_str().unwrap()
        };
        assert_eq!(best("rays_ms", true), "wide-4");
        assert_eq!(best("bytes_per_triangle", true), "quantized-4");
        assert_eq!(best("rays_ms", false), "quantized-4");
        assert_eq!(best("pairs_ms", false), "quantized-4");
        // Advisor: the advice and the default within 15% of each other on
        // the geometric mean (the chapter gives both), and never off by 2.5x
        // (each cell is the fastest of about 250 noisy timings; the run
        // recorded on 2026-11-26 16:35, a noisy hour, had two cells at 2.2x
        // where earlier runs stayed under 2x).
        let adv = run["advisor"].as_array().unwrap();
        let geo =
            |k: &str| (adv.iter().map(|r| num(r, k).ln()).sum::<f64>() / adv.len() as f64).exp();
        let (advice, default) = (geo("ratio"), geo("default_ratio"));
        assert!((advice / default - 1.0).abs() < 0.15, "{advice} {default}");
        let claim =
            format!("advice takes {advice:.2}x the best time and the default {default:.2}x");
        assert!(
            include_str!("src/performance.md").contains(&claim),
            "performance.md should say: {claim}"
        );
        assert!(adv.iter().all(|r| num(r, "ratio") < 2.5));
    }

    /// Snippets reach glam through `bvhkit::glam`, so that they paste into
    /// a project whose only dependency is bvhkit.
    #[test]
    fn snippets_use_glam_through_bvhkit() {
        for file in super::CHAPTERS {
            let text =
                std::fs::read_to_string(format!("{}/src/{file}", env!("CARGO_MANIFEST_DIR")))
                    .unwrap();
            for (k, block) in text.split("```").enumerate().skip(1).step_by(2) {
                if !block.starts_with("rust") {
                    continue;
                }
                let bare = block
                    .match_indices("glam::")
                    .any(|(at, _)| !block[..at].ends_with("bvhkit::"));
                assert!(
                    !bare,
                    "{file}, code block {}: `glam::` without `bvhkit::`",
                    k / 2 + 1
                );
            }
        }
    }

    /// The embedded chapter's footprint table is the one `scripts/embedded-demo`
    /// wrote (recorded by `scripts/book-measure`, stamped with the toolchain),
    /// every set is in it, and the minimal set is within the budget the
    /// chapter states (64 KiB of flash, 6 KiB of stack over the baseline).
    #[test]
    fn recorded_embedded_footprint_is_complete_and_within_budget() {
        let chapter = include_str!("src/embedded.md");
        assert!(chapter.contains("{{#include measured/embedded-footprint.md}}"));
        let table = include_str!("src/measured/embedded-footprint.md");
        let stamp = table.lines().next().unwrap();
        assert!(
            stamp.starts_with("Recorded ") && stamp.contains(" UTC with rustc "),
            "{stamp}"
        );
        let row = |set: &str| -> Vec<u64> {
            let line = table
                .lines()
                .find(|l| l.starts_with(&format!("| {set} |")))
                .unwrap_or_else(|| panic!("no row for {set}"));
            line.split('|')
                .skip(2)
                .filter_map(|c| c.trim().parse().ok())
                .collect()
        };
        for set in [
            "baseline",
            "boxes",
            "minimal",
            "minimal,print-display",
            "minimal,print-debug",
            "minimal,print-float",
            "minimal,init-empty",
            "minimal,strategies",
            "typical",
            "everything",
        ] {
            assert_eq!(row(set).len(), 6, "{set}");
        }
        // Each step's own stack high-water mark, in bytes.
        let step = |set: &str, step: &str| -> u64 {
            let line = table
                .lines()
                .find(|l| l.starts_with(&format!("| {set} | {step} |")))
                .unwrap_or_else(|| panic!("no step {step} of {set}"));
            line.split('|').nth(3).unwrap().trim().parse().unwrap()
        };
        let minimal = row("minimal");
        // The boxes firmware links no software `f64` routine (the script
        // fails otherwise) and stays within its guard budget.
        let boxes = row("boxes");
        assert_eq!(boxes[5], 0, "boxes: soft-double routines");
        assert!(boxes[1] <= 36 * 1024 && boxes[4] <= 4 * 1024, "{boxes:?}");
        assert!(
            minimal[1] <= 64 * 1024 && minimal[4] <= 6 * 1024,
            "{minimal:?}"
        );
        // The chapter's figures, derived from the table: what printing
        // with `{}` and `{:?}` adds, and how far the minimal set is from the
        // 32 KiB / 4 KiB aim.
        let display = row("minimal,print-display")[0] - minimal[0];
        let debug = row("minimal,print-debug")[0] - minimal[0];
        let thousands = |n: u64| {
            if n >= 1000 {
                format!("{} {:03}", n / 1000, n % 1000)
            } else {
                n.to_string()
            }
        };
        let kb = |n: u64| format!("{:.1} KB", n as f64 / 1000.0);
        // The chapter names the step that sets the typical set's stack.
        assert_eq!(
            row("typical")[3],
            step("typical", "build-sah-sphere"),
            "embedded.md says the sphere build sets the typical stack"
        );
        assert!(step("typical", "aabb-moved") < step("typical", "build-sah-sphere"));
        let more = |set: &str| kb(row(set)[0] - minimal[0]);
        for claim in [
            format!("takes {} more flash.", more("minimal,init-empty")),
            format!(
                "takes\n  {} more flash than `minimal`",
                more("minimal,print-float")
            ),
            format!(
                "would add {} (`minimal,strategies`)",
                more("minimal,strategies")
            ),
            format!("`Node::ZERO` {} of initialised", more("minimal,init-empty")),
            format!(
                "B moved: {}\n  (`aabb-moved` in the per-step table) against {} for",
                kb(step("typical", "aabb-moved")),
                kb(step("typical", "aabb-sah-dfs"))
            ),
            format!(
                "sphere tree's build, {}\n  (`build-sah-sphere`), just ahead of",
                kb(step("typical", "build-sah-sphere"))
            ),
            format!(
                "Minimal stack** is the builder: {} for `build-sah-a`",
                kb(step("minimal", "build-sah-a"))
            ),
            format!(
                "a pair query takes {}, a ray {}.",
                kb(step("minimal", "aabb-sah-dfs")),
                kb(step("minimal", "aabb-dfs"))
            ),
            format!("its numbers, {display} B more"),
            format!("{} more than `as_str` ({} B)", kb(debug), thousands(debug)),
            if minimal[4] <= 4096 {
                format!(
                    "the stack is within it ({} B over the\nbaseline), the flash {} over",
                    thousands(minimal[4]),
                    kb(minimal[1].saturating_sub(32 * 1024))
                )
            } else {
                format!(
                    "the stack is {} over it, the flash\n{}",
                    kb(minimal[4] - 4096),
                    kb(minimal[1].saturating_sub(32 * 1024))
                )
            },
            // The boxes firmware against its aims.
            format!(
                "**Stack**: build {}, pairs {}, rays {} (`boxes-build`,",
                kb(step("boxes", "boxes-build")),
                kb(step("boxes", "boxes-pairs")),
                kb(step("boxes", "boxes-rays"))
            ),
            format!(
                "**Flash**: {} for the whole firmware, {} of it over the\n  baseline.",
                kb(row("boxes")[0]),
                kb(row("boxes")[1])
            ),
        ] {
            assert!(chapter.contains(&claim), "embedded.md should say: {claim}");
        }
    }

    /// The cost model's held-out table (characteristics chapter) is
    /// rendered from the recorded `bvhkit cost-model` run
    /// (`book/src/measured/cost-model.json`, by `scripts/book-measure`):
    /// per held-out scene and volume, the queries predicted within 25% and
    /// the worst error. `BVHKIT_BLESS` writes the table; otherwise it must be
    /// what the run gives, and the chapter's claims must hold in the run.
    #[test]
    fn recorded_cost_model_table_and_claims() {
        let run: serde_json::Value =
            serde_json::from_str(include_str!("src/measured/cost-model.json")).unwrap();
        let rows = run["rows"].as_array().unwrap();
        let (mut scenes, mut volumes) = (Vec::new(), Vec::new());
        for r in rows {
            let (s, v) = (r["scene"].as_str().unwrap(), r["volume"].as_str().unwrap());
            if !scenes.contains(&s) {
                scenes.push(s);
            }
            if !volumes.contains(&v) {
                volumes.push(v);
            }
        }
        let err = |r: &serde_json::Value| r["error"].as_f64().unwrap();
        let mut table = format!(
            "Recorded {} · {} interleaved rounds per query.\n\n| held-out scene | {} |\n|---|{}\n",
            run["recorded"].as_str().unwrap(),
            run["rounds"],
            volumes.join(" | "),
            "---|".repeat(volumes.len())
        );
        for s in &scenes {
            table += &format!("| {s} |");
            for v in &volumes {
                let cell: Vec<f64> = rows
                    .iter()
                    .filter(|r| r["scene"] == *s && r["volume"] == *v)
                    .map(err)
                    .collect();
                let within = cell.iter().filter(|e| e.abs() <= 0.25).count();
                let worst = cell
                    .iter()
                    .copied()
                    .max_by(|a, b| a.abs().total_cmp(&b.abs()))
                    .unwrap();
                table += &format!(" {within}/{}, {:+.0}% |", cell.len(), worst * 100.0);
            }
            table += "\n";
        }
        let within = rows.iter().filter(|r| err(r).abs() <= 0.25).count();
        table += &format!(
            "\n{within} of the {} held-out queries ({}%) are predicted within 25%.\n",
            rows.len(),
            within * 100 / rows.len()
        );
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/src/measured/cost-model.md");
        if std::env::var_os("BVHKIT_BLESS").is_some() {
            std::fs::write(path, &table).unwrap();
        }
        assert_eq!(
            std::fs::read_to_string(path).unwrap(),
            table,
            "the cost-model table differs from its recorded run: BVHKIT_BLESS=1 cargo test -p bvhkit-book --lib"
        );
        // The chapter: most held-out queries within 25%; misses both ways;
        // the worst an over-prediction on a sphere tree.
        assert!(within * 10 >= rows.len() * 8, "{within} of {}", rows.len());
        assert!(rows.iter().any(|r| err(r) > 0.25) && rows.iter().any(|r| err(r) < -0.25));
        let worst = rows
            .iter()
            .max_by(|a, b| err(a).abs().total_cmp(&err(b).abs()))
            .unwrap();
        assert!(err(worst) > 0.0 && worst["volume"] == "sphere", "{worst}");
        let chapter = include_str!("src/characteristics.md");
        assert!(chapter.contains("{{#include measured/cost-model.md}}"));
        // "Cv per traversal": an overlap visit over twice a larger visit for
        // every volume, over five times for spheres and OBBs; Ce several
        // times Cp.
        for m in run["models"].as_array().unwrap() {
            let visit = |t: &str| {
                m["visit_ns"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .find(|p| p[0] == t)
                    .unwrap()[1]
                    .as_f64()
                    .unwrap()
            };
            let ratio = visit("stack overlap") / visit("stack larger");
            let many = m["volume"] == "sphere" || m["volume"] == "obb";
            assert!(
                ratio > 2.0 && (!many || ratio > 5.0),
                "{} {ratio}",
                m["volume"]
            );
            let (ce, cp) = (
                m["exact_ns"].as_f64().unwrap(),
                m["prim_ns"].as_f64().unwrap(),
            );
            assert!(ce > 4.0 * cp, "{} {ce} {cp}", m["volume"]);
        }
    }

    /// The committed figures are what the code draws now (`bvhkit figures`
    /// redraws them), and each is shown by the chapter it names.
    #[test]
    fn figures_match_the_code_and_their_chapters_show_them() {
        let src = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/src"));
        let problems = bvhkit_std::figures::check(src, &src.join("figures")).unwrap();
        assert!(
            problems.is_empty(),
            "run `cargo run --release -p bvhkit-std --bin bvhkit -- figures`:\n{}",
            problems.join("\n")
        );
        // Every chapter has at least one (the explorer page is itself the picture).
        let summary = include_str!("src/SUMMARY.md");
        let figures = bvhkit_std::figures::all(src).unwrap();
        for chapter in summary
            .split("](")
            .skip(1)
            .filter_map(|s| s.split(')').next())
        {
            assert!(
                chapter == "explorer.md" || figures.iter().any(|f| f.chapter == chapter),
                "{chapter} has no generated figure"
            );
        }
        for f in figures {
            let chapter = std::fs::read_to_string(src.join(f.chapter)).unwrap();
            assert!(
                chapter.contains(&format!("](figures/{}.svg)", f.name)),
                "{} does not show figures/{}.svg",
                f.chapter,
                f.name
            );
        }
    }

    /// Every chapter listed in SUMMARY.md is compiled here, and vice versa.
    #[test]
    fn summary_and_doctests_list_the_same_chapters() {
        let summary = include_str!("src/SUMMARY.md");
        for file in super::CHAPTERS {
            assert!(
                summary.contains(&format!("({file})")),
                "{file} missing from SUMMARY.md"
            );
        }
        let linked = summary.matches(".md)").count();
        assert_eq!(
            linked,
            super::CHAPTERS.len(),
            "SUMMARY.md links a chapter the doctest crate does not include"
        );
    }

    /// The recorded peer run the performance chapter includes is there, is
    /// stamped (date, machine, peers) and shows only checked, exact answers.
    #[test]
    fn recorded_peer_run_is_complete_and_exact() {
        let chapter = include_str!("src/performance.md");
        assert!(chapter.contains("{{#include measured/peers.md}}"));
        let run = include_str!("src/measured/peers.md");
        let stamp = run
            .lines()
            .find(|l| l.contains(" UTC · "))
            .expect("stamp line");
        assert!(stamp.contains("cores") && stamp.contains("parry3d") && stamp.contains("obvhs"));
        let rows: Vec<&str> = run
            .lines()
            .skip_while(|l| !l.starts_with("#### Every tree"))
            .filter(|l| l.starts_with("| ") && !l.starts_with("| mesh"))
            .collect();
        for krate in ["bvhkit", "parry3d", "obvhs", "bvh"] {
            assert!(
                rows.iter().any(|r| r.contains(&format!("| {krate} |"))),
                "{krate}"
            );
        }
        for r in &rows {
            assert!(
                r.trim_end().ends_with("| exact |"),
                "not checked exact: {r}"
            );
        }
        assert!(!run.contains("WRONG"));
        // What "Reading it" says, on every mesh of the targets table: SAH
        // below parry3d's; build and pairs below 1x parry3d but above the
        // 0.33x target; the fastest build below obvhs's from 20,000
        // triangles, above it on the elephant; default rays below CWBVH;
        // quantized bytes below CWBVH's.
        let targets: Vec<Vec<f64>> = run
            .lines()
            .skip_while(|l| !l.starts_with("#### Targets"))
            .take_while(|l| !l.starts_with("#### Best"))
            .filter(|l| l.starts_with("| ") && !l.starts_with("| mesh"))
            .map(|l| {
                let cells: Vec<&str> = l.split('|').map(str::trim).collect();
                // The triangle count, then the ratios.
                let tris: f64 = cells[2].parse().unwrap();
                core::iter::once(tris)
                    .chain(
                        cells[3..]
                            .iter()
                            .filter_map(|c| c.strip_suffix('x')?.parse().ok()),
                    )
                    .collect()
            })
            .collect();
        assert!(targets.len() >= 5);
        for r in &targets {
            let [
                tris,
                build,
                sah,
                fastest,
                _,
                pairs,
                rays,
                best_rays,
                bytes,
                quality,
                _,
            ] = r[..]
            else {
                panic!("targets row {r:?}")
            };
            // "faster than parry3d's binned builder on the meshes of 20,000
            // triangles and more" (below that, within the noise).
            // "beats obvhs's `fastest_build` on the meshes of 20,000
            // triangles and more, and not on the elephant" ("1.2x to 2x").
            let (build_ok, fastest_ok) = if tris >= 19_000.0 {
                (build < 1.0, fastest < 1.0)
            } else {
                (build < 1.25, (1.0..2.5).contains(&fastest))
            };
            assert!(sah < 1.0 && build_ok && build > 0.33 && fastest_ok, "{r:?}");
            // "12 to 13% below that of obvhs's `medium_build`" (the target:
            // at least 5% below).
            assert!((0.865..0.885).contains(&quality), "{r:?}");
            // "the best bvhkit layout (4-wide) ... at 0.87x to 1.08x of its
            // rays per second".
            assert!((0.865..1.085).contains(&best_rays), "{r:?}");
            // "faster than parry3d's `leaf_pairs` on every mesh but the
            // dragon" (19,994 triangles).
            let dragon = (19_000.0..20_000.0).contains(&tris);
            assert!(!dragon || (pairs - 1.40).abs() < 0.005, "{r:?}");
            assert!(
                (pairs < 1.0 || dragon) && pairs > 0.33 && rays < 1.0 && bytes < 1.0,
                "{r:?}"
            );
        }
        let chapter = include_str!("src/performance.md");
        assert!(chapter.contains("not yet three\n  times faster"));
        assert!(chapter.contains("1.40x in the latest run"));
        assert!(chapter.contains("at 0.87x to 1.08x of its\n  rays per second"));
        assert!(chapter.contains("on the meshes of about 20,000 triangles and more"));
        assert!(chapter.contains("The fastest builder beats obvhs's `fastest_build` on the meshes of\n  about 20,000 triangles and more, and not on the elephant."));
        assert!(chapter.contains(
            "The default tree's SAH cost is 12 to 13% below that of obvhs's\n  `medium_build`"
        ));
    }

    /// The top-down chapter's scaling table is a recorded run of the
    /// `parallel_build` example (which asserts every parallel tree equal to
    /// the sequential one before printing its row): stamped, over 1M
    /// triangles, with the sequential build and pools of 1 and 2 threads.
    #[test]
    fn recorded_parallel_build_is_complete() {
        let chapter = include_str!("src/top-down.md");
        assert!(chapter.contains("{{#include measured/parallel-build.md}}"));
        let run = include_str!("src/measured/parallel-build.md");
        assert!(run.starts_with("Recorded ") && run.contains(" UTC · ") && run.contains("cores"));
        let words: Vec<&str> = run.split_whitespace().collect();
        let triangles: usize = words
            .windows(2)
            .find(|w| w[1] == "triangles,")
            .and_then(|w| w[0].parse().ok())
            .expect("the triangle count");
        assert!(triangles >= 1_000_000, "{triangles}");
        let rows: Vec<Vec<&str>> = run
            .lines()
            .filter(|l| l.starts_with("| `"))
            .map(|l| l.split('|').map(str::trim).collect())
            .collect();
        let threads: Vec<(&str, &str)> = rows.iter().map(|r| (r[1], r[2])).collect();
        assert_eq!(
            threads,
            [
                ("`OwnedBvh::build`", "1"),
                ("`OwnedBvh::build_parallel`", "1"),
                ("`OwnedBvh::build_parallel`", "2"),
            ]
        );
        for r in &rows {
            let ms: f64 = r[3].parse().expect("median ms");
            assert!(ms > 0.0 && r[5].ends_with('x'), "{r:?}");
        }
    }

    /// The bottom-up chapter's leaf-collapse table is a recorded run of the
    /// `collapse_sweep` example (which checks every tree's pairs and rays
    /// against the top-down tree's before printing its row): stamped, three
    /// meshes with every row, and the chapter's readings computed from it.
    #[test]
    fn recorded_collapse_sweep_and_its_readings() {
        let chapter = include_str!("src/bottom-up.md");
        assert!(chapter.contains("{{#include measured/collapse.md}}"));
        let run = include_str!("src/measured/collapse.md");
        assert!(
            run.starts_with("Recorded ") && run.contains(" UTC · "),
            "{run}"
        );
        let rows: Vec<Vec<&str>> = run
            .lines()
            .filter(|l| l.starts_with("| ") && !l.starts_with("| mesh"))
            .map(|l| {
                l.split('|')
                    .map(str::trim)
                    .filter(|c| !c.is_empty())
                    .collect()
            })
            .collect();
        let meshes = ["armadillo", "ChineseDragon-10kv", "bunny00"];
        assert_eq!(rows.len(), 13 * meshes.len());
        let get = |mesh: &str, tree: &str, collapse: &str, col: usize| -> f64 {
            rows.iter()
                .find(|r| r[0] == mesh && r[1] == tree && r[2] == collapse)
                .unwrap_or_else(|| panic!("no row {mesh} {tree} {collapse}"))[col]
                .parse()
                .unwrap()
        };
        let (nodes, sah, pairs, rays) = (4, 5, 6, 7);
        let default = "4, ct 3 (default)";
        let range = |v: Vec<f64>| {
            let lo = v.iter().cloned().fold(f64::INFINITY, f64::min);
            let hi = v.iter().cloned().fold(0.0, f64::max);
            format!("{lo:.2} to {hi:.2}")
        };
        let (mut pair_ratio, mut node_ratio, mut ray_ratio, mut off_best) =
            (Vec::new(), Vec::new(), Vec::new(), 0.0f64);
        let (mut against_top_down, mut r1_build) = (Vec::new(), Vec::new());
        for mesh in meshes {
            for tree in ["PLOC r1", "PLOC r16", "insertion"] {
                let ratio = |col| get(mesh, tree, default, col) / get(mesh, tree, "none", col);
                pair_ratio.push(ratio(pairs));
                node_ratio.push(ratio(nodes));
                ray_ratio.push(ratio(rays));
            }
            for tree in ["PLOC r1", "PLOC r16"] {
                // Node price 1 minimises the SAH cost: below one per leaf's.
                assert!(get(mesh, tree, "4, ct 1", sah) < get(mesh, tree, "none", sah));
                let best = ["4, ct 1", "4, ct 2", default]
                    .iter()
                    .map(|c| get(mesh, tree, c, pairs))
                    .fold(f64::INFINITY, f64::min);
                off_best = off_best.max(get(mesh, tree, default, pairs) / best - 1.0);
            }
            // Against the top-down tree: PLOC r16's pairs, its build (not
            // faster), PLOC r1's build.
            let (build, td) = (3, "top-down default");
            let top_down = |col| get(mesh, td, "(4 per leaf)", col);
            against_top_down.push(get(mesh, "PLOC r16", default, pairs) / top_down(pairs));
            assert!(
                get(mesh, "PLOC r16", default, build) > top_down(build),
                "{mesh}"
            );
            r1_build.push(get(mesh, "PLOC r1", default, build) / top_down(build));
        }
        for claim in [
            format!("pair query in {} of the time", range(pair_ratio)),
            format!("with {} of the nodes", range(node_ratio)),
            format!("rays in {} of the time", range(ray_ratio)),
            format!("within {:.0}% of the fastest", (off_best * 100.0).ceil()),
            format!(
                "pairs in {} of the top-down tree's time",
                range(against_top_down)
            ),
            format!("builds in {} of its time", {
                let lo = r1_build.iter().cloned().fold(f64::INFINITY, f64::min);
                let hi = r1_build.iter().cloned().fold(0.0, f64::max);
                format!("{lo:.1} to {hi:.1}")
            }),
        ] {
            assert!(chapter.contains(&claim), "bottom-up.md should say: {claim}");
        }
    }
}
