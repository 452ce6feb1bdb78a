//! The `baked` feature set: trees built on the host and queried in place.
//! `build.rs` builds both objects' trees with bvhkit on the host and bakes
//! them (`Bvh::bake`); the firmware holds the bytes in flash
//! (`include_bytes!`), opens each with `Bvh::from_baked` (one validation
//! pass, no copy: the nodes are read from flash), checks it against the
//! triangles it was built over, and runs the minimal set's pair query and
//! rays. No builder is linked.

use core::ptr::addr_of_mut;

use bvhkit::baked::Aligned;
use bvhkit::{Aabb, Bvh, Descent, Node, RayOrder, Triangle};
use cortex_m_semihosting::hprintln;

use crate::scene::{self, N};
use crate::Clock;

/// The trees, as `build.rs` baked them: in flash, aligned for reading in place.
static TREE_A: &Aligned<[u8]> = &Aligned(*include_bytes!(concat!(env!("OUT_DIR"), "/a.bvhk")));
static TREE_B: &Aligned<[u8]> = &Aligned(*include_bytes!(concat!(env!("OUT_DIR"), "/b.bvhk")));

const NO_TRIANGLE: Triangle = Triangle::new(
    bvhkit::glam::Vec3::ZERO,
    bvhkit::glam::Vec3::ZERO,
    bvhkit::glam::Vec3::ZERO,
);
static mut TRIS_A: [Triangle; N] = [NO_TRIANGLE; N];
static mut TRIS_B: [Triangle; N] = [NO_TRIANGLE; N];
/// Validation scratch: one bit per node or primitive of the larger tree.
static mut SEEN: [u32; Bvh::<Aabb>::seen_words(bvhkit::max_nodes(N), N)] =
    [0; Bvh::<Aabb>::seen_words(bvhkit::max_nodes(N), N)];

/// Opens both trees, prints `baked <a bytes> <b bytes>`, then the pair and
/// ray lines the host checks (`pairs baked-sah-dfs ...`, `ray baked-dfs ...`).
#[inline(never)]
pub fn run(clock: &Clock) -> Result<(), bvhkit::Error> {
    // SAFETY: called once; the only references to these buffers.
    let (tris_a, tris_b, seen) = unsafe {
        (
            &mut *addr_of_mut!(TRIS_A),
            &mut *addr_of_mut!(TRIS_B),
            &mut *addr_of_mut!(SEEN),
        )
    };
    scene::object(0, tris_a);
    scene::object(1, tris_b);
    hprintln!("scene {} {}", N, N);
    let (tris_a, tris_b): (&[Triangle], &[Triangle]) = (tris_a, tris_b);
    hprintln!("baked {} {}", TREE_A.0.len(), TREE_B.0.len());
    let a = clock.time("baked-open-a", || Bvh::from_baked(&TREE_A.0, seen))?;
    // The bytes say nothing of which triangles they were built over: check.
    clock.time("baked-validate-a", || a.validate(tris_a, seen))?;
    let b = Bvh::from_baked(&TREE_B.0, seen)?;
    b.validate(tris_b, seen)?;
    let _: &[Node<Aabb>] = a.nodes(); // read from flash, never copied
    hprintln!("tree a nodes {} depth {}", a.node_count(), a.depth());
    crate::pairs(clock, "pairs", "baked-sah-dfs", |f| {
        bvhkit::overlapping_pairs(&a, tris_a, &b, tris_b, Descent::Larger, f)
    })?;
    crate::rays(clock, "baked-dfs", &a, tris_a, RayOrder::DepthFirst)
}
