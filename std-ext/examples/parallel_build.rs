//! The parallel build's scaling: the default top-down build on one thread
//! (`OwnedBvh::build`) against `OwnedBvh::build_parallel` in pools of 1, 2,
//! ... threads, on the built-in rock (`--subdivisions S`, default 8: 1.31M
//! triangles). Every parallel tree is checked equal to the sequential one.
//!
//! `cargo run --release -p bvhkit-std --example parallel_build -- [--subdivisions S] [--runs R] [--threads 1,2,4]`
use bvhkit::{Aabb, TopDown};
use bvhkit_std::{OwnedBvh, ParallelBuild};
use std::time::Instant;

fn arg<T: std::str::FromStr>(name: &str, default: T) -> T {
    let args: Vec<String> = std::env::args().collect();
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Median and minimum of `runs` timings of `f`, in milliseconds.
fn time<T>(runs: usize, mut f: impl FnMut() -> T) -> (f64, f64, T) {
    let mut ms = Vec::new();
    let mut last = None;
    for _ in 0..runs {
        let t = Instant::now();
        last = Some(f());
        ms.push(t.elapsed().as_secs_f64() * 1e3);
    }
    ms.sort_by(f64::total_cmp);
    (ms[ms.len() / 2], ms[0], last.expect("at least one run"))
}

fn main() {
    let s: u32 = arg("--subdivisions", 8);
    let runs: usize = arg("--runs", 5).max(1);
    let threads: String = arg("--threads", "1,2".to_string());
    let tris = bvhkit_std::scene::rock(s, 1);
    let builder = TopDown::default();
    let (seq_med, seq_min, seq) = time(runs, || {
        OwnedBvh::<Aabb>::build(&builder, &tris).expect("builds")
    });
    println!(
        "{} triangles, {} cores available, median of {runs} builds",
        tris.len(),
        std::thread::available_parallelism().map_or(1, |n| n.get())
    );
    println!();
    println!("| build | threads | median ms | min ms | speed-up (medians) |");
    println!("|---|---:|---:|---:|---:|");
    println!("| `OwnedBvh::build` | 1 | {seq_med:.1} | {seq_min:.1} | 1.00x |");
    for k in threads
        .split(',')
        .filter_map(|t| t.trim().parse::<usize>().ok())
    {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(k)
            .build()
            .expect("thread pool");
        let (med, min, tree) = pool.install(|| {
            time(runs, || {
                OwnedBvh::<Aabb>::build_parallel(&builder, &tris).expect("builds")
            })
        });
        assert_eq!(tree.view().nodes(), seq.view().nodes(), "same nodes");
        assert_eq!(tree.view().indices(), seq.view().indices(), "same indices");
        println!(
            "| `OwnedBvh::build_parallel` | {k} | {med:.1} | {min:.1} | {:.2}x |",
            seq_med / med
        );
    }
}
