//! The "everything" feature set: every pair traversal with every descent
//! rule, OBB and 14-DOP trees, the bottom-up (PLOC) and insertion builders,
//! best-first rays and the quantized 4-wide layout.

use core::ptr::addr_of_mut;

use bvhkit::build::{BottomUp, BottomUpScratch, Cluster, DynNode, Insertion};
use bvhkit::layout::{QuantNode, QuantizedWide};
use bvhkit::{
    max_nodes, Aabb, Bvh, Descent, Dop14, Node, Obb, PairTraversal, Pairs, Query, Ray, RayOrder,
    TopDown, Triangle,
};

use crate::scene::{self, N};
use crate::{print_pairs, print_ray, Clock};

const CLUSTERS: usize = BottomUp::scratch_len(N).0;
const WORK: usize = BottomUp::scratch_len(N).1;
const KEYS: usize = BottomUp::scratch_len(N).2;
const STORAGE: usize = Insertion::scratch_len(N).0;

static mut OBBS: [Node<Obb>; max_nodes(N)] = [Node::ZERO; max_nodes(N)];
static mut DOPS: [Node<Dop14>; max_nodes(N)] = [Node::ZERO; max_nodes(N)];
static mut PLOC: [Node<Aabb>; max_nodes(N)] = [Node::ZERO; max_nodes(N)];
static mut INSERTED: [Node<Aabb>; max_nodes(N)] = [Node::ZERO; max_nodes(N)];
static mut INDEX: [[u32; N]; 4] = [[0; N]; 4];
static mut CLUSTER: [Cluster<Aabb>; CLUSTERS] = [Cluster::EMPTY; CLUSTERS];
static mut WORK_BUF: [u32; WORK] = [0; WORK];
static mut KEY_BUF: [u64; KEYS] = [0; KEYS];
static mut DYN: [DynNode<Aabb>; STORAGE] = [DynNode::EMPTY; STORAGE];
static mut ORDER: [u32; Insertion::scratch_len(N).1] = [0; Insertion::scratch_len(N).1];
static mut QUANT: [QuantNode; QuantizedWide::max_records(N)] =
    [QuantNode::ZERO; QuantizedWide::max_records(N)];

/// Counts and digests the pairs of one configuration and prints them.
fn report<A, H>(
    clock: &Clock,
    label: &str,
    q: Pairs<'_, A, H, Triangle, Triangle, Descent>,
    t: PairTraversal,
) -> Result<(), bvhkit::Error>
where
    A: bvhkit::Hierarchy,
    H: bvhkit::Hierarchy<Bv = A::Bv>,
{
    let mut digest = 0u32;
    let count = clock.time(label, || {
        q.traversal(t)
            .for_each(|i, j| digest = digest.wrapping_add(scene::mix(i, j)))
    })?;
    print_pairs("pairs", label, count, digest);
    Ok(())
}

#[inline(never)]
pub fn run(
    clock: &Clock,
    tris_a: &[Triangle],
    tris_b: &[Triangle],
    a: &Bvh<'static, Aabb>,
    b: &Bvh<'static, Aabb>,
) -> Result<(), bvhkit::Error> {
    // SAFETY: called once; the only references to these buffers.
    let (obbs, dops, ploc, inserted, index, cluster, work, keys, dyn_nodes, order, quant) = unsafe {
        (
            &mut *addr_of_mut!(OBBS),
            &mut *addr_of_mut!(DOPS),
            &mut *addr_of_mut!(PLOC),
            &mut *addr_of_mut!(INSERTED),
            &mut *addr_of_mut!(INDEX),
            &mut *addr_of_mut!(CLUSTER),
            &mut *addr_of_mut!(WORK_BUF),
            &mut *addr_of_mut!(KEY_BUF),
            &mut *addr_of_mut!(DYN),
            &mut *addr_of_mut!(ORDER),
            &mut *addr_of_mut!(QUANT),
        )
    };
    let [i0, i1, i2, i3] = index;

    // Every traversal with every descent rule, on the AABB trees.
    let mut label = [0u8; 40];
    for rule in Descent::ALL {
        for t in PairTraversal::all(rule) {
            let name = join(&mut label, t.name(), rule.name());
            report(clock, name, Pairs::new(a, tris_a, b, tris_b), t)?;
        }
    }

    // Other volumes: B's OBB and 14-DOP trees against each other.
    let o = clock.time("build-sah-obb", || TopDown::sah().build(tris_b, obbs, i0))?;
    let mut digest = 0u32;
    let count = clock.time("pairs-obb", || {
        bvhkit::overlapping_pairs(&o, tris_b, &o, tris_b, Descent::Larger, |i, j| {
            digest = digest.wrapping_add(scene::mix(i, j))
        })
    })?;
    print_pairs("selfb", "obb-sah-dfs", count, digest);
    let d = clock.time("build-sah-dop14", || TopDown::sah().build(tris_b, dops, i1))?;
    let mut digest = 0u32;
    let count = clock.time("pairs-dop14", || {
        bvhkit::overlapping_pairs(&d, tris_b, &d, tris_b, Descent::Simultaneous, |i, j| {
            digest = digest.wrapping_add(scene::mix(i, j))
        })
    })?;
    print_pairs("selfb", "dop14-sah-simultaneous", count, digest);

    // Other builders for A, queried against B's SAH tree.
    let mut scratch = BottomUpScratch {
        clusters: cluster,
        work,
        keys,
    };
    let p = clock.time("build-ploc", || {
        BottomUp::default().build(tris_a, ploc, i2, &mut scratch)
    })?;
    report(
        clock,
        "ploc-larger",
        Pairs::new(&p, tris_a, b, tris_b),
        PairTraversal::default(),
    )?;
    let ins = clock.time("build-insertion", || {
        Insertion::default().build(tris_a, dyn_nodes, order, inserted, i3)
    })?;
    report(
        clock,
        "insertion-larger",
        Pairs::new(&ins, tris_a, b, tris_b),
        PairTraversal::default(),
    )?;

    // Best-first rays, and rays on the quantized 4-wide layout.
    let q = clock.time("convert-quantized", || QuantizedWide::from_bvh(a, quant))?;
    for (label, order, quantized) in [
        ("aabb-best-first", RayOrder::BestFirst, false),
        ("quantized-dfs", RayOrder::DepthFirst, true),
    ] {
        for r in 0..scene::RAYS {
            let (o, dir) = scene::ray(r);
            let ray = Ray::new(o, dir, f32::INFINITY)?;
            let hit = if quantized {
                q.cast_ray(tris_a, &ray, order, ())?
            } else {
                a.cast_ray(tris_a, &ray, order, ())?
            };
            print_ray(label, r, hit);
        }
    }
    Ok(())
}

/// `first-second` in `buf`, as a `&str` (no allocation).
fn join<'b>(buf: &'b mut [u8; 40], first: &str, second: &str) -> &'b str {
    let mut n = 0;
    for &c in first.as_bytes().iter().chain(b"-").chain(second.as_bytes()) {
        buf[n] = c;
        n += 1;
    }
    core::str::from_utf8(&buf[..n]).unwrap_or("?")
}
