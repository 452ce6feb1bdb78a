//! `bvhkit cost-model`: fits the unit costs on training scenes and predicts
//! held-out ones; a held-out mesh file appears in the report with a
//! prediction for every query, and a bad mesh file is an error naming it.

use std::process::Command;

fn bvhkit(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_bvhkit"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn quick_run_fits_four_volumes_and_predicts_every_held_out_query() {
    let dir = std::env::temp_dir().join(format!("bvhkit-cli-cost-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // A small closed mesh: an octahedron, subdivided by nothing.
    let mesh = dir.join("octahedron.off");
    std::fs::write(
        &mesh,
        "OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 1\n0 0 -1\n\
         3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n",
    )
    .unwrap();
    let out = bvhkit(&[
        "cost-model",
        "--quick",
        "--rounds",
        "1",
        "--json",
        mesh.to_str().unwrap(),
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report: serde_json::Value = serde_json::from_str(&text).unwrap();
    let models = report["models"].as_array().unwrap();
    let volumes: Vec<&str> = models
        .iter()
        .map(|m| m["volume"].as_str().unwrap())
        .collect();
    assert_eq!(volumes, ["aabb", "sphere", "obb", "14-dop"]);
    for m in models {
        for key in ["update_ns", "prim_ns", "exact_ns", "fixed_ns"] {
            let c = m[key].as_f64().unwrap();
            assert!(c >= 0.0 && c.is_finite(), "{key} = {c}");
        }
        assert_eq!(
            m["visit_ns"].as_array().unwrap().len(),
            9,
            "one Cv per traversal"
        );
    }
    let rows = report["rows"].as_array().unwrap();
    let held: Vec<&serde_json::Value> = rows
        .iter()
        .filter(|r| r["held_out"].as_bool().unwrap())
        .collect();
    // Two held-out scenes (the quick rock and the octahedron) x two motions
    // x nine traversals x four volumes.
    assert_eq!(held.len(), 2 * 2 * 9 * 4);
    assert!(held.iter().any(|r| r["scene"] == "octahedron"));
    for r in &held {
        let (m, p) = (
            r["measured_ms"].as_f64().unwrap(),
            r["predicted_ms"].as_f64().unwrap(),
        );
        assert!(m > 0.0 && p > 0.0 && p.is_finite(), "{r}");
    }
    // No training row is marked held out, and training rows exist.
    assert!(rows.iter().any(|r| !r["held_out"].as_bool().unwrap()));
}

#[test]
fn a_mesh_without_triangles_is_noted_and_left_out() {
    let dir = std::env::temp_dir().join(format!("bvhkit-cli-cost-empty-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let empty = dir.join("nothing.obj");
    std::fs::write(&empty, "# vertices only\nv 0 0 0\nv 1 0 0\n").unwrap();
    let out = bvhkit(&[
        "cost-model",
        "--quick",
        "--rounds",
        "1",
        "--json",
        empty.to_str().unwrap(),
    ]);
    let (text, err) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(out.status.success(), "{text}{err}");
    assert!(err.contains("nothing.obj has no triangles"), "{err}");
    let report: serde_json::Value = serde_json::from_str(&text).unwrap();
    let rows = report["rows"].as_array().unwrap();
    assert!(rows.iter().all(|r| r["scene"] != "nothing"));
    // Only the quick rock is held out: two motions x nine traversals x four volumes.
    assert_eq!(
        rows.iter()
            .filter(|r| r["held_out"].as_bool().unwrap())
            .count(),
        72
    );
}

#[test]
fn a_bad_mesh_file_is_an_error_naming_it() {
    let out = bvhkit(&["cost-model", "--quick", "--rounds", "1", "no/such/mesh.obj"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("no/such/mesh.obj"), "{err}");
}
