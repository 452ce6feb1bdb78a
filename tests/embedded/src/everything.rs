//! The "everything" feature set: every pair traversal with every descent
//! rule, OBB and 14-DOP trees, the bottom-up (PLOC) and insertion builders,
//! best-first rays and the quantized 4-wide layout.

use core::ptr::addr_of_mut;

use bvhkit::builders::{BottomUp, BottomUpScratch, Cluster, DynNode, Insertion};
use bvhkit::layout::{QuantNode, QuantizedWide};
use bvhkit::{
    max_nodes, Aabb, Bvh, Descent, Dop14, Node, Obb, PairTraversal, Pairs, RayOrder, TopDown,
    Triangle,
};

use crate::scene::N;
use crate::{pairs, rays, Clock};

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
            pairs(clock, "pairs", name, |f| {
                Pairs::new(a, tris_a, b, tris_b).traversal(t).for_each(f)
            })?;
        }
    }

    // Other volumes: B's OBB and 14-DOP trees against each other.
    let o = clock.time("build-sah-obb", || TopDown::sah().build(tris_b, obbs, i0))?;
    pairs(clock, "selfb", "obb-sah-dfs", |f| {
        bvhkit::overlapping_pairs(&o, tris_b, &o, tris_b, Descent::Larger, f)
    })?;
    let d = clock.time("build-sah-dop14", || TopDown::sah().build(tris_b, dops, i1))?;
    pairs(clock, "selfb", "dop14-sah-simultaneous", |f| {
        bvhkit::overlapping_pairs(&d, tris_b, &d, tris_b, Descent::Simultaneous, f)
    })?;

    // Other builders for A, queried against B's SAH tree.
    let mut scratch = BottomUpScratch {
        clusters: cluster,
        work,
        keys,
    };
    let p = clock.time("build-ploc", || {
        BottomUp::default().build(tris_a, ploc, i2, &mut scratch)
    })?;
    pairs(clock, "pairs", "ploc-larger", |f| {
        bvhkit::overlapping_pairs(&p, tris_a, b, tris_b, Descent::Larger, f)
    })?;
    let ins = clock.time("build-insertion", || {
        Insertion::default().build(tris_a, dyn_nodes, order, inserted, i3)
    })?;
    pairs(clock, "pairs", "insertion-larger", |f| {
        bvhkit::overlapping_pairs(&ins, tris_a, b, tris_b, Descent::Larger, f)
    })?;

    // Best-first rays, and rays on the quantized 4-wide layout.
    rays(clock, "aabb-best-first", a, tris_a, RayOrder::BestFirst)?;
    let q = clock.time("convert-quantized", || QuantizedWide::from_bvh(a, quant))?;
    rays(clock, "quantized-dfs", &q, tris_a, RayOrder::DepthFirst)?;
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
