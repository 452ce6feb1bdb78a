//! Build with any builder of the library from arbitrary coordinates (NaN,
//! infinities, subnormals, 1e38, duplicates, or tame values at scales from
//! 1e-30 to 1e30), then query (pairs, a region, a ray, a sphere and a box
//! cast, nearest): an error for bad input, otherwise every answer equals
//! brute force. Never a panic.
#![no_main]
use bvhkit::glam::Vec3;
use bvhkit::{brute_force, Aabb, Pairs, Ray, RayOrder, ShapeCast, Triangle};
use bvhkit_std::builders::catalogue;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let Some((&control, rest)) = data.split_first() else {
        return;
    };
    let builders = catalogue();
    let (name, _, builder) = &builders[control as usize % builders.len()];
    let tame = control & 0x80 != 0;
    let scale = 10f32.powi(((control >> 3) % 13) as i32 * 5 - 30);
    let coord = |b: &[u8]| -> f32 {
        if tame {
            // A coarse grid (many duplicates) at this scale.
            (i16::from_le_bytes([b[0], b[1]]) as f32 / 64.0) * scale
        } else {
            f32::from_le_bytes([b[0], b[1], b[2], b[3]])
        }
    };
    let width = if tame { 2 } else { 4 };
    let values: Vec<f32> = rest.chunks_exact(width).map(coord).collect();
    let mut tris: Vec<Triangle> = values
        .chunks_exact(9)
        .take(if name.contains("exhaustive") { 40 } else { 200 })
        .map(|c| {
            Triangle::new(
                Vec3::new(c[0], c[1], c[2]),
                Vec3::new(c[3], c[4], c[5]),
                Vec3::new(c[6], c[7], c[8]),
            )
        })
        .collect();
    // The last triangle gives the queries; the others are the scene.
    let queries = if tris.len() > 1 {
        tris.split_off(tris.len() - 1)
    } else {
        Vec::new()
    };
    let tree = match builder.build::<Aabb>(&tris) {
        Ok(t) => t,
        Err(_) => return,
    };
    let t = tree.view();
    // Pairs against itself.
    let mut want = Vec::new();
    brute_force::pairs(&tris, &tris, |i, j| want.push((i, j)));
    let mut got = Vec::new();
    Pairs::new(&t, &tris, &t, &tris)
        .for_each(|i, j| got.push((i, j)))
        .expect("a built tree answers");
    got.sort_unstable();
    want.sort_unstable();
    assert_eq!(got, want, "{name}: pairs");
    // A region, a ray and a point from the last triangle's corners.
    if let Some(q) = queries.first() {
        let region = Aabb::new(q.v[0].min(q.v[1]), q.v[0].max(q.v[1]));
        let mut hits = Vec::new();
        match t.overlapping(&tris, &region, |i| hits.push(i)) {
            Ok(_) => {
                let mut want = Vec::new();
                brute_force::overlapping(&tris, &region, |i| want.push(i));
                hits.sort_unstable();
                assert_eq!(hits, want, "{name}: region");
            }
            Err(bvhkit::Error::InvalidQuery(_)) => {}
            Err(e) => panic!("{name}: region query failed: {e}"),
        }
        if let Ok(ray) = Ray::new(q.v[0], q.v[2] - q.v[0], f32::INFINITY) {
            let got = t.cast_ray(&tris, &ray, RayOrder::DepthFirst, ()).unwrap();
            let want = brute_force::ray_closest(&tris, &ray);
            assert_eq!(
                got.map(|h| h.t),
                want.map(|h| h.t),
                "{name}: ray {ray:?} over {tris:?}: tree {got:?}, brute force {want:?}"
            );
        }
        // A ball and a box swept along the same path, sized by the second
        // corner's distance (refused when it is not a finite size).
        let size = q.v[1].distance(q.v[0]);
        let half = Vec3::splat(size * 0.5);
        for cast in [
            ShapeCast::sphere(q.v[0], size, q.v[2] - q.v[0], f32::INFINITY),
            ShapeCast::aabb(
                &Aabb::new(q.v[0] - half, q.v[0] + half),
                q.v[2] - q.v[0],
                1.0,
            ),
        ]
        .into_iter()
        .flatten()
        {
            let got = t
                .cast_shape(&tris, &cast, RayOrder::DepthFirst, ())
                .unwrap();
            let want = brute_force::cast_closest(&tris, &cast);
            assert_eq!(
                got.map(|h| h.t),
                want.map(|h| h.t),
                "{name}: cast {cast:?} over {tris:?}: tree {got:?}, brute force {want:?}"
            );
        }
        match t.nearest(&tris, q.v[2], ()) {
            Ok(got) => {
                let want = brute_force::nearest(&tris, q.v[2]);
                assert_eq!(
                    got.map(|n| n.distance_squared),
                    want.map(|n| n.distance_squared),
                    "{name}: nearest"
                );
            }
            Err(bvhkit::Error::InvalidQuery(_)) => {}
            Err(e) => panic!("{name}: nearest failed: {e}"),
        }
    }
});
