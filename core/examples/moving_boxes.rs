//! A broad phase for moving objects: each frame the objects that moved say
//! so, and the tracker reports the pairs that began and ended.
//! `cargo run -p bvhkit --example moving_boxes`
use bvhkit::builders::{DynNode, DynamicConfig};
use bvhkit::collision::{PairEvent, PairTracker, Slot, TrackerStorage};
use bvhkit::glam::Vec3;
use bvhkit::{brute_force, Aabb};

const N: usize = 500;

/// Object `i`'s box at `frame`: boxes circling at their own speeds.
fn at(i: usize, frame: usize) -> Aabb {
    let a = i as f32 * 0.9 + frame as f32 * 0.01 * (1 + i % 3) as f32;
    let c = Vec3::new(a.cos(), a.sin(), (i % 10) as f32 * 0.1) * (10.0 + (i % 7) as f32);
    Aabb::new(c - 0.5, c + 0.5)
}

fn main() -> Result<(), bvhkit::Error> {
    let (mut nodes, mut slots, mut boxes) = (
        vec![DynNode::EMPTY; 2 * N - 1],
        vec![Slot::EMPTY; N],
        vec![Aabb::EMPTY; N],
    );
    let (mut moved, mut pairs, mut next) = (vec![0; N], vec![(0, 0); 8 * N], vec![(0, 0); 8 * N]);
    let storage = TrackerStorage {
        nodes: &mut nodes,
        slots: &mut slots,
        boxes: &mut boxes,
        moved: &mut moved,
        pairs: &mut pairs,
        next: &mut next,
    };
    let mut world = PairTracker::new(
        storage,
        DynamicConfig {
            margin: 0.2,
            ..Default::default()
        },
    )?;
    for i in 0..N {
        world.insert(i as u32, &at(i, 0))?;
    }
    let (mut began, mut ended) = (0, 0);
    for frame in 1..=100 {
        for i in 0..N {
            world.set_bounds(i as u32, &at(i, frame))?;
        }
        world.step(|e| match e {
            PairEvent::Begin(..) => began += 1,
            PairEvent::End(..) => ended += 1,
        })?;
        let now: Vec<Aabb> = (0..N).map(|i| at(i, frame)).collect();
        assert_eq!(
            world.pairs().len(),
            brute_force::self_pairs(&now, |_, _| {})
        );
    }
    println!(
        "{N} boxes, 100 frames: {} pairs now, {began} began, {ended} ended",
        world.pairs().len()
    );
    Ok(())
}
