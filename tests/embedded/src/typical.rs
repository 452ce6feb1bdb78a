//! The "typical" feature set: an exact narrow phase with B moved, a sphere
//! tree, and ray casts on the 4-wide layout.

use core::ptr::addr_of_mut;

use bvhkit::layout::{Wide, WideNode};
use bvhkit::{
    max_nodes, Aabb, Bvh, Node, Pairs, Query, Ray, RayOrder, Rigid, Sphere, TopDown, Triangle,
};
use cortex_m_semihosting::hprintln;

use crate::scene::{self, N};
use crate::{print_pairs, print_ray, Clock};

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
    let mut digest = 0u32;
    let count = clock.time("exact-moved", || {
        Pairs::new(a, tris_a, b, tris_b)
            .in_frame(motion)
            .exact()
            .for_each(|i, j| digest = digest.wrapping_add(scene::mix(i, j)))
    })?;
    print_pairs("exact", "aabb-moved", count, digest);

    let s = clock.time("build-sah-sphere", || {
        TopDown::sah().build(tris_a, spheres, sphere_index)
    })?;
    let mut digest = 0u32;
    let count = clock.time("pairs-sphere", || {
        bvhkit::overlapping_pairs(&s, tris_a, &s, tris_a, bvhkit::Descent::Larger, |i, j| {
            digest = digest.wrapping_add(scene::mix(i, j))
        })
    })?;
    print_pairs("self", "sphere-sah-dfs", count, digest);

    hprintln!(
        "wide records {} of {}",
        Wide::records_needed(a)?,
        wide.len()
    );
    let w = clock.time("convert-wide", || Wide::from_bvh(a, wide))?;
    let mut rays = [None; scene::RAYS];
    clock.time("rays-wide", || -> Result<(), bvhkit::Error> {
        for (r, out) in rays.iter_mut().enumerate() {
            let (o, d) = scene::ray(r);
            *out = w.cast_ray(
                tris_a,
                &Ray::new(o, d, f32::INFINITY)?,
                RayOrder::DepthFirst,
                (),
            )?;
        }
        Ok(())
    })?;
    for (r, hit) in rays.iter().enumerate() {
        print_ray("wide-dfs", r, *hit);
    }
    Ok(())
}
