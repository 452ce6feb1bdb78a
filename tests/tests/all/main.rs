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
