//! `bvhkit advise` end to end: the advice is printed and, measured, every
//! combination's answers equal brute force.

#[test]
fn the_cli_advises_and_measures() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_bvhkit"))
        .args([
            "advise",
            "--subdivisions",
            "1",
            "--query",
            "rays",
            "--measure",
            "--runs",
            "1",
            "--rays",
            "20",
        ])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}");
    assert!(
        text.contains("advice: sah / aabb / wide-4 / depth-first"),
        "{text}"
    );
    assert!(text.contains("answers all equal brute force"), "{text}");
}
