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
