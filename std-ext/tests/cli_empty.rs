//! A valid mesh file with no faces is an empty scene, not an error: `stats`,
//! `collide` and `advise` report zeros and exit 0.

use std::process::Command;

fn run(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_bvhkit"))
        .args(args)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {text}{err}");
    assert!(!text.contains("NaN"), "{args:?}: {text}");
    text
}

/// The value printed after `label` on its line.
fn value<'t>(text: &'t str, label: &str) -> &'t str {
    text.lines()
        .find(|l| l.starts_with(label))
        .and_then(|l| l.split_whitespace().last())
        .unwrap_or_else(|| panic!("no '{label}' in:\n{text}"))
}

#[test]
fn empty_meshes_give_zeros_and_exit_zero() {
    let dir = std::env::temp_dir().join(format!("bvhkit-cli-empty-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let empty = dir.join("no-faces.obj");
    std::fs::write(&empty, "# vertices only\nv 0 0 0\nv 1 0 0\n").unwrap();
    let off = dir.join("quad.off");
    std::fs::write(
        &off,
        "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n",
    )
    .unwrap();
    let (empty, off) = (empty.to_str().unwrap(), off.to_str().unwrap());

    let stats = run(&["stats", empty, "--runs", "1"]);
    assert_eq!(value(&stats, "nodes"), "0");
    assert_eq!(value(&stats, "SAH cost"), "0.00");

    for (a, b) in [(empty, empty), (empty, off), (off, empty)] {
        let collide = run(&["collide", a, b, "--runs", "1"]);
        assert_eq!(value(&collide, "intersecting pairs"), "0", "{a} {b}");
        assert_eq!(value(&collide, "bv tests (Nv)"), "0", "{a} {b}");
    }
    // The quad against itself does touch: the empty cases are not zero by accident.
    let both = run(&["collide", off, off, "--runs", "1"]);
    assert_ne!(value(&both, "intersecting pairs"), "0");

    let advice = run(&["advise", empty, "--measure", "--runs", "1"]);
    assert!(advice.contains("answers all equal brute force"), "{advice}");
}
