//! Refitting after motion keeps every invariant and every answer: random
//! trees, random subsets of primitives moved by random amounts, incremental
//! and full refits, with and without a margin, for every volume type.

use bvhkit::builders::{refit_all, Refit};
use bvhkit::glam::Vec3;
use bvhkit::{
    brute_force, Aabb, BoundingVolume, Bounds, Counts, Dop14, Error, Obb, Same, Sphere, TopDown,
    Triangle,
};
use bvhkit_tests::*;
use proptest::prelude::*;

/// One animation step: which primitives move, and by how much.
type Step = Vec<(usize, (f32, f32, f32))>;

fn moves() -> impl Strategy<Value = Step> {
    prop::collection::vec(
        (0usize..1000, (-3.0f32..3.0, -3.0f32..3.0, -3.0f32..3.0)),
        0..30,
    )
}

fn check<B: BoundingVolume>(
    cfg: &TopDown,
    a: &[Triangle],
    b: &[Triangle],
    steps: &[Step],
    margin: f32,
    incremental: bool,
) -> Result<(), TestCaseError> {
    let (mut nodes, idx, _) =
        build::<B, _>(cfg, a).map_err(|e| TestCaseError::fail(format!("{e}")))?;
    let (nb, ib, _) = build::<B, _>(cfg, b).map_err(|e| TestCaseError::fail(format!("{e}")))?;
    let mut prims = a.to_vec();
    let scale = region_in(a, 0.0, 1.0).extent().max_element().max(1e-3) * 0.1;
    refit_all(&mut nodes, &idx, &prims, margin, ()).unwrap();
    let (mut parents, mut leaf_of) = (vec![0u32; nodes.len()], vec![0u32; prims.len()]);
    let refit = Refit::new(&nodes, &idx, &mut parents, &mut leaf_of).unwrap();
    for step in steps {
        let mut moved: Vec<u32> = Vec::new();
        for &(i, (x, y, z)) in step {
            let i = i % prims.len();
            prims[i] = prims[i].translated(Vec3::new(x, y, z) * scale);
            moved.push(i as u32);
        }
        let mut counts = Counts::default();
        if incremental {
            refit
                .moved(&mut nodes, &idx, &prims, &moved, margin, &mut counts)
                .unwrap();
            prop_assert!(counts.updates as usize <= moved.len() * (nodes.len()));
        } else {
            refit_all(&mut nodes, &idx, &prims, margin, &mut counts).unwrap();
            prop_assert_eq!(counts.updates as usize, nodes.len());
        }
        // `open` validates: children inside parents, primitives inside leaves.
        let ta = open(&nodes, &idx, &prims);
        let tb = open(&nb, &ib, b);
        let region = region_in(&prims, 0.2, 0.7);
        let mut got = Vec::new();
        ta.overlapping(&prims, &region, |i| got.push(i)).unwrap();
        got.sort_unstable();
        let mut want = Vec::new();
        brute_force::overlapping(&prims, &region, |i| want.push(i));
        prop_assert_eq!(got, want);
        check_pairs(&ta, &prims, &tb, b, &Same, Bounds, cfg)?;
    }
    Ok(())
}

proptest! {
    #![proptest_config(proptest_config(32))]

    #[test]
    fn refits_keep_invariants_and_answers(
        cfg in any_top_down(), a in scene(40), b in scene(30),
        steps in prop::collection::vec(moves(), 1..5),
        margin in prop_oneof![Just(0.0f32), 0.0f32..0.5],
        incremental in any::<bool>(),
    ) {
        check::<Aabb>(&cfg, &a, &b, &steps, margin, incremental)?;
        check::<Sphere>(&cfg, &a, &b, &steps, margin, incremental)?;
        check::<Obb>(&cfg, &a, &b, &steps, margin, incremental)?;
        check::<Dop14>(&cfg, &a, &b, &steps, margin, incremental)?;
    }
}

#[test]
fn refit_errors_instead_of_panicking() {
    let tris: Vec<Triangle> = (0..6)
        .map(|i| Triangle::new(Vec3::X * i as f32, Vec3::Y, Vec3::Z))
        .collect();
    let (mut nodes, idx, _) =
        build::<Aabb, _>(&TopDown::default().with_max_leaf_size(1), &tris).unwrap();
    assert!(refit_all(&mut nodes, &idx, &tris, f32::NAN, ()).is_err());
    assert!(refit_all(&mut nodes, &idx, &tris, -1.0, ()).is_err());
    assert!(refit_all(&mut nodes, &idx, &tris[..3], 0.0, ()).is_err());
    let mut bad = tris.clone();
    bad[2].v[1].x = f32::INFINITY;
    assert!(matches!(
        refit_all(&mut nodes, &idx, &bad, 0.0, ()),
        Err(Error::NonFiniteCoordinate { primitive: 2 })
    ));
    let (mut parents, mut leaf_of) = (vec![0u32; nodes.len()], vec![0u32; tris.len()]);
    let refit = Refit::new(&nodes, &idx, &mut parents, &mut leaf_of).unwrap();
    assert!(refit.moved(&mut nodes, &idx, &bad, &[2], 0.0, ()).is_err());
    assert!(refit
        .moved(&mut nodes, &idx, &tris, &[99], 0.0, ())
        .is_err());
    // Storage not laid out parent-before-children is refused.
    let mut swapped = nodes.clone();
    swapped.swap(0, 1);
    assert!(refit_all(&mut swapped, &idx, &tris, 0.0, ()).is_err());
    let mut short = vec![0u32; 1];
    assert!(Refit::new(&nodes, &idx, &mut short, &mut leaf_of.clone()).is_err());
}
