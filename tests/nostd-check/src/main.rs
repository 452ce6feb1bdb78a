//! Builds and queries a tree with no std, no allocator and stack storage only;
//! exits 0 when the answer matches brute force.
#![no_std]
#![no_main]

use bvhkit::glam::{Quat, Vec3};
use bvhkit::{
    brute_force, overlapping_pairs, Aabb, Descent, Exact, Node, PairTraversal, Pairs, Ray,
    RayOrder, Rigid, Sphere, TopDown, Triangle,
};

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}

#[no_mangle]
pub extern "C" fn rust_eh_personality() {}

#[link(name = "c")]
extern "C" {}

fn scene(shift: f32) -> [Triangle; 64] {
    core::array::from_fn(|i| {
        let o = Vec3::new((i % 8) as f32, (i / 8) as f32 + shift, 0.0);
        Triangle::new(
            o,
            o + Vec3::new(1.2, 0.0, 0.0),
            o + Vec3::new(0.0, 1.1, 0.4),
        )
    })
}

fn run() -> Result<bool, bvhkit::Error> {
    let (a, b) = (scene(0.0), scene(0.5));
    let mut na = [Node::<Aabb>::EMPTY; bvhkit::max_nodes(64)];
    let mut nb = [Node::<Aabb>::EMPTY; bvhkit::max_nodes(64)];
    let (mut ia, mut ib) = ([0u32; 64], [0u32; 64]);
    let ta = TopDown::sah().build(&a, &mut na, &mut ia)?;
    let tb = TopDown::median().build(&b, &mut nb, &mut ib)?;
    let mut found = 0usize;
    overlapping_pairs(&ta, &a, &tb, &b, Descent::Larger, |_, _| found += 1)?;
    let mut ns = [Node::<Sphere>::EMPTY; bvhkit::max_nodes(64)];
    let mut is = [0u32; 64];
    let ts = TopDown::sah().build(&a, &mut ns, &mut is)?;
    let mut spheres = 0usize;
    overlapping_pairs(&ts, &a, &ts, &a, Descent::Simultaneous, |_, _| spheres += 1)?;
    // Exact narrow phase with B moved (rigid transform, robust predicates).
    let motion = Rigid::new(Quat::from_rotation_z(0.3), Vec3::new(0.2, 0.1, 0.0))?;
    let exact = Pairs::new(&ta, &a, &tb, &b)
        .traversal(PairTraversal::LEAF_DIRECTED)
        .in_frame(motion)
        .exact()
        .count()?;
    let exact_ref = brute_force::pairs_placed(&a, &b, &motion, Exact, |_, _| {});
    let ray = Ray::new(Vec3::new(3.3, 2.2, 5.0), -Vec3::Z, f32::INFINITY)?;
    let hit = ta.cast_ray(&a, &ray, RayOrder::BestFirst, ())?;
    Ok(found > 0
        && found == brute_force::pairs(&a, &b, |_, _| {})
        && spheres == brute_force::pairs(&a, &a, |_, _| {})
        && exact > 0
        && exact == exact_ref
        && hit.is_some()
        && hit == brute_force::ray_closest(&a, &ray))
}

#[no_mangle]
pub extern "C" fn main(_argc: i32, _argv: *const *const u8) -> i32 {
    match run() {
        Ok(true) => 0,
        _ => 1,
    }
}
