//! The placement flags of `bvhkit collide` act on the built-in scene as they
//! do on mesh files: moving B far away leaves no pair, turning it changes the
//! answer, and a scale (which a moved tree cannot follow) is refused with a
//! message instead of being ignored.

use std::process::{Command, Output};

fn collide(extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bvhkit"))
        .args([
            "collide",
            "--subdivisions",
            "3",
            "--runs",
            "1",
            "--verify",
            "--json",
        ])
        .args(extra)
        .output()
        .unwrap()
}

fn pairs(extra: &[&str]) -> (u64, u64) {
    let out = collide(extra);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{extra:?}: {text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let field = |name: &str| -> u64 {
        let at = text
            .find(&format!("\"{name}\":"))
            .unwrap_or_else(|| panic!("{name} in {text}"));
        text[at + name.len() + 3..]
            .trim_start()
            .split(|c: char| !c.is_ascii_digit())
            .next()
            .unwrap()
            .parse()
            .unwrap()
    };
    assert!(
        text.contains("\"verified\": true") || text.contains("\"verified\":true"),
        "{text}"
    );
    (field("candidate_pairs"), field("intersecting_pairs"))
}

#[test]
fn placement_flags_move_b_in_the_built_in_scene() {
    let (default_candidates, default_hits) = pairs(&[]);
    assert!(default_candidates > 0 && default_hits > 0);
    assert_eq!(pairs(&["--translate-b", "1000,0,0"]), (0, 0));
    let turned = pairs(&["--rotate-b", "0,40,0"]);
    assert_ne!(
        turned,
        (default_candidates, default_hits),
        "rotation ignored"
    );
    let nudged = pairs(&["--translate-b", "0.2,0,0"]);
    assert_ne!(
        nudged,
        (default_candidates, default_hits),
        "translation ignored"
    );
}

#[test]
fn a_scale_on_the_built_in_scene_is_refused_with_a_reason() {
    let out = collide(&["--scale-b", "2"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("scale") && err.contains("mesh files"), "{err}");
    // Scale 1 is no scale.
    assert!(collide(&["--scale-b", "1"]).status.success());
}
