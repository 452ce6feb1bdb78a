//! A static scene as on a microcontroller: no heap, every buffer a fixed
//! array sized by `const fn`s, one build, then a region query, a ray and the
//! overlapping pairs of two objects. `cargo run -p bvhkit --example static_scene`
use bvhkit::glam::Vec3;
use bvhkit::{
    brute_force, max_nodes, overlapping_pairs, Aabb, Descent, Node, Ray, RayOrder, TopDown,
    Triangle,
};

const N: usize = 64;

/// A row of `N` small triangles along x, lifted by `dz`.
fn row(dz: f32) -> [Triangle; N] {
    core::array::from_fn(|i| {
        let o = Vec3::new(i as f32 * 0.5, 0.0, dz);
        Triangle::new(
            o,
            o + Vec3::new(0.6, 0.0, 0.0),
            o + Vec3::new(0.0, 0.6, 0.3),
        )
    })
}

fn main() -> Result<(), bvhkit::Error> {
    let (a, b) = (row(0.0), row(0.2));
    let mut nodes_a = [Node::<Aabb>::ZERO; max_nodes(N)];
    let mut nodes_b = [Node::<Aabb>::ZERO; max_nodes(N)];
    let (mut idx_a, mut idx_b) = ([0u32; N], [0u32; N]);
    let tree_a = TopDown::sah().build(&a, &mut nodes_a, &mut idx_a)?;
    let tree_b = TopDown::sah().build(&b, &mut nodes_b, &mut idx_b)?;

    let region = Aabb::new(Vec3::new(4.0, -1.0, -1.0), Vec3::new(6.0, 1.0, 1.0));
    let in_region = tree_a.overlapping(&a, &region, |_| {})?;
    assert_eq!(in_region, brute_force::overlapping(&a, &region, |_| {}));

    let ray = Ray::new(Vec3::new(10.2, 0.1, 5.0), -Vec3::Z, f32::INFINITY)?;
    let hit = tree_a.cast_ray(&a, &ray, RayOrder::default(), ())?;
    assert_eq!(hit, brute_force::ray_closest(&a, &ray));

    let pairs = overlapping_pairs(&tree_a, &a, &tree_b, &b, Descent::Larger, |_, _| {})?;
    assert_eq!(pairs, brute_force::pairs(&a, &b, |_, _| {}));
    println!(
        "{N} + {N} triangles in {} + {} nodes: {in_region} in the region, ray hit {:?}, {pairs} overlapping pairs",
        tree_a.node_count(),
        tree_b.node_count(),
        hit.map(|h| h.prim)
    );
    Ok(())
}
