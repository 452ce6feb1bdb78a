//! Numerical stress (#19): slivers, needles, axis-aligned coplanar sheets and
//! duplicated triangles, placed at offsets from 1e-6 to 1e7 and scaled from
//! 1e-3 to 1e3, built by every builder of the library (each top-down preset,
//! PLOC, the exhaustive bottom-up, the insertion builders) into every volume
//! type and viewed in every layout (AABB, sphere and 14-DOP trees; OBB and
//! 18/26-DOP trees as built); every answer (regions, rays, nearest, pairs
//! under every traversal, same frame and moved) against brute force.
//!
//! The default case count keeps CI fast; `PROPTEST_CASES=200` for a long run.

use crate::layouts::{run_all, run_boxes};
use bvhkit::glam::Vec3;
use bvhkit::{Aabb, BoundingVolume, Dop14, Dop18, Dop26, Node, Obb, Sphere, Triangle};
use bvhkit_std::builders::{catalogue, Builder};
use bvhkit_tests::{check_trees_against_brute_force, proptest_config, region_in};
use proptest::prelude::*;

/// One triangle's shape before placement.
#[derive(Clone, Copy, Debug)]
enum Shape {
    /// Ordinary, about unit size.
    Plain,
    /// Long and very thin: width 1e-5 of its length.
    Sliver,
    /// Three nearly collinear vertices, two of them a millionth apart.
    Needle,
}

fn unit() -> impl Strategy<Value = Vec3> {
    (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn shaped() -> impl Strategy<Value = (Shape, Vec3, Vec3, Vec3, f32)> {
    (
        prop_oneof![Just(Shape::Plain), Just(Shape::Sliver), Just(Shape::Needle)],
        unit(),
        unit(),
        unit(),
        0.5f32..5.0,
    )
}

fn triangle((shape, a, d, n): (Shape, Vec3, Vec3, Vec3), len: f32) -> Triangle {
    let a = a * 10.0;
    let d = d.try_normalize().unwrap_or(Vec3::X) * len;
    match shape {
        Shape::Plain => Triangle::new(a, a + d, a + n),
        Shape::Sliver => Triangle::new(a, a + d, a + d + n * (1e-5 * len)),
        Shape::Needle => Triangle::new(a, a + d, a + d * (1.0 + 1e-6)),
    }
}

/// A stressed scene and how it was made (for the failure message).
fn stress_scene(max: usize) -> impl Strategy<Value = (Vec<Triangle>, String)> {
    (
        prop::collection::vec(shaped(), 1..max),
        prop_oneof![Just(None), (0usize..3).prop_map(Some)],
        0usize..12,
        (-6.0f32..7.0, [any::<bool>(), any::<bool>(), any::<bool>()]),
        -3.0f32..3.0,
    )
        .prop_map(|(shapes, sheet, copies, (offset_exp, signs), scale_exp)| {
            let mut tris: Vec<Triangle> = shapes
                .iter()
                .map(|&(s, a, d, n, len)| triangle((s, a, d, n), len))
                .collect();
            // A coplanar, axis-aligned sheet: one coordinate shared by all.
            if let Some(axis) = sheet {
                for t in &mut tris {
                    for v in &mut t.v {
                        v[axis] = 0.25;
                    }
                }
            }
            // Exact duplicates of the first triangles (identical centroids).
            let k = tris.len();
            for i in 0..copies {
                tris.push(tris[i % k.min(2)]);
            }
            let scale = 10f32.powf(scale_exp);
            let offset = Vec3::from_array(signs.map(|s| if s { 1.0 } else { -1.0 }))
                * 10f32.powf(offset_exp);
            for t in &mut tris {
                for v in &mut t.v {
                    *v = *v * scale + offset;
                }
            }
            let how = format!(
                "{} triangles, sheet {sheet:?}, {copies} copies, offset {offset}, scale {scale:e}",
                tris.len()
            );
            (tris, how)
        })
}

/// Builds `a` and `b` with `builder` into volume `B`, then runs `layouts`
/// (every layout's checks) on the two trees' nodes and indices.
fn check<B: BoundingVolume>(
    name: &str,
    builder: &Builder,
    (a, b): (&[Triangle], &[Triangle]),
    layouts: impl FnOnce((&[Node<B>], &[u32]), (&[Node<B>], &[u32])) -> Result<(), TestCaseError>,
) -> Result<(), TestCaseError> {
    let fail = |e: String| TestCaseError::fail(format!("{name} {}: {e}", B::NAME));
    let built = |p: &[Triangle]| builder.build::<B>(p).map_err(|e| fail(e.to_string()));
    let (ta, tb) = (built(a)?, built(b)?);
    let (va, vb) = (ta.plain_view(), tb.plain_view());
    layouts((va.nodes(), va.indices()), (vb.nodes(), vb.indices())).map_err(|e| fail(e.to_string()))
}

proptest! {
    #![proptest_config(proptest_config(6))]

    #[test]
    fn every_builder_volume_and_layout_survives_stressed_scenes(
        (a, how_a) in stress_scene(24),
        (b, how_b) in stress_scene(24),
        probe in (0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0),
    ) {
        let scenes = (a.as_slice(), b.as_slice());
        let region = region_in(&a, probe.0, probe.1);
        for (name, _, builder) in catalogue() {
            let context = |e: TestCaseError| TestCaseError::fail(format!("{e}\n  A: {how_a}\n  B: {how_b}"));
            // Every layout, for the volume types the layout tests instantiate.
            check::<Aabb>(name, &builder, scenes, |x, y| run_all(x, y, &a, &b, probe)).map_err(context)?;
            check::<Sphere>(name, &builder, scenes, |x, y| run_all(x, y, &a, &b, probe)).map_err(context)?;
            check::<Dop14>(name, &builder, scenes, |x, y| run_all(x, y, &a, &b, probe)).map_err(context)?;
            // The other volumes on the canonical tree, every query (every
            // layout again would compile the layout checks three more
            // times, minutes of CI for the same layout code).
            check::<Obb>(name, &builder, scenes, |x, y| {
                check_trees_against_brute_force(x, &a, y, &b, &region, &name)
            })
            .map_err(context)?;
            check::<Dop18>(name, &builder, scenes, |x, y| {
                check_trees_against_brute_force(x, &a, y, &b, &region, &name)
            })
            .map_err(context)?;
            check::<Dop26>(name, &builder, scenes, |x, y| {
                check_trees_against_brute_force(x, &a, y, &b, &region, &name)
            })
            .map_err(context)?;
            // The 4-wide layouts hold boxes only.
            check::<Aabb>(name, &builder, scenes, |x, y| run_boxes(x, y, &a, &b, probe)).map_err(context)?;
        }
    }
}
