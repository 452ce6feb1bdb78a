//! Checks the output of the embedded demo (`tests/embedded`, run under QEMU
//! by `scripts/embedded-demo`) against brute force on the host: the same
//! scene (this file includes the firmware's `scene.rs`), every answer line
//! recomputed without a tree.
//!
//! ```text
//! cargo run -p bvhkit-std --example embedded_check -- minimal < firmware.log
//! ```
//! Exits 0 when every expected line is present and every answer matches.

use std::collections::BTreeSet;
use std::io::Read;

use bvhkit::{brute_force, Aabb, Exact, Ray, Rigid, Triangle};

#[path = "../../tests/embedded/src/scene.rs"]
#[allow(dead_code)]
mod scene;

/// Labels each feature set must print, by kind.
fn expected(set: &str) -> Vec<(&'static str, String)> {
    if set == "baked" {
        // Trees baked on the host, opened in place on the device.
        return vec![
            ("pairs", "baked-sah-dfs".into()),
            ("ray", "baked-dfs".into()),
        ];
    }
    let mut e = vec![
        ("pairs", "aabb-sah-dfs".to_string()),
        ("ray", "aabb-dfs".to_string()),
    ];
    if set == "typical" || set == "everything" {
        e.push(("exact", "aabb-moved".into()));
        e.push(("self", "sphere-sah-dfs".into()));
        e.push(("ray", "wide-dfs".into()));
    }
    if set == "everything" {
        for rule in bvhkit::Descent::ALL {
            for t in bvhkit::PairTraversal::all(rule) {
                e.push(("pairs", format!("{}-{}", t.name(), rule.name())));
            }
        }
        e.push(("selfb", "obb-sah-dfs".into()));
        e.push(("selfb", "dop14-sah-simultaneous".into()));
        e.push(("pairs", "ploc-larger".into()));
        e.push(("pairs", "insertion-larger".into()));
        e.push(("ray", "aabb-best-first".into()));
        e.push(("ray", "quantized-dfs".into()));
    }
    e
}

fn digest(f: impl FnOnce(&mut dyn FnMut(u32, u32)) -> usize) -> (usize, u32) {
    let mut d = 0u32;
    let n = f(&mut |i, j| d = d.wrapping_add(scene::mix(i, j)));
    (n, d)
}

fn main() {
    let set = std::env::args().nth(1).unwrap_or_else(|| "minimal".into());
    if !["minimal", "typical", "everything", "boxes", "baked"].contains(&set.as_str()) {
        eprintln!("usage: embedded_check minimal|typical|everything|boxes|baked < firmware.log");
        std::process::exit(2);
    }
    let mut log = String::new();
    std::io::stdin()
        .read_to_string(&mut log)
        .expect("read the firmware log");
    if set == "boxes" {
        check_boxes(&log);
        return;
    }

    let mut a =
        [Triangle::new(Default::default(), Default::default(), Default::default()); scene::N];
    let mut b = a;
    scene::object(0, &mut a);
    scene::object(1, &mut b);
    let (rotation, shift) = scene::motion();
    let motion = Rigid::new(rotation, shift).expect("the demo's motion is valid");
    let bounds_ab = digest(|f| brute_force::pairs(&a, &b, f));
    let bounds_aa = digest(|f| brute_force::pairs(&a, &a, f));
    let bounds_bb = digest(|f| brute_force::pairs(&b, &b, f));
    let exact_ab = digest(|f| brute_force::pairs_placed(&a, &b, &motion, Exact, f));
    let rays: Vec<String> = (0..scene::RAYS)
        .map(|r| {
            let (o, d) = scene::ray(r);
            let ray = Ray::new(o, d, f32::INFINITY).unwrap();
            match brute_force::ray_closest(&a, &ray) {
                Some(h) => format!("{} {:08x}", h.prim, h.t.to_bits()),
                None => "none 0".into(),
            }
        })
        .collect();

    let (mut checked, mut failures) = (0, Vec::new());
    let mut seen: BTreeSet<(String, String)> = BTreeSet::new();
    let mut ray_lines: BTreeSet<(String, usize)> = BTreeSet::new();
    for line in log.lines() {
        let f: Vec<&str> = line.split_whitespace().collect();
        let Some(&kind) = f.first() else { continue };
        let want = match kind {
            "error" | "panic" => {
                failures.push(format!("firmware reported: {line}"));
                continue;
            }
            "scene" => {
                if f.get(1..3) != Some(&[&*scene::N.to_string(), &*scene::N.to_string()][..]) {
                    failures.push(format!("scene size differs: {line}"));
                }
                continue;
            }
            "pairs" | "self" | "selfb" | "exact" if f.len() == 4 => {
                let (n, d) = match kind {
                    "pairs" => bounds_ab,
                    "self" => bounds_aa,
                    "selfb" => bounds_bb,
                    _ => exact_ab,
                };
                seen.insert((kind.to_string(), f[1].to_string()));
                format!("{n} {d:08x}")
            }
            "ray" if f.len() == 5 => {
                let r: usize = f[2].parse().unwrap_or(usize::MAX);
                let Some(want) = rays.get(r) else {
                    failures.push(format!("unknown ray: {line}"));
                    continue;
                };
                ray_lines.insert((f[1].to_string(), r));
                seen.insert(("ray".into(), f[1].to_string()));
                want.clone()
            }
            _ => continue,
        };
        let got = f[f.len() - 2..].join(" ");
        checked += 1;
        if got != want {
            failures.push(format!("{line}\n    host (brute force): {want}"));
        }
    }
    for (kind, label) in expected(&set) {
        if !seen.contains(&(kind.to_string(), label.clone())) {
            failures.push(format!("missing line: {kind} {label}"));
        }
        if kind == "ray" {
            let n = ray_lines.iter().filter(|(l, _)| *l == label).count();
            if n != scene::RAYS {
                failures.push(format!("ray {label}: {n} of {} rays printed", scene::RAYS));
            }
        }
    }
    if failures.is_empty() {
        println!(
            "embedded demo ({set}): {checked} answers match the host's brute force \
             ({} bounds pairs, {} exact pairs moved, {} rays)",
            bounds_ab.0,
            exact_ab.0,
            scene::RAYS
        );
    } else {
        for f in &failures {
            eprintln!("MISMATCH {f}");
        }
        eprintln!(
            "embedded demo ({set}): {} problems, {checked} answers checked",
            failures.len()
        );
        std::process::exit(1);
    }
}

/// The `boxes` firmware: each frame's pairs and rays against brute force,
/// every line present.
fn check_boxes(log: &str) {
    let mut want = std::collections::BTreeMap::new();
    for f in 0..scene::FRAMES {
        let boxes: Vec<Aabb> = (0..scene::BOXES).map(|i| scene::moving_box(i, f)).collect();
        let (n, d) = digest(|g| brute_force::self_pairs(&boxes, g));
        want.insert(format!("boxpairs f{f}"), format!("{n} {d:08x}"));
        // The same tree as the firmware's, bit for bit: the host bins the
        // three axes in one pass, the Cortex-M4 one axis at a time.
        let mut nodes = vec![bvhkit::Node::<Aabb>::ZERO; bvhkit::max_nodes(boxes.len())];
        let mut idx = vec![0u32; boxes.len()];
        let tree = bvhkit::TopDown::sah()
            .build(&boxes, &mut nodes, &mut idx)
            .expect("the host builds the boxes");
        let t = scene::tree_digest(tree.nodes(), tree.indices());
        want.insert(
            format!("boxtree f{f}"),
            format!("{} {t:08x}", tree.node_count()),
        );
        for r in 0..scene::BOX_RAYS {
            let (o, dir) = scene::box_ray(r, f);
            let ray = Ray::new(o, dir, f32::INFINITY).unwrap();
            let hit = match brute_force::ray_closest(&boxes, &ray) {
                Some(h) => format!("{} {:08x}", h.prim, h.t.to_bits()),
                None => "none 0".into(),
            };
            want.insert(format!("boxray f{f} {r}"), hit);
        }
    }
    let mut failures = Vec::new();
    let mut checked = 0;
    for line in log.lines() {
        let f: Vec<&str> = line.split_whitespace().collect();
        let key_len = match f.first() {
            Some(&"error") | Some(&"panic") => {
                failures.push(format!("firmware reported: {line}"));
                continue;
            }
            Some(&"boxpairs") | Some(&"boxtree") => 2,
            Some(&"boxray") => 3,
            _ => continue,
        };
        if f.len() != key_len + 2 {
            failures.push(format!("malformed line: {line}"));
            continue;
        }
        let key = f[..key_len].join(" ");
        let Some(expected) = want.remove(&key) else {
            failures.push(format!("unexpected or repeated line: {line}"));
            continue;
        };
        checked += 1;
        let got = f[key_len..].join(" ");
        if got != expected {
            failures.push(format!("{line}\n    host (brute force): {expected}"));
        }
    }
    failures.extend(want.keys().map(|k| format!("missing line: {k}")));
    if failures.is_empty() {
        println!(
            "embedded demo (boxes): {checked} answers match the host's brute force \
             and its trees ({} frames of {} boxes, {} rays each)",
            scene::FRAMES,
            scene::BOXES,
            scene::BOX_RAYS
        );
    } else {
        for f in &failures {
            eprintln!("MISMATCH {f}");
        }
        eprintln!(
            "embedded demo (boxes): {} problems, {checked} answers checked",
            failures.len()
        );
        std::process::exit(1);
    }
}
