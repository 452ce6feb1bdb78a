//! Built-in scenes, generated (no download, deterministic).
//!
//! The default scene is a pair of "rocks": a finely subdivided icosphere with a
//! layered, seeded displacement, and a rotated and shifted copy that overlaps it
//! partly. It has the properties of a scanned mesh that matter to a BVH:
//! small, similar-size triangles on a closed curved surface, with bumps at
//! several scales, and a contact region between two objects.

use bvhkit::glam::{Mat3, Vec3};
use bvhkit::{Aabb, Triangle};
use std::collections::HashMap;

/// A displaced icosphere with `20 * 4^subdivisions` triangles (6 -> 81 920).
pub fn rock(subdivisions: u32, seed: u64) -> Vec<Triangle> {
    let (vertices, faces) = icosphere(subdivisions);
    let s = seed as f32 * 0.001;
    let displaced: Vec<Vec3> = vertices
        .iter()
        .map(|&d| {
            let n = (d.x * 3.1 + s).sin() * (d.y * 2.7 - s).cos() * 0.08
                + (d.y * 7.3 + d.z * 5.1 + s).sin() * 0.03
                + (d.z * 17.0 - d.x * 13.0).sin() * (d.y * 11.0).cos() * 0.01
                + ((d.x + d.y) * 41.0).sin() * 0.002;
            d * (1.0 + n)
        })
        .collect();
    faces
        .iter()
        .map(|f| Triangle::new(displaced[f[0]], displaced[f[1]], displaced[f[2]]))
        .collect()
}

/// Rotates about y by `angle` radians and then translates.
pub fn transformed(tris: &[Triangle], angle: f32, offset: Vec3) -> Vec<Triangle> {
    let m = Mat3::from_rotation_y(angle) * Mat3::from_rotation_x(angle * 0.5);
    tris.iter()
        .map(|t| Triangle {
            v: t.v.map(|p| m * p + offset),
        })
        .collect()
}

/// The default scene: two overlapping rocks of 81 920 triangles each.
pub fn default_pair() -> (Vec<Triangle>, Vec<Triangle>) {
    let a = rock(6, 1);
    let b = transformed(&rock(6, 2), 0.7, Vec3::new(1.35, 0.2, 0.1));
    (a, b)
}

/// The default pair at another size: `rock_pair(6)` is [`default_pair`].
pub fn rock_pair(subdivisions: u32) -> (Vec<Triangle>, Vec<Triangle>) {
    if subdivisions == 6 {
        return default_pair();
    }
    let a = rock(subdivisions, 1);
    let b = transformed(&rock(subdivisions, 2), 0.7, Vec3::new(1.35, 0.2, 0.1));
    (a, b)
}

/// A small deterministic generator (SplitMix64) for the generated scenes.
pub(crate) struct Rng(pub(crate) u64);

impl Rng {
    pub(crate) fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }
    pub(crate) fn vec(&mut self) -> Vec3 {
        Vec3::new(self.next(), self.next(), self.next()) * 2.0 - Vec3::ONE
    }
}

/// `n` small triangles spread uniformly in the cube [-1, 1]^3 (a "soup").
pub fn soup(n: usize, seed: u64) -> Vec<Triangle> {
    let mut r = Rng(seed);
    let size = 1.0 / (n as f32).cbrt();
    (0..n)
        .map(|_| {
            let a = r.vec();
            Triangle::new(a, a + r.vec() * size, a + r.vec() * size)
        })
        .collect()
}

/// `n` small triangles in 24 tight clusters of different sizes (very uneven density).
pub fn clustered(n: usize, seed: u64) -> Vec<Triangle> {
    let mut r = Rng(seed);
    let centres: Vec<(Vec3, f32)> = (0..24)
        .map(|i| (r.vec(), 0.02 + 0.1 * (i % 5) as f32 / 4.0))
        .collect();
    (0..n)
        .map(|i| {
            let (c, spread) = centres[i % centres.len()];
            // Sum of three uniforms: roughly normal around the centre.
            let a = c + (r.vec() + r.vec() + r.vec()) * spread / 3.0;
            let size = spread * 0.1;
            Triangle::new(a, a + r.vec() * size, a + r.vec() * size)
        })
        .collect()
}

/// `n` long, thin triangles (blades of grass or hair): length 0.08, width
/// 0.002, leaning in random directions, rooted over the square [-1, 1]^2.
pub fn slivers(n: usize, seed: u64) -> Vec<Triangle> {
    let mut r = Rng(seed);
    (0..n)
        .map(|_| {
            let root = Vec3::new(r.vec().x, 0.0, r.vec().z);
            let dir = (Vec3::Y + r.vec() * 0.6).normalize() * 0.08;
            let side = Vec3::new(0.002, 0.0, 0.0);
            Triangle::new(root, root + side, root + dir)
        })
        .collect()
}

fn icosphere(subdivisions: u32) -> (Vec<Vec3>, Vec<[usize; 3]>) {
    let t = (1.0 + 5.0f32.sqrt()) / 2.0;
    let mut v: Vec<Vec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| Vec3::new(x, y, z).normalize())
    .collect();
    let mut f: Vec<[usize; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdivisions {
        let mut mid: HashMap<(usize, usize), usize> = HashMap::new();
        let mut midpoint = |a: usize, b: usize, v: &mut Vec<Vec3>| {
            let key = (a.min(b), a.max(b));
            *mid.entry(key).or_insert_with(|| {
                v.push(((v[a] + v[b]) * 0.5).normalize());
                v.len() - 1
            })
        };
        let mut next = Vec::with_capacity(f.len() * 4);
        for [a, b, c] in f {
            let ab = midpoint(a, b, &mut v);
            let bc = midpoint(b, c, &mut v);
            let ca = midpoint(c, a, &mut v);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        f = next;
    }
    (v, f)
}

#[cfg(all(test, feature = "cli"))]
mod tests {
    use super::*;

    #[test]
    fn default_scene_is_large_and_overlapping() {
        let (a, b) = default_pair();
        assert_eq!(a.len(), 81_920);
        assert_eq!(b.len(), 81_920);
        assert!(a.iter().all(|t| t.area() > 0.0));
        // The objects overlap somewhere but not everywhere.
        let pairs = crate::tour::reference_pairs(&a, &b);
        assert!(
            pairs.len() > 100 && pairs.len() < 1_000_000,
            "{}",
            pairs.len()
        );
    }
}

/// Boxes of side 1 drifting in a cube, bouncing off its walls: the moving
/// scene of the broad-phase benchmarks (`--bench broad_phase`,
/// `bench-peers --broad-phase`, the `profile_broad_phase` example). The
/// cube is sized for a fixed density, about 4 overlapping pairs per box.
///
/// ```
/// let mut drift = bvhkit_std::scene::Drift::new(1000);
/// let before = drift.boxes();
/// let mut moved = 0;
/// drift.advance(10, 0, |_, _| moved += 1); // one box in ten moves
/// assert_eq!(moved, 100);
/// assert_ne!(drift.boxes(), before);
/// ```
#[derive(Clone, Debug)]
pub struct Drift {
    /// Each box's minimum corner.
    pub positions: Vec<Vec3>,
    /// Each box's move per step.
    pub velocities: Vec<Vec3>,
    /// The cube's side.
    pub side: f32,
}

impl Drift {
    /// `n` boxes, placed and set moving by a small deterministic generator.
    pub fn new(n: usize) -> Self {
        let side = (n as f32 * 2.0).cbrt() * 1.6;
        let mut s = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 40) as f32 / (1u64 << 24) as f32
        };
        let positions = (0..n)
            .map(|_| Vec3::new(next(), next(), next()) * side)
            .collect();
        let velocities = (0..n)
            .map(|_| (Vec3::new(next(), next(), next()) - 0.5) * 0.04)
            .collect();
        Drift {
            positions,
            velocities,
            side,
        }
    }

    /// The box of side 1 at minimum corner `p`.
    pub fn boxed(p: Vec3) -> Aabb {
        Aabb::new(p, p + 1.0)
    }

    /// Every box, in order.
    pub fn boxes(&self) -> Vec<Aabb> {
        self.positions.iter().map(|&p| Self::boxed(p)).collect()
    }

    /// Moves every `every`-th box (starting at `step % every`, so that
    /// successive steps move different boxes), bouncing off the walls, and
    /// calls `f(i, box)` for each moved box.
    pub fn advance(&mut self, every: usize, step: usize, mut f: impl FnMut(usize, Aabb)) {
        let n = self.positions.len();
        for i in (step % every..n).step_by(every) {
            let (p, v) = (&mut self.positions[i], &mut self.velocities[i]);
            *p += *v;
            for a in 0..3 {
                if p[a] < 0.0 || p[a] > self.side {
                    v[a] = -v[a];
                }
            }
            f(i, Self::boxed(*p));
        }
    }
}
