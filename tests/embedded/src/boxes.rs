//! The `boxes` feature set: what an engine's broad phase does each frame on
//! a microcontroller. 64 moving boxes in a static array; every frame the
//! tree is rebuilt from scratch (`TopDown::sah()`, the default), every
//! overlapping pair of boxes is found once (the tree against itself), and
//! four rays are cast. Boxes only: no triangle, no narrow phase, so this is
//! the smallest useful firmware, the one the embedded chapter's size and
//! stack targets are about.

use core::ptr::addr_of_mut;

use bvhkit::query::SelfPairs;
use bvhkit::{max_nodes, Aabb, Node, Ray, RayOrder, TopDown};
use cortex_m_semihosting::hprintln;

use crate::scene::{self, BOXES, BOX_RAYS, FRAMES};
use crate::Clock;

static mut BOX_ARRAY: [Aabb; BOXES] =
    [Aabb::new(bvhkit::glam::Vec3::ZERO, bvhkit::glam::Vec3::ZERO); BOXES];
static mut NODES: [Node<Aabb>; max_nodes(BOXES)] = [Node::ZERO; max_nodes(BOXES)];
static mut INDEX: [u32; BOXES] = [0; BOXES];

/// Runs the frames, printing `boxpairs f<k> <count> <digest>` and
/// `boxray f<k> <r> <prim|none> <t bits>` lines for the host check. The
/// first frame's steps are timed and their stack measured.
#[inline(never)]
pub fn run(clock: &Clock) -> Result<(), bvhkit::Error> {
    // SAFETY: called once; the only references to these buffers.
    let (boxes, nodes, index) = unsafe {
        (
            &mut *addr_of_mut!(BOX_ARRAY),
            &mut *addr_of_mut!(NODES),
            &mut *addr_of_mut!(INDEX),
        )
    };
    hprintln!("boxes {} frames {}", BOXES, FRAMES);
    for f in 0..FRAMES {
        for (i, b) in boxes.iter_mut().enumerate() {
            *b = scene::moving_box(i, f);
        }
        let boxes: &[Aabb] = boxes;
        let timed = f == 0;
        let (nodes, index) = (&mut nodes[..], &mut index[..]);
        let tree = step(clock, timed, "boxes-build", || {
            TopDown::sah().build(boxes, nodes, index)
        })?;
        if timed {
            hprintln!(
                "tree boxes nodes {} depth {}",
                tree.node_count(),
                tree.depth()
            );
        }
        let digest = scene::tree_digest(tree.nodes(), tree.indices());
        hprintln!("boxtree f{} {} {:08x}", f, tree.node_count(), digest);
        let mut digest = 0u32;
        let count = step(clock, timed, "boxes-pairs", || {
            SelfPairs::new(&tree, boxes)
                .for_each(|i, j| digest = digest.wrapping_add(scene::mix(i, j)))
        })?;
        hprintln!("boxpairs f{} {} {:08x}", f, count, digest);
        let mut hits = [None; BOX_RAYS];
        step(
            clock,
            timed,
            "boxes-rays",
            || -> Result<(), bvhkit::Error> {
                for (r, out) in hits.iter_mut().enumerate() {
                    let (o, d) = scene::box_ray(r, f);
                    let ray = Ray::new(o, d, f32::INFINITY)?;
                    *out = tree.cast_ray(boxes, &ray, RayOrder::DepthFirst, ())?;
                }
                Ok(())
            },
        )?;
        for (r, hit) in hits.iter().enumerate() {
            match hit {
                Some(h) => hprintln!("boxray f{} {} {} {:08x}", f, r, h.prim, h.t.to_bits()),
                None => hprintln!("boxray f{} {} none 0", f, r),
            }
        }
    }
    Ok(())
}

/// Runs `work`, timed and its stack measured when `timed`.
fn step<T>(clock: &Clock, timed: bool, label: &str, work: impl FnOnce() -> T) -> T {
    if timed {
        clock.time(label, work)
    } else {
        work()
    }
}
