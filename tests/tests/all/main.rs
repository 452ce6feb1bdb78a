//! The integration, property and stress tests, one module per subject, in one
//! test binary: one link instead of twenty, which keeps `cargo test` and
//! mutation testing (`scripts/mutants`, which rebuilds the tests per mutant)
//! affordable. `alloc_free` stays its own binary: it installs a counting
//! global allocator, which every test in the process would feed.
//!
//! One subject: `cargo test -p bvhkit-tests --test all quality::`.

mod advisor;
mod bad_input;
mod baked;
mod bottom_up;
mod broad_phase;
mod contact;
mod corners;
mod distance;
mod empty;
mod equivalence;
mod fits;
mod frames;
mod insertion;
mod kdop_measures;
mod layouts;
mod measures;
mod mesh;
mod narrow;
mod pitfalls;
mod quality;
mod refit;
mod single_queries;
mod sizing;
mod stress;
mod system;

/// proptest replays the failures it saved from
/// `tests/proptest-regressions/<module>.txt`, one file per module of this
/// binary. Seeds saved anywhere else (as they were next to each test file
/// before the tests became one binary) are silently never replayed.
#[test]
fn saved_failures_sit_where_proptest_replays_them() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests");
    let mut stray = Vec::new();
    let mut dirs = vec![root.clone()];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                dirs.push(path);
            } else if path
                .extension()
                .is_some_and(|e| e == "proptest-regressions")
            {
                stray.push(path);
            }
        }
    }
    assert!(stray.is_empty(), "seeds proptest never reads: {stray:?}");
    let saved = root.join("proptest-regressions");
    let mut files = 0;
    for entry in std::fs::read_dir(&saved).unwrap() {
        let path = entry.unwrap().path();
        let module = path.file_stem().unwrap().to_string_lossy().into_owned();
        assert!(
            root.join("all").join(format!("{module}.rs")).exists(),
            "{} holds seeds of no module of this binary",
            path.display()
        );
        files += 1;
    }
    assert!(files > 0, "no saved failures at {}", saved.display());
}
