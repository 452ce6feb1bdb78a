//! Shape casts (#22): 1,000 spheres and 1,000 boxes thrown at a
//! 20,480-triangle rock, depth-first and best-first, next to the same
//! 1,000 rays (a cast is a ray against grown boxes with a costlier exact
//! primitive test, so rays are the floor), and against brute force over
//! every triangle for 20 casts (the cost the tree saves).
//!
//! ```text
//! cargo bench -p bvhkit-std --bench casts
//! ```

use bvhkit::glam::Vec3;
use bvhkit::{brute_force, Aabb, Primitive, Ray, RayOrder, ShapeCast, TopDown};
use bvhkit_std::{scene, OwnedBvh};
use criterion::{criterion_group, criterion_main, Criterion};

/// A deterministic point in the unit cube, from a counter (splitmix64).
fn unit(k: u64) -> Vec3 {
    let mut z = k.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut next = || {
        z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut x = z;
        x = (x ^ (x >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        x = (x ^ (x >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((x ^ (x >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    };
    Vec3::new(next(), next(), next())
}

fn bench(c: &mut Criterion) {
    let tris = scene::rock(5, 7);
    let tree = OwnedBvh::<Aabb>::build(&TopDown::default(), &tris).expect("builds");
    let bvh = tree.view();
    let bounds = tris.iter().fold(Aabb::EMPTY, |u, t| u.union(&t.bounds()));
    let size = bounds.max - bounds.min;
    let inside = |k: u64| bounds.min + unit(k) * size;
    // Paths from points on a sphere around the rock towards points inside it.
    let paths: Vec<(Vec3, Vec3)> = (0..1_000u64)
        .map(|k| {
            let from = bounds.center() + (unit(2 * k) - 0.5).normalize_or(Vec3::X) * size.length();
            (from, inside(2 * k + 1) - from)
        })
        .collect();
    let rays: Vec<Ray> = paths
        .iter()
        .map(|&(o, d)| Ray::new(o, d, f32::INFINITY).expect("finite ray"))
        .collect();
    let extent = size.max_element();
    let shapes = |name: &str| -> Vec<ShapeCast> {
        paths
            .iter()
            .map(|&(o, d)| match name {
                "sphere-1%" => ShapeCast::sphere(o, extent * 0.01, d, f32::INFINITY),
                "sphere-5%" => ShapeCast::sphere(o, extent * 0.05, d, f32::INFINITY),
                _ => {
                    let h = Vec3::new(0.02, 0.01, 0.03) * extent;
                    ShapeCast::aabb(&Aabb::new(o - h, o + h), d, f32::INFINITY)
                }
            })
            .map(|c| c.expect("finite cast"))
            .collect()
    };

    let mut g = c.benchmark_group("casts-20480");
    g.bench_function("rays-depth-first", |b| {
        b.iter(|| {
            rays.iter()
                .filter(|r| {
                    bvh.cast_ray(&tris, r, RayOrder::DepthFirst, ())
                        .expect("casts")
                        .is_some()
                })
                .count()
        })
    });
    for name in ["sphere-1%", "sphere-5%", "box-2%"] {
        let casts = shapes(name);
        for (order_name, order) in [
            ("depth-first", RayOrder::DepthFirst),
            ("best-first", RayOrder::BestFirst),
        ] {
            g.bench_function(format!("{name}-{order_name}"), |b| {
                b.iter(|| {
                    casts
                        .iter()
                        .filter(|c| {
                            bvh.cast_shape(&tris, c, order, ())
                                .expect("casts")
                                .is_some()
                        })
                        .count()
                })
            });
        }
        g.bench_function(format!("{name}-brute-force-20"), |b| {
            b.iter(|| {
                casts[..20]
                    .iter()
                    .filter(|c| brute_force::cast_closest(&tris, c).is_some())
                    .count()
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
