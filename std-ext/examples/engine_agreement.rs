//! Counts, for every engine query of #22 (the dynamic tree queried in place,
//! the incremental broad phase, self-collision, distances, contact geometry
//! and shape casts), how many answers were compared with brute force and how
//! many agreed. The property tests check the same things on random scenes
//! (`cargo test -p bvhkit-tests`); this example runs a fixed, larger set and
//! prints the counts: `cargo run --release -p bvhkit-std --example engine_agreement`.
//! Exits non-zero on any disagreement.

use bvhkit::builders::{DynNode, DynamicConfig, DynamicTree, Rotations};
use bvhkit::collision::PairTracker;
use bvhkit::glam::{Quat, Vec3};
use bvhkit::narrow::{triangle_contact, triangles_intersect};
use bvhkit::query::{Distance, SelfPairs};
use bvhkit::{
    brute_force, Aabb, Pairs, Primitive, Query, Ray, RayOrder, Rigid, ShapeCast, TopDown, Triangle,
};
use bvhkit_std::OwnedBvh;
use std::process::ExitCode;

/// Compared, agreed, and how many of the answers were not empty (a hit, a
/// pair, a contact), per query.
#[derive(Default)]
struct Tally {
    rows: Vec<(String, usize, usize, usize)>,
}

impl Tally {
    fn add(&mut self, what: &str, agreed: bool, something: bool) {
        let i = match self.rows.iter().position(|r| r.0 == what) {
            Some(i) => i,
            None => {
                self.rows.push((what.to_string(), 0, 0, 0));
                self.rows.len() - 1
            }
        };
        let r = &mut self.rows[i];
        r.1 += 1;
        r.2 += agreed as usize;
        r.3 += something as usize;
    }
}

/// A small deterministic generator.
struct Rng(u64);
impl Rng {
    fn unit(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
    fn point(&mut self, lo: Vec3, size: Vec3) -> Vec3 {
        lo + Vec3::new(self.unit(), self.unit(), self.unit()) * size
    }
}

fn sorted(mut v: Vec<(u32, u32)>) -> Vec<(u32, u32)> {
    v.sort_unstable();
    v
}

fn main() -> ExitCode {
    let mut t = Tally::default();
    let mut rng = Rng(0x5eed_0022);
    let rock = bvhkit_std::scene::rock(4, 1); // 5,120 triangles
    let bounds = rock.iter().fold(Aabb::EMPTY, |b, x| b.union(&x.bounds()));
    let (lo, size) = (bounds.min - bounds.extent() * 0.2, bounds.extent() * 1.4);

    // The dynamic tree, queried where it is (default and area rotations),
    // after inserting every triangle and moving a third of them.
    for rotations in [DynamicConfig::default().rotations, Rotations::Area] {
        let config = DynamicConfig {
            rotations,
            margin: 0.01,
            ..Default::default()
        };
        let mut storage = vec![DynNode::<Aabb>::EMPTY; 2 * rock.len() - 1];
        let mut tree = DynamicTree::new(&mut storage, config).unwrap();
        let mut moved = rock.clone();
        let handles: Vec<_> = rock
            .iter()
            .enumerate()
            .map(|(i, x)| tree.insert(i as u32, &x.bounds()).unwrap())
            .collect();
        for (i, h) in handles.iter().enumerate().step_by(3) {
            let d = (rng.point(Vec3::splat(-1.0), Vec3::splat(2.0))) * 0.05;
            moved[i] = Triangle::new(moved[i].v[0] + d, moved[i].v[1] + d, moved[i].v[2] + d);
            tree.update(*h, &moved[i].bounds()).unwrap();
        }
        tree.optimize(rock.len()).unwrap();
        for _ in 0..500 {
            let c = rng.point(lo, size);
            let corner = rng.point(bounds.min, bounds.extent());
            let region = Aabb::new(corner, corner + bounds.extent() * 0.1);
            let mut got = Vec::new();
            tree.overlapping(&moved, &region, |i| got.push(i)).unwrap();
            let mut want = Vec::new();
            brute_force::overlapping(&moved, &region, |i| want.push(i));
            got.sort_unstable();
            t.add("dynamic tree: box region", got == want, !want.is_empty());
            let ray = Ray::new(
                c,
                (rng.point(lo, size) - c).normalize_or(Vec3::X),
                f32::INFINITY,
            )
            .unwrap();
            let got = tree
                .cast_ray(&moved, &ray, RayOrder::default(), ())
                .unwrap();
            let want = brute_force::ray_closest(&moved, &ray);
            t.add("dynamic tree: closest ray hit", got == want, want.is_some());
            let got = tree.nearest(&moved, c, ()).unwrap();
            let want = brute_force::nearest(&moved, c);
            t.add(
                "dynamic tree: nearest triangle",
                got == want,
                want.is_some(),
            );
        }
        // Pairs against a static tree of a moved copy.
        let other: Vec<Triangle> = rock
            .iter()
            .map(|x| Triangle::new(x.v[0] + 0.003, x.v[1] + 0.003, x.v[2] + 0.003))
            .collect();
        let ob = OwnedBvh::<Aabb>::build(&TopDown::default(), &other).unwrap();
        let mut got = Vec::new();
        Pairs::new(&tree, &moved, &ob.view(), &other)
            .for_each(|i, j| got.push((i, j)))
            .unwrap();
        let mut want = Vec::new();
        brute_force::pairs(&moved, &other, |i, j| want.push((i, j)));
        let some = !want.is_empty();
        t.add(
            "dynamic tree: pairs with a static tree",
            sorted(got) == sorted(want),
            some,
        );
    }

    // The incremental broad phase: 2,000 boxes drifting, every step's pairs.
    let n = 2000;
    let mut drift = bvhkit_std::scene::Drift::new(n);
    let mut buffers = bvhkit_std::TrackerBuffers::new(n, 16 * n);
    let config = DynamicConfig {
        margin: 0.1,
        ..Default::default()
    };
    let mut world = PairTracker::new(buffers.storage(), config).unwrap();
    let mut boxes = drift.boxes();
    for (i, b) in boxes.iter().enumerate() {
        world.insert(i as u32, b).unwrap();
    }
    world.step(|_| {}).unwrap();
    for step in 0..60 {
        let every = if step % 2 == 0 { 1 } else { 10 };
        drift.advance(every, step, |i, b| {
            boxes[i] = b;
            world.set_bounds(i as u32, &b).unwrap()
        });
        world.step(|_| {}).unwrap();
        let mut want = Vec::new();
        brute_force::self_pairs(&boxes, |i, j| want.push((i, j)));
        let some = !want.is_empty();
        let got = sorted(world.pairs().to_vec());
        t.add("broad phase: pairs after a step", got == sorted(want), some);
    }

    // Self-collision of one mesh: every pair of overlapping boxes, once.
    let tree = OwnedBvh::<Aabb>::build(&TopDown::default(), &rock).unwrap();
    let view = tree.view();
    let mut got = Vec::new();
    SelfPairs::new(&view, &rock)
        .keep_adjacent()
        .for_each(|i, j| got.push((i, j)))
        .unwrap();
    let mut want = Vec::new();
    brute_force::self_pairs(&rock, |i, j| want.push((i, j)));
    let some = !want.is_empty();
    t.add(
        "self pairs (keep adjacent)",
        sorted(got) == sorted(want),
        some,
    );

    // Distances and contacts: the rock against turned and shifted copies.
    let small = bvhkit_std::scene::rock(2, 3); // 320 triangles
    let st = OwnedBvh::<Aabb>::build(&TopDown::default(), &small).unwrap();
    for k in 0..40 {
        let motion = Rigid::new(
            Quat::from_rotation_y(k as f32 * 0.15),
            Vec3::new(0.2 * k as f32 - 4.0, 0.01 * k as f32, 0.0),
        )
        .unwrap();
        let placed: Vec<Triangle> = small
            .iter()
            .map(|x| {
                Triangle::new(
                    motion.apply(x.v[0]),
                    motion.apply(x.v[1]),
                    motion.apply(x.v[2]),
                )
            })
            .collect();
        let pt = OwnedBvh::<Aabb>::build(&TopDown::default(), &placed).unwrap();
        let (sv, pv) = (st.view(), pt.view());
        let got = Distance::new(&sv, &small, &pv, &placed).closest().unwrap();
        let want = brute_force::closest_pair(&small, &placed);
        let same = match (got, want) {
            (Some(g), Some(w)) => g.points.distance_squared == w.points.distance_squared,
            (g, w) => g.is_none() && w.is_none(),
        };
        let apart = want.is_some_and(|w| w.points.distance_squared > 0.0);
        t.add("distance: closest pair (not empty: apart)", same, apart);
        let d = 0.05f64;
        let mut got = Vec::new();
        Distance::new(&sv, &small, &pv, &placed)
            .within(d, |i, j| got.push((i, j)))
            .unwrap();
        let mut want = Vec::new();
        brute_force::pairs_within(&small, &placed, d, |i, j| want.push((i, j)));
        let some = !want.is_empty();
        t.add(
            "distance: pairs within 0.05",
            sorted(got) == sorted(want),
            some,
        );
        for (i, a) in small.iter().enumerate() {
            for b in placed.iter().skip(i % 7).step_by(7) {
                let meet = triangles_intersect(a, b);
                let found = triangle_contact(a, b).is_some();
                t.add(
                    "contact: found exactly when the triangles meet",
                    found == meet,
                    meet,
                );
            }
        }
    }

    // Shape casts: balls and boxes thrown at the rock.
    for k in 0..600 {
        let from = rng.point(lo, size);
        let dir = (rng.point(bounds.min, bounds.extent()) - from).normalize_or(Vec3::X);
        let r = 0.002 + rng.unit() * 0.05;
        let cast = if k % 2 == 0 {
            ShapeCast::sphere(from, r, dir, f32::INFINITY).unwrap()
        } else {
            ShapeCast::aabb(&Aabb::new(from - r, from + r), dir, f32::INFINITY).unwrap()
        };
        let what = if k % 2 == 0 {
            "cast: ball"
        } else {
            "cast: box"
        };
        let got = view
            .cast_shape(&rock, &cast, RayOrder::default(), ())
            .unwrap();
        let want = brute_force::cast_closest(&rock, &cast);
        t.add(what, got == want, want.is_some());
    }

    let mut ok = true;
    println!("| query | compared with brute force | agreed | not empty (a hit, pair, contact) |");
    println!("|---|---:|---:|---:|");
    for (what, n, agreed, some) in &t.rows {
        println!("| {what} | {n} | {agreed} | {some} |");
        ok &= n == agreed;
    }
    if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
