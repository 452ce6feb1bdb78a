//! Local frames: a scene in `f64` world coordinates, entered into `f32`
//! trees relative to a frame at it, answers as the same scene does at the
//! world's origin, however far away it is; world boxes entered into the
//! frame contain what they contained in the world.

use bvhkit::glam::DVec3;
use bvhkit::{brute_force, Aabb, Exact, LocalFrame, Pairs, Primitive, Same, TopDown, Triangle};
use bvhkit_std::OwnedBvh;
use bvhkit_tests::proptest_config;
use proptest::prelude::*;

/// A triangle on a 2^-8 grid near the origin: exact in `f32`, and in `f64`
/// after any integer offset below 2^40.
fn triangle() -> impl Strategy<Value = [DVec3; 3]> {
    let p = || {
        (-256i32..=256, -256i32..=256, -256i32..=256)
            .prop_map(|(x, y, z)| DVec3::new(x.into(), y.into(), z.into()) / 256.0)
    };
    (p(), p(), p()).prop_map(|(a, b, c)| [a, a + b * 0.5, a + c * 0.5])
}

fn exact_pairs(a: &[Triangle], b: &[Triangle]) -> Result<Vec<(u32, u32)>, bvhkit::Error> {
    let ta = OwnedBvh::<Aabb>::build(&TopDown::default(), a)?;
    let tb = OwnedBvh::<Aabb>::build(&TopDown::default(), b)?;
    let mut got = Vec::new();
    Pairs::new(&ta.view(), a, &tb.view(), b)
        .exact()
        .for_each(|i, j| got.push((i, j)))?;
    got.sort_unstable();
    Ok(got)
}

proptest! {
    #![proptest_config(proptest_config(48))]

    #[test]
    fn scenes_far_away_answer_in_a_frame_as_at_the_origin(
        a in prop::collection::vec(triangle(), 0..40),
        b in prop::collection::vec(triangle(), 0..40),
        offset in (-(1i64 << 39)..(1i64 << 39), -(1i64 << 39)..(1i64 << 39), -(1i64 << 30)..(1i64 << 30)),
        query in (triangle(), 0.0f64..1.0),
    ) {
        let offset = DVec3::new(offset.0 as f64, offset.1 as f64, offset.2 as f64);
        let at_origin = LocalFrame::new(DVec3::ZERO)?;
        let frame = LocalFrame::new(offset)?;
        let enter = |w: &[[DVec3; 3]], f: &LocalFrame, by: DVec3| -> Vec<Triangle> {
            w.iter().map(|t| f.triangle(t.map(|v| v + by))).collect()
        };
        let (oa, ob) = (enter(&a, &at_origin, DVec3::ZERO), enter(&b, &at_origin, DVec3::ZERO));
        let (fa, fb) = (enter(&a, &frame, offset), enter(&b, &frame, offset));
        // The frame gives back the very triangles of the origin: the pairs follow.
        prop_assert_eq!(&fa, &oa);
        let want = {
            let mut w = Vec::new();
            brute_force::pairs_placed(&oa, &ob, &Same, Exact, |i, j| w.push((i, j)));
            w.sort_unstable();
            w
        };
        prop_assert_eq!(exact_pairs(&fa, &fb)?, want);

        // A world box, entered outward, finds every triangle whose world
        // corners it touches (brute force in f64).
        let (t, grow) = query;
        let lo = t.iter().fold(DVec3::INFINITY, |m, &v| m.min(v)) - grow + offset;
        let hi = t.iter().fold(DVec3::NEG_INFINITY, |m, &v| m.max(v)) + grow + offset;
        let region = frame.aabb(lo, hi);
        prop_assert!(region.min.as_dvec3().cmple(lo - offset).all());
        prop_assert!(region.max.as_dvec3().cmpge(hi - offset).all());
        // The triangles' boxes as primitives: the query tests boxes, as
        // the brute force below does.
        let boxes: Vec<Aabb> = fa.iter().map(|t| t.bounds()).collect();
        let tree = OwnedBvh::<Aabb>::build(&TopDown::default(), &boxes)?;
        let mut found = Vec::new();
        tree.view().overlapping(&boxes, &region, |i| found.push(i))?;
        for (i, w) in a.iter().enumerate() {
            let (wl, wh) = w.iter().fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), &v| (l.min(v + offset), h.max(v + offset)));
            if wl.cmple(hi).all() && wh.cmpge(lo).all() {
                prop_assert!(found.contains(&(i as u32)), "world box misses triangle {}", i);
            }
        }
    }
}
