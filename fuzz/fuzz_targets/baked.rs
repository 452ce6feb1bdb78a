//! A baked tree opened from arbitrary bytes (`Bvh::from_baked`): either
//! refused with an error, or opened, and then it passes `validate` against
//! the primitives it names or is refused there, and a query on it runs to
//! the end. Never a panic, never a hang, never a read out of bounds. The
//! input follows the start of a genuine header, so that the fuzzer reaches
//! past the magic, the version and the kind.
#![no_main]
use bvhkit::glam::Vec3;
use bvhkit::{Aabb, Bvh, Pairs, Triangle};

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let tris: Vec<Triangle> = (0..8)
        .map(|i| {
            let o = Vec3::new(i as f32, 0.0, 0.0);
            Triangle::new(o, o + Vec3::X * 0.9, o + Vec3::Y)
        })
        .collect();
    // Header: magic, version 1, kind 1; the fuzzer writes everything after.
    let mut bytes = Vec::with_capacity(12 + data.len());
    bytes.extend_from_slice(b"BVHK");
    bytes.extend_from_slice(&1u32.to_le_bytes());
    bytes.extend_from_slice(&1u32.to_le_bytes());
    bytes.extend_from_slice(data);
    // A fresh `Vec<u8>` comes from the allocator aligned to at least 8 on
    // the hosts the fuzzer runs on (`from_baked` would refuse it otherwise).
    let aligned = &bytes[..];
    let Ok(need) = Bvh::<Aabb>::baked_seen_words(aligned) else {
        return;
    };
    let mut seen = vec![0u32; need.min(1 << 16)];
    let Ok(tree) = Bvh::from_baked(aligned, &mut seen) else {
        return;
    };
    if tree.primitive_count() == tris.len() && tree.validate(&tris, &mut seen).is_ok() {
        let _ = Pairs::new(&tree, &tris, &tree, &tris).count();
    }
});
