//! `bvhkit collide --distance`: the distance between two meshes, checked
//! against values worked out by hand on flat sheets (apart, parallel above
//! each other, crossing), on the built-in scene moved apart, against brute
//! force (`--verify`) throughout, and with an empty mesh.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bvhkit(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bvhkit"))
        .args(args)
        .output()
        .unwrap()
}

/// `collide --distance --verify --json --runs 1` with `args`: the report,
/// after checking the run succeeded and both answers equal brute force.
fn distance_json(args: &[&str]) -> Value {
    let mut all = vec!["collide", "--distance", "--verify", "--json", "--runs", "1"];
    all.extend_from_slice(args);
    let out = bvhkit(&all);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{args:?}: {text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_str(&text).unwrap_or_else(|e| panic!("{e}: {text}"));
    assert_eq!(v["verified"], Value::Bool(true), "{v}");
    assert_eq!(v["distance_verified"], Value::Bool(true), "{v}");
    assert_eq!(v["reference_distance"], v["distance"], "{v}");
    assert!(v["distance_time_ms"].as_f64().unwrap() >= 0.0, "{v}");
    v
}

fn point(v: &Value, key: &str) -> [f64; 3] {
    let p = v[key].as_array().unwrap_or_else(|| panic!("{key} in {v}"));
    [0, 1, 2].map(|k| p[k].as_f64().unwrap())
}

/// A temporary folder for this test binary.
fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bvhkit-cli-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The square [0, 2] x [0, 2] in the plane z = 0 as an OBJ file: `n` x `n`
/// cells of two triangles each.
fn write_sheet(path: &Path, n: usize) {
    let mut obj = String::new();
    for j in 0..=n {
        for i in 0..=n {
            let s = 2.0 / n as f64;
            obj += &format!("v {} {} 0\n", i as f64 * s, j as f64 * s);
        }
    }
    let at = |i: usize, j: usize| j * (n + 1) + i + 1;
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            obj += &format!("f {a} {b} {c}\nf {a} {c} {d}\n");
        }
    }
    std::fs::write(path, obj).unwrap();
}

#[test]
fn distance_between_sheets_matches_the_geometry() {
    let dir = temp_dir("distance");
    let sheet = dir.join("sheet.obj");
    write_sheet(&sheet, 6);
    let sheet = sheet.to_str().unwrap();

    // B beside A and above it: A's edge x = 2 and B's edge x = 2.3 are 0.3
    // apart in x and 0.4 in z, so sqrt(0.3^2 + 0.4^2) = 0.5 apart.
    let v = distance_json(&[sheet, sheet, "--translate-b", "2.3,0,0.4"]);
    let d = v["distance"].as_f64().unwrap();
    let expected = (0.3f64 * 0.3 + 0.4 * 0.4).sqrt();
    assert!((d - expected).abs() < 1e-6, "{d} against {expected}");
    let (a, b) = (point(&v, "closest_a"), point(&v, "closest_b"));
    assert!((a[0] - 2.0).abs() < 1e-6 && a[2] == 0.0, "{a:?}");
    assert!(
        (b[0] - 2.3).abs() < 1e-6 && (b[2] - 0.4).abs() < 1e-6,
        "{b:?}"
    );
    assert_eq!(a[1], b[1], "the edges are parallel to y: {a:?} {b:?}");
    assert_eq!(v["intersecting_pairs"], 0);
    let pair = v["closest_pair"].as_array().unwrap();
    assert_eq!(pair.len(), 2);
    assert!(pair.iter().all(|i| i.as_u64().unwrap() < 72), "{v}");

    // Parallel, B a quarter above A and overlapping it in x and y.
    let v = distance_json(&[sheet, sheet, "--translate-b", "0.5,0.5,0.25"]);
    assert_eq!(v["distance"].as_f64(), Some(0.25), "{v}");
    assert_eq!(point(&v, "closest_a")[2], 0.0);
    assert_eq!(point(&v, "closest_b")[2], 0.25);

    // B turned upright (y becomes z) and pushed through A along y = 0.9: the
    // sheets cross, so the distance is 0 and the contacts are not empty.
    let v = distance_json(&[
        sheet,
        sheet,
        "--rotate-b",
        "90,0,0",
        "--translate-b",
        "0.5,0.9,-1",
    ]);
    assert_eq!(v["distance"].as_f64(), Some(0.0), "{v}");
    assert!(v["intersecting_pairs"].as_u64().unwrap() > 0, "{v}");
    // One common point, up to the rounding of where an edge crosses a face.
    let (a, b) = (point(&v, "closest_a"), point(&v, "closest_b"));
    assert!((0..3).all(|k| (a[k] - b[k]).abs() < 1e-9), "{a:?} {b:?}");
    assert!(
        a[2].abs() < 1e-9 && (a[1] - 0.9).abs() < 1e-6,
        "on y = 0.9 in A: {a:?}"
    );

    // The same sheet in text: the distance line and the brute-force line.
    let out = bvhkit(&[
        "collide",
        sheet,
        sheet,
        "--translate-b",
        "2.3,0,0.4",
        "--distance",
        "--verify",
        "--runs",
        "1",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    let line = |label: &str| {
        text.lines()
            .find(|l| l.starts_with(label))
            .unwrap_or_else(|| panic!("no '{label}' in:\n{text}"))
            .to_string()
    };
    assert!(line("distance  ").contains("0.500000"), "{text}");
    assert!(line("distance time").contains("ms"), "{text}");
    assert!(text.contains("distance: match"), "{text}");
}

#[test]
fn distance_on_the_built_in_scene_touching_and_moved_apart() {
    let base = ["--subdivisions", "2"];
    let v = distance_json(&base);
    assert_eq!(v["distance"].as_f64(), Some(0.0), "the rocks overlap: {v}");
    assert!(v["intersecting_pairs"].as_u64().unwrap() > 0);
    assert!(v["distance_bv_tests"].as_u64().unwrap() > 0, "{v}");

    let mut apart = base.to_vec();
    apart.extend(["--translate-b", "4,0,0"]);
    let v = distance_json(&apart);
    let d = v["distance"].as_f64().unwrap();
    // Rocks of radius about 1 whose centres are more than 5 apart.
    assert!(d > 2.0 && d < 5.0, "{v}");
    let (a, b) = (point(&v, "closest_a"), point(&v, "closest_b"));
    let between = ((0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>()).sqrt();
    assert!((between - d).abs() < 1e-9, "{between} {d}");
}

#[test]
fn distance_with_an_empty_mesh_is_null_and_says_so() {
    let dir = temp_dir("distance-empty");
    let (empty, sheet) = (dir.join("empty.obj"), dir.join("sheet.obj"));
    std::fs::write(&empty, "# no faces\nv 0 0 0\n").unwrap();
    write_sheet(&sheet, 2);
    let (empty, sheet) = (empty.to_str().unwrap(), sheet.to_str().unwrap());
    for (a, b) in [(empty, sheet), (sheet, empty), (empty, empty)] {
        let v = distance_json(&[a, b]);
        assert!(
            v["distance"].is_null() && v["closest_pair"].is_null(),
            "{v}"
        );
        assert!(v["closest_a"].is_null() && v["closest_b"].is_null(), "{v}");
        let out = bvhkit(&["collide", a, b, "--distance", "--runs", "1"]);
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(out.status.success(), "{text}");
        assert!(text.contains("none (an object has no triangles)"), "{text}");
    }
}

#[test]
fn distance_is_refused_with_self_and_on_large_verified_scenes() {
    let out = bvhkit(&["collide", "--self", "--distance", "--subdivisions", "1"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--distance") && err.contains("--self"),
        "{err}"
    );

    // Brute force over 81 920^2 pairs would run for many minutes.
    let out = bvhkit(&["collide", "--distance", "--verify", "--runs", "1"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("limit") && err.contains("--verify"), "{err}");
}
