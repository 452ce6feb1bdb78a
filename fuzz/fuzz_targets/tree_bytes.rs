//! A tree reopened from arbitrary bytes (`Bvh::from_parts`, as from a file):
//! either refused with an error, or valid, and then every query on it
//! answers like brute force. Never a panic, never a hang.
#![no_main]
use bvhkit::glam::Vec3;
use bvhkit::{brute_force, Aabb, Bvh, Node, Pairs, Ray, RayOrder, Triangle};

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    // Eight triangles along x, 0..8.
    let tris: Vec<Triangle> = (0..8)
        .map(|i| {
            let o = Vec3::new(i as f32, 0.0, 0.0);
            Triangle::new(o, o + Vec3::X * 0.9, o + Vec3::Y)
        })
        .collect();
    // Node records of 32 bytes (min, max, first, count), then u32 indices.
    let word = |k: usize| -> u32 {
        let b = &data[4 * k..4 * k + 4];
        u32::from_le_bytes([b[0], b[1], b[2], b[3]])
    };
    let words = data.len() / 4;
    let Some(&n_nodes) = data.first() else { return };
    let n_nodes = (n_nodes as usize % 20).min(words / 8);
    let f = |k: usize| f32::from_bits(word(k));
    let nodes: Vec<Node<Aabb>> = (0..n_nodes)
        .map(|n| {
            let k = 8 * n;
            Node {
                bv: Aabb::new(
                    Vec3::new(f(k), f(k + 1), f(k + 2)),
                    Vec3::new(f(k + 3), f(k + 4), f(k + 5)),
                ),
                first: word(k + 6),
                count: word(k + 7),
            }
        })
        .collect();
    let indices: Vec<u32> = (8 * n_nodes..words).take(16).map(word).collect();
    let mut seen = vec![0u32; Bvh::<Aabb>::seen_words(nodes.len(), tris.len())];
    let Ok(t) = Bvh::from_parts(&nodes, &indices, &tris, &mut seen) else {
        return;
    };
    let mut got = Vec::new();
    Pairs::new(&t, &tris, &t, &tris)
        .for_each(|i, j| got.push((i, j)))
        .expect("a valid tree answers");
    let mut want = Vec::new();
    brute_force::pairs(&tris, &tris, |i, j| want.push((i, j)));
    got.sort_unstable();
    want.sort_unstable();
    assert_eq!(got, want);
    let all = Aabb::new(Vec3::splat(-1.0), Vec3::splat(10.0));
    assert_eq!(t.overlapping(&tris, &all, |_| {}), Ok(8));
    let ray = Ray::new(Vec3::new(3.2, 0.1, -1.0), Vec3::Z, f32::INFINITY).unwrap();
    let hit = t.cast_ray(&tris, &ray, RayOrder::DepthFirst, ()).unwrap();
    assert_eq!(
        hit.map(|h| h.prim),
        brute_force::ray_closest(&tris, &ray).map(|h| h.prim)
    );
    let near = t.nearest(&tris, Vec3::new(5.5, 2.0, 0.0), ()).unwrap();
    assert_eq!(
        near.map(|n| n.prim),
        brute_force::nearest(&tris, Vec3::new(5.5, 2.0, 0.0)).map(|n| n.prim)
    );
});
