//! The "typical" feature set: an exact narrow phase with B moved, a sphere
//! tree, and ray casts on the 4-wide layout.

use core::ptr::addr_of_mut;

use bvhkit::layout::{Wide, WideNode};
use bvhkit::{max_nodes, Aabb, Bvh, Node, Pairs, RayOrder, Rigid, Sphere, TopDown, Triangle};
use cortex_m_semihosting::hprintln;

use crate::scene::{self, N};
use crate::{pairs, rays, Clock};

static mut SPHERES: [Node<Sphere>; max_nodes(N)] = [Node::ZERO; max_nodes(N)];
static mut SPHERE_INDEX: [u32; N] = [0; N];
static mut WIDE: [WideNode; N] = [WideNode::ZERO; N];

#[inline(never)]
pub fn run(
    clock: &Clock,
    tris_a: &[Triangle],
    tris_b: &[Triangle],
    a: &Bvh<'static, Aabb>,
    b: &Bvh<'static, Aabb>,
) -> Result<(), bvhkit::Error> {
    // SAFETY: called once; the only references to these buffers.
    let (spheres, sphere_index, wide) = unsafe {
        (
            &mut *addr_of_mut!(SPHERES),
            &mut *addr_of_mut!(SPHERE_INDEX),
            &mut *addr_of_mut!(WIDE),
        )
    };

    let (rotation, shift) = scene::motion();
    let motion = Rigid::new(rotation, shift)?;
    pairs(clock, "exact", "aabb-moved", |f| {
        Pairs::new(a, tris_a, b, tris_b)
            .in_frame(motion)
            .exact()
            .for_each(f)
    })?;

    let s = clock.time("build-sah-sphere", || {
        TopDown::sah().build(tris_a, spheres, sphere_index)
    })?;
    pairs(clock, "self", "sphere-sah-dfs", |f| {
        bvhkit::overlapping_pairs(&s, tris_a, &s, tris_a, bvhkit::Descent::Larger, f)
    })?;

    hprintln!(
        "wide records {} of {}",
        Wide::records_needed(a)?,
        wide.len()
    );
    let w = clock.time("convert-wide", || Wide::from_bvh(a, wide))?;
    rays(clock, "wide-dfs", &w, tris_a, RayOrder::DepthFirst)?;
    Ok(())
}
