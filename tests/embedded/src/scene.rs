//! The demo scene, shared by the firmware and the host check
//! (`std-ext/examples/embedded_check.rs` includes this file), so both sides
//! compute on the very same numbers. Only `+ - *` on small integers-as-floats
//! are used: no `sin`, `cos` or `sqrt`, whose last bit may differ between the
//! target's `libm` and the host's C library.

use bvhkit::glam::Vec3;
use bvhkit::Triangle;

/// Quads per side of each sheet; each sheet has `2 * SIDE * SIDE` triangles.
pub const SIDE: usize = 10;
/// Triangles per object.
pub const N: usize = 2 * SIDE * SIDE;
/// Rays cast into object A.
pub const RAYS: usize = 8;

/// A bumpy height value on the integer grid, in `[0, 0.5)`.
fn bump(i: usize, j: usize, seed: usize) -> f32 {
    let h = (i * 7 + j * 13 + seed * 5 + i * j) % 8;
    h as f32 * 0.0625
}

/// Object A: a bumpy horizontal sheet over `[0, 10] x [0, 10]` at height about 1.
/// Object B: a bumpy vertical sheet in the plane `y = 5.1`, spanning the same `x`
/// and heights `[-2, 8]`, so it cuts A along a line.
pub fn object(which: usize, out: &mut [Triangle; N]) {
    let point = |i: usize, j: usize| {
        let (u, v) = (i as f32, j as f32);
        if which == 0 {
            Vec3::new(u, v, 1.0 + bump(i, j, 0))
        } else {
            Vec3::new(u + 0.25, 5.1 + bump(i, j, 1) - 0.25, v - 2.0)
        }
    };
    let mut k = 0;
    for i in 0..SIDE {
        for j in 0..SIDE {
            let (p00, p10, p01, p11) = (
                point(i, j),
                point(i + 1, j),
                point(i, j + 1),
                point(i + 1, j + 1),
            );
            out[k] = Triangle::new(p00, p10, p11);
            out[k + 1] = Triangle::new(p00, p11, p01);
            k += 2;
        }
    }
}

/// Ray `r`: straight down onto A from above, at a fractional grid position.
pub fn ray(r: usize) -> (Vec3, Vec3) {
    let x = 0.5 + (r * 37 % 23) as f32 * 0.5;
    let y = 0.25 + (r * 53 % 19) as f32 * 0.625;
    (Vec3::new(x, y, 20.0), Vec3::new(0.0, 0.0, -1.0))
}

#[allow(dead_code)] // not used by the minimal set
/// The rigid motion applied to B for the exact query: a quarter turn about `z`
/// (exact in floating point) and a shift.
pub fn motion() -> (bvhkit::glam::Quat, Vec3) {
    (
        bvhkit::glam::Quat::from_xyzw(
            0.0,
            0.0,
            core::f32::consts::FRAC_1_SQRT_2,
            core::f32::consts::FRAC_1_SQRT_2,
        ),
        Vec3::new(10.3, -0.2, 0.0),
    )
}

/// Order-independent digest of a pair set: wrapping sum of a mix of each pair.
pub fn mix(i: u32, j: u32) -> u32 {
    let h = i.wrapping_mul(0x9E37_79B1) ^ j.wrapping_mul(0x85EB_CA77).rotate_left(13);
    h ^ (h >> 15)
}

/// Moving boxes of the `boxes` firmware (an engine's broad phase on a
/// microcontroller): `BOXES` boxes, `FRAMES` frames, `BOX_RAYS` rays a frame.
#[allow(dead_code)] // not used by the triangle sets
pub const BOXES: usize = 64;
#[allow(dead_code)] // not used by the triangle sets
pub const FRAMES: usize = 4;
#[allow(dead_code)]
pub const BOX_RAYS: usize = 4;

/// Box `i` in frame `f`: a side of 1 to 2.75 on a 16 x 16 x 4 field, moving
/// by a quarter-unit step a frame. Every coordinate is a multiple of 1/4, so
/// host and target compute the same boxes bit for bit.
#[allow(dead_code)]
pub fn moving_box(i: usize, f: usize) -> bvhkit::Aabb {
    let q = |k: usize| k as f32 * 0.25;
    // u32, not usize: the same hash on the 32-bit target and a 64-bit host.
    let h = ((i as u32).wrapping_mul(2_654_435_761) >> 7) as usize;
    let lo = Vec3::new(
        q((h % 61) + f * (1 + i % 3)),
        q((h / 61 % 59) + f * (i % 2)),
        q((h / 3599 % 13) + f * (i % 5 / 3)),
    );
    let side = Vec3::new(q(4 + h % 8), q(4 + h / 8 % 8), q(4 + h / 64 % 8));
    bvhkit::Aabb::new(lo, lo + side)
}

/// Ray `r` of frame `f` through the box field: along `x`, `y` or a diagonal.
#[allow(dead_code)]
pub fn box_ray(r: usize, f: usize) -> (Vec3, Vec3) {
    let y = 1.0 + (r * 5 + f * 3) as f32;
    match r % 4 {
        0 => (Vec3::new(-5.0, y, 1.5), Vec3::X),
        1 => (Vec3::new(y, -5.0, 2.0), Vec3::Y),
        2 => (Vec3::new(-5.0, -5.0, 1.0), Vec3::new(1.0, 1.0, 0.125)),
        _ => (Vec3::new(y, 30.0, 0.5), Vec3::new(0.25, -1.0, 0.0)),
    }
}

/// Digest of a tree, bit for bit: every node's bounds, first and count,
/// then the index array, in order. The host builds the same scene with the
/// same builder and compares: a microcontroller bins one axis at a time
/// where the host bins all three at once, and both must give the same tree.
#[allow(dead_code)]
pub fn tree_digest(nodes: &[bvhkit::Node<bvhkit::Aabb>], indices: &[u32]) -> u32 {
    let mut h = 0x811C_9DC5u32;
    let mut eat = |w: u32| h = (h ^ w).wrapping_mul(0x0100_0193);
    for n in nodes {
        for v in [n.bv.min, n.bv.max] {
            for c in v.to_array() {
                eat(c.to_bits());
            }
        }
        eat(n.first);
        eat(n.count);
    }
    for &i in indices {
        eat(i);
    }
    h
}
