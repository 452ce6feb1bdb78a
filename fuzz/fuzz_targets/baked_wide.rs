//! A baked 4-wide tree opened from arbitrary bytes, as kind 2
//! (`Wide::from_baked`) and as kind 3 (`QuantizedWide::from_baked`): either
//! refused with an error, or opened, and then `validate`, a pair query and
//! a ray on it run to the end. Never a panic, never a hang, never a read out
//! of bounds. The input follows the start of a genuine header and is copied
//! to a 64-byte aligned buffer, so that the fuzzer reaches past the magic,
//! the version, the kind and the alignment check.
#![no_main]
use bvhkit::glam::Vec3;
use bvhkit::layout::{QuantizedWide, Wide};
use bvhkit::{Pairs, Query, Ray, RayOrder, Triangle};

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let tris: Vec<Triangle> = (0..8)
        .map(|i| {
            let o = Vec3::new(i as f32, 0.0, 0.0);
            Triangle::new(o, o + Vec3::X * 0.9, o + Vec3::Y)
        })
        .collect();
    // Header: magic, version 1, the kind; the fuzzer writes everything
    // after, at a 64-byte aligned address within a slightly larger buffer.
    let len = 12 + data.len();
    let mut buf = vec![0u8; len + 64];
    let at = buf.as_ptr().align_offset(64).min(64);
    for kind in [2u32, 3] {
        let bytes = &mut buf[at..at + len];
        bytes[..4].copy_from_slice(b"BVHK");
        bytes[4..8].copy_from_slice(&1u32.to_le_bytes());
        bytes[8..12].copy_from_slice(&kind.to_le_bytes());
        bytes[12..].copy_from_slice(data);
        let bytes = &bytes[..];
        let ray = Ray::new(Vec3::new(3.5, 0.2, 1.0), -Vec3::Z, f32::INFINITY).ok();
        if kind == 2 {
            let Ok(need) = Wide::baked_seen_words(bytes) else {
                continue;
            };
            let mut seen = vec![0u32; need.min(1 << 16)];
            let Ok(wide) = Wide::from_baked(bytes, &mut seen) else {
                continue;
            };
            if wide.validate(&tris).is_ok() {
                let _ = Pairs::new(&wide, &tris, &wide, &tris).count();
                if let Some(ray) = &ray {
                    let _ = Query::cast_ray(&wide, &tris, ray, RayOrder::BestFirst, ());
                }
            }
        } else {
            let Ok(need) = QuantizedWide::baked_seen_words(bytes) else {
                continue;
            };
            let mut seen = vec![0u32; need.min(1 << 16)];
            let Ok(q) = QuantizedWide::from_baked(bytes, &mut seen) else {
                continue;
            };
            if q.validate(&tris).is_ok() {
                let _ = Pairs::new(&q, &tris, &q, &tris).count();
                if let Some(ray) = &ray {
                    let _ = Query::cast_ray(&q, &tris, ray, RayOrder::BestFirst, ());
                }
            }
        }
    }
});
